//! Time, end to end: frame ranges and the farm, motion blur against
//! closed forms and against static renders (moving occluders and moving
//! emitters, seen and sampled), and located errors for the new fields.
//! Scenes are tiny (2 × 64 to 64²) and few-sampled.

mod common;

use common::{load_in, message, render_loaded, ronray, root};
use glam::{Mat4, Vec3};
use ronray::anim::{Interpolation, TransformTrack};
use ronray::imageio::{Image, compare};
use ronray::load::{Overrides, load_str};
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    root().join("tests/fixtures/anim")
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ronray-anim-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> (bool, String) {
    let out = ronray(args);
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn frames_range_writes_what_separate_frame_runs_write() {
    let dir = scratch("range");
    let scene = fixtures().join("turntable.ron");
    let template = dir.join("range_{frame:04}.exr");
    let (ok, err) = run(&[
        "render",
        s(&scene),
        "--frames",
        "3..5",
        "-o",
        s(&template),
        "--progress",
        "none",
    ]);
    assert!(ok, "--frames 3..5 failed: {err}");
    let mut distinct = Vec::new();
    for f in 3..=5 {
        let single = dir.join(format!("single_{f}.exr"));
        let n = f.to_string();
        let (ok, err) = run(&[
            "render",
            s(&scene),
            "--frame",
            &n,
            "-o",
            s(&single),
            "--progress",
            "none",
        ]);
        assert!(ok, "--frame {f} failed: {err}");
        let a = std::fs::read(dir.join(format!("range_{f:04}.exr"))).unwrap();
        let b = std::fs::read(&single).unwrap();
        assert!(a == b, "frame {f} of --frames differs from --frame {f}");
        distinct.push(a);
    }
    assert!(
        distinct[0] != distinct[2],
        "frames 3 and 5 should differ: things move"
    );
}

#[test]
fn frame_auto_takes_the_job_index_and_composes_with_tiles() {
    let dir = scratch("auto");
    let scene = fixtures().join("turntable.ron");
    // Job 3 of an array over 3 frames × 2 tiles: frame 3 + ⌊3/2⌋ = 4, tile 1.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ronray"))
        .args(["render", s(&scene), "--frame", "auto", "--tile", "auto/2", "-o"])
        .arg(dir.join("job_{frame}_{tile}.exr"))
        .args(["--progress", "none"])
        .env("SLURM_ARRAY_TASK_ID", "3")
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.join("job_4_1.exr").is_file(), "expected frame 4, tile 1");
    let given = dir.join("given.exr");
    let (ok, err) = run(&[
        "render",
        s(&scene),
        "--frame",
        "4",
        "--tile",
        "1/2",
        "-o",
        s(&given),
        "--progress",
        "none",
    ]);
    assert!(ok, "{err}");
    assert!(std::fs::read(dir.join("job_4_1.exr")).unwrap() == std::fs::read(&given).unwrap());
}

#[test]
fn assemble_refuses_pieces_of_different_frames() {
    let dir = scratch("assemble");
    let scene = fixtures().join("turntable.ron");
    let (a, b) = (dir.join("a.exr"), dir.join("b.exr"));
    assert!(
        run(&[
            "render",
            s(&scene),
            "--frame",
            "3",
            "--tile",
            "0/2",
            "-o",
            s(&a),
            "--progress",
            "none"
        ])
        .0
    );
    assert!(
        run(&[
            "render",
            s(&scene),
            "--frame",
            "4",
            "--tile",
            "1/2",
            "-o",
            s(&b),
            "--progress",
            "none"
        ])
        .0
    );
    let (ok, err) = run(&["assemble", s(&a), s(&b), "-o", s(&dir.join("whole.exr"))]);
    assert!(!ok, "pieces of frames 3 and 4 were assembled");
    assert!(
        err.contains("different animation frames") && err.contains("frame 3") && err.contains("frame 4"),
        "{err}"
    );
    // The same frame's tiles do assemble.
    let c = dir.join("c.exr");
    assert!(
        run(&[
            "render",
            s(&scene),
            "--frame",
            "3",
            "--tile",
            "1/2",
            "-o",
            s(&c),
            "--progress",
            "none"
        ])
        .0
    );
    let (ok, err) = run(&["assemble", s(&a), s(&c), "-o", s(&dir.join("whole.exr"))]);
    assert!(ok, "{err}");
}

#[test]
fn several_frames_need_a_frame_field_and_stay_in_range() {
    let dir = scratch("template");
    let scene = fixtures().join("turntable.ron");
    let (ok, err) = run(&[
        "render",
        s(&scene),
        "--frames",
        "3..4",
        "-o",
        s(&dir.join("one.exr")),
    ]);
    assert!(!ok && err.contains("{frame}"), "{err}");
    let (ok, err) = run(&[
        "render",
        s(&scene),
        "--frames",
        "4..9",
        "-o",
        s(&dir.join("f{frame}.exr")),
    ]);
    assert!(!ok && err.contains("outside the scene's frames 3..=5"), "{err}");
    assert!(
        !dir.join("f4.exr").exists(),
        "nothing is drawn before the range is refused"
    );
    let (ok, err) = run(&["render", s(&scene), "--frame", "9", "-o", s(&dir.join("f.exr"))]);
    assert!(
        !ok && err.contains("frame 9 is outside") && err.contains("--frame 9"),
        "{err}"
    );
}

/// A scene with `body` spliced in: errors must name their place.
fn errors_of(text: &str) -> String {
    match load_str(&fixtures().join("test.ron"), text, &Overrides::default()) {
        Ok(_) => panic!("expected the scene to be refused:\n{text}"),
        Err(e) => message(&e),
    }
}

const CAMERA: &str = "camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40";

#[test]
fn time_fields_give_located_errors() {
    let keys = format!(
        "Scene(\n    {CAMERA},\n        keys: [\n            (frame: 5, eye: (0, 0, 4), target: (0, 0, 0)),\n            (frame: 2, eye: (0, 0, 3), target: (0, 0, 0)),\n        ],\n    ),\n)\n"
    );
    let e = errors_of(&keys);
    assert!(
        e.contains("keys out of order: frame 2 comes after frame 5") && e.contains(":5:"),
        "{e}"
    );
    let range = format!("Scene(\n    animation: (frames: (1, 10), frame: 12),\n    {CAMERA}),\n)\n");
    let e = errors_of(&range);
    assert!(
        e.contains("frame 12 is outside the scene's frames 1..=10") && e.contains(":2:"),
        "{e}"
    );
    let shutter = format!("Scene(\n    {CAMERA},\n        shutter: (0.5, 0.2)),\n)\n");
    let e = errors_of(&shutter);
    assert!(e.contains("shutter (0.5, 0.2)") && e.contains(":3:"), "{e}");
    let both = format!(
        "Scene(\n    {CAMERA}),\n    meshes: {{ \"sq\": (file: \"square.obj\") }},\n    materials: {{ \"m\": Lambert(albedo: (1, 1, 1)) }},\n    objects: [\n        Instance(mesh: \"sq\", material: \"m\", transform: [Translate((1, 0, 0))],\n            keys: [(frame: 0, transform: [Scale((0, 1, 1))])]),\n    ],\n)\n"
    );
    let e = errors_of(&both);
    assert!(e.contains("takes its placement from them"), "{e}");
    assert!(
        e.contains("zero factor") && e.contains("objects[0].keys[0].transform[0]"),
        "{e}"
    );
}

#[test]
fn keys_of_different_handedness_give_a_located_error() {
    let text = format!(
        "Scene(\n    {CAMERA}),\n    meshes: {{ \"sq\": (file: \"square.obj\") }},\n    materials: {{ \"m\": Lambert(albedo: (1, 1, 1)) }},\n    objects: [\n        Instance(mesh: \"sq\", material: \"m\", emission: (radiance: (1, 1, 1)), keys: [\n            (frame: 0, transform: [Scale((1, 1, 1))]),\n            (frame: 1, transform: [Scale((-1, 1, 1))]),\n        ]),\n    ],\n)\n"
    );
    let e = errors_of(&text);
    assert!(
        e.contains("turns inside out") && e.contains("objects[0].keys[1].transform") && e.contains(":8:"),
        "{e}"
    );
    // The same keys, both mirrored, are fine; and a keyed instance may emit.
    let fine = text.replace("Scale((1, 1, 1))", "Scale((1, -1, 1))");
    load_in(&fixtures(), &fine, &Overrides::default());
}

/// The analytic scene: an orthographic camera 8 units wide over a
/// 64-pixel row, an emissive wall of radiance 1 behind, and in front a
/// black 2-unit square crossing from x = −2 to x = +2 at constant speed
/// while the shutter is open. A pixel centred at x sees the wall for the
/// part of the shutter the square leaves it uncovered.
fn moving_square(shutter: &str) -> String {
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 5), target: (0, 0, 0), projection: Orthographic(view_height: 0.25), shutter: {shutter}),
    film: (width: 64, height: 2, spp: 4096, sampler: Independent, allocation: Even, filter: Gaussian(radius: 0.001, sigma: 0.05)),
    integrator: Direct(light_samples: 1),
    materials: {{ "black": Lambert(albedo: (0, 0, 0)) }},
    meshes: {{ "square": (file: "square.obj") }},
    objects: [
        Rect(center: (0, 0, -1), half_u: (10, 0, 0), half_v: (0, 10, 0), material: "black", emission: (radiance: (1, 1, 1))),
        Instance(mesh: "square", material: "black", keys: [
            (frame: 0, transform: [Scale((2, 4, 1)), Translate((-2, 0, 1))]),
            (frame: 1, transform: [Scale((2, 4, 1)), Translate((2, 0, 1))]),
        ]),
    ],
)"#
    )
}

#[test]
fn motion_blur_gives_each_pixel_its_shutter_time_coverage() {
    let l = load_in(&fixtures(), &moving_square("(0, 1)"), &Overrides::default());
    let img = render_loaded(&l);
    let mut worst = 0.0f64;
    for x in 0..64 {
        // Pixel centre in world units, and the fraction of the shutter
        // during which the square (centre −2 + 4t, half-width 1) covers it.
        let p = -4.0 + (x as f64 + 0.5) * 0.125;
        let (t0, t1) = (
            ((p - 1.0 + 2.0) / 4.0).clamp(0.0, 1.0),
            ((p + 1.0 + 2.0) / 4.0).clamp(0.0, 1.0),
        );
        let expected = 1.0 - (t1 - t0);
        for y in 0..2 {
            let got = f64::from(img.pixels[y * 64 + x].x);
            worst = worst.max((got - expected).abs());
        }
    }
    assert!(
        worst < 1e-3,
        "worst pixel is {worst:e} from its shutter-time coverage"
    );
}

/// [`moving_square`] turned inside out: the square itself emits (radiance
/// `(1, 0.5, 0.25)`) over nothing (black), so a pixel centred at x is lit
/// for the part of the shutter the square covers it.
fn moving_emitter(shutter: &str) -> String {
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 5), target: (0, 0, 0), projection: Orthographic(view_height: 0.25), shutter: {shutter}),
    film: (width: 64, height: 2, spp: 4096, sampler: Independent, allocation: Even, filter: Gaussian(radius: 0.001, sigma: 0.05)),
    integrator: Direct(light_samples: 1),
    materials: {{ "black": Lambert(albedo: (0, 0, 0)) }},
    meshes: {{ "square": (file: "square.obj") }},
    objects: [
        Instance(mesh: "square", material: "black", emission: (radiance: (1, 0.5, 0.25)), keys: [
            (frame: 0, transform: [Scale((2, 4, 1)), Translate((-2, 0, 1))]),
            (frame: 1, transform: [Scale((2, 4, 1)), Translate((2, 0, 1))]),
        ]),
    ],
)"#
    )
}

/// The fraction of the shutter (0, 1) during which the square of
/// [`moving_square`] and [`moving_emitter`] (centre −2 + 4t, half-width 1)
/// covers the pixel centred at column `x` of 64 over 8 units.
fn coverage(x: usize) -> f64 {
    let p = -4.0 + (x as f64 + 0.5) * 0.125;
    let (t0, t1) = (
        ((p - 1.0 + 2.0) / 4.0).clamp(0.0, 1.0),
        ((p + 1.0 + 2.0) / 4.0).clamp(0.0, 1.0),
    );
    t1 - t0
}

#[test]
fn moving_emitter_gives_each_pixel_its_shutter_time_coverage() {
    let l = load_in(&fixtures(), &moving_emitter("(0, 1)"), &Overrides::default());
    assert_eq!(l.scene.lights.len(), 1, "the moving square is a light");
    let img = render_loaded(&l);
    let radiance = [1.0, 0.5, 0.25];
    let mut worst = 0.0f64;
    for x in 0..64 {
        for y in 0..2 {
            let px = img.pixels[y * 64 + x];
            for (c, got) in [px.x, px.y, px.z].into_iter().enumerate() {
                worst = worst.max((f64::from(got) - radiance[c] * coverage(x)).abs());
            }
        }
    }
    common::report(&format!(
        "moving emitter: worst pixel channel {worst:.1e} from radiance × shutter-time coverage"
    ));
    assert!(
        worst < 1e-3,
        "worst pixel is {worst:e} from radiance × its shutter-time coverage"
    );
}

/// 64² renders of `text(seed)` at seeds 1 and 2: the two renders the
/// reference bar compares.
fn two_renders(text: impl Fn(u64) -> String) -> (Image, Image) {
    let r = |seed| render_loaded(&load_in(&fixtures(), &text(seed), &Overrides::default()));
    (r(1), r(2))
}

/// The mean of 64 still renders at the centres of 64 equal parts of the
/// shutter (0, 1), `still(t, seed)` the scene frozen at time t, each with
/// its own seed: the reference a blurred render converges to.
fn mean_of_stills(still: impl Fn(f64, u64) -> String) -> Image {
    let mut mean: Option<Image> = None;
    for k in 0..64u64 {
        let t = (k as f64 + 0.5) / 64.0;
        let one = render_loaded(&load_in(&fixtures(), &still(t, 1000 + k), &Overrides::default()));
        match &mut mean {
            None => {
                mean = Some(Image {
                    pixels: one.pixels.iter().map(|p| *p / 64.0).collect(),
                    ..one
                })
            }
            Some(m) => m
                .pixels
                .iter_mut()
                .zip(&one.pixels)
                .for_each(|(m, p)| *m += *p / 64.0),
        }
    }
    mean.expect("64 stills")
}

/// A diffuse floor lit from half a unit above by a square lamp facing
/// down that moves across, turns 40° and stretches from 0.5 to 1.5 wide
/// while the shutter is open, and by a small still lamp (so the light
/// tree has two lights to choose from). Direct light only
/// (`max_depth: 2`): next-event estimation of the moving lamp weighed by
/// MIS against BSDF samples that hit it. `at: Some(t)` freezes the lamp at
/// time t, written by hand as the keys interpolate (scale and translation
/// linearly, the rotation about the fixed axis at constant speed): an
/// ordinary still emissive instance, sampled by the still mesh light.
fn moving_lamp(shutter: &str, spp: u32, seed: u64, at: Option<f64>) -> String {
    let place = |u: f64| {
        format!(
            "[Scale(({}, 0.5, 1)), Rotate(axis: (1, 0, 0), degrees: {}), Translate(({}, {}, {}))]",
            0.5 + u,
            90.0 + 40.0 * u,
            -0.8 + 1.6 * u,
            0.6 - 0.2 * u,
            0.2 * u
        )
    };
    let lamp = match at {
        Some(u) => format!("transform: {}", place(u)),
        None => format!(
            "keys: [(frame: 0, transform: {}), (frame: 1, transform: {})]",
            place(0.0),
            place(1.0)
        ),
    };
    format!(
        r#"Scene(
    camera: (eye: (0, 2.5, 3.5), target: (0, 0, 0), fov_y_degrees: 45, shutter: {shutter}),
    film: (width: 64, height: 64, spp: {spp}, seed: {seed}, sampler: Independent, allocation: Even),
    integrator: Path(max_depth: 2),
    materials: {{ "floor": Lambert(albedo: (0.8, 0.8, 0.8)), "black": Lambert(albedo: (0, 0, 0)) }},
    lights: [Rect(center: (1.5, 1.5, -1.5), half_u: (0.2, 0, 0), half_v: (0, 0, 0.2), radiance: (3, 3, 3))],
    meshes: {{ "square": (file: "square.obj") }},
    objects: [
        Rect(center: (0, 0, 0), half_u: (2, 0, 0), half_v: (0, 0, -2), material: "floor"),
        Instance(mesh: "square", material: "black", emission: (radiance: (6, 5, 4)), {lamp}),
    ],
)"#
    )
}

#[test]
fn moving_lamp_lights_the_floor_as_the_mean_of_still_lamps() {
    // 256 spp: at 64, the image mean of the seed-1 render strayed 1.08%
    // from the reference (2.6σ of its own noise; six other seeds averaged
    // within 0.04% of it), past the bar's 1%. The reference, 64 stills at
    // 16 spp, has four times as many samples per pixel.
    let (a, b) = two_renders(|seed| moving_lamp("(0, 1)", 256, seed, None));
    let reference = mean_of_stills(|t, seed| moving_lamp("(0, 0)", 16, seed, Some(t)));
    common::reference_bar("moving lamp", &a, &b, &reference, None, 0.01);
    // And the motion matters: the lamp frozen at its opening lights the
    // floor elsewhere, far outside that bar.
    let frozen = render_loaded(&load_in(
        &fixtures(),
        &moving_lamp("(0, 0)", 64, 1, Some(0.0)),
        &Overrides::default(),
    ));
    let err = |x: &Image| compare(x, &reference, None).expect("same size").rmse;
    let noise = compare(&a, &b, None).expect("same size").rmse / 2f64.sqrt();
    common::report(&format!(
        "moving lamp: RMSE vs mean of stills {:.4}, own noise {noise:.4}; the lamp frozen at the opening {:.4}",
        err(&a),
        err(&frozen)
    ));
    assert!(err(&frozen) > 3.0 * noise, "the lamp hardly moved");
}

/// The Cornell box's short block (from `assets/`), turning 20° about the
/// vertical and moving 0.3 to the right over the frame, at 64²;
/// `shutter` decides when the picture is taken. `at: Some(t)` replaces the
/// keys by `transform`, the placement at time t as the keys interpolate it
/// (the rotation about the fixed axis at constant speed, the translation
/// linearly), written by hand.
fn moving_block(shutter: &str, spp: u32, seed: u64, at: Option<f64>) -> String {
    let block = match at {
        Some(u) => format!(
            "transform: [Rotate(axis: (0, 1, 0), degrees: {}), Translate(({}, 0, 0))]",
            20.0 * u,
            0.3 * u
        ),
        None => "keys: [\n            (frame: 0, transform: []),\n            (frame: 1, transform: [Rotate(axis: (0, 1, 0), degrees: 20), Translate((0.3, 0, 0))]),\n        ]".to_string(),
    };
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 3.9), target: (0, 0, 0), fov_y_degrees: 37.5, shutter: {shutter}),
    film: (width: 64, height: 64, spp: {spp}, seed: {seed}, sampler: Independent, allocation: Even),
    integrator: Path(max_depth: 4, rr_depth: 3),
    materials: {{
        "white": Lambert(albedo: (0.8, 0.7, 0.66)),
        "red": Lambert(albedo: (0.57, 0.04, 0.04)),
        "green": Lambert(albedo: (0.1, 0.38, 0.08)),
    }},
    lights: [Rect(center: (0, 0.99, 0), half_u: (0.23, 0, 0), half_v: (0, 0, 0.19), radiance: (18, 14, 7))],
    meshes: {{ "block": (file: "../../../assets/short_block.obj") }},
    objects: [
        Rect(center: (0, -1, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "white"),
        Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), material: "white"),
        Rect(center: (0, 0, -1), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "white"),
        Rect(center: (-1, 0, 0), half_u: (0, 1, 0), half_v: (0, 0, 1), material: "red"),
        Rect(center: (1, 0, 0), half_u: (0, 0, 1), half_v: (0, 1, 0), material: "green"),
        Instance(mesh: "block", material: "white", {block}),
    ],
)"#
    )
}

#[test]
fn moving_block_matches_the_mean_of_static_renders_at_stratified_times() {
    // Two blurred renders at 64 spp against the mean of 64 still renders
    // at the centres of 64 equal parts of the shutter, 8 spp each (512
    // samples per pixel in all, a reference 8× less noisy than either
    // render), held to tests/reference.rs's bar.
    let (a, b) = two_renders(|seed| moving_block("(0, 1)", 64, seed, None));
    let reference = mean_of_stills(|t, seed| moving_block("(0, 0)", 8, seed, Some(t)));
    common::reference_bar("moving block", &a, &b, &reference, None, 0.01);
    // And the bar sees the motion: the block frozen at its first instant
    // (two seeds, as above) has blocks off the blurred reference.
    let frozen = |seed| {
        render_loaded(&load_in(
            &fixtures(),
            &moving_block("(0, 0)", 64, seed, None),
            &Overrides::default(),
        ))
    };
    let (f1, f2) = (frozen(1), frozen(2));
    common::report(&format!(
        "moving block: RMSE vs mean of stills {:.4}; frozen at the opening {:.4}",
        compare(&a, &reference, None).expect("same size").rmse,
        compare(&f1, &reference, None).expect("same size").rmse
    ));
    let seen = std::panic::catch_unwind(|| common::check_blocks("frozen block", &f1, &f2, &reference));
    assert!(
        seen.is_err(),
        "the block frozen at its opening passes the bar: the test cannot see motion"
    );
}

#[test]
fn closed_shutter_equals_the_static_render_of_that_instant() {
    let render = |text: &str| render_loaded(&load_in(&fixtures(), text, &Overrides::default()));
    // On the last key: the key's own matrix, exactly.
    let still = render(&moving_block("(0, 0)", 8, 3, Some(1.0)));
    let closed = render(&moving_block("(1, 1)", 8, 3, None));
    assert!(
        still.pixels == closed.pixels,
        "a closed shutter at the last key differs from the static block there"
    );
}

#[test]
fn closed_shutter_between_keys_equals_the_static_render_of_the_interpolated_transform() {
    let u = 0.37f32;
    // The keys as the loader composes them (steps applied in order), and
    // their interpolation at u.
    let key1 = Mat4::from_translation(Vec3::new(0.3, 0.0, 0.0))
        * (Mat4::from_axis_angle(Vec3::Y.normalize(), 20f32.to_radians()) * Mat4::IDENTITY);
    let track = TransformTrack::new(&[(0.0, Mat4::IDENTITY), (1.0, key1)], Interpolation::Linear);
    let m = track.at(u);
    // That placement is the rotation by 20u° and the translation by 0.3u,
    // composed by hand.
    let by_hand = Mat4::from_translation(Vec3::new(0.3 * u, 0.0, 0.0))
        * Mat4::from_axis_angle(Vec3::Y, (20.0 * u).to_radians());
    assert!(
        m.abs_diff_eq(by_hand, 1e-6),
        "interpolated placement {m} vs rotate 20u°, translate 0.3u {by_hand}"
    );
    // The moving block with the shutter closed at u renders exactly as the
    // still block given that matrix.
    let rows: Vec<String> = (0..4)
        .map(|r| {
            let row = m.row(r);
            format!("({:?}, {:?}, {:?}, {:?})", row.x, row.y, row.z, row.w)
        })
        .collect();
    let with_matrix = moving_block("(0, 0)", 8, 3, Some(0.0)).replace(
        "transform: [Rotate(axis: (0, 1, 0), degrees: 0), Translate((0, 0, 0))]",
        &format!("transform: [Matrix(({}))]", rows.join(", ")),
    );
    assert!(with_matrix.contains("Matrix"), "the static twin was not made");
    let render = |text: &str| render_loaded(&load_in(&fixtures(), text, &Overrides::default()));
    let closed = render(&moving_block(&format!("({u}, {u})"), 8, 3, None));
    let still = render(&with_matrix);
    assert!(
        still.pixels == closed.pixels,
        "a closed shutter at {u}, between the keys, differs from the static block placed there"
    );
    // The instant shows: the block at u is not the block at the first key.
    let first = render(&moving_block("(0, 0)", 8, 3, None));
    assert!(
        first.pixels != closed.pixels,
        "the block at {u} is where it was at 0"
    );
}
