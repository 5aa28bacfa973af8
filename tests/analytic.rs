//! Integrators against closed-form answers.

mod common;

use glam::Vec3A;
use ronray::load::{Overrides, load_str};
use ronray::math::Ray;
use std::f32::consts::PI;
use std::path::Path;

use common::{load_text as scene, mean_li};

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
    let (img, _) = ronray::render::render(&s.scene, &s.view, &Default::default());
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

/// Inside a closed Lambert sphere (albedo ρ = 0.5, radius 1) with a point
/// light of intensity π at its centre, every wall receives E = π/r² = π
/// directly: direct lighting sees ρE/π = 0.5; with every bounce the
/// radiosity is B = ρE/(1 − ρ), so path tracing sees B/π = 1.
#[test]
fn closed_sphere_direct_and_path_match_closed_forms() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 60),
            film: (width: 8, height: 8, spp: 1),
            integrator: {integrator},
            materials: {{ "half": Lambert(albedo: (0.5, 0.5, 0.5)) }},
            lights: [Point(position: (0, 0, 0), intensity: (3.14159265, 3.14159265, 3.14159265))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "half")],
        )"#
        )
    };
    let ray = Ray::new(Vec3A::ZERO, Vec3A::new(0.3, -0.2, -1.0).normalize());
    let direct = mean_li(&scene(&text("Direct(light_samples: 1)")), ray, 16);
    assert!(
        (direct.x - 0.5).abs() < 0.005,
        "direct: expected 0.5, got {}",
        direct.x
    );
    let path = mean_li(&scene(&text("Path(max_depth: -1, rr_depth: 5)")), ray, 200_000);
    assert!((path.x - 1.0).abs() < 0.01, "path: expected 1.0, got {}", path.x);
    let two = mean_li(&scene(&text("Path(max_depth: 2, rr_depth: 5)")), ray, 16);
    assert!(
        (two.x - 0.5).abs() < 0.005,
        "path max_depth 2 is direct lighting: got {}",
        two.x
    );
}

/// White furnace: inside a closed box whose six walls all emit Le = 1 and
/// reflect with albedo ρ = 0.5, radiance is Le/(1 − ρ) = 2 everywhere.
#[test]
fn furnace_emitting_enclosure_gives_le_over_one_minus_rho() {
    // Six inward-facing walls of the cube [-1, 1]³ (half_u × half_v points in).
    let walls = [
        ("(0, -1, 0)", "(0, 0, 1)", "(1, 0, 0)"),
        ("(0, 1, 0)", "(1, 0, 0)", "(0, 0, 1)"),
        ("(-1, 0, 0)", "(0, 1, 0)", "(0, 0, 1)"),
        ("(1, 0, 0)", "(0, 0, 1)", "(0, 1, 0)"),
        ("(0, 0, -1)", "(1, 0, 0)", "(0, 1, 0)"),
        ("(0, 0, 1)", "(0, 1, 0)", "(1, 0, 0)"),
    ];
    let lights: Vec<String> = walls
        .iter()
        .map(|(c, u, v)| {
            format!(r#"Rect(center: {c}, half_u: {u}, half_v: {v}, radiance: (1, 1, 1), material: "half")"#)
        })
        .collect();
    let s = scene(&format!(
        r#"Scene(
        camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 60),
        integrator: Path(max_depth: -1, rr_depth: 5),
        materials: {{ "half": Lambert(albedo: (0.5, 0.5, 0.5)) }},
        lights: [{}],
    )"#,
        lights.join(", ")
    ));
    for d in [Vec3A::new(0.1, 0.2, -1.0), Vec3A::new(0.9, -0.7, 0.2)] {
        let got = mean_li(&s, Ray::new(Vec3A::new(0.1, 0.0, 0.2), d.normalize()), 100_000);
        assert!((got.x - 2.0).abs() < 0.02, "expected 2.0, got {}", got.x);
    }
}

/// Without mirrors or glass, Whitted shades exactly like direct lighting.
#[test]
fn whitted_equals_direct_without_specular_surfaces() {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.ron"))
        .expect("scene");
    let render = |integrator: &str| {
        let t = text.replace("integrator: Path(max_depth: 8, rr_depth: 5)", integrator);
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.ron");
        let o = Overrides {
            spp: Some(4),
            size: Some((32, 32)),
            seed: Some(5),
            ..Default::default()
        };
        let l = load_str(&path, &t, &o).expect("scene loads");
        ronray::render::render(&l.scene, &l.view, &Default::default()).0
    };
    let direct = render("integrator: Direct(light_samples: 2)");
    let whitted = render("integrator: Whitted(max_depth: 5, light_samples: 2)");
    assert!(direct.pixels.iter().any(|p| p.x > 0.0), "the image is not black");
    assert_eq!(
        direct, whitted,
        "Whitted differs from Direct on a purely diffuse scene"
    );
}
