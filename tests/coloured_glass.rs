//! Coloured glass (`attenuation` on `Glass` and `RoughGlass`): Beer–Lambert
//! absorption inside the solid, against closed forms in every integrator
//! that crosses glass, against the same solid filled with an absorbing
//! medium (the media code, an independent estimator), light-traced
//! caustics against the path tracer's, and wrong values refused where
//! they are written.

use crate::common;

use common::{load_text as scene, mean_li, message};
use glam::Vec3A;
use ronray::load::{Overrides, load_str};
use ronray::math::Ray;

/// σ of `attenuation: (color: (0.5, 0.25, 1.0), distance: 1)`.
fn sigma() -> Vec3A {
    Vec3A::new(2f32.ln(), 4f32.ln(), 0.0)
}

/// exp(−σ·t) per channel.
fn beer(sigma: Vec3A, t: f32) -> Vec3A {
    Vec3A::new((-sigma.x * t).exp(), (-sigma.y * t).exp(), (-sigma.z * t).exp())
}

/// What [`sigma`]'s glass keeps over `t`.
fn kept(t: f32) -> Vec3A {
    beer(sigma(), t)
}

/// A unit ball of coloured glass of index `ior` at the origin under a white
/// sky, rendered by `integrator`; `extra` objects and `media` beside it.
fn ball(ior: f32, integrator: &str, extra: &str, media: &str) -> String {
    format!(
        r#"Scene(
        camera: (eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40),
        integrator: {integrator},
        {media}
        materials: {{
            "tea": Glass(ior: {ior}, attenuation: (color: (0.5, 0.25, 1.0), distance: 1)),
        }},
        lights: [Environment(radiance: (1, 1, 1))],
        objects: [Sphere(center: (0, 0, 0), radius: 1, material: "tea"), {extra}],
    )"#
    )
}

/// The integrators that follow a ray through glass: the path tracer, the
/// path tracer in a scene with a medium (its volumetric branch: a wisp of
/// fog in a ball far from the rays), and Whitted's specular chains.
fn integrators(ior: f32) -> Vec<(&'static str, String)> {
    let fog = r#"media: { "wisp": Homogeneous(sigma_t: (0.01, 0.01, 0.01), albedo: (0.5, 0.5, 0.5)) },"#;
    let far = r#"Sphere(center: (30, 30, -30), radius: 0.1, interior: "wisp")"#;
    vec![
        (
            "Path",
            ball(ior, "Path(max_depth: 64, caustics: PathOnly)", "", ""),
        ),
        ("Path with media", ball(ior, "Path(max_depth: 64)", far, fog)),
        ("Whitted", ball(ior, "Whitted(max_depth: 64)", "", "")),
    ]
}

fn assert_close(got: Vec3A, want: Vec3A, tol: f32, what: &str) {
    for c in 0..3 {
        assert!(
            (got[c] - want[c]).abs() <= tol * want[c].max(0.05),
            "{what}, channel {c}: {got} against {want}"
        );
    }
}

/// An index-matched ball (η = 1: no reflection, no bending) shows the sky
/// through exactly its chord: exp(−σ·2√(1 − b²)) at offset b from the centre.
#[test]
fn an_index_matched_ball_absorbs_along_its_chord_in_every_integrator() {
    for (name, text) in integrators(1.0) {
        let l = scene(&text);
        for b in [0.0f32, 0.5, 0.8, 0.95] {
            let ray = Ray::new(Vec3A::new(b, 0.0, 5.0), Vec3A::new(0.0, 0.0, -1.0));
            let want = kept(2.0 * (1.0 - b * b).sqrt());
            assert_close(mean_li(&l, ray, 64), want, 2e-3, &format!("{name}, offset {b}"));
        }
        // Beside the ball: the sky, untouched.
        let beside = Ray::new(Vec3A::new(1.5, 0.0, 5.0), Vec3A::new(0.0, 0.0, -1.0));
        assert_close(
            mean_li(&l, beside, 16),
            Vec3A::ONE,
            1e-4,
            &format!("{name}, beside"),
        );
    }
}

/// Through the centre of a glass ball (η 1.5, normal incidence, F = 0.04):
/// the front's reflection plus every path through: enter (1 − F), cross
/// (a = e^{−2σ}), leave (1 − F) or reflect back and forth (F·a each time):
/// F + (1 − F)²·a / (1 − F·a), the sky being 1 on both sides.
#[test]
fn a_glass_ball_sums_its_inner_reflections_each_absorbed() {
    let f = (0.5f32 / 2.5).powi(2);
    let a = kept(2.0);
    let want = Vec3A::splat(f) + (1.0 - f) * (1.0 - f) * a / (Vec3A::ONE - f * a);
    for (name, text) in integrators(1.5) {
        let got = mean_li(
            &scene(&text),
            Ray::new(Vec3A::new(0.0, 0.0, 5.0), Vec3A::new(0.0, 0.0, -1.0)),
            40_000,
        );
        // Clear glass would give 1 in every channel: the green channel
        // (a = 1/16) is far from it.
        assert_close(got, want, 0.01, name);
    }
}

/// A camera inside coloured glass sees it on the way to the surface it
/// looks at (the first surface reached from inside says where the path
/// started), and a light inside the glass is seen through what lies
/// between.
#[test]
fn cameras_and_lights_inside_the_glass_are_absorbed_on_the_way() {
    for (name, text) in integrators(1.0) {
        let l = scene(&text.replace("radius: 1,", "radius: 2,"));
        let from_centre = Ray::new(Vec3A::ZERO, Vec3A::new(0.6, 0.0, 0.8));
        assert_close(
            mean_li(&l, from_centre, 64),
            kept(2.0),
            2e-3,
            &format!("{name}, eye inside"),
        );
    }
    // A lamp (radiance 3) at x = 1.2 inside a ball of radius 2: the ray from
    // x = 5 crosses 0.8 of glass to it.
    let lamp =
        r#"Sphere(center: (1.4, 0, 0), radius: 0.2, material: "black", emission: (radiance: (3, 3, 3)))"#;
    let text = ball(1.0, "Path(max_depth: 64, caustics: PathOnly)", lamp, "")
        .replace("radius: 1,", "radius: 2,")
        .replace(
            r#""tea": Glass"#,
            r#""black": Lambert(albedo: (0, 0, 0)), "tea": Glass"#,
        );
    let l = scene(&text);
    let ray = Ray::new(Vec3A::new(5.0, 0.0, 0.0), Vec3A::new(-1.0, 0.0, 0.0));
    assert_close(mean_li(&l, ray, 64), 3.0 * kept(0.4), 2e-3, "a lamp inside");
}

/// The same rough-glass ball holding a lamp, over a floor, once with
/// `attenuation` and once clear but filled with a purely absorbing medium
/// of the same σ (the volumetric path tracer, which finds the medium by
/// the object's `interior`): the two share no absorption code, and must
/// agree ray by ray —
/// through the glass onto the lamp, onto the floor it lights, and on the
/// ball's rough surface lit from inside (next-event estimation through the
/// inside).
#[test]
fn coloured_glass_matches_the_ball_filled_with_an_absorbing_medium() {
    let text = |filled: bool| {
        let (glass, media, interior) = if filled {
            (
                r#"RoughGlass(roughness: 0.3, ior: 1.5)"#,
                r#"media: { "tea": Homogeneous(sigma_a: (0.6931472, 1.3862944, 0), sigma_s: (0, 0, 0)) },"#,
                r#", interior: "tea""#,
            )
        } else {
            (
                r#"RoughGlass(roughness: 0.3, ior: 1.5, attenuation: (color: (0.5, 0.25, 1.0), distance: 1))"#,
                "",
                "",
            )
        };
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 5), target: (0, 0.5, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 12, caustics: PathOnly),
            {media}
            materials: {{
                "grey": Lambert(albedo: (0.6, 0.6, 0.6)),
                "black": Lambert(albedo: (0, 0, 0)),
                "glass": {glass},
            }},
            lights: [Environment(radiance: (0.1, 0.1, 0.1))],
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                Sphere(center: (0, 1.2, 0), radius: 1, material: "glass"{interior}),
                Sphere(center: (0, 1.2, 0), radius: 0.25, material: "black", emission: (radiance: (8, 8, 8))),
            ],
        )"#
        )
    };
    let (clear_tea, filled) = (scene(&text(false)), scene(&text(true)));
    assert!(clear_tea.scene.media.is_none() && filled.scene.media.is_some());
    let eye = Vec3A::new(0.0, 1.0, 5.0);
    for (what, target) in [
        ("the lamp", Vec3A::new(0.0, 1.2, 0.0)),
        ("the ball's edge", Vec3A::new(0.8, 1.6, 0.0)),
        ("the floor beside", Vec3A::new(1.3, 0.0, 0.5)),
        ("the floor before", Vec3A::new(0.0, 0.0, 1.6)),
    ] {
        let ray = Ray::new(eye, (target - eye).normalize());
        let n = 40_000;
        let (a, b) = (mean_li(&clear_tea, ray, n), mean_li(&filled, ray, n));
        for c in 0..3 {
            assert!(
                (a[c] - b[c]).abs() <= 0.04 * a[c].max(b[c]) + 2e-3,
                "{what}, channel {c}: attenuation {a} against the absorbing medium {b}"
            );
        }
        // And the channels differ as σ says: blue is not absorbed.
        assert!(a.z > a.y, "{what}: {a}");
    }
}

/// Light-traced caustics through a coloured glass ball (its absorption
/// carried along the light paths) against the path tracer alone, whole
/// image and by blocks.
#[test]
fn light_traced_caustics_through_coloured_glass_match_the_path_tracer() {
    let text = |caustics: &str, seed: u32| {
        format!(
            r#"Scene(
            camera: (eye: (0, 3, 4), target: (0, 0.3, 0), fov_y_degrees: 40),
            film: (width: 24, height: 24, spp: 512, seed: {seed}),
            integrator: Path(max_depth: 8, caustics: {caustics}),
            materials: {{
                "grey": Lambert(albedo: (0.7, 0.7, 0.7)),
                "amber": Glass(ior: 1.5, attenuation: (color: (0.9, 0.5, 0.15), distance: 0.6)),
            }},
            lights: [Rect(center: (1.5, 3, 0), half_u: (0.3, 0, 0), half_v: (0, 0, 0.3), radiance: (20, 20, 20))],
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                Sphere(center: (0, 0.5, 0), radius: 0.5, material: "amber"),
            ],
        )"#
        )
    };
    let mean = |caustics: &str| {
        let mut px = Vec::new();
        for seed in 0..2 {
            let img = common::render_loaded(&scene(&text(caustics, seed)));
            if px.is_empty() {
                px = vec![Vec3A::ZERO; img.pixels.len()];
            }
            for (p, q) in px.iter_mut().zip(&img.pixels) {
                *p += Vec3A::new(q.x, q.y, q.z) * 0.5;
            }
        }
        px
    };
    let (traced, path) = (mean("LightTracing"), mean("PathOnly"));
    let block = |px: &[Vec3A], bx: usize, by: usize| -> Vec3A {
        let mut s = Vec3A::ZERO;
        for y in by * 8..by * 8 + 8 {
            for x in bx * 8..bx * 8 + 8 {
                s += px[y * 24 + x];
            }
        }
        s / 64.0
    };
    for by in 0..3 {
        for bx in 0..3 {
            let (a, b) = (block(&traced, bx, by), block(&path, bx, by));
            for c in 0..3 {
                assert!(
                    (a[c] - b[c]).abs() <= 0.06 * a[c].max(b[c]) + 0.01,
                    "block ({bx}, {by}) channel {c}: light-traced {a} against path-traced {b}"
                );
            }
        }
    }
}

/// Each wrong attenuation is an error at its own path, all at once.
#[test]
fn wrong_attenuations_are_located_errors() {
    let text = r#"Scene(
        camera: (eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40),
        materials: {
            "a": Glass(attenuation: (color: (0, 0.5, 1.2), distance: 1)),
            "b": Glass(attenuation: (color: (0.5, 0.5, 0.5), distance: 0)),
            "c": RoughGlass(roughness: 0.2, attenuation: (color: (0.5, 0.5, 0.5), distance: inf)),
            "d": Glass(thin: true, attenuation: (color: (0.5, 0.5, 0.5), distance: 1)),
        },
        lights: [Environment(radiance: (1, 1, 1))],
        objects: [
            Sphere(center: (0, 0, 0), radius: 1, material: "a"),
            Sphere(center: (3, 0, 0), radius: 1, material: "b"),
            Sphere(center: (6, 0, 0), radius: 1, material: "c"),
            Sphere(center: (9, 0, 0), radius: 1, material: "d"),
        ],
    )"#;
    let dir = tempfile::tempdir().expect("temp dir");
    let e = match load_str(&dir.path().join("s.ron"), text, &Overrides::default()) {
        Ok(_) => panic!("wrong attenuations must not load"),
        Err(e) => message(&e),
    };
    for want in [
        "materials.a.attenuation.color",
        "(0, 1]",
        "materials.b.attenuation.distance",
        "materials.c.attenuation.distance",
        "materials.d.attenuation",
        "a thin sheet has no inside",
    ] {
        assert!(e.contains(want), "missing `{want}` in:\n{e}");
    }
}

/// Every number of the fuzz seed `fuzz/corpus/scene/coloured_glass.ron`
/// replaced in turn by a hostile one: each variant loads or is refused, and
/// each that loads renders finite pixels.
#[test]
fn hostile_numbers_in_coloured_glass_never_panic_and_render_finite() {
    let seed = std::fs::read_to_string(common::root().join("fuzz/corpus/scene/coloured_glass.ron"))
        .expect("the fuzz seed");
    assert!(!scene(&seed).scene.absorption.is_empty(), "the seed absorbs");
    let (numbers, loaded, refused) = common::hostile_number_sweep(&seed, &common::root().join("scenes"));
    assert!(numbers > 40, "{numbers} numbers");
    assert!(loaded > 0 && refused > 0, "{loaded} loaded, {refused} refused");
}

/// A generated family: 1 to 5 disjoint index-matched solids (balls, and
/// axis-aligned boxes traced as SDFs), each with its own colour and
/// distance, some holding a clear ball (ice in a drink), under a white sky,
/// seen along random rays — some from inside a solid. Whatever the mix, a
/// ray keeps exp(−Σ σᵢ·(chordᵢ − iceᵢ)), chordᵢ the length of the ray
/// inside solid i from its origin on and iceᵢ the length inside its ice.
#[test]
fn random_index_matched_solids_absorb_along_their_chords() {
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut rand = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    let mut checked = 0;
    for family in 0..12 {
        // Solids on a row along x, 3 apart, so they never overlap.
        let count = 1 + family % 5;
        let mut solids = Vec::new();
        let (mut materials, mut objects) = (String::from(r#""ice": Glass(ior: 1),"#), String::new());
        for i in 0..count {
            let centre = Vec3A::new(3.0 * i as f32 - 6.0, rand() - 0.5, rand() - 0.5);
            let colour = [0.2 + 0.8 * rand(), 0.2 + 0.8 * rand(), 0.2 + 0.8 * rand()];
            let distance = 0.3 + 2.0 * rand();
            let sigma = Vec3A::from_array(colour.map(|c| -c.ln() / distance));
            materials += &format!(
                r#""m{i}": Glass(ior: 1, attenuation: (color: ({}, {}, {}), distance: {distance})),"#,
                colour[0], colour[1], colour[2]
            );
            let size = 0.4 + 0.8 * rand();
            let is_box = rand() < 0.5;
            if is_box {
                let h = Vec3A::new(size, 0.5 + 0.5 * rand(), 0.3 + 0.7 * rand());
                objects += &format!(
                    r#"Sdf(shape: Box(half_extents: ({}, {}, {})), material: "m{i}", transform: [Translate(({}, {}, {}))]),"#,
                    h.x, h.y, h.z, centre.x, centre.y, centre.z
                );
                solids.push((centre, Some(h), size, sigma, h.min_element()));
            } else {
                objects += &format!(
                    r#"Sphere(center: ({}, {}, {}), radius: {size}, material: "m{i}"),"#,
                    centre.x, centre.y, centre.z
                );
                solids.push((centre, None, size, sigma, size));
            }
            // Ice: a clear ball inside, half the solid's smallest extent.
            let ice = if rand() < 0.5 { 0.5 * solids[i].4 } else { 0.0 };
            solids[i].4 = ice;
            if ice > 0.0 {
                objects += &format!(
                    r#"Sphere(center: ({}, {}, {}), radius: {ice}, material: "ice"),"#,
                    centre.x, centre.y, centre.z
                );
            }
        }
        // The length of ray o + t·d (t ≥ 0) inside each solid.
        type Solid = (Vec3A, Option<Vec3A>, f32, Vec3A, f32);
        let chord = |o: Vec3A, d: Vec3A, (c, half, r, ..): &Solid| -> f32 {
            let (t0, t1) = match half {
                Some(h) => {
                    let (mut lo, mut hi) = (f32::NEG_INFINITY, f32::INFINITY);
                    for a in 0..3 {
                        let (a0, a1) = ((c[a] - h[a] - o[a]) / d[a], (c[a] + h[a] - o[a]) / d[a]);
                        lo = lo.max(a0.min(a1));
                        hi = hi.min(a0.max(a1));
                    }
                    (lo, hi)
                }
                None => {
                    let oc = o - *c;
                    let b = oc.dot(d);
                    let disc = b * b - (oc.length_squared() - r * r);
                    if disc <= 0.0 {
                        return 0.0;
                    }
                    (-b - disc.sqrt(), -b + disc.sqrt())
                }
            };
            (t1.min(f32::INFINITY) - t0.max(0.0)).max(0.0)
        };
        // No Russian roulette: a ray through several solids and their ice
        // has more segments than `rr_depth`'s default.
        for integrator in [
            "Path(max_depth: 64, rr_depth: 64, caustics: PathOnly)",
            "Whitted(max_depth: 64)",
        ] {
            let l = scene(&format!(
                r#"Scene(
                camera: (eye: (0, 0, 9), target: (0, 0, 0), fov_y_degrees: 40),
                integrator: {integrator},
                materials: {{ {materials} }},
                lights: [Environment(radiance: (1, 1, 1))],
                objects: [{objects}],
            )"#
            ));
            for k in 0..6 {
                // From afar along a random direction through the row, or
                // from a point inside one of the solids.
                let target = solids[k % count].0 + 0.3 * Vec3A::new(rand() - 0.5, rand() - 0.5, rand() - 0.5);
                let d = Vec3A::new(rand() - 0.5, rand() - 0.5, rand() - 0.5).normalize();
                let o = if k % 3 == 2 { target } else { target - 20.0 * d };
                let want = solids.iter().fold(Vec3A::ONE, |acc, s| {
                    let ice = (s.0, None, s.4, Vec3A::ZERO, 0.0);
                    let t = chord(o, d, s) - if s.4 > 0.0 { chord(o, d, &ice) } else { 0.0 };
                    acc * beer(s.3, t)
                });
                let got = mean_li(&l, Ray::new(o, d), 4);
                for c in 0..3 {
                    assert!(
                        (got[c] - want[c]).abs() <= 2e-3 + 2e-3 * want[c],
                        "family {family} ({integrator}), ray {k} from {o} along {d}, channel {c}: {got} against {want}"
                    );
                }
                checked += 1;
            }
        }
    }
    assert_eq!(checked, 144);
}

/// Coloured glass so thick for its `distance` that it keeps under 1/1000
/// of every channel warns, at the distance, with the object's thickness;
/// a reasonable distance, or one channel that gets through, does not.
#[test]
fn coloured_glass_too_dark_to_see_through_warns() {
    let text = |material: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 8),
            materials: {{ "g": {material} }},
            lights: [Environment(radiance: (1, 1, 1))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "g")],
        )"#
        )
    };
    // Written in centimetres in a scene of metres: 2 units across, 0.01 per
    // halving: 2^-200.
    let dark = r#"Glass(attenuation: (color: (0.5, 0.5, 0.5), distance: 0.01))"#;
    let wrapped = format!(r#"NormalMap(map: (0.5, 0.5, 1), material: {dark})"#);
    for m in [dark, wrapped.as_str()] {
        let notes = common::notes_text(&scene(&text(m)));
        assert!(
            notes.contains("objects[0]") && notes.contains("will look black") && notes.contains("2.000"),
            "{m}: {notes}"
        );
    }
    for m in [
        r#"Glass(attenuation: (color: (0.5, 0.5, 0.5), distance: 1))"#,
        // Blue gets through: a deep blue ball, not a black one.
        r#"RoughGlass(roughness: 0.2, attenuation: (color: (0.01, 0.01, 0.9), distance: 0.1))"#,
    ] {
        let notes = common::notes_text(&scene(&text(m)));
        assert!(!notes.contains("will look black"), "{m}: {notes}");
    }
}

/// An absorption coefficient past f32 (a tiny colour over a tiny distance)
/// absorbs everything — not read as clear, and no NaN where a path starts
/// on the surface (length 0).
#[test]
fn an_absorption_past_f32_absorbs_everything() {
    let text = ball(1.0, "Path(max_depth: 64, caustics: PathOnly)", "", "").replace(
        "(color: (0.5, 0.25, 1.0), distance: 1)",
        "(color: (1e-38, 0.5, 1), distance: 1e-38)",
    );
    let l = scene(&text);
    let sigma = l
        .scene
        .absorption
        .iter()
        .flatten()
        .next()
        .copied()
        .unwrap_or_default();
    assert_eq!(sigma.x, f32::MAX, "{sigma}");
    let got = mean_li(
        &l,
        Ray::new(Vec3A::new(0.2, 0.0, 5.0), Vec3A::new(0.0, 0.0, -1.0)),
        16,
    );
    assert!(got.is_finite() && got.x == 0.0 && got.z == 1.0, "{got}");
    assert!(common::render_loaded(&l).pixels.iter().all(|p| p.is_finite()));
}
