//! Hostile input is normal input (issue 13): scenes that validate never
//! panic and never put a NaN or an infinity on the film, whatever their
//! numbers; files that are not regular files are refused without blocking.

use crate::common;

use common::root;
use ronray::frame::{RenderOptions, render_whole};
use ronray::load::{Loaded, Overrides, load_str};
use ronray::math::Pcg32;
use std::path::Path;

fn load_tiny(dir: &Path, text: &str) -> Option<Loaded> {
    let o = Overrides {
        size: Some((8, 8)),
        spp: Some(1),
        ..Default::default()
    };
    load_str(&dir.join("gen.ron"), text, &o).ok()
}

/// Renders and asserts every pixel is finite.
fn assert_finite(l: &Loaded, what: &str) {
    let img = render_whole(&l.scene, &l.view, &RenderOptions::default()).0;
    if let Some(p) = img.pixels.iter().find(|p| !p.is_finite()) {
        panic!("{what}: a pixel is {p}");
    }
}

const HEAD: &str = r#"camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
    materials: { "m": Lambert(albedo: (0.5, 0.5, 0.5)), "g": Glass(ior: 1.5), "c": CookTorrance(roughness: 0.3, fresnel: Metal(Gold)) },
    meshes: { "b": (file: "block.obj") },"#;

/// Scenes that once validated and then panicked in `render` with huge but
/// finite numbers — an instance scaled by 2e19, an SDF sphere of radius 2e19
/// around the camera, a mesh scaled by 3e37 — are now refused with a located
/// error (coordinates beyond ±1e15 overflow f32 when squared); a thin lens at
/// 1e7 focused 1e-6 away renders finite pixels.
#[test]
fn huge_but_finite_numbers_are_refused_or_render_finite() {
    let dir = root().join("tests/fixtures/hardening");
    let cases = [
        "Instance(mesh: \"b\", material: \"m\", transform: [Scale((2e19, 2e19, 2e19))])",
        "Sdf(shape: Sphere(radius: 2e19), material: \"m\")",
        "Mesh(file: \"block.obj\", material: \"m\", transform: [Scale((3e37, 3e37, 3e37))])",
    ];
    for object in cases {
        let text = format!(
            "Scene({HEAD} lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))], objects: [{object}])"
        );
        let o = Overrides::default();
        match load_str(&dir.join("gen.ron"), &text, &o) {
            Err(e) => {
                let r = e.report().expect("diagnostics");
                assert!(
                    r.diagnostics
                        .iter()
                        .any(|d| d.message.contains("beyond") && d.line > 0),
                    "{}",
                    r.render(false)
                );
            }
            Ok(_) => panic!("{object} loaded"),
        }
    }
    let lens = format!(
        "Scene({} lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))], objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])",
        HEAD.replace(
            "camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40)",
            "camera: (eye: (1e7, 1, 4), target: (0, 0, 0), fov_y_degrees: 40, aperture_radius: 0.5, focus_distance: 1e-6)"
        )
    );
    assert_finite(&load_tiny(&dir, &lens).expect("validates"), "thin lens at 1e7");
}

/// A number from 1e-30 to 1e16 (either sign, so some are past the limit),
/// or a plain one.
fn extreme(rng: &mut Pcg32) -> f32 {
    let r = rng.next_f32();
    if r < 0.3 {
        return (rng.next_f32() * 4.0 - 2.0).round();
    }
    let mag = 10f32.powf(rng.next_f32() * 46.0 - 30.0);
    if rng.next_f32() < 0.5 { -mag } else { mag }
}

fn v3(rng: &mut Pcg32) -> String {
    format!("({:e}, {:e}, {:e})", extreme(rng), extreme(rng), extreme(rng))
}

/// A few hundred generated scenes with extreme coordinates, sizes, scales
/// and light strengths: each one that validates renders without a panic and
/// with every pixel finite.
#[test]
fn generated_extreme_scenes_render_finite_pixels() {
    let dir = root().join("tests/fixtures/hardening");
    let mut rng = Pcg32::new(13, 1);
    let mut rendered = 0;
    for case in 0..300 {
        let s = |rng: &mut Pcg32| extreme(rng).abs();
        let object = match case % 6 {
            0 => format!(
                "Sphere(center: {}, radius: {:e}, material: \"m\")",
                v3(&mut rng),
                s(&mut rng)
            ),
            1 => format!(
                "Rect(center: {}, half_u: {}, half_v: {}, material: \"c\")",
                v3(&mut rng),
                v3(&mut rng),
                v3(&mut rng)
            ),
            2 => format!(
                "Plane(point: {}, normal: {}, material: \"m\")",
                v3(&mut rng),
                v3(&mut rng)
            ),
            3 => format!(
                "Instance(mesh: \"b\", material: \"g\", transform: [Scale(({e:e}, {e:e}, {e:e})), Translate({})])",
                v3(&mut rng),
                e = s(&mut rng)
            ),
            4 => format!(
                "Sdf(shape: Torus(major: {:e}, minor: {:e}), material: \"m\")",
                s(&mut rng),
                s(&mut rng)
            ),
            _ => format!(
                "Sphere(center: {}, radius: {:e}, material: \"g\")",
                v3(&mut rng),
                s(&mut rng)
            ),
        };
        let light = match case % 4 {
            0 | 2 => format!(
                "Point(position: {}, intensity: ({e:e}, {e:e}, {e:e}))",
                v3(&mut rng),
                e = s(&mut rng)
            ),
            1 => format!(
                "Rect(center: {}, half_u: {}, half_v: {}, radiance: ({e:e}, {e:e}, {e:e}))",
                v3(&mut rng),
                v3(&mut rng),
                v3(&mut rng),
                e = s(&mut rng)
            ),
            // A sun beside a lamp: the light tree weighs both.
            _ => format!(
                "Directional(direction: {}, irradiance: ({e:e}, {e:e}, {e:e})), Point(position: {}, intensity: (1, 1, 1))",
                v3(&mut rng),
                v3(&mut rng),
                e = s(&mut rng)
            ),
        };
        let camera = format!(
            "camera: (eye: {}, target: {}, fov_y_degrees: 40)",
            v3(&mut rng),
            v3(&mut rng)
        );
        let integrator = [
            "Direct(light_samples: 1)",
            "Path(max_depth: 4)",
            "Whitted(max_depth: 3, light_samples: 1)",
        ][case % 3];
        let text = format!(
            "Scene({} integrator: {integrator}, lights: [{light}], objects: [{object}, Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])",
            HEAD.replace(
                "camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40)",
                &camera
            )
        );
        if let Some(l) = load_tiny(&dir, &text) {
            assert_finite(&l, &text);
            rendered += 1;
        }
    }
    assert!(
        rendered >= 100,
        "only {rendered} of 300 generated scenes validated"
    );
}

/// Every shipped scene, at a tiny size: every pixel finite.
#[test]
fn shipped_scenes_render_finite_pixels() {
    for e in std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .flatten()
    {
        let p = e.path();
        if p.extension().is_none_or(|x| x != "ron") {
            continue;
        }
        let text = std::fs::read_to_string(&p).expect("read");
        let o = Overrides {
            size: Some((16, 16)),
            spp: Some(2),
            ..Default::default()
        };
        let l = load_str(&p, &text, &o).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
        assert_finite(&l, &p.display().to_string());
    }
}

/// 16,000 mistakes in one file are all reported, and printing them is
/// linear in their number (it took 25 s when each diagnostic re-indexed the
/// file's lines; the bound here is a hang guard, far above the real time).
#[test]
fn sixteen_thousand_errors_print_in_linear_time() {
    let objects: String = (0..16_000)
        .map(|i| format!("    Sphere(center: ({i}, 0, 0), radius: 1, material: \"nope{i}\"),\n"))
        .collect();
    let text = format!(
        "Scene(\n  camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n  lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],\n  objects: [\n{objects}  ],\n)"
    );
    let e = match load_str(Path::new("many.ron"), &text, &Overrides::default()) {
        Err(e) => e,
        Ok(_) => panic!("loaded"),
    };
    let r = e.report().expect("diagnostics");
    assert_eq!(r.diagnostics.len(), 16_000);
    let t = std::time::Instant::now();
    let printed = r.render(false);
    assert!(printed.contains("nope15999"));
    assert!(t.elapsed().as_secs() < 10, "printing took {:?}", t.elapsed());
}

/// A roulette depth of u32::MAX (minutes per sample) is refused, located.
#[test]
fn roulette_depth_has_an_upper_bound() {
    let text = "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), integrator: Path(max_depth: -1, rr_depth: 4294967295), lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))])";
    let e = load_str(Path::new("rr.ron"), text, &Overrides::default())
        .err()
        .expect("refused");
    let d = &e.report().expect("diagnostics").diagnostics;
    assert!(
        d.iter()
            .any(|d| d.path.as_deref() == Some("integrator.rr_depth") && d.line == 1),
        "{d:?}"
    );
}

/// `--threads 100000` is refused by the command line, before any thread
/// starts.
#[test]
fn thread_count_has_an_upper_bound() {
    let o = common::ronray(&[
        "render",
        "scenes/cornell.ron",
        "--threads",
        "100000",
        "-o",
        "/nonexistent/x.png",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("1..=1024"));
}

/// A PFM of `w`×`h` RGB pixels all `v` (bottom row first, little-endian).
fn pfm(w: u32, h: u32, v: f32) -> Vec<u8> {
    let mut b = format!("PF\n{w} {h}\n-1.0\n").into_bytes();
    for _ in 0..w * h * 3 {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

/// `diff` on a PFM whose header claims a huge size is an error, not an
/// overflow and an out-of-bounds index.
#[test]
fn diff_refuses_a_pfm_claiming_a_huge_size() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (a, b) = (dir.path().join("a.pfm"), dir.path().join("b.pfm"));
    let mut huge = b"PF\n4294967295 4294967295\n-1.0\n".to_vec();
    huge.extend_from_slice(&[0; 64]);
    std::fs::write(&a, huge).expect("write");
    std::fs::write(&b, pfm(2, 2, 0.5)).expect("write");
    let o = common::ronray(&["diff", a.to_str().expect("utf-8"), b.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("PFM"));
}

/// A NaN pixel makes the RMSE NaN: `--max-rmse` must fail, not pass.
#[test]
fn diff_gate_fails_on_a_nan_pixel() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (a, b) = (dir.path().join("a.pfm"), dir.path().join("b.pfm"));
    std::fs::write(&a, pfm(2, 2, f32::NAN)).expect("write");
    std::fs::write(&b, pfm(2, 2, 0.5)).expect("write");
    let o = common::ronray(&[
        "diff",
        a.to_str().expect("utf-8"),
        b.to_str().expect("utf-8"),
        "--max-rmse",
        "0.1",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `diff --heatmap` never overwrites one of the images it compares.
#[test]
fn diff_heatmap_does_not_overwrite_an_input() {
    let dir = tempfile::tempdir().expect("temp dir");
    let a = dir.path().join("a.png");
    let img = ronray::imageio::Image::new(2, 2);
    ronray::imageio::write_image(&img, &a).expect("write");
    let before = std::fs::read(&a).expect("read");
    let p = a.to_str().expect("utf-8");
    let o = common::ronray(&["diff", p, p, "--heatmap", p]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        std::fs::read(&a).expect("read"),
        before,
        "the input was rewritten"
    );
}

/// The output may not be a file the scene reads (here its own OBJ): it is
/// refused and the file is untouched.
#[test]
fn render_refuses_to_overwrite_an_input_of_the_scene() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::copy(
        root().join("tests/fixtures/hardening/block.obj"),
        dir.path().join("block.png"),
    )
    .expect("copy");
    let scene = dir.path().join("s.ron");
    std::fs::write(
        &scene,
        "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (width: 8, height: 8, spp: 1), materials: { \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }, lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))], objects: [Mesh(file: \"block.png\", material: \"m\")])",
    )
    .expect("write");
    let before = std::fs::read(dir.path().join("block.png")).expect("read");
    let o = common::ronray_in(dir.path(), &["render", "s.ron", "-o", "block.png"]);
    assert_eq!(o.status.code(), Some(1), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("which the scene reads"));
    assert_eq!(std::fs::read(dir.path().join("block.png")).expect("read"), before);
}

/// A scene's own `film.output` stays inside its folder: absolute paths and
/// `..` are located errors (the command line's `-o` may go anywhere).
#[test]
fn film_output_may_not_leave_the_scene_folder() {
    for out in ["/tmp/x.png", "../x.png", "a/../../x.png"] {
        let text = format!(
            "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (output: \"{out}\"), lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))])"
        );
        let e = load_str(Path::new("o.ron"), &text, &Overrides::default())
            .err()
            .expect("refused");
        let d = &e.report().expect("diagnostics").diagnostics;
        assert!(
            d.iter()
                .any(|d| d.path.as_deref() == Some("film.output") && d.message.contains("leaves")),
            "{out}: {d:?}"
        );
    }
}

/// CRC-32 (PNG's), for a hand-made header.
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in bytes {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A PNG whose header says `w`×`h` (8-bit RGB), with an empty data stream.
fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut out = vec![0x89];
    out.extend_from_slice(b"PNG\r\n\x1a\n");
    let mut chunk = |kind: &[u8], data: &[u8]| {
        out.extend_from_slice(&(data.len() as u32).to_be_bytes());
        let mut body = kind.to_vec();
        body.extend_from_slice(data);
        out.extend_from_slice(&body);
        out.extend_from_slice(&crc32(&body).to_be_bytes());
    };
    let mut ihdr = Vec::new();
    ihdr.extend_from_slice(&w.to_be_bytes());
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 2, 0, 0, 0]);
    chunk(b"IHDR", &ihdr);
    chunk(b"IDAT", &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]);
    chunk(b"IEND", &[]);
    out
}

/// An 11000 × 11000 texture (small on disk, 2.6 GB decoded) is refused from
/// its header, with a located error, before anything is decoded.
#[test]
fn a_huge_texture_is_refused_before_decoding() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("big.png"), png_header_only(11_000, 11_000)).expect("write");
    let text = "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), materials: { \"t\": Lambert(albedo: \"big.png\") }, lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))], objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"t\")])";
    let e = load_str(&dir.path().join("s.ron"), text, &Overrides::default())
        .err()
        .expect("refused");
    let d = &e.report().expect("diagnostics").diagnostics;
    assert!(
        d.iter().any(|d| d.message.contains("11000×11000") && d.line == 1),
        "{d:?}"
    );
}

/// CPU time of the calling thread, in nanoseconds (not the wall clock: the
/// machine may be busy with other work).
fn thread_cpu_ns() -> u128 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    assert_eq!(rc, 0, "clock_gettime");
    t.tv_sec as u128 * 1_000_000_000 + t.tv_nsec as u128
}

/// CPU time to load a scene with `n` errors of each kind (a material that
/// does not exist, a misspelt field) and print them, the best of two runs.
fn errors_work(n: usize) -> u128 {
    let objects: String = (0..n)
        .map(|i| {
            format!(
                "    Sphere(center: ({i}, 0, 0), radius: 1, material: \"nope{i}\"),\n    Sphere(centre: ({i}, 1, 0), radius: 1),\n"
            )
        })
        .collect();
    let text = format!(
        "Scene(\n  camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n  materials: {{ \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }},\n  lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],\n  objects: [\n{objects}  ],\n)"
    );
    (0..2)
        .map(|_| {
            let t = thread_cpu_ns();
            let e = match load_str(Path::new("many.ron"), &text, &Overrides::default()) {
                Err(e) => e,
                Ok(_) => panic!("loaded"),
            };
            let r = e.report().expect("diagnostics");
            let printed = r.render(false);
            let work = thread_cpu_ns() - t;
            assert!(
                r.diagnostics.len() >= n && printed.contains(&format!("nope{}", n - 1)),
                "{} diagnostics for {n} bad objects",
                r.diagnostics.len()
            );
            work
        })
        .min()
        .expect("two runs")
}

/// Loading and printing 64,000 mistakes costs about 4× what 16,000 do, not
/// 16× (each was located by scanning the file from its start, and a
/// misspelt field's path found by looking at every value in the file: 64k
/// took 5 minutes). Thread CPU time, best of two; the bound, 8×, is halfway
/// between linear and quadratic.
#[test]
fn sixty_four_thousand_errors_load_in_linear_time() {
    let (n, m) = (16_000, 64_000);
    let small = errors_work(n);
    let large = errors_work(m);
    let ratio = large as f64 / small as f64;
    assert!(
        ratio < 8.0,
        "{m} bad objects took {:.2} s of CPU, {n} took {:.2} s: {ratio:.1}× for 4× the errors (linear is 4×, quadratic 16×)",
        large as f64 * 1e-9,
        small as f64 * 1e-9
    );
}

/// Light selection weighs every directional light at every shading point,
/// so their number is bounded (`MAX_DIRECTIONAL_LIGHTS`): 64 load, 65 are
/// an error at `lights` that names the limit and how to merge them.
#[test]
fn directional_lights_are_bounded() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let scene = |n: usize| {
        let suns = (0..n)
            .map(|k| {
                format!(
                    "Directional(direction: ({}, -1, 0), irradiance: (0.1, 0.1, 0.1))",
                    k as f32 * 0.01
                )
            })
            .collect::<Vec<_>>()
            .join(", ");
        format!(
            r#"Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
            materials: {{ "m": Lambert(albedo: (0.5, 0.5, 0.5)) }},
            lights: [{suns}],
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "m")])"#
        )
    };
    let l = load_tiny(dir.path(), &scene(64)).expect("64 suns load");
    assert_finite(&l, "64 suns");
    match load_str(&dir.path().join("gen.ron"), &scene(65), &Overrides::default()) {
        Err(ronray::load::LoadError::Invalid(r)) => {
            let text = r.render(false);
            assert!(
                text.contains("65 directional lights") && text.contains("MAX_DIRECTIONAL_LIGHTS"),
                "{text}"
            );
        }
        Err(e) => panic!("not a located error: {e}"),
        Ok(_) => panic!("65 suns loaded"),
    }
}
