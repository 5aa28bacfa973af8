//! Integrators against closed-form answers.

use glam::Vec3A;
use ronray::integrators::Counters;
use ronray::math::{Pcg32, Ray};
use ronray::sampler::Sampler;
use ronray::scene::{Overrides, load_str};
use std::f32::consts::PI;
use std::path::Path;

fn scene(text: &str) -> ronray::scene::Scene {
    match load_str(Path::new("analytic.ron"), text, &Overrides::default()) {
        Ok(l) => l.scene,
        Err(e) => panic!(
            "test scene must load: {e}\n{}",
            e.report().map(|r| r.to_string()).unwrap_or_default()
        ),
    }
}

/// Mean radiance along `ray` over `n` independent estimates.
fn mean_li(scene: &ronray::scene::Scene, ray: Ray, n: u32) -> Vec3A {
    let mut sum = Vec3A::ZERO;
    let mut c = Counters::default();
    for i in 0..n {
        let mut sampler = Sampler::independent(Pcg32::for_sample(0, 0, i, 99));
        sum += scene.integrator.li(scene, &ray, &mut sampler, &mut c);
    }
    sum / n as f32
}

#[test]
fn direct_point_light_on_lambert_plane_matches_closed_form() {
    // Plane y = 0, albedo 0.5; point light 2 above the origin, I = 10 W/sr.
    let s = scene(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 20),
        film: (width: 33, height: 33, spp: 16),
        integrator: Direct(light_samples: 1),
        materials: { "grey": Lambert(albedo: (0.5, 0.5, 0.5)) },
        lights: [Point(position: (0, 2, 0), intensity: (10, 10, 10))],
        objects: [Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey")],
    )"#,
    );
    // The pixel at the image centre sees the origin, straight below the light.
    let (img, _) = ronray::render::render(&s, &Default::default());
    let got = img.get(16, 16);
    let expected = 0.5 / PI * 10.0 * 1.0 / 4.0;
    for c in 0..3 {
        let rel = (got[c] - expected).abs() / expected;
        assert!(
            rel < 0.01,
            "channel {c}: expected {expected}, got {} ({:.2}% off)",
            got[c],
            rel * 100.0
        );
    }
    // And the exact point, from a ray aimed at it: cos θ / r² off axis too.
    let x = Vec3A::new(1.5, 0.0, 0.0);
    let got = mean_li(
        &s,
        Ray::new(
            Vec3A::new(1.5, 1.0, 1.0),
            (x - Vec3A::new(1.5, 1.0, 1.0)).normalize(),
        ),
        1,
    );
    let r2 = 1.5f32 * 1.5 + 4.0;
    let expected = 0.5 / PI * 10.0 * (2.0 / r2.sqrt()) / r2;
    assert!(
        (got.x - expected).abs() / expected < 1e-3,
        "off-axis: expected {expected}, got {}",
        got.x
    );
}

/// Irradiance from a uniform, one-sided Lambertian polygon emitter of radiance
/// `l` at point `x` with normal `n` (Lambert's formula: E = L/2 Σ βᵢ n·γᵢ).
fn polygon_irradiance(x: Vec3A, n: Vec3A, verts: &[Vec3A], l: f32) -> f32 {
    let mut sum = 0.0;
    for i in 0..verts.len() {
        let a = (verts[i] - x).normalize();
        let b = (verts[(i + 1) % verts.len()] - x).normalize();
        let beta = a.dot(b).clamp(-1.0, 1.0).acos();
        sum += beta * n.dot(a.cross(b).normalize());
    }
    0.5 * l * sum.abs()
}

#[test]
fn direct_quad_light_irradiance_matches_polygon_formula() {
    // A 0.8 × 1 light 1.5 above the floor, off to the side, facing down
    // (edge_u × edge_v = x × z = −y).
    let s = scene(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 20),
        integrator: Direct(light_samples: 64),
        materials: { "white": Lambert(albedo: (1, 1, 1)) },
        lights: [Quad(corner: (0.2, 1.5, -0.4), edge_u: (0.8, 0, 0), edge_v: (0, 0, 1), radiance: (5, 5, 5))],
        objects: [Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "white")],
    )"#,
    );
    let verts = [
        Vec3A::new(0.2, 1.5, -0.4),
        Vec3A::new(1.0, 1.5, -0.4),
        Vec3A::new(1.0, 1.5, 0.6),
        Vec3A::new(0.2, 1.5, 0.6),
    ];
    for x in [Vec3A::ZERO, Vec3A::new(0.6, 0.0, 0.1), Vec3A::new(-1.0, 0.0, 0.5)] {
        let e = polygon_irradiance(x, Vec3A::Y, &verts, 5.0);
        let expected = e / PI; // Lambert, albedo 1: L = E/π
        let o = x + Vec3A::new(-0.3, 1.0, 1.0);
        let got = mean_li(&s, Ray::new(o, (x - o).normalize()), 2048);
        let rel = (got.x - expected).abs() / expected;
        assert!(
            rel < 0.01,
            "at {x}: expected {expected}, got {} ({:.2}% off)",
            got.x,
            rel * 100.0
        );
    }
}
