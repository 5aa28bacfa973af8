//! `ronray check`: golden-image regression checks.

mod common;

use common::{ronray_in, root};
use ronray::check::{DEFAULT_TOLERANCE, golden_error};
use ronray::imageio::read_image;

/// Every shipped scene matches its golden image (this is `ronray check
/// scenes`, run by `cargo test`).
#[test]
fn shipped_scenes_match_their_goldens() {
    let o = ronray_in(&root(), &["check", "scenes"]);
    assert!(
        o.status.success(),
        "regressions:\n{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The tolerance sits above the noise: a render with another seed passes.
#[test]
fn golden_tolerance_is_above_reseeded_noise() {
    for scene in [
        "cornell.ron",
        "cornell_specular.ron",
        "materials.ron",
        "bunny.ron",
    ] {
        let render = |seed: &str| {
            let dir = tempfile::tempdir().expect("tmp");
            let out = dir.path().join("x.png");
            let path = root().join("scenes").join(scene);
            let size = if scene == "materials.ron" {
                "64x36"
            } else {
                "64x64"
            };
            let args = [
                "render",
                path.to_str().expect("utf-8"),
                "-o",
                out.to_str().expect("utf-8"),
                "--size",
                size,
            ];
            let spp = if scene == "cornell_specular.ron" {
                "64"
            } else {
                "16"
            };
            let o = ronray_in(&root(), &[&args[..], &["--spp", spp, "--seed", seed]].concat());
            assert!(o.status.success());
            read_image(&out).expect("png")
        };
        let e = golden_error(&render("0"), &render("7")).expect("same size");
        println!("{scene}: re-seeded error {e:.5}");
        assert!(
            e < 0.5 * DEFAULT_TOLERANCE as f64,
            "{scene}: noise alone scores {e:.5}, too close to the tolerance"
        );
    }
}

/// A one-material change is caught, the unchanged scene passes, and
/// `--bless` rewrites only the failed golden.
#[test]
fn check_catches_material_change_and_bless_rewrites_only_failures() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    std::fs::create_dir_all(d.join("assets")).expect("mkdir");
    std::fs::create_dir_all(d.join("scenes")).expect("mkdir");
    for f in ["tall_block.obj", "short_block.obj"] {
        std::fs::copy(root().join("assets").join(f), d.join("assets").join(f)).expect("copy");
    }
    let cornell = std::fs::read_to_string(root().join("scenes/cornell.ron")).expect("scene");
    std::fs::write(d.join("scenes/a.ron"), &cornell).expect("write");
    std::fs::write(d.join("scenes/b.ron"), &cornell).expect("write");

    let first = ronray_in(d, &["check", "scenes"]);
    assert_eq!(first.status.code(), Some(1), "missing goldens fail");
    assert!(String::from_utf8_lossy(&first.stdout).contains("MISSING"));
    assert!(ronray_in(d, &["check", "scenes", "--bless"]).status.success());
    assert!(
        ronray_in(d, &["check", "scenes"]).status.success(),
        "blessed goldens pass"
    );

    // One material of b changes colour: red wall → blue.
    let changed = cornell.replace("0.570068, 0.0430135, 0.0443706", "0.05, 0.05, 0.6");
    assert_ne!(changed, cornell);
    std::fs::write(d.join("scenes/b.ron"), changed).expect("write");
    let golden_a = std::fs::read(d.join("scenes/golden/a.png")).expect("golden a");
    let golden_b = std::fs::read(d.join("scenes/golden/b.png")).expect("golden b");
    let o = ronray_in(d, &["check", "scenes"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "the change must be caught:\n{out}");
    assert!(
        out.lines().any(|l| l.contains("a.ron") && l.contains(" ok ")),
        "a passes:\n{out}"
    );
    assert!(
        out.lines().any(|l| l.contains("b.ron") && l.contains("FAIL")),
        "b fails:\n{out}"
    );
    assert!(d.join("scenes/golden/b.new.png").exists() && d.join("scenes/golden/b.diff.png").exists());

    // Touch a's golden time stamp reference, then bless.
    let before_a = std::fs::metadata(d.join("scenes/golden/a.png"))
        .and_then(|m| m.modified())
        .expect("mtime");
    std::thread::sleep(std::time::Duration::from_millis(20));
    assert!(ronray_in(d, &["check", "scenes", "--bless"]).status.success());
    let after_a = std::fs::metadata(d.join("scenes/golden/a.png"))
        .and_then(|m| m.modified())
        .expect("mtime");
    assert_eq!(before_a, after_a, "a passing golden must not be rewritten");
    assert_eq!(std::fs::read(d.join("scenes/golden/a.png")).expect("a"), golden_a);
    assert_ne!(
        std::fs::read(d.join("scenes/golden/b.png")).expect("b"),
        golden_b,
        "b's golden was rewritten"
    );
    assert!(
        !d.join("scenes/golden/b.new.png").exists(),
        "by-products are cleaned up"
    );
    assert!(ronray_in(d, &["check", "scenes"]).status.success());
}
