//! Every area light and the environment against closed forms: the
//! estimate of irradiance (or of ∫ L dω) from `sample` matches the exact
//! value, and the density `sample` reports is the one `pdf` gives for the
//! same direction (what MIS relies on).

use super::*;
use crate::geometry::{Geometry, Hit, NO_LIGHT};
use crate::math::Pcg32;
use crate::math::sampling::{UNIFORM_SPHERE_PDF, uniform_sphere};
use std::f32::consts::PI;

/// The hit record a ray along `ls.wi` would make on the light's surface.
fn hit_of(ls: &LightSample) -> Hit {
    Hit {
        t: ls.dist,
        p: ls.p,
        p_error: 0.0,
        ng: ls.n,
        ns: ls.n,
        uv: Vec2::ZERO,
        material: 0,
        light: NO_LIGHT,
        color: Vec3A::ONE,
    }
}

/// Irradiance at `p` (normal `n`) estimated from `n_samples` light samples,
/// checking on the way that each sample's pdf is `Light::pdf`'s.
pub(super) fn irradiance(light: &Light, p: Vec3A, n: Vec3A, n_samples: u32) -> f64 {
    let geo = Geometry::default();
    let mut rng = Pcg32::new(11, 3);
    let mut sum = 0.0f64;
    for _ in 0..n_samples {
        let Some(ls) = light.sample(p, Vec3A::ZERO, rng.next_vec2(), Draw::Independent, &geo) else {
            continue;
        };
        assert!(ls.pdf > 0.0 && ls.pdf.is_finite(), "pdf {}", ls.pdf);
        assert!((ls.wi.length() - 1.0).abs() < 1e-4);
        let again = light.pdf(p, ls.wi, &hit_of(&ls));
        assert!(
            (again - ls.pdf).abs() <= 2e-3 * ls.pdf,
            "sample pdf {} vs pdf() {again}",
            ls.pdf
        );
        sum += (ls.li.x * ls.wi.dot(n).max(0.0) / ls.pdf) as f64;
    }
    sum / n_samples as f64
}

#[test]
fn sphere_light_irradiance_is_point_like() {
    // A uniform sphere fully above the horizon lights like a point of intensity
    // L·πr²: E = π L r² cos θ / d².
    let light = Light::Sphere(SphereLight {
        texture: None,
        mitsuba_uv: false,
        center: Vec3A::new(0.3, 2.0, -0.2),
        radius: 0.5,
        radiance: Rgb::splat(3.0),
        two_sided: false,
    });
    for p in [Vec3A::ZERO, Vec3A::new(1.5, 0.0, 0.4)] {
        let to_c = Vec3A::new(0.3, 2.0, -0.2) - p;
        let d2 = to_c.length_squared();
        let want = PI * 3.0 * 0.25 * (to_c.y / d2.sqrt()) / d2;
        let got = irradiance(&light, p, Vec3A::Y, 200_000);
        assert!(
            ((got - want as f64) / want as f64).abs() < 0.01,
            "at {p}: {got} vs {want}"
        );
    }
    // Far away, the cone is tiny (the series branch).
    let far = Light::Sphere(SphereLight {
        texture: None,
        mitsuba_uv: false,
        center: Vec3A::new(0.0, 100.0, 0.0),
        radius: 0.5,
        radiance: Rgb::ONE,
        two_sided: false,
    });
    let want = PI * 0.25 / 10_000.0;
    let got = irradiance(&far, Vec3A::ZERO, Vec3A::Y, 20_000);
    assert!(
        ((got - want as f64) / want as f64).abs() < 0.01,
        "far: {got} vs {want}"
    );
}

#[test]
fn two_sided_sphere_lights_its_inside() {
    // Inside a two-sided sphere of radiance L, every direction sees L: E = π L.
    let light = Light::Sphere(SphereLight {
        texture: None,
        mitsuba_uv: false,
        center: Vec3A::ZERO,
        radius: 2.0,
        radiance: Rgb::splat(0.5),
        two_sided: true,
    });
    let got = irradiance(&light, Vec3A::new(0.4, -0.3, 0.2), Vec3A::Y, 200_000);
    assert!((got - 0.5 * PI as f64).abs() < 0.01 * PI as f64, "{got}");
    let one_sided = Light::Sphere(SphereLight {
        texture: None,
        mitsuba_uv: false,
        two_sided: false,
        center: Vec3A::ZERO,
        radius: 2.0,
        radiance: Rgb::ONE,
    });
    assert!(
        one_sided
            .sample(
                Vec3A::ZERO,
                Vec3A::ZERO,
                Vec2::splat(0.5),
                Draw::Independent,
                &Geometry::default()
            )
            .is_none()
    );
}

/// Lambert's polygon formula, E = L/2 Σ βᵢ n·γᵢ.
pub(super) fn polygon_irradiance(x: Vec3A, n: Vec3A, verts: &[Vec3A], l: f32) -> f32 {
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
fn mesh_light_irradiance_matches_polygon_formula() {
    // Two triangles of very different areas facing down, and a back-facing one
    // that must not light the point below.
    let (a, b, c, d) = (
        Vec3A::new(-1.0, 2.0, -1.0),
        Vec3A::new(1.0, 2.0, -1.0),
        Vec3A::new(1.0, 2.0, 1.0),
        Vec3A::new(-0.8, 2.0, 1.0),
    );
    let tris = vec![[a, b, c], [a, c, d]];
    // Counter-clockwise seen from below: (b − a) × (c − a) points down.
    assert!((b - a).cross(c - a).y < 0.0);
    let light = Light::Mesh(MeshLight::new(tris, Rgb::splat(2.0), false).expect("area"));
    for p in [Vec3A::ZERO, Vec3A::new(0.7, 0.5, -0.3)] {
        let want = polygon_irradiance(p, Vec3A::Y, &[a, b, c, d], 2.0);
        let got = irradiance(&light, p, Vec3A::Y, 200_000);
        assert!(
            ((got - want as f64) / want as f64).abs() < 0.01,
            "at {p}: {got} vs {want}"
        );
    }
    assert_eq!(
        irradiance(&light, Vec3A::new(0.0, 3.0, 0.0), Vec3A::NEG_Y, 1000),
        0.0
    );
    assert!((light.power().x - PI * 2.0 * 3.8).abs() < 1e-3, "Φ = π A L");
}

#[test]
fn two_sided_quad_emits_and_is_sampled_from_behind() {
    let mut q = QuadLight::new(Vec3A::new(-0.5, 1.0, -0.5), Vec3A::Z, Vec3A::X, Rgb::ONE);
    // u × v = z × x = +y: the front faces up, the point below sees the back.
    assert!(q.n.y > 0.0);
    let below = Vec3A::ZERO;
    assert_eq!(irradiance(&Light::Quad(q.clone()), below, Vec3A::Y, 100), 0.0);
    q.two_sided = true;
    let verts = [
        Vec3A::new(-0.5, 1.0, -0.5),
        Vec3A::new(-0.5, 1.0, 0.5),
        Vec3A::new(0.5, 1.0, 0.5),
        Vec3A::new(0.5, 1.0, -0.5),
    ];
    let want = polygon_irradiance(below, Vec3A::Y, &verts, 1.0);
    let got = irradiance(&Light::Quad(q.clone()), below, Vec3A::Y, 100_000);
    assert!(
        ((got - want as f64) / want as f64).abs() < 0.01,
        "{got} vs {want}"
    );
    assert!((q.power().x - 2.0 * PI).abs() < 1e-5, "Φ = 2π A L two-sided");
}

/// The Cornell light: a 0.46 × 0.38 rectangle just below the ceiling, facing down.
fn cornell_light() -> QuadLight {
    QuadLight::new(
        Vec3A::new(-0.23, 0.99, -0.19),
        Vec3A::new(0.46, 0.0, 0.0),
        Vec3A::new(0.0, 0.0, 0.38),
        Rgb::ONE,
    )
    .flipped_if_up()
}

impl QuadLight {
    /// The same light with its emitting side down (u and v swapped if needed).
    fn flipped_if_up(self) -> Self {
        if self.n.y > 0.0 {
            QuadLight::new(self.corner, self.v, self.u, self.radiance)
        } else {
            self
        }
    }
}

#[test]
fn rect_light_irradiance_matches_polygon_formula_near_and_far() {
    // From the floor (solid-angle sampling), from just below the ceiling
    // beside the light (near-grazing: large d²/cos spread), and from far away
    // (tiny solid angle: the area fallback).
    let q = cornell_light();
    assert!(q.n.y < 0.0);
    let verts = [q.corner, q.corner + q.u, q.corner + q.u + q.v, q.corner + q.v];
    for (p, n) in [
        (Vec3A::new(0.2, -1.0, 0.3), Vec3A::Y),
        (Vec3A::new(0.35, 0.95, -0.1), Vec3A::NEG_X),
        (Vec3A::new(0.1, 0.7, 0.05), Vec3A::Y),
        (Vec3A::new(0.0, -60.0, 0.0), Vec3A::Y),
    ] {
        let want = polygon_irradiance(p, n, &verts, 1.0);
        let got = irradiance(&Light::Quad(q.clone()), p, n, 100_000);
        assert!(
            ((got - want as f64) / want as f64).abs() < 0.01,
            "at {p}: {got} vs {want}"
        );
    }
}

#[test]
fn rect_light_sampling_has_lower_variance_than_area_sampling() {
    // Beside the light, just below the ceiling, area sampling's d²/cos θl
    // varies over orders of magnitude; by solid angle only the receiver's
    // cosine is left. A skewed parallelogram of nearly the same shape is
    // sampled by area: compare the per-sample spread of the two estimates.
    let rect = cornell_light();
    let area_only = QuadLight::new(rect.corner, rect.u, rect.v + 1e-3 * rect.u, Rgb::ONE);
    let (p, n) = (Vec3A::new(0.3, 0.97, 0.0), Vec3A::NEG_X);
    let spread = |q: QuadLight| {
        let (mut rng, mut s, mut s2) = (Pcg32::new(3, 1), 0.0f64, 0.0f64);
        let m = 20_000;
        for _ in 0..m {
            let e = q
                .sample(p, rng.next_vec2())
                .map_or(0.0, |ls| (ls.wi.dot(n).max(0.0) / ls.pdf) as f64);
            s += e;
            s2 += e * e;
        }
        let mean = s / m as f64;
        (s2 / m as f64 - mean * mean).sqrt() / mean
    };
    let (by_angle, by_area) = (spread(rect), spread(area_only));
    assert!(
        by_angle < 0.5 * by_area,
        "relative std dev {by_angle} by solid angle vs {by_area} by area"
    );
}

#[test]
fn rect_light_pdf_integrates_to_one() {
    // ∫ pdf dω over the rectangle's solid angle = 1, estimated by hand-made
    // uniform points on the rectangle (density d²/(cos θl A) in solid angle),
    // from points where each branch (solid angle, area fallback) is taken.
    let q = cornell_light();
    let mut rng = Pcg32::new(21, 4);
    for p in [
        Vec3A::new(0.1, -0.9, 0.2),
        Vec3A::new(0.3, 0.9, 0.1),
        Vec3A::new(3.0, -80.0, 1.0),
    ] {
        let m = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..m {
            let u = rng.next_vec2();
            let d = q.corner + u.x * q.u + u.y * q.v - p;
            let (dist, w) = (d.length(), d.normalize());
            let area_pdf = dist * dist / (-w.dot(q.n) * q.area);
            sum += (q.pdf(p, w, dist) / area_pdf) as f64;
        }
        let got = sum / m as f64;
        assert!((got - 1.0).abs() < 0.01, "from {p}: ∫ pdf dω = {got}");
    }
}

/// A 16 × 8 map: a dim gradient and one bright pixel, off-centre.
fn test_map() -> EnvMap {
    let (w, h) = (16u32, 8u32);
    let mut rgb = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let v = if (i, j) == (11, 2) {
                40.0
            } else {
                0.1 + 0.05 * (i + j) as f32
            };
            rgb.extend_from_slice(&[v, 0.5 * v, 0.25 * v]);
        }
    }
    EnvMap::from_rgb(w, h, &rgb)
}

#[test]
fn environment_mapping_follows_the_reference_convention() {
    // A map whose pixel (i, j) is (i, j, 0): the bilinear lookup at a pixel
    // returns it, so directions decode to pixel coordinates. Columns sit at
    // (i + ½)/W, rows at j/(H − 1) (row 0 the zenith), as Mitsuba 3.9.1's
    // `envmap` evaluates them.
    let (w, h) = (8u32, 4u32);
    let rgb = (0..h)
        .flat_map(|j| (0..w).flat_map(move |i| [i as f32, j as f32, 0.0]))
        .collect::<Vec<f32>>();
    let env = EnvironmentLight::from_map(EnvMap::from_rgb(w, h, &rgb), 1.0, 0.0);
    let centre = |i: f32, j: f32| {
        let (u, v) = ((i + 0.5) / w as f32, j / (h - 1) as f32);
        let (st, ct) = (PI * v).sin_cos();
        let (sp, cp) = (2.0 * PI * u).sin_cos();
        Vec3A::new(st * sp, ct, -st * cp)
    };
    for (i, j) in [(0.0, 0.5), (3.0, 1.0), (6.0, 2.9), (2.0, 2.5)] {
        let got = env.le(centre(i, j));
        assert!(
            (got - Vec3A::new(i, j, 0.0)).length() < 1e-3,
            "pixel ({i}, {j}): {got}"
        );
    }
    // Values Mitsuba 3.9.1's `envmap` returns for this map (probed through its
    // Python API), across the seam and between rows.
    let dir = |u: f32, v: f32| {
        let (st, ct) = (PI * v).sin_cos();
        let (sp, cp) = (2.0 * PI * u).sin_cos();
        Vec3A::new(st * sp, ct, -st * cp)
    };
    for (u, v, mitsuba) in [
        (0.01, 0.4, [3.94, 2.2]),
        (0.99, 0.4, [5.06, 2.2]),
        (0.3, 0.4, [2.9, 2.2]),
    ] {
        let got = env.le(dir(u, v)) + Vec3A::new(1.0, 1.0, 0.0);
        assert!(
            (got.x - mitsuba[0]).abs() < 1e-3 && (got.y - mitsuba[1]).abs() < 1e-3,
            "at ({u}, {v}): {got} vs Mitsuba's {mitsuba:?}"
        );
    }
    // u = 0.5 looks along +z, 0.25 along +x, 0.75 along −x; v = 0 is up.
    let u_of = |d: Vec3A| env.le(d).x / w as f32 + 0.5 / w as f32;
    assert!((u_of(Vec3A::Z) - 0.5).abs() < 1e-3 && (u_of(Vec3A::X) - 0.25).abs() < 1e-3);
    assert!((u_of(Vec3A::NEG_X) - 0.75).abs() < 1e-3);
    assert!(env.le(Vec3A::Y).y < 1e-3 && (env.le(Vec3A::NEG_Y).y - 3.0).abs() < 1e-3);
    // Turned by 90° about +y, what the map shows along +z appears along +x.
    let turned = EnvironmentLight::from_map(test_map(), 1.0, 90.0);
    let plain = EnvironmentLight::from_map(test_map(), 1.0, 0.0);
    let d = Vec3A::new(0.0, 0.3, 1.0).normalize();
    let d_turned = Vec3A::new(1.0, 0.3, 0.0).normalize();
    assert!((turned.le(d_turned) - plain.le(d)).length() < 1e-5);
}

#[test]
fn environment_sampling_integrates_the_map() {
    for rotation in [0.0, 37.0] {
        let env = EnvironmentLight::from_map(test_map(), 2.0, rotation);
        let light = Light::Environment(Box::new(env.clone()));
        let geo = Geometry::default();
        // Reference ∫ L dω by uniform sphere sampling, and the cached one.
        let mut rng = Pcg32::new(1, 2);
        let n = 400_000;
        let mut uniform = 0.0f64;
        let mut sampled = 0.0f64;
        for _ in 0..n {
            uniform += (env.le(uniform_sphere(rng.next_vec2())).x / UNIFORM_SPHERE_PDF) as f64;
            let ls = light
                .sample(Vec3A::ZERO, Vec3A::ZERO, rng.next_vec2(), Draw::Independent, &geo)
                .expect("a direction");
            assert!(ls.dist.is_infinite() && ls.pdf > 0.0);
            let again = env.pdf(ls.wi, Vec3A::ZERO);
            assert!((again - ls.pdf).abs() <= 2e-3 * ls.pdf, "{} vs {again}", ls.pdf);
            assert!((ls.li - env.le(ls.wi)).length() <= 1e-3 * ls.li.length() + 1e-6);
            sampled += (ls.li.x / ls.pdf) as f64;
        }
        let (uniform, sampled) = (uniform / n as f64, sampled / n as f64);
        let cached = (env.power().x / (PI * env.scene_radius * env.scene_radius)) as f64;
        assert!(
            (sampled - uniform).abs() < 0.01 * uniform,
            "importance {sampled} vs uniform {uniform}"
        );
        assert!(
            (cached - uniform).abs() < 0.01 * uniform,
            "power {cached} vs {uniform}"
        );
    }
}

#[test]
fn environment_pdf_integrates_to_one() {
    let env = EnvironmentLight::from_map(test_map(), 1.0, 0.0);
    let mut rng = Pcg32::new(4, 4);
    let n = 400_000;
    let sum: f64 = (0..n)
        .map(|_| (env.pdf(uniform_sphere(rng.next_vec2()), Vec3A::ZERO) / UNIFORM_SPHERE_PDF) as f64)
        .sum();
    assert!(
        (sum / n as f64 - 1.0).abs() < 0.01,
        "∫ pdf dω = {}",
        sum / n as f64
    );
}

#[test]
fn constant_environment_power_and_uniform_mode() {
    let mut env = EnvironmentLight::constant(Rgb::splat(0.5));
    env.scene_radius = 2.0;
    assert!(
        (env.power().x - PI * 4.0 * 4.0 * PI * 0.5).abs() < 1e-3,
        "π R² · 4π L"
    );
    let mut map = EnvironmentLight::from_map(test_map(), 1.0, 0.0);
    map.sampling = EnvSampling::Uniform;
    assert_eq!(map.pdf(Vec3A::Y, Vec3A::ZERO), UNIFORM_SPHERE_PDF);
}

/// A constant sky seen from a surface is sampled by the cosine about its
/// normal: the density integrates to one over the sphere, matches what
/// `sample` returns, is zero below the surface, and an unoccluded Lambert
/// surface's irradiance estimate `L cos / pdf` is exactly `π L` per sample.
#[test]
fn constant_environment_from_a_surface_samples_the_cosine() {
    let env = EnvironmentLight::constant(Rgb::splat(0.5));
    let geo = Geometry::default();
    let light = Light::Environment(Box::new(env.clone()));
    let mut rng = Pcg32::new(6, 2);
    for _ in 0..50 {
        let n = uniform_sphere(rng.next_vec2());
        let m = 20_000;
        let integral: f64 = (0..m)
            .map(|_| (env.pdf(uniform_sphere(rng.next_vec2()), n) / UNIFORM_SPHERE_PDF) as f64)
            .sum::<f64>()
            / m as f64;
        assert!((integral - 1.0).abs() < 0.03, "∫ pdf dω = {integral} for n {n}");
        for _ in 0..100 {
            let Some(ls) = light.sample(Vec3A::ZERO, n, rng.next_vec2(), Draw::Independent, &geo) else {
                continue;
            };
            let cos = ls.wi.dot(n);
            assert!(cos > 0.0, "a direction below the surface");
            assert!((env.pdf(ls.wi, n) - ls.pdf).abs() <= 1e-4 * ls.pdf.max(1.0));
            assert!((ls.li.x * cos / ls.pdf - PI * 0.5).abs() < 1e-3);
            assert_eq!(env.le_and_pdf(ls.wi, n), (env.le(ls.wi), env.pdf(ls.wi, n)));
        }
        assert_eq!(env.pdf(-n, n), 0.0);
    }
}

#[test]
fn environment_le_and_pdf_are_le_and_pdf_bit_for_bit() {
    let mut rng = Pcg32::new(8, 1);
    for rotation in [0.0, 37.0] {
        for sampling in [EnvSampling::Importance, EnvSampling::Uniform] {
            let mut env = EnvironmentLight::from_map(test_map(), 1.5, rotation);
            env.sampling = sampling;
            let mut constant = EnvironmentLight::constant(Rgb::new(0.2, 0.3, 0.4));
            constant.sampling = sampling;
            for _ in 0..20_000 {
                let d = uniform_sphere(rng.next_vec2());
                for e in [&env, &constant] {
                    for n in [Vec3A::ZERO, Vec3A::Y] {
                        let (le, pdf) = e.le_and_pdf(d, n);
                        assert_eq!(le, e.le(d), "le along {d}");
                        assert_eq!(pdf.to_bits(), e.pdf(d, n).to_bits(), "pdf along {d}");
                    }
                }
            }
            // The poles, where sin θ = 0.
            for d in [Vec3A::Y, -Vec3A::Y] {
                assert_eq!(
                    env.le_and_pdf(d, Vec3A::ZERO),
                    (env.le(d), env.pdf(d, Vec3A::ZERO))
                );
            }
        }
    }
}

/// Irradiance at `p` (normal `n`) from `light` by brute force: uniform
/// directions over the sphere, each traced against `shape` and weighted by
/// what the light emits at the hit.
fn irradiance_by_tracing(
    light: &Light,
    shape: &crate::geometry::Shape,
    p: Vec3A,
    n: Vec3A,
    count: u32,
) -> f64 {
    let geo = Geometry::default();
    let mut rng = Pcg32::new(5, 9);
    let mut sum = 0.0f64;
    for _ in 0..count {
        let w = uniform_sphere(rng.next_vec2());
        let ray = crate::math::Ray::new(p, w);
        let Some(t) = shape.intersect_t(&ray, f32::INFINITY, &geo) else {
            continue;
        };
        let hit = shape.hit(&ray, t, &geo);
        sum += (light.emitted(&hit, -w).x * w.dot(n).max(0.0) / UNIFORM_SPHERE_PDF) as f64;
    }
    sum / count as f64
}

#[test]
fn textured_emitters_sample_what_they_emit() {
    use crate::geometry::{Quad, Shape, Sphere};
    use crate::materials::texture::{Tex, UvTransform};
    let checker = Emission::new(
        &Tex::Checker {
            a: Rgb::splat(3.0),
            b: Rgb::splat(0.2),
            scale: 3.0,
            uv: UvTransform::default(),
        },
        &[],
    );
    let p = Vec3A::new(0.1, 0.0, 0.2);
    let n = Vec3A::new(0.3, 1.0, -0.2).normalize();
    let mut cases = Vec::new();
    for mitsuba_uv in [false, true] {
        let (center, radius) = (Vec3A::new(0.2, 1.2, -0.1), 0.6);
        let mut l = SphereLight::new(center, radius, Rgb::ZERO).with_emission(checker.clone());
        l.mitsuba_uv = mitsuba_uv;
        let s = Sphere {
            center,
            radius,
            material: 0,
            light: 0,
            mitsuba_uv,
        };
        cases.push((
            format!("sphere (Mitsuba UVs {mitsuba_uv})"),
            Light::Sphere(l),
            Shape::Sphere(s),
        ));
    }
    // Near: solid-angle sampling of the rectangle; far: by area.
    for (name, y) in [("near quad", 0.6), ("far quad", 3.0)] {
        let (c, u, v) = (
            Vec3A::new(-0.6, y, -0.5),
            Vec3A::new(1.2, 0.0, 0.0),
            Vec3A::new(0.0, 0.0, 1.3),
        );
        let q = QuadLight::new(c, u, v, Rgb::ZERO).with_emission(checker.clone());
        cases.push((
            name.to_string(),
            Light::Quad(q),
            Shape::Quad(Quad::new(c, u, v, 0, 0)),
        ));
    }
    for (name, light, shape) in cases {
        let sampled = irradiance(&light, p, n, 200_000);
        let traced = irradiance_by_tracing(&light, &shape, p, n, 2_000_000);
        assert!(
            ((sampled - traced) / traced).abs() < 0.02,
            "{name}: sampled {sampled:.4}, traced {traced:.4}"
        );
    }
}

/// A rectangle written as two triangles (as an OBJ lamp is) becomes one
/// quad light that lights a point exactly as the triangles did; shapes that
/// are not one parallelogram stay triangles.
#[test]
fn a_rectangle_of_two_triangles_becomes_a_quad_light() {
    let (a, b, c, d) = (
        Vec3A::new(-0.5, 2.0, -0.4),
        Vec3A::new(0.5, 2.0, -0.4),
        Vec3A::new(0.5, 2.0, 0.4),
        Vec3A::new(-0.5, 2.0, 0.4),
    );
    // Counter-clockwise seen from below: (b − a) × (c − a) points down.
    let mesh = MeshLight::new(vec![[a, b, c], [a, c, d]], Rgb::splat(2.0), false).expect("area");
    let quad = mesh.as_parallelogram().expect("a rectangle");
    assert!((quad.area - mesh.area()).abs() < 1e-6);
    assert!(quad.n.dot(Vec3A::NEG_Y) > 0.999_999, "emits downward: {}", quad.n);
    assert!(!quad.two_sided);
    assert_eq!(mesh.power(), Light::Quad(quad.clone()).power());
    let quad = Light::Quad(quad);
    for p in [Vec3A::ZERO, Vec3A::new(0.7, 0.5, -0.3), Vec3A::new(0.1, 1.8, 0.0)] {
        let want = polygon_irradiance(p, Vec3A::Y, &[a, b, c, d], 2.0);
        let got = irradiance(&quad, p, Vec3A::Y, 200_000);
        assert!(
            ((got - want as f64) / want as f64).abs() < 0.01,
            "at {p}: {got} vs {want}"
        );
    }
    // Seen from above (the back), nothing.
    assert_eq!(
        irradiance(&quad, Vec3A::new(0.0, 3.0, 0.0), Vec3A::NEG_Y, 1000),
        0.0
    );
    // Either diagonal, and the triangles listed in either order.
    for tris in [vec![[a, b, d], [b, c, d]], vec![[c, d, a], [a, b, c]]] {
        let q = MeshLight::new(tris, Rgb::ONE, true)
            .expect("area")
            .as_parallelogram();
        let q = q.expect("a rectangle");
        assert!((q.area - 0.8).abs() < 1e-6 && q.two_sided);
    }
    // Not one parallelogram: a kite, triangles wound apart, three triangles,
    // two triangles without a shared edge.
    let kite = Vec3A::new(-0.8, 2.0, 0.4);
    let not = [
        vec![[a, b, c], [a, c, kite]],
        vec![[a, b, c], [a, d, c]],
        vec![[a, b, c], [a, c, d], [a, c, d]],
        vec![
            [a, b, c],
            [a + Vec3A::X * 3.0, b + Vec3A::X * 3.0, c + Vec3A::X * 3.0],
        ],
    ];
    for tris in not {
        let m = MeshLight::new(tris.clone(), Rgb::ONE, false).expect("area");
        assert!(m.as_parallelogram().is_none(), "{tris:?}");
    }
}
