//! The `ronray` binary as a user drives it.

use crate::common;

use common::{ronray, ronray_in, root};
use std::path::{Path, PathBuf};

fn tempdir() -> tempfile::TempDir {
    tempfile::tempdir().expect("temp dir")
}

fn path_str(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

#[test]
fn render_is_identical_whatever_the_thread_count() {
    let dir = tempdir();
    let scene = root().join("scenes/cornell.ron");
    let (a, b) = (dir.path().join("t1.png"), dir.path().join("t2.exr"));
    let (c, d) = (dir.path().join("t1.exr"), dir.path().join("t2.png"));
    for (out, threads) in [(&a, "1"), (&d, "2"), (&c, "1"), (&b, "2")] {
        let o = ronray(&[
            "render",
            path_str(&scene),
            "-o",
            path_str(out),
            "--size",
            "48x40",
            "--spp",
            "4",
            "--threads",
            threads,
        ]);
        assert!(
            o.status.success(),
            "render failed: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
    let read = |p: &Path| std::fs::read(p).expect("output written");
    assert!(
        read(&a) == read(&d),
        "PNG bytes differ between --threads 1 and --threads 2"
    );
    assert!(
        read(&c) == read(&b),
        "EXR bytes differ between --threads 1 and --threads 2"
    );
}

#[test]
fn invalid_scene_leaves_existing_output_untouched() {
    let dir = tempdir();
    let out = dir.path().join("keep.png");
    std::fs::write(&out, b"previous image bytes").expect("write");
    let bad = root().join("tests/fixtures/broken/three_mistakes.ron");
    let o = ronray(&["render", path_str(&bad), "-o", path_str(&out)]);
    assert_eq!(o.status.code(), Some(1), "an invalid scene must exit with 1");
    assert_eq!(
        std::fs::read(&out).expect("still there"),
        b"previous image bytes",
        "output was modified"
    );
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("three_mistakes.ron:3:40") && err.contains("nothing was written"),
        "stderr:\n{err}"
    );
    let leftovers: Vec<_> = std::fs::read_dir(dir.path())
        .expect("dir")
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name() != "keep.png")
        .collect();
    assert!(leftovers.is_empty(), "temporary files left behind: {leftovers:?}");
}

#[test]
fn every_shipped_scene_validates() {
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 2, "expected the shipped scenes, found {scenes:?}");
    let args: Vec<&str> = std::iter::once("validate")
        .chain(scenes.iter().map(|p| path_str(p)))
        .collect();
    let o = ronray(&args);
    assert!(
        o.status.success(),
        "validate failed:\n{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

#[test]
fn validate_reports_failure_with_exit_code() {
    let bad = root().join("tests/fixtures/broken/unknown_material.ron");
    let o = ronray(&["validate", path_str(&bad)]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("did you mean `white`?"), "stderr:\n{err}");
}

#[test]
fn diff_reports_metrics_and_threshold() {
    let dir = tempdir();
    let scene = root().join("scenes/cornell.ron");
    let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
    for (out, seed) in [(&a, "1"), (&b, "2")] {
        let o = ronray(&[
            "render",
            path_str(&scene),
            "-o",
            path_str(out),
            "--size",
            "32x32",
            "--spp",
            "2",
            "--seed",
            seed,
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let same = ronray(&["diff", path_str(&a), path_str(&a), "--max-rmse", "0"]);
    assert!(same.status.success(), "an image equals itself");
    assert!(String::from_utf8_lossy(&same.stdout).contains("rmse     0.000000"));
    let heat = dir.path().join("heat.png");
    let differ = ronray(&[
        "diff",
        path_str(&a),
        path_str(&b),
        "--max-rmse",
        "1e-6",
        "--heatmap",
        path_str(&heat),
    ]);
    assert_eq!(
        differ.status.code(),
        Some(1),
        "different seeds differ: {}",
        String::from_utf8_lossy(&differ.stdout)
    );
    assert!(heat.exists(), "heat map written");
    let small = dir.path().join("small.png");
    let o = ronray(&[
        "render",
        path_str(&scene),
        "-o",
        path_str(&small),
        "--size",
        "16x16",
        "--spp",
        "1",
    ]);
    assert!(o.status.success());
    let sized = ronray(&["diff", path_str(&a), path_str(&small)]);
    assert_eq!(sized.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&sized.stderr).contains("sizes differ"));
}

/// `ronray new NAME` writes a commented starter scene that validates
/// without a warning and renders; it never replaces an existing file.
#[test]
fn new_writes_a_starter_scene_that_validates_and_renders() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    let o = ronray_in(d, &["new", "first"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(d.join("first.ron")).expect("first.ron written");
    assert!(
        text.contains("ronray render first.ron"),
        "the comments name the file:\n{text}"
    );
    for part in ["camera:", "lights:", "Plane(", "Sphere(", "// "] {
        assert!(text.contains(part), "starter has {part}:\n{text}");
    }
    let v = ronray_in(d, &["validate", "--deny-warnings", "first.ron"]);
    assert!(v.status.success(), "{}", String::from_utf8_lossy(&v.stderr));
    let r = ronray_in(
        d,
        &[
            "render",
            "first.ron",
            "--size",
            "64x36",
            "--spp",
            "4",
            "-o",
            "first.png",
        ],
    );
    assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
    let img = ronray::imageio::read_image(&d.join("first.png")).expect("rendered");
    let mean: f32 = img.pixels.iter().map(|p| p.x + p.y + p.z).sum::<f32>() / img.pixels.len() as f32;
    assert!(mean > 0.05, "the starter scene is lit (mean {mean})");
    let again = ronray_in(d, &["new", "first"]);
    assert_eq!(again.status.code(), Some(1), "an existing scene is not replaced");
    assert_eq!(std::fs::read_to_string(d.join("first.ron")).expect("read"), text);
    assert!(
        ronray::syntax::format(&text, false).is_ok_and(|f| f == text),
        "the starter is already formatted"
    );
}

#[test]
fn bench_scenes_renders_each_reference_twin_and_reports_its_error() {
    // A folder laid out like ../shared/refs: the 64² Cornell reference and
    // mask, and a reference with no ronray twin.
    let dir = tempdir();
    let refs = root().join("tests/fixtures/refs");
    std::fs::copy(
        refs.join("cornell_diffuse_64.pfm"),
        dir.path().join("cornell_diffuse_ref.pfm"),
    )
    .expect("copy");
    std::fs::copy(
        refs.join("cornell_diffuse_64.pfm"),
        dir.path().join("no_twin_ref.pfm"),
    )
    .expect("copy");
    let scenes = root().join("scenes");
    let o = ronray(&[
        "bench",
        "--scenes",
        path_str(dir.path()),
        "--ronray-scenes",
        path_str(&scenes),
        "--spp",
        "2,8",
        "--sampler",
        "Independent",
        "--threads",
        "2",
    ]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "bench failed: {}{out}",
        String::from_utf8_lossy(&o.stderr)
    );
    let rows: Vec<Vec<&str>> = out
        .lines()
        .filter(|l| l.starts_with("| cornell_diffuse |"))
        .map(|l| l.split('|').map(str::trim).collect())
        .collect();
    assert_eq!(rows.len(), 2, "one row per spp:\n{out}");
    // Columns: scene, sampler, spp, s, CPU s, Msamples/s, Mrays/s, RMSE, off light.
    let rmse = |r: &Vec<&str>| r[8].parse::<f64>().unwrap_or(f64::NAN);
    assert!(
        rmse(&rows[0]) > rmse(&rows[1]),
        "more samples, less error:\n{out}"
    );
    assert!(
        rows.iter().all(|r| r[9] == "no mask"),
        "no mask was given:\n{out}"
    );
    assert!(out.contains("| no_twin | no ronray scene"), "{out}");
}
