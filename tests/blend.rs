//! `Blend` materials: the mix in expectation (against closed forms, with
//! interreflection, so that a choice shared between a path's bounces would
//! show), each end of the weight exactly its material in every integrator,
//! and the located errors.

use crate::common;

use common::{furnace, load_text, mean_li, root};
use glam::Vec3A;
use ronray::frame::render_whole;
use ronray::imageio::Image;
use ronray::integrators::Counters;
use ronray::load::Loaded;
use ronray::load::{LoadError, Overrides, load_str};
use ronray::math::Ray;
use ronray::math::SampleRng;
use ronray::sampler::Sampler;
use std::f32::consts::PI;

/// Uniform numbers in [0, 1) from a xorshift generator seeded `state`.
fn xorshift(mut state: u64) -> impl FnMut() -> f32 {
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// [`mean_li`] over `n` rays from `from` within `spread` (radians, about)
/// of `d`: a blend picks by a hash of the ray and the hit, as a cut-out
/// does, so one ray repeated always picks the same material at its first
/// hit (a render's camera rays differ from sample to sample).
fn mean_li_around(l: &Loaded, from: Vec3A, d: Vec3A, spread: f32, n: u32) -> Vec3A {
    let mut sum = Vec3A::ZERO;
    let mut uniform = xorshift(0x2545_f491_4f6c_dd1d);
    let mut next = || uniform() - 0.5;
    let mut c = Counters::default();
    for i in 0..n {
        let jitter = Vec3A::new(next(), next(), next()) * spread;
        let ray = Ray::new(from, (d.normalize() + jitter).normalize());
        let mut sampler = Sampler::independent(SampleRng::for_sample(0, 0, i, 99));
        sum += l.view.integrator.li(&l.scene, &ray, &mut sampler, &mut c);
    }
    sum / n as f32
}

/// A blend of albedos 0.2 and 0.8 at weight 0.25 reflects as albedo 0.35:
/// radiance 1/(1 − 0.35) ≈ 1.538 in the furnace. Had a path kept one
/// choice for all its bounces the mean would be 0.75/0.8 + 0.25/0.2 ≈ 2.19;
/// had the pick ignored the weight (half and half), 1/(1 − 0.5) = 2. Nested
/// blends and wrappers around the blend give the same mix.
#[test]
fn a_blend_in_a_furnace_reflects_the_mixed_albedo() {
    let cases = [
        (
            "Blend(weight: 0.25, a: Lambert(albedo: 0.2), b: Lambert(albedo: 0.8))",
            0.35,
        ),
        // 0.5 × (0.5 × 0.2 + 0.5 × 0.8) + 0.5 × 0.6 = 0.55.
        (
            "Blend(weight: 0.5, a: Blend(weight: 0.5, a: Lambert(albedo: 0.2), b: Lambert(albedo: 0.8)), \
             b: Lambert(albedo: 0.6))",
            0.55,
        ),
        // A flat normal map around the blend changes nothing.
        (
            "NormalMap(map: (0.5, 0.5, 1), material: Blend(weight: 0.75, a: Lambert(albedo: 0.2), \
             b: Lambert(albedo: 0.8)))",
            0.65,
        ),
    ];
    for (material, rho) in cases {
        let s = load_text(&furnace(material));
        let want = 1.0 / (1.0 - rho);
        for d in [Vec3A::new(0.1, 0.2, -1.0), Vec3A::new(0.9, -0.7, 0.2)] {
            let got = mean_li_around(&s, Vec3A::new(0.1, 0.0, 0.2), d, 0.2, 100_000);
            assert!(
                (got.x - want).abs() < 0.015 * want,
                "{material}: expected 1/(1 − {rho}) = {want}, got {}",
                got.x
            );
        }
    }
}

/// A generated family: random blend trees (a blend at the top, up to three
/// levels, random weights, albedos in [0.05, 0.85], some under a flat
/// normal map) in the furnace, each against 1/(1 − ρ) with ρ the tree's
/// mixed albedo.
#[test]
fn random_blend_trees_in_a_furnace_reflect_their_mixed_albedo() {
    let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
    // A tree as RON and its mixed albedo.
    fn tree(depth: u32, next: &mut dyn FnMut() -> f32) -> (String, f32) {
        if depth == 0 || (depth < 3 && next() < 0.3) {
            let rho = 0.05 + 0.8 * next();
            return (format!("Lambert(albedo: {rho})"), rho);
        }
        let w = (next() * 100.0).round() / 100.0;
        let (a, ra) = tree(depth - 1, next);
        let (b, rb) = tree(depth - 1, next);
        let blend = format!("Blend(weight: {w}, a: {a}, b: {b})");
        let wrapped = if next() < 0.3 {
            format!("NormalMap(map: (0.5, 0.5, 1), material: {blend})")
        } else {
            blend
        };
        (wrapped, (1.0 - w) * ra + w * rb)
    }
    for _ in 0..6 {
        let (material, rho) = tree(3, &mut next);
        let s = load_text(&furnace(&material));
        let want = 1.0 / (1.0 - rho);
        let got = mean_li_around(
            &s,
            Vec3A::new(0.1, 0.0, 0.2),
            Vec3A::new(0.3, 0.2, -1.0),
            0.3,
            60_000,
        );
        assert!(
            (got.x - want).abs() < 0.02 * want,
            "{material}: expected 1/(1 − {rho}) = {want}, got {}",
            got.x
        );
    }
}

/// A textured weight picks per point: a floor under a sun, blended by a
/// checker between albedos 0.2 (weight 0) and 0.8 (weight 1), is ρE/π with
/// the square's own ρ, and 0.5 × (0.2 + 0.8)·E/π where a second checker
/// makes the weight a half.
#[test]
fn a_textured_weight_picks_per_point() {
    let text = |weight: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 2),
            materials: {{ "floor": Blend(weight: {weight}, a: Lambert(albedo: 0.2), b: Lambert(albedo: 0.8)) }},
            lights: [Directional(direction: (0, -1, 0), irradiance: (1, 1, 1))],
            objects: [Rect(center: (0, 0, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "floor")],
        )"#
        )
    };
    // The rect's uv: (0, 0) at (−1, 0, 1), u along +x, v along −z; a 2 × 2
    // checker has `a` on the squares at uv (¼, ¼) and (¾, ¾).
    let from = Vec3A::new(0.0, 1.0, 3.0);
    let toward = |x: f32, z: f32| Vec3A::new(x, 0.0, z) - from;
    let (on_a, on_b) = (toward(-0.5, 0.5), toward(0.5, 0.5));
    // Within a square: ±0.05 rad is ±0.15 at the floor, 3 away.
    let s = load_text(&text("Checker(a: 0, b: 1, scale: 2)"));
    for (d, rho) in [(on_a, 0.2), (on_b, 0.8)] {
        let got = mean_li_around(&s, from, d, 0.05, 2_000).x;
        let want = rho / PI;
        assert!(
            (got - want).abs() < 1e-4,
            "weight from the checker: {got}, expected {want}"
        );
    }
    let half = load_text(&text("Checker(a: 0.5, b: 0.5, scale: 2)"));
    let got = mean_li_around(&half, from, on_a, 0.05, 40_000).x;
    let want = 0.5 / PI;
    assert!(
        (got - want).abs() < 0.02 * want,
        "weight ½: {got}, expected {want}"
    );
}

/// Renders `text` (as if it were a file in `scenes/`) at 32², 4 spp.
fn render(text: &str) -> Image {
    let o = Overrides {
        spp: Some(4),
        size: Some((32, 32)),
        seed: Some(7),
        ..Default::default()
    };
    let loaded = match load_str(&root().join("scenes/test.ron"), text, &o) {
        Ok(l) => l,
        Err(LoadError::Invalid(r)) => panic!("{}\n{text}", r.render(false)),
        Err(e) => panic!("{e}\n{text}"),
    };
    render_whole(&loaded.scene, &loaded.view, &Default::default()).0
}

fn bits(i: &Image) -> Vec<[u32; 3]> {
    i.pixels.iter().map(|p| p.to_array().map(f32::to_bits)).collect()
}

/// At weight 0 a blend is its `a` and at weight 1 its `b`, bit for bit, in
/// every integrator and with what the scene does around the surface:
/// cut-outs (shadow rays pass through them), normal maps, glass that the
/// caustic light tracer aims at, and a fog the volumetric path tracer
/// walks through.
#[test]
fn a_blend_at_either_end_is_exactly_that_material() {
    let glass = "Cutout(opacity: Checker(a: 1, b: 0.3, scale: 3), material: Glass(ior: 1.5))";
    let mapped = "NormalMap(map: Checker(a: (0.6, 0.5, 0.9), b: (0.4, 0.5, 0.9), scale: 4), \
                  material: RoughPlastic(diffuse: (0.7, 0.3, 0.2), roughness: 0.2))";
    let scene = |integrator: &str, ball: &str, extra: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 2, 4), target: (0, 0.5, 0), fov_y_degrees: 40),
            integrator: {integrator},
            materials: {{ "floor": Lambert(albedo: 0.6), "ball": {ball} }},
            lights: [
                Point(position: (1, 3, 1), intensity: (20, 20, 20)),
                Environment(radiance: (0.1, 0.1, 0.1)),
            ],
            objects: [
                Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: "floor"),
                Sphere(center: (0, 0.7, 0), radius: 0.7, material: "ball"),
            ],
            {extra}
        )"#
        )
    };
    let fog = "media: { \"fog\": Homogeneous(sigma_a: (0.05, 0.05, 0.05), sigma_s: (0.2, 0.2, 0.2)) }, medium: \"fog\",";
    let integrators = [
        ("Path(max_depth: 6)", ""),
        ("Path(max_depth: 6, caustics: LightTracing)", ""),
        ("Direct()", ""),
        ("Whitted(max_depth: 4)", ""),
        ("Path(max_depth: 6)", fog),
    ];
    for (integrator, extra) in integrators {
        for (a, b) in [(glass, mapped), (mapped, glass)] {
            let plain_a = render(&scene(integrator, a, extra));
            let plain_b = render(&scene(integrator, b, extra));
            for (weight, want, which) in [("0", &plain_a, "a"), ("1", &plain_b, "b")] {
                let blend = format!("Blend(weight: {weight}, a: {a}, b: {b})");
                let got = render(&scene(integrator, &blend, extra));
                assert!(
                    bits(&got) == bits(want),
                    "{integrator} {extra}: a blend at weight {weight} is not its `{which}` ({})",
                    if which == "a" { a } else { b }
                );
            }
        }
    }
}

fn error(material: &str) -> String {
    let text = format!(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 40),
        materials: {{ "m": {material} }},
        lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],
        objects: [Sphere(center: (0, 0, 0), radius: 1, material: "m")],
    )"#
    );
    match load_str(&root().join("scenes/test.ron"), &text, &Overrides::default()) {
        Ok(_) => panic!("loaded:\n{text}"),
        Err(LoadError::Invalid(r)) => r.render(false),
        Err(e) => panic!("not a located error: {e}"),
    }
}

/// A weight outside [0, 1], a component's own mistake, a cut-out inside a
/// cut-out through a blend, and blends nested past the limit are located
/// errors.
#[test]
fn wrong_blends_are_located_errors() {
    let e = error("Blend(weight: 1.5, a: Lambert(albedo: 0.5), b: Mirror())");
    assert!(
        e.contains("materials.m.weight") && e.contains("0 is all `a`"),
        "{e}"
    );
    let e = error("Blend(weight: 0.5, a: Lambert(albedo: 0.5), b: Lambert(albedo: 2))");
    assert!(e.contains("materials.m.b.albedo"), "{e}");
    let e = error(
        "Cutout(opacity: 0.5, material: Blend(weight: 0.5, a: Lambert(albedo: 0.5), \
         b: Cutout(opacity: 0.5, material: Mirror())))",
    );
    assert!(e.contains("a cut-out inside a cut-out"), "{e}");
    let mut deep = "Lambert(albedo: 0.5)".to_string();
    for _ in 0..17 {
        deep = format!("Blend(weight: 0.5, a: {deep}, b: Mirror())");
    }
    let e = error(&deep);
    assert!(e.contains("nested more than 16 deep"), "{e}");
    let mut sixteen = "Lambert(albedo: 0.5)".to_string();
    for _ in 0..16 {
        sixteen = format!("Blend(weight: 0.5, a: {sixteen}, b: Lambert(albedo: 0.5))");
    }
    let text = format!(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 40),
        materials: {{ "m": {sixteen} }},
        lights: [Point(position: (0, 2, 4), intensity: (1, 1, 1))],
        objects: [Sphere(center: (0, 0, 0), radius: 1, material: "m")],
    )"#
    );
    let l = load_text(&text);
    let ray = Ray::new(Vec3A::new(0.0, 1.0, 3.0), Vec3A::new(0.0, -1.0, -3.0).normalize());
    let li = mean_li(&l, ray, 100);
    assert!(li.is_finite() && li.x > 0.0, "sixteen deep renders: {li}");
}

/// The fuzz seed `fuzz/corpus/scene/blend.ron` (blends inside blends,
/// cut-outs on either side, glass, a mirror) with each of its numbers in
/// turn replaced by a hostile one: every variant loads or is refused, and
/// every one that loads renders finite pixels.
#[test]
fn hostile_numbers_in_blends_never_panic_and_render_finite() {
    let seed = std::fs::read_to_string(root().join("fuzz/corpus/scene/blend.ron")).expect("the fuzz seed");
    let l = load_text(&seed);
    assert!(
        l.scene.surfaces.iter().any(|s| s.blend.is_some()),
        "the seed has blends"
    );
    let (numbers, loaded, refused) = common::hostile_number_sweep(&seed, &common::root().join("scenes"));
    assert!(numbers > 40, "{numbers} numbers");
    assert!(loaded > 0 && refused > 0, "{loaded} loaded, {refused} refused");
}
