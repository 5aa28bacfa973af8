//! Commands that used to lose a file, do nothing silently or abort (issue
//! 13): `check` with a corrupt or wrong-size golden, `gallery` with two
//! scenes of one name or a zero width, numeric flags at 0, NaN or huge,
//! a film larger than the machine's memory, Ctrl-C during a render.

use crate::common;

use common::ronray_in;
use std::path::Path;

/// A tiny scene (8×8 test render) in `dir/scenes/<name>.ron`.
fn tiny_scene(dir: &Path, sub: &str, name: &str) {
    let folder = dir.join(sub);
    std::fs::create_dir_all(&folder).expect("mkdir");
    std::fs::write(
        folder.join(format!("{name}.ron")),
        "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (width: 16, height: 16, spp: 1), test: (width: 8, spp: 1), materials: { \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }, lights: [Point(position: (0, 3, 0), intensity: (5, 5, 5))], objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])",
    )
    .expect("write");
}

fn text(o: &std::process::Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

/// A golden that does not decode, or has another size, is a failure named
/// for what it is (not "missing"); `--bless` keeps it unless `--force`.
#[test]
fn check_reports_a_corrupt_or_wrong_size_golden_and_bless_keeps_it() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    tiny_scene(d, "scenes", "s");
    std::fs::create_dir_all(d.join("scenes/golden")).expect("mkdir");
    let golden = d.join("scenes/golden/s.png");
    let wrong = ronray::imageio::Image::new(5, 3);
    for (bytes, expect) in [
        (b"not a png at all".to_vec(), "corrupt golden"),
        (
            {
                ronray::imageio::write_image(&wrong, &golden).expect("write");
                std::fs::read(&golden).expect("read")
            },
            "golden is 5×3, render is 8×8",
        ),
    ] {
        std::fs::write(&golden, &bytes).expect("write");
        let o = ronray_in(d, &["check", "scenes"]);
        assert_eq!(o.status.code(), Some(1), "{}", text(&o));
        assert!(
            text(&o).contains(expect) && !text(&o).contains("MISSING"),
            "{}",
            text(&o)
        );
        let o = ronray_in(d, &["check", "scenes", "--bless"]);
        assert_eq!(o.status.code(), Some(1), "bless refuses: {}", text(&o));
        assert!(text(&o).contains("--force"), "{}", text(&o));
        assert_eq!(
            std::fs::read(&golden).expect("read"),
            bytes,
            "the golden was kept"
        );
    }
    let o = ronray_in(d, &["check", "scenes", "--bless", "--force"]);
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        ronray_in(d, &["check", "scenes"]).status.success(),
        "the forced golden passes"
    );
}

/// Two scenes of one name in different folders would write one gallery
/// image: refused before rendering, naming both.
#[test]
fn gallery_refuses_two_scenes_of_the_same_name() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    tiny_scene(d, "a", "room");
    tiny_scene(d, "b", "room");
    let o = ronray_in(d, &["gallery", "a", "b", "--out", "g", "--width", "8"]);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    assert!(
        text(&o).contains("a/room.ron") && text(&o).contains("b/room.ron"),
        "{}",
        text(&o)
    );
    assert!(!d.join("g/room.png").exists(), "nothing was rendered");
}

/// Numeric flags that would do nothing or pass everything are refused:
/// `gallery --width 0`, `check --tolerance` NaN/0/negative, `diff
/// --max-rmse NaN`, `--threads 0`, a huge `--size`.
#[test]
fn numeric_flags_refuse_zero_nan_and_huge_values() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    tiny_scene(d, "scenes", "s");
    let img = ronray::imageio::Image::new(2, 2);
    ronray::imageio::write_image(&img, &d.join("x.png")).expect("write");
    let cases: &[&[&str]] = &[
        &["gallery", "scenes", "--out", "g", "--width", "0"],
        &["gallery", "scenes", "--out", "g", "--width", "99999"],
        &["gallery", "scenes", "--out", "g", "--width", "8", "--spp", "0"],
        &["check", "scenes", "--tolerance", "NaN"],
        &["check", "scenes", "--tolerance", "0"],
        &["check", "scenes", "--tolerance", "-1"],
        &["diff", "x.png", "x.png", "--max-rmse", "NaN"],
        &["diff", "x.png", "x.png", "--max-rmse", "-1"],
        &["render", "scenes/s.ron", "--threads", "0"],
        &["render", "scenes/s.ron", "--size", "0x8"],
        &["render", "scenes/s.ron", "--size", "99999x8"],
        &["render", "scenes/s.ron", "--spp", "0"],
        &["render", "scenes/s.ron", "--max-memory", "0"],
    ];
    for args in cases {
        let o = ronray_in(d, args);
        assert!(
            !o.status.success() && !o.stderr.is_empty(),
            "{args:?} must fail with a message: {}",
            text(&o)
        );
    }
    assert!(!d.join("g").exists());
}

/// The largest film the loader accepts needs far more memory than a small
/// machine has: refused before allocating, with the estimate, the limit
/// and how to raise it (here the limit is `--max-memory`, so the test does
/// not depend on the machine).
#[test]
fn a_film_larger_than_memory_is_refused_before_allocating() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    tiny_scene(d, "scenes", "s");
    let o = ronray_in(
        d,
        &[
            "render",
            "scenes/s.ron",
            "--size",
            "16384x16384",
            "--max-memory",
            "1",
            "-o",
            "big.png",
        ],
    );
    let t = text(&o);
    assert_eq!(o.status.code(), Some(1), "{t}");
    assert!(
        t.contains("16384×16384") && t.contains("GiB") && t.contains("--max-memory"),
        "{t}"
    );
    assert!(!d.join("big.png").exists());
    let o = ronray_in(
        d,
        &["render", "scenes/s.ron", "--max-memory", "1", "-o", "small.png"],
    );
    assert!(o.status.success(), "{}", text(&o));
}

/// Ctrl-C during a render: the process stops with 130 and leaves no
/// temporary file (the write itself is covered in `imageio/write.rs`).
#[test]
fn an_interrupted_render_leaves_no_temporary_file() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    tiny_scene(d, "scenes", "s");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_ronray"))
        .args([
            "render",
            "scenes/s.ron",
            "--size",
            "2048x2048",
            "--spp",
            "64",
            "-o",
            "out.exr",
        ])
        .current_dir(d)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("spawn");
    std::thread::sleep(std::time::Duration::from_millis(300));
    let kill = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(kill.success());
    let status = child.wait().expect("wait");
    assert_eq!(status.code(), Some(130), "{status:?}");
    let left: Vec<_> = std::fs::read_dir(d)
        .expect("list")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".ronray-") || n == "out.exr")
        .collect();
    assert!(left.is_empty(), "{left:?}");
}
