//! The SDF sphere against the analytic sphere: renders, hit points,
//! normals, texture coordinates and rays spawned from its hits.

use super::{render_seed, scene};
use glam::Vec3A;
use ronray::imageio::{Image, compare};
use ronray::load::Loaded;
use ronray::math::{Pcg32, Ray, ray_epsilon, sampling::uniform_sphere};
use ronray::scene::Scene;

const CENTER: Vec3A = Vec3A::new(0.1, 0.2, 0.0);
const RADIUS: f32 = 0.8;
const SDF_SPHERE: &str =
    r#"Sdf(shape: Sphere(radius: 0.8), material: "m", transform: [Translate((0.1, 0.2, 0))])"#;
const ANALYTIC_SPHERE: &str = r#"Sphere(center: (0.1, 0.2, 0), radius: 0.8, material: "m")"#;

/// A sphere (`object`), checker-textured to test UVs too; `full` adds a
/// floor and an area light (whose quad is a shape), else only the sphere.
fn sphere_scene(object: &str, full: bool) -> Loaded {
    let (floor, light) = if full {
        (
            r#"Plane(point: (0, -0.6, 0), normal: (0, 1, 0), material: "floor"),"#,
            "Rect(center: (1, 3, 2), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (20, 20, 20))",
        )
    } else {
        ("", "Point(position: (1, 3, 2), intensity: (5, 5, 5))")
    };
    scene(&format!(
        r#"Scene(
        camera: (eye: (0.3, 1, 4), target: (0.1, 0.2, 0), fov_y_degrees: 30),
        film: (width: 40, height: 40, spp: 4),
        integrator: Direct(light_samples: 1),
        materials: {{
            "m": Lambert(albedo: Checker(a: (0.8, 0.3, 0.2), b: (0.2, 0.6, 0.8), scale: 4)),
            "floor": Lambert(albedo: (0.5, 0.5, 0.5)),
        }},
        lights: [{light}],
        objects: [{floor} {object}],
    )"#
    ))
}

fn rmse(a: &Image, b: &Image) -> f64 {
    compare(a, b, None).unwrap().rmse
}

#[test]
fn sdf_sphere_renders_like_analytic_sphere() {
    let (mut sdf, mut ana) = (
        sphere_scene(SDF_SPHERE, true),
        sphere_scene(ANALYTIC_SPHERE, true),
    );
    let (s1, a1, a2) = (
        render_seed(&mut sdf, 1),
        render_seed(&mut ana, 1),
        render_seed(&mut ana, 2),
    );
    let s2 = render_seed(&mut sdf, 2);
    // The noise of one render: two independent renders differ by √2 of it.
    let noise = rmse(&a1, &a2) / 2f64.sqrt();
    let same_seed = rmse(&s1, &a1);
    let other_seed = rmse(&s2, &a1);
    println!("noise {noise:.5}, sdf vs analytic: same seed {same_seed:.5}, other seed {other_seed:.5}");
    assert!(noise > 0.0, "the renders should be noisy at 4 spp");
    assert!(
        same_seed < 0.25 * noise,
        "same seed: RMSE {same_seed} should be far below the noise {noise}"
    );
    assert!(
        other_seed < 1.1 * 2f64.sqrt() * noise,
        "other seeds: RMSE {other_seed} should be that of two analytic renders, {}",
        2f64.sqrt() * noise
    );
}

#[test]
fn sdf_sphere_hits_where_analytic_sphere_does() {
    let (sdf, ana) = (
        sphere_scene(SDF_SPHERE, false),
        sphere_scene(ANALYTIC_SPHERE, false),
    );
    let mut rng = Pcg32::new(7, 7);
    let (mut hits, mut grazing, mut spawned) = (0, 0, 0);
    for _ in 0..5000 {
        let o = CENTER + uniform_sphere(rng.next_vec2()) * RADIUS * (1.2 + 4.0 * rng.next_f32());
        let aim = CENTER + uniform_sphere(rng.next_vec2()) * RADIUS * 1.1 * rng.next_f32().cbrt();
        let ray = Ray::new(o, (aim - o).normalize());
        // Closest approach of the ray's line to the centre.
        let to_c = CENTER - o;
        let miss = (to_c - to_c.dot(ray.d) * ray.d).length();
        // Within 1e-3·r of tangent, where a hit slides along the ray by
        // √(2r·δ) for a surface δ off: only hit-or-miss is ill-posed there.
        let tangent = (miss - RADIUS).abs() < 1e-3 * RADIUS;
        match (
            sdf.scene.intersect(&ray, f32::INFINITY),
            ana.scene.intersect(&ray, f32::INFINITY),
        ) {
            (Some(s), Some(a)) => {
                hits += 1;
                let on_sphere = ((s.p - CENTER).length() - RADIUS).abs();
                assert!(on_sphere < 1e-5, "SDF hit {} is {on_sphere} off the sphere", s.p);
                let err = (s.p - a.p).length();
                assert!(
                    tangent || err < 1e-3 * RADIUS,
                    "ray {ray:?}: SDF hit {} vs {}",
                    s.p,
                    a.p
                );
                grazing += u32::from(tangent);
                assert!(s.ng.dot(a.ng) > 0.999, "normals {} vs {}", s.ng, a.ng);
                // Same texture coordinates, but where u wraps or at the poles.
                let du = (s.uv - a.uv).abs();
                assert!(
                    tangent || a.ng.y.abs() > 0.99 || du.y < 1e-3 && (du.x < 1e-3 || du.x > 0.999),
                    "uv {} vs {}",
                    s.uv,
                    a.uv
                );
                spawned += check_spawn(&sdf.scene, &s, &mut rng);
            }
            (None, None) => {}
            _ if tangent => grazing += 1,
            (s, a) => panic!("ray {ray:?} passing {miss} from the centre: SDF {s:?}, analytic {a:?}"),
        }
    }
    println!("{hits} hits, {grazing} nearly tangent rays, {spawned} spawned rays");
    assert!(hits > 2000 && grazing < 10, "{hits} hits, {grazing} grazing");
}

/// A ray spawned outward from a convex surface hits nothing; one spawned
/// inward exits on the far side, not at its own origin.
fn check_spawn(scene: &Scene, hit: &ronray::geometry::Hit, rng: &mut Pcg32) -> u32 {
    let mut w = uniform_sphere(rng.next_vec2());
    if w.dot(hit.ng) < 0.0 {
        w = -w;
    }
    let off = hit.ng * ray_epsilon(hit.p);
    let out = Ray::new(hit.p + off, w);
    let again = scene.intersect(&out, f32::INFINITY);
    assert!(
        again.is_none(),
        "outward ray {out:?} from {} (normal {}, |p - c| - r = {}) re-hit its surface: {again:?}",
        hit.p,
        hit.ng,
        (hit.p - CENTER).length() - RADIUS
    );
    let inward = Ray::new(hit.p - off, -w);
    let exit = scene
        .intersect(&inward, f32::INFINITY)
        .expect("an inward ray must leave the sphere");
    // Far root of |o − t·w − c| = r from the spawned origin.
    let (oc, d) = (inward.o - CENTER, -w);
    let b = -oc.dot(d);
    let chord = b + (b * b - (oc.length_squared() - RADIUS * RADIUS)).sqrt();
    // Grazing chords end at a grazing angle, where a hit threshold along the
    // normal is long along the ray: check where, and that it left its origin.
    let off_surface = ((exit.p - CENTER).length() - RADIUS).abs();
    if exit.t < 0.5 * chord {
        let o = &scene.geometry.sdfs[0];
        println!(
            "DEBUG hit {:?} off {off} d(origin) {} d(p) {}",
            hit,
            o.sdf.distance(inward.o),
            o.sdf.distance(hit.p)
        );
        for k in 0..6 {
            let t = exit.t * k as f32 / 3.0;
            println!("DEBUG t {t} d {}", o.sdf.distance(inward.at(t)));
        }
        println!(
            "DEBUG {:?}",
            ronray::geometry::sdf::trace(&o.sdf, &inward, 0.0, f32::INFINITY, &o.params)
        );
    }
    assert!(
        off_surface < 1e-3 * RADIUS && exit.t > 0.5 * chord,
        "inward ray exits after {} (chord {chord}), {off_surface} off the sphere",
        exit.t
    );
    2
}
