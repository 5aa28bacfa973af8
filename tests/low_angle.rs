//! Light at low angles and far from the origin: a large Lambert floor under a
//! quad, a point and a spot light, at receivers whose direction to the light
//! makes 0° to 85° with their normal, with the whole set-up moved 0.1 to 1000
//! units from the origin. Shadow rays used to stop on the light's own surface
//! past about 60°, leaving a far floor black (issue 19).

use glam::{DVec3, Vec3A};
use ronray::integrators::Counters;
use ronray::load::{Loaded, Overrides, load_str};
use ronray::math::{Pcg32, Ray, SampleRng};
use ronray::sampler::Sampler;
use std::path::Path;

const ALBEDO: f64 = 0.5;
const HEIGHT: f64 = 4.0;
/// Rect light half extents (x, z) and radiance, emitting downward.
const HALF: (f64, f64) = (1.5, 0.75);
const RADIANCE: f64 = 10.0;
const INTENSITY: f64 = 50.0;
const ANGLES_DEGREES: [f64; 10] = [0.0, 15.0, 30.0, 45.0, 55.0, 60.0, 65.0, 70.0, 80.0, 85.0];
const DISTANCES: [f64; 4] = [0.1, 10.0, 100.0, 1000.0];

/// Where the set-up sits: `dist` from the origin, off every axis so that no
/// coordinate stays small.
fn base(dist: f64) -> DVec3 {
    DVec3::new(0.6, 0.48, 0.64).normalize() * dist
}

fn v(p: DVec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

fn scene(integrator: &str, light: &str, b: DVec3) -> Loaded {
    let text = format!(
        r#"Scene(
        camera: (eye: {eye}, target: {b}, fov_y_degrees: 30),
        integrator: {integrator},
        materials: {{ "floor": Lambert(albedo: ({ALBEDO}, {ALBEDO}, {ALBEDO})) }},
        lights: [{light}],
        objects: [Plane(point: {b}, normal: (0, 1, 0), material: "floor")],
    )"#,
        eye = v(b + DVec3::new(0.0, 10.0, 10.0)),
        b = v(b),
    );
    match load_str(Path::new("low_angle.ron"), &text, &Overrides::default()) {
        Ok(l) => l,
        Err(e) => panic!("test scene must load: {e}\n{text}"),
    }
}

fn lights(b: DVec3) -> [(&'static str, String); 3] {
    let c = b + DVec3::new(0.0, HEIGHT, 0.0);
    [
        (
            "rect",
            format!(
                "Rect(center: {}, half_u: ({}, 0, 0), half_v: (0, 0, {}), radiance: ({RADIANCE}, {RADIANCE}, {RADIANCE}))",
                v(c),
                HALF.0,
                HALF.1
            ),
        ),
        (
            "point",
            format!(
                "Point(position: {}, intensity: ({INTENSITY}, {INTENSITY}, {INTENSITY}))",
                v(c)
            ),
        ),
        (
            "spot",
            format!(
                "Spot(position: {}, direction: (0, -1, 0), intensity: ({INTENSITY}, {INTENSITY}, {INTENSITY}), cone_degrees: 179)",
                v(c)
            ),
        ),
    ]
}

/// Outgoing radiance of the floor at `x` (relative to the light's foot), by
/// midpoint quadrature over the rect in f64: ρ/π ∫ L cosθr cosθl / r² dA.
fn rect_expected(x: DVec3) -> f64 {
    let (nu, nv) = (600, 300);
    let (du, dv) = (2.0 * HALF.0 / nu as f64, 2.0 * HALF.1 / nv as f64);
    let mut e = 0.0;
    for i in 0..nu {
        for j in 0..nv {
            let q = DVec3::new(
                -HALF.0 + (i as f64 + 0.5) * du,
                HEIGHT,
                -HALF.1 + (j as f64 + 0.5) * dv,
            );
            let d = q - x;
            let r2 = d.length_squared();
            let cos_r = d.y / r2.sqrt();
            e += RADIANCE * cos_r * cos_r / r2 * du * dv; // cosθl = cosθr for parallel planes
        }
    }
    ALBEDO / std::f64::consts::PI * e
}

/// ρ/π · I cosθ / r² for a point (and a spot inside its cone).
fn point_expected(x: DVec3) -> f64 {
    let d = DVec3::new(0.0, HEIGHT, 0.0) - x;
    let r2 = d.length_squared();
    ALBEDO / std::f64::consts::PI * INTENSITY * (d.y / r2.sqrt()) / r2
}

/// Mean radiance seen along a ray straight down onto `x`.
fn mean_li(s: &Loaded, x: DVec3, n: u32) -> f64 {
    let o = x + DVec3::new(0.0, 1.0, 0.0);
    let ray = Ray::new(Vec3A::new(o.x as f32, o.y as f32, o.z as f32), Vec3A::NEG_Y);
    let mut c = Counters::default();
    let mut sum = 0.0f64;
    for i in 0..n {
        let mut sampler = Sampler::independent(SampleRng::for_sample(3, 7, i, 19));
        sum += s.view.integrator.li(&s.scene, &ray, &mut sampler, &mut c).x as f64;
    }
    sum / n as f64
}

fn check(integrator: &str, samples: u32) {
    let mut failures = Vec::new();
    for dist in DISTANCES {
        let b = base(dist);
        for (kind, light) in lights(b) {
            let s = scene(integrator, &light, b);
            for deg in ANGLES_DEGREES {
                let x = DVec3::new(HEIGHT * deg.to_radians().tan(), 0.0, 0.0);
                let (expected, n) = match kind {
                    "rect" => (rect_expected(x), samples),
                    _ => (point_expected(x), 1),
                };
                let got = mean_li(&s, b + x, n);
                let rel = (got - expected).abs() / expected;
                if rel > 0.01 {
                    failures.push(format!(
                        "{kind} light, {deg}° at {dist} from the origin: expected {expected:.6}, got {got:.6} ({:.1}% off)",
                        rel * 100.0
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{integrator}:\n{}", failures.join("\n"));
}

#[test]
fn direct_lights_a_floor_at_every_angle_and_distance_from_the_origin() {
    check("Direct(light_samples: 1)", 8192);
}

#[test]
fn path_lights_a_floor_at_every_angle_and_distance_from_the_origin() {
    check("Path(max_depth: 2)", 16384);
}

#[test]
fn whitted_lights_a_floor_at_every_angle_and_distance_from_the_origin() {
    check("Whitted(max_depth: 1, light_samples: 1)", 8192);
}

/// An object's RON text, given where to move it.
type Placed<'a> = dyn Fn(&str) -> String + 'a;

/// Rays leaving a hit at grazing angles (0.001° to 5° above the tangent
/// plane) on convex shapes — sphere, rect, plane and a box mesh — placed
/// 0.1 to 1000 units from the origin must not hit their own surface again.
#[test]
fn grazing_bounce_rays_do_not_re_hit_their_own_surface() {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets");
    let block = assets.join("tall_block.obj");
    // Each shape, moved to `b` by its last transform step.
    let shapes: [(&str, &Placed<'_>); 4] = [
        ("sphere", &|b| {
            format!("Sphere(center: (0, 0, 0), radius: 0.7, material: \"m\", transform: [Translate({b})])")
        }),
        ("rect", &|b| {
            format!(
                "Rect(center: (0, 0, 0), half_u: (0.9, 0.1, 0), half_v: (0, 0.2, 0.6), material: \"m\", transform: [Translate({b})])"
            )
        }),
        ("plane", &|b| {
            format!(
                "Plane(point: (0, 0, 0), normal: (0.2, 1, 0.1), material: \"m\", transform: [Translate({b})])"
            )
        }),
        ("box mesh", &|b| {
            format!(
                "Mesh(file: {:?}, material: \"m\", transform: [Translate((0, 0.4, 0.35)), Translate({b})])",
                block.display()
            )
        }),
    ];
    let mut failures = Vec::new();
    for dist in DISTANCES {
        let b = base(dist);
        for (name, object) in &shapes {
            let text = format!(
                r#"Scene(
                camera: (eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 30),
                materials: {{ "m": Lambert(albedo: (0.5, 0.5, 0.5)) }},
                lights: [Point(position: (0, 5, 0), intensity: (1, 1, 1))],
                objects: [{}],
            )"#,
                object(&v(b))
            );
            let s = match load_str(Path::new("grazing.ron"), &text, &Overrides::default()) {
                Ok(l) => l.scene,
                Err(e) => panic!("{name}: {e}\n{text}"),
            };
            let centre = Vec3A::new(b.x as f32, b.y as f32, b.z as f32);
            let mut rng = Pcg32::new(7, dist as u64);
            let mut hits = 0;
            for case in 0..1000 {
                let u = |r: &mut Pcg32| r.next_f32() * 2.0 - 1.0;
                let from =
                    centre + Vec3A::new(u(&mut rng), u(&mut rng), u(&mut rng)).normalize_or(Vec3A::Y) * 3.0;
                let to = centre + 0.3 * Vec3A::new(u(&mut rng), u(&mut rng), u(&mut rng));
                let Some(hit) = s.intersect(&Ray::new(from, (to - from).normalize()), f32::INFINITY) else {
                    continue;
                };
                hits += 1;
                // The side the ray came from, and a tangent on it.
                let n = if hit.ng.dot(from - hit.p) > 0.0 {
                    hit.ng
                } else {
                    -hit.ng
                };
                let t = n.any_orthonormal_vector();
                let t = (t * rng.next_f32().mul_add(2.0, -1.0) + n.cross(t)).normalize();
                let degrees = [0.001f32, 0.01, 0.1, 1.0, 5.0][case % 5];
                let a = degrees.to_radians();
                let w = (t * a.cos() + n * a.sin()).normalize();
                let ray = ronray::integrators::spawn(&hit, w);
                if let Some(again) = s.intersect(&ray, f32::INFINITY) {
                    failures.push(format!(
                        "{name} at {dist} from the origin, {degrees}° above the surface: re-hit at t = {}",
                        again.t
                    ));
                }
            }
            assert!(
                hits > 100,
                "{name} at {dist}: only {hits} of 1000 set-up rays hit"
            );
        }
    }
    assert!(
        failures.is_empty(),
        "{} re-hits:\n{}",
        failures.len(),
        failures[..failures.len().min(20)].join("\n")
    );
}
