//! `ronray check`: golden-image regression checks.

mod common;

use common::{ronray_in, root};
use ronray::check::{golden_path, render_test, score};
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

/// The tolerance sits above the noise: every shipped scene rendered with
/// another seed scores well under it against its golden.
#[test]
fn golden_tolerance_is_above_reseeded_noise() {
    let scenes = ronray::check::collect(&[root().join("scenes")]).expect("scenes/");
    assert!(scenes.len() >= 8, "{} scenes", scenes.len());
    let mut worst = (0.0f64, String::new());
    for scene in &scenes {
        let name = scene
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("?")
            .to_string();
        let golden = read_image(&golden_path(scene)).expect("golden");
        let (img, t) = render_test(scene, None, &["test.seed=7".into()]).expect("renders");
        let s = score(&img, &golden).expect("same size");
        println!(
            "{name}: re-seeded score {:.3} (whole-image relMSE {:.5})",
            s.worst, s.whole
        );
        assert!(
            s.worst < 0.6 * t.tolerance as f64,
            "{name}: noise alone scores {:.3}, too close to the tolerance {}",
            s.worst,
            t.tolerance
        );
        if s.worst > worst.0 {
            worst = (s.worst, name);
        }
    }
    println!("largest re-seeded score: {:.3} ({})", worst.0, worst.1);
}

/// A folder with the Cornell box plus one small red sphere on the floor
/// (radius 0.2 in a 2-unit box: about 6 pixels across in a 64-pixel test
/// render), its golden blessed; returns the folder and the scene text.
fn small_sphere_scene() -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    std::fs::create_dir_all(d.join("assets")).expect("mkdir");
    std::fs::create_dir_all(d.join("scenes")).expect("mkdir");
    for f in ["tall_block.obj", "short_block.obj"] {
        std::fs::copy(root().join("assets").join(f), d.join("assets").join(f)).expect("copy");
    }
    let cornell = std::fs::read_to_string(root().join("scenes/cornell.ron")).expect("scene");
    let tall = "        Mesh(file: \"../assets/tall_block.obj\"";
    assert!(cornell.contains(tall));
    let text = cornell.replace(
        tall,
        &format!("        Sphere(center: (-0.45, -0.8, 0.55), radius: 0.2, material: \"red\"),\n{tall}"),
    );
    std::fs::write(d.join("scenes/ball.ron"), &text).expect("write");
    let o = ronray_in(d, &["check", "scenes", "--bless"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (dir, text)
}

/// Runs `check scenes` on `changed` text and returns (exit code, stdout).
fn check_changed(dir: &std::path::Path, changed: &str) -> (Option<i32>, String) {
    std::fs::write(dir.join("scenes/ball.ron"), changed).expect("write");
    let o = ronray_in(dir, &["check", "scenes"]);
    (o.status.code(), String::from_utf8_lossy(&o.stdout).into_owned())
}

/// The regression a whole-image mean missed: the small sphere recoloured
/// from red to green. It fails, and the summary links an HTML page showing
/// the new render, the golden and the difference.
#[test]
fn check_fails_a_small_sphere_recoloured() {
    let (dir, text) = small_sphere_scene();
    let recoloured = text.replace(
        "radius: 0.2, material: \"red\"",
        "radius: 0.2, material: \"green\"",
    );
    assert_ne!(recoloured, text);
    let (code, out) = check_changed(dir.path(), &recoloured);
    println!("{out}");
    assert_eq!(code, Some(1), "the recoloured sphere must fail:\n{out}");
    let page = dir.path().join("scenes/golden/ball.html");
    assert!(
        out.contains("report: ") && out.contains("ball.html"),
        "summary links the report:\n{out}"
    );
    let html = std::fs::read_to_string(&page).expect("report page");
    for img in ["ball.new.png", "ball.png", "ball.diff.png"] {
        assert!(
            html.contains(&format!("src=\"{img}\"")),
            "report shows {img}:\n{html}"
        );
        assert!(
            dir.path().join("scenes/golden").join(img).exists(),
            "{img} written"
        );
    }
}

/// The other regression: the same sphere at half its radius.
#[test]
fn check_fails_a_small_sphere_at_half_radius() {
    let (dir, text) = small_sphere_scene();
    let shrunk = text.replace(
        "center: (-0.45, -0.8, 0.55), radius: 0.2",
        "center: (-0.45, -0.9, 0.55), radius: 0.1",
    );
    assert_ne!(shrunk, text);
    let (code, out) = check_changed(dir.path(), &shrunk);
    println!("{out}");
    assert_eq!(code, Some(1), "the half-size sphere must fail:\n{out}");
    // Restored, the scene passes again and the by-products are removed.
    let (code, out) = check_changed(dir.path(), &text);
    assert_eq!(code, Some(0), "{out}");
    assert!(!dir.path().join("scenes/golden/ball.html").exists());
}

/// `--set` changes the scene (and its test settings) for the check only;
/// `--tolerance` replaces the scene's.
#[test]
fn check_set_and_tolerance_apply() {
    let (dir, _) = small_sphere_scene();
    let d = dir.path();
    let reseeded = ronray_in(d, &["check", "scenes", "--set", "test.seed=7"]);
    let out = String::from_utf8_lossy(&reseeded.stdout);
    assert!(reseeded.status.success(), "re-seeded passes:\n{out}");
    let strict = ronray_in(
        d,
        &["check", "scenes", "--set", "test.seed=7", "--tolerance", "0.0001"],
    );
    let out = String::from_utf8_lossy(&strict.stdout);
    assert_eq!(
        strict.status.code(),
        Some(1),
        "noise is over a tiny tolerance:\n{out}"
    );
    assert!(out.contains("0.0001"), "the tolerance given is shown:\n{out}");
    let recoloured = ronray_in(
        d,
        &["check", "scenes", "--set", "materials.red.albedo=(0.1, 0.4, 0.1)"],
    );
    assert_eq!(
        recoloured.status.code(),
        Some(1),
        "a --set recolour fails the check"
    );
    let bad = ronray_in(d, &["check", "scenes", "--set", "film.spq=3"]);
    assert_eq!(bad.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("spp"),
        "a misspelt --set gets a suggestion"
    );
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
