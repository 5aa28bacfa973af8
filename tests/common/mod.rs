//! Helpers shared by the end-to-end tests: the crate root, the `ronray`
//! binary, loading scene text and rendering it. The integration binary
//! (`tests/main.rs`) and the two on their own (`fuzz_corpus`, `denoise`)
//! each use a different subset, hence the `dead_code` allowance.
#![allow(dead_code)]

use glam::Vec3A;
use ronray::frame::{RenderOptions, render_whole};
use ronray::imageio::Image;
use ronray::integrators::Counters;
use ronray::load::{LoadError, Loaded, Overrides, load_str};
use ronray::math::{Ray, SampleRng};
use ronray::sampler::Sampler;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs the `ronray` binary in `dir`.
pub fn ronray_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ronray"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the ronray binary runs")
}

/// As [`ronray_in`], but a run that has not ended after `limit` is killed
/// and the test fails saying so: a regression to a hang (a FIFO read, a
/// pipe waited on) fails instead of stopping the test run.
pub fn ronray_within(dir: &Path, args: &[&str], limit: std::time::Duration) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_ronray"));
    cmd.args(args);
    run_within(cmd, dir, args, limit)
}

/// As [`ronray_within`], with the process's address space capped at
/// `gib` GiB (`ulimit -v`): a regression that sizes an allocation from a
/// hostile header then fails at once (an abort) instead of taking the
/// shared machine's memory.
pub fn ronray_within_memory(dir: &Path, args: &[&str], limit: std::time::Duration, gib: u64) -> Output {
    let mut cmd = Command::new("sh");
    cmd.arg("-c")
        .arg(format!("ulimit -v {} && exec \"$0\" \"$@\"", gib << 20))
        .arg(env!("CARGO_BIN_EXE_ronray"))
        .args(args);
    run_within(cmd, dir, args, limit)
}

/// Runs `cmd` in `dir`, killed and failed after `limit` (`args` name it).
fn run_within(mut cmd: Command, dir: &Path, args: &[&str], limit: std::time::Duration) -> Output {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = cmd
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the ronray binary runs");
    // Each pipe drained on its own thread, so a chatty child never blocks.
    let drain = |r: Option<Box<dyn Read + Send>>| {
        std::thread::spawn(move || {
            let mut v = Vec::new();
            if let Some(mut r) = r {
                let _ = r.read_to_end(&mut v);
            }
            v
        })
    };
    let out = drain(child.stdout.take().map(|r| Box::new(r) as Box<dyn Read + Send>));
    let err = drain(child.stderr.take().map(|r| Box::new(r) as Box<dyn Read + Send>));
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("wait") {
            break s;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "`ronray {}` did not end within {limit:?}: it hangs",
                args.join(" ")
            );
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
    }
}

/// Runs the `ronray` binary in the repository root.
pub fn ronray(args: &[&str]) -> Output {
    ronray_in(&root(), args)
}

/// A load error as the user sees it: the rendered report, or the message.
pub fn message(e: &LoadError) -> String {
    e.report().map_or_else(|| e.to_string(), |r| r.render(false))
}

/// Loads scene text as if it were the file `dir/test.ron`, panicking with
/// the report.
pub fn load_in(dir: &Path, text: &str, overrides: &Overrides) -> Loaded {
    load_str(&dir.join("test.ron"), text, overrides)
        .unwrap_or_else(|e| panic!("test scene must load: {}\n{text}", message(&e)))
}

/// [`load_in`] the repository root, without overrides.
pub fn load_text(text: &str) -> Loaded {
    load_in(&root(), text, &Overrides::default())
}

/// An enclosure (the cube [−1, 1]³) whose six walls all emit radiance 1
/// and reflect with `material`, seen from inside: radiance 1/(1 − ρ)
/// everywhere for a diffuse albedo ρ.
pub fn furnace(material: &str) -> String {
    // Inward-facing walls: half_u × half_v points in.
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
            format!(r#"Rect(center: {c}, half_u: {u}, half_v: {v}, radiance: (1, 1, 1), material: "wall")"#)
        })
        .collect();
    format!(
        r#"Scene(
        camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 60),
        integrator: Path(max_depth: -1, rr_depth: 5),
        materials: {{ "wall": {material} }},
        lights: [{}],
    )"#,
        lights.join(", ")
    )
}

/// A loaded scene's warnings and notes, one message a line.
pub fn notes_text(l: &Loaded) -> String {
    l.warnings
        .diagnostics
        .iter()
        .map(|d| d.message.clone())
        .collect::<Vec<_>>()
        .join("\n")
}

/// Renders a loaded scene with default options; every pixel must be finite.
pub fn render_loaded(l: &Loaded) -> Image {
    let img = render_whole(&l.scene, &l.view, &RenderOptions::default()).0;
    assert!(
        img.pixels.iter().all(|p| p.is_finite()),
        "a render has NaN or infinite pixels"
    );
    img
}

/// Mean radiance along `ray` over `n` independent estimates of the scene's
/// integrator, with a fixed seed.
pub fn mean_li(l: &Loaded, ray: Ray, n: u32) -> Vec3A {
    let mut sum = Vec3A::ZERO;
    let mut c = Counters::default();
    for i in 0..n {
        let mut sampler = Sampler::independent(SampleRng::for_sample(0, 0, i, 99));
        sum += l.view.integrator.li(&l.scene, &ray, &mut sampler, &mut c);
    }
    sum / n as f32
}

/// The path of `tool` on `PATH`. When it is missing, the calling test is
/// skipped: this says so on the terminal (past the test harness's capture,
/// so a plain `cargo test` shows it) with how to install the tool, and
/// returns `None` — unless `RONRAY_REQUIRE_TOOLS=1` (set by `.ci/run`, which
/// installs every tool) makes a missing tool a failure.
pub fn tool_or_skip(tool: &str, test: &str, install: &str) -> Option<PathBuf> {
    let found = std::env::var_os("PATH")
        .iter()
        .flat_map(std::env::split_paths)
        .map(|d| d.join(tool))
        .find(|p| p.is_file());
    if found.is_none() {
        skip_or_fail(
            test,
            &format!("`{tool}` is not installed ({install})"),
            "install it to run this test",
        );
    }
    found
}

/// Reports that `test` cannot run because of `why`: on the terminal (past
/// the harness's capture) with `remedy`, or as a failure when
/// `RONRAY_REQUIRE_TOOLS=1` says every tool and service must be there.
pub fn skip_or_fail(test: &str, why: &str, remedy: &str) {
    use std::io::Write;
    if std::env::var("RONRAY_REQUIRE_TOOLS").as_deref() == Ok("1") {
        panic!("{test}: {why}, and RONRAY_REQUIRE_TOOLS=1 requires it");
    }
    let _ = writeln!(std::io::stderr(), "skipped {test}: {why}; {remedy}");
}

/// Prints a line past the test harness's capture (measured figures).
pub fn report(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// Sum of a pixel's channels, in f64.
pub fn sum(p: &ronray::math::Rgb) -> f64 {
    f64::from(p.x + p.y + p.z)
}

/// Mean channel sum of each `q` × `q` block of a `w`-wide image, row-major:
/// for region-by-region comparisons.
pub fn blocks(px: &[ronray::math::Rgb], w: usize, q: usize) -> Vec<f64> {
    let h = px.len() / w;
    let mut out = vec![0.0; (w / q) * (h / q)];
    for (i, p) in px.iter().enumerate() {
        let (x, y) = (i % w, i / w);
        out[(y / q) * (w / q) + x / q] += sum(p) / (q * q) as f64;
    }
    out
}

/// The bar `tests/reference.rs` holds renders to against a (nearly exact)
/// reference, for two renders `a` and `b` of the same scene at different
/// seeds: over the pixels not in `skip`, and over all pixels, the RMSE of
/// `a` against the reference within 1.1 × its own noise (RMSE(a, b)/√2)
/// plus 0.002; every 8 × 8 block within [`check_blocks`]'s tolerance; each
/// channel's image mean within `mean_rel` of the reference's. An unbiased
/// renderer's error against the reference is its own noise; bias shows up
/// as error in excess of it.
pub fn reference_bar(
    label: &str,
    a: &ronray::imageio::Image,
    b: &ronray::imageio::Image,
    reference: &ronray::imageio::Image,
    skip: Option<&[bool]>,
    mean_rel: f64,
) {
    use ronray::imageio::compare;
    let sets: &[(&str, Option<&[bool]>)] = match skip {
        Some(s) => &[("all pixels", None), ("off the light", Some(s))],
        None => &[("all pixels", None)],
    };
    for (which, skip) in sets {
        let err = compare(a, reference, *skip).expect("same size").rmse;
        let noise = compare(a, b, *skip).expect("same size").rmse / 2f64.sqrt();
        // Reference noise at 64² is ~0.0006 for the Mitsuba references;
        // allow for it and for the spread of the noise estimate itself.
        let bound = 1.1 * noise + 0.002;
        assert!(
            err <= bound,
            "{label} ({which}): RMSE vs the reference {err:.5} exceeds 1.1 × own noise {noise:.5} + 0.002 — biased?"
        );
    }
    check_blocks(label, a, b, reference);
    let c = compare(a, reference, None).expect("same size");
    for ch in 0..3 {
        // Half of the image mean's own noise at this spp is far below 1%.
        let rel = (c.mean_a[ch] - c.mean_b[ch]).abs() / c.mean_b[ch];
        assert!(
            rel < mean_rel,
            "{label}: channel {ch} mean {:.5} vs reference {:.5} (tolerance {mean_rel})",
            c.mean_a[ch],
            c.mean_b[ch]
        );
    }
}

/// Block side in pixels for the regional check.
pub const BLOCK: usize = 8;
/// Blocks whose reference mean (every channel) is below this are too dark to
/// judge relatively; their absolute error is within the noise term anyway.
pub const TINY: f64 = 1e-3;

/// Every 8 × 8 block's mean, per channel, averaged over the two independent
/// renders `a` and `b`, must be within 4σ + 3% of the reference mean + 0.001.
/// σ is the noise of that average, estimated from the per-pixel differences
/// of `a` and `b`: Var(pixel of (a+b)/2) = E[(a − b)²]/4, and a block mean
/// of n pixels has Σ Var / n². The 3% covers the reference's own noise and
/// the heavy tail of caustic noise (a block under the glass sphere of
/// `cornell_specular` strayed 11% at 64 spp with one render and converges to
/// the reference within 0.2% at 4096); a region at half its brightness fails.
pub fn check_blocks(
    label: &str,
    a: &ronray::imageio::Image,
    b: &ronray::imageio::Image,
    reference: &ronray::imageio::Image,
) {
    use ronray::imageio::{Image, blocks};
    let mean_ab = Image {
        width: a.width,
        height: a.height,
        pixels: a
            .pixels
            .iter()
            .zip(&b.pixels)
            .map(|(x, y)| 0.5 * (*x + *y))
            .collect(),
    };
    let vs_ref = blocks(&mean_ab, reference, BLOCK).expect("same size");
    let noise = blocks(a, b, BLOCK).expect("same size");
    let mut bad = Vec::new();
    for (r, n) in vs_ref.iter().zip(&noise) {
        if r.mean_b.iter().all(|&m| m < TINY) {
            continue;
        }
        for ch in 0..3 {
            let sigma = n.sum_sq_diff[ch].sqrt() / (2.0 * r.pixels as f64);
            let tol = 4.0 * sigma + 0.03 * r.mean_b[ch] + 0.001;
            let err = (r.mean_a[ch] - r.mean_b[ch]).abs();
            if err > tol {
                bad.push(format!(
                    "block at ({}, {}) channel {ch}: {:.5} vs reference {:.5} (tolerance {tol:.5})",
                    r.x, r.y, r.mean_a[ch], r.mean_b[ch]
                ));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "{label}: {} block(s) off the reference:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// [`check_blocks`]'s bar on the pixels `skip` leaves (a block keeps its
/// kept pixels; one with fewer than a quarter kept is not judged): the
/// blocks off the reference, described, or none.
pub fn masked_blocks_off(
    a: &ronray::imageio::Image,
    b: &ronray::imageio::Image,
    reference: &ronray::imageio::Image,
    skip: &[bool],
) -> Vec<String> {
    let (w, h) = (a.width as usize, a.height as usize);
    let mut bad = Vec::new();
    for by in (0..h).step_by(BLOCK) {
        for bx in (0..w).step_by(BLOCK) {
            let kept: Vec<usize> = (by..(by + BLOCK).min(h))
                .flat_map(|y| (bx..(bx + BLOCK).min(w)).map(move |x| y * w + x))
                .filter(|&i| !skip[i])
                .collect();
            if kept.len() * 4 < BLOCK * BLOCK {
                continue;
            }
            let n = kept.len() as f64;
            for ch in 0..3 {
                let get = |img: &ronray::imageio::Image, i: usize| f64::from(img.pixels[i][ch]);
                let mean_ab = kept.iter().map(|&i| 0.5 * (get(a, i) + get(b, i))).sum::<f64>() / n;
                let mean_ref = kept.iter().map(|&i| get(reference, i)).sum::<f64>() / n;
                if mean_ref < TINY {
                    continue;
                }
                let sum_sq: f64 = kept.iter().map(|&i| (get(a, i) - get(b, i)).powi(2)).sum();
                let sigma = sum_sq.sqrt() / (2.0 * n);
                let tol = 4.0 * sigma + 0.03 * mean_ref + 0.001;
                if (mean_ab - mean_ref).abs() > tol {
                    bad.push(format!(
                        "block at ({bx}, {by}) channel {ch}: {mean_ab:.5} vs reference {mean_ref:.5} (tolerance {tol:.5})"
                    ));
                }
            }
        }
    }
    bad
}

/// Each number of scene text `seed` (loaded as a file in `dir`) replaced
/// in turn by one of −1, 0, 1e30, −0.0, 1e-30, 2, inf or NaN: every
/// variant must load or be refused without a panic, and every one that
/// loads must render finite pixels (8 × 8, 2 spp). Returns how many
/// numbers, and how many variants loaded and were refused.
pub fn hostile_number_sweep(seed: &str, dir: &Path) -> (usize, usize, usize) {
    // Each number token's byte range.
    let bytes = seed.as_bytes();
    let mut numbers = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_digit() && (i == 0 || !bytes[i - 1].is_ascii_alphanumeric()) {
            let start = if i > 0 && bytes[i - 1] == b'-' { i - 1 } else { i };
            let mut end = i;
            while end < bytes.len() && (bytes[end].is_ascii_digit() || bytes[end] == b'.') {
                end += 1;
            }
            numbers.push((start, end));
            i = end;
        } else {
            i += 1;
        }
    }
    let (mut loaded, mut refused) = (0, 0);
    for (k, &(start, end)) in numbers.iter().enumerate() {
        let hostile = ["-1", "0", "1e30", "-0.0", "1e-30", "2", "inf", "NaN"][k % 8];
        let text = format!("{}{hostile}{}", &seed[..start], &seed[end..]);
        let o = Overrides {
            spp: Some(2),
            size: Some((8, 8)),
            ..Default::default()
        };
        match load_str(&dir.join("test.ron"), &text, &o) {
            Ok(l) => {
                loaded += 1;
                let img = render_whole(&l.scene, &l.view, &Default::default()).0;
                assert!(
                    img.pixels.iter().all(|p| p.is_finite()),
                    "{hostile} at byte {start}: non-finite pixels"
                );
            }
            Err(_) => refused += 1,
        }
    }
    (numbers.len(), loaded, refused)
}
