//! Files that are not what a scene says they are (issue 13): a FIFO or a
//! device as OBJ or MTL, an OBJ at the edge of `f32`, non-ASCII text in an
//! include or a JSON scene, one texture spelled two ways, a batch with one
//! hostile scene. None may block, abort, panic or cost a summary.

mod common;

use common::{ronray_in, root};
use ronray::load::{Overrides, load_str};
use std::path::Path;
use std::time::{Duration, Instant};

const HEAD: &str = r#"camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (width: 8, height: 8, spp: 1),
    materials: { "m": Lambert(albedo: (0.5, 0.5, 0.5)) },
    lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],"#;

fn mkfifo(p: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(p)
        .status()
        .expect("mkfifo");
    assert!(ok.success());
}

/// A FIFO or `/dev/zero` as an OBJ, and a FIFO as its MTL: refused at once
/// (a FIFO would block for ever, `/dev/zero` aborted on a 4 GiB allocation).
#[test]
fn a_fifo_or_device_as_obj_or_mtl_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    mkfifo(&d.join("pipe.obj"));
    mkfifo(&d.join("pipe.mtl"));
    let obj = std::fs::read_to_string(root().join("tests/fixtures/hardening/block.obj")).expect("read");
    std::fs::write(d.join("uses_pipe.obj"), format!("mtllib pipe.mtl\n{obj}")).expect("w");
    let t0 = Instant::now();
    for file in ["pipe.obj", "/dev/zero"] {
        let text = format!("Scene({HEAD} objects: [Mesh(file: \"{file}\", material: \"m\")])");
        let e = load_str(&d.join("s.ron"), &text, &Overrides::default()).err();
        let shown = e.as_ref().map(common::message).unwrap_or_default();
        assert!(shown.contains("not a regular file"), "{file}: {shown}");
    }
    for data in [
        ronray::geometry::obj::load_obj_data(Path::new("/dev/zero")).err(),
        ronray::geometry::obj::load_obj_data(&d.join("pipe.obj")).err(),
    ] {
        assert!(data.is_some_and(|e| e.contains("not a regular file")));
    }
    // The MTL is a FIFO: the mesh loads with a note, without blocking.
    let loaded = ronray::geometry::obj::load_obj_data(&d.join("uses_pipe.obj")).expect("loads");
    assert!(
        loaded.warnings.iter().any(|w| w.contains("not a regular file")),
        "{:?}",
        loaded.warnings
    );
    assert!(
        t0.elapsed() < Duration::from_secs(10),
        "blocked for {:?}",
        t0.elapsed()
    );
}

/// `bench` on an OBJ whose vertices are near ±3e38 (the BVH once indexed an
/// empty slot with the non-finite rays it made): no panic.
#[test]
fn bench_survives_an_obj_at_the_edge_of_f32() {
    let dir = tempfile::tempdir().expect("tmp");
    let obj = "v -3e38 -3e38 0\nv 3e38 -3e38 0\nv 0 3e38 3e38\nv 3e38 3e38 -3e38\nf 1 2 3\nf 2 4 3\n";
    std::fs::write(dir.path().join("edge.obj"), obj).expect("w");
    let o = ronray_in(dir.path(), &["bench", "edge.obj", "--threads", "1"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_ne!(o.status.code(), Some(101), "bench panicked: {err}");
    assert!(!err.contains("panicked"), "{err}");
}

/// `check` and `gallery` over a folder with one hostile scene (coordinates
/// beyond the limit) and one good one: the hostile one is reported, the
/// good one still runs, and the summary is printed.
#[test]
fn check_and_gallery_finish_their_summary_despite_a_hostile_scene() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    std::fs::create_dir_all(d.join("scenes")).expect("mkdir");
    let good = format!(
        "Scene({HEAD} test: (width: 8, spp: 1), objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])"
    );
    let bad = good.replace("radius: 1,", "radius: 2e19,");
    std::fs::write(d.join("scenes/a_bad.ron"), bad).expect("w");
    std::fs::write(d.join("scenes/b_good.ron"), good).expect("w");
    let o = ronray_in(d, &["check", "scenes"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        out.contains("a_bad.ron") && out.contains("INVALID") && out.contains("b_good.ron"),
        "{out}"
    );
    let o = ronray_in(d, &["gallery", "scenes", "--out", "g", "--width", "8"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("b_good"),
        "the good scene is in the gallery"
    );
    assert!(d.join("g/b_good.png").exists());
}

/// A syntax error beside non-ASCII text in an include and in a JSON scene
/// (the printer once sliced inside a character): located, no panic.
#[test]
fn non_ascii_text_in_an_include_or_json_is_located_without_panic() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    std::fs::write(
        d.join("inc.ron"),
        "\u{feff}(materials: { \"é\": Lambert(albedo: (0.5,\u{a0}0.5 0.5)) })",
    )
    .expect("w");
    std::fs::write(d.join("s.ron"), format!("Scene({HEAD} include: [\"inc.ron\"])")).expect("w");
    std::fs::write(
        d.join("s.json"),
        "\u{feff}{ \"camera\": { \"eye\": [0, 1, 4], \"target\": [0, 0, 0], \"fov_y_degrees\": “40” } }",
    )
    .expect("w");
    for (scene, file) in [("s.ron", "inc.ron"), ("s.json", "s.json")] {
        let o = ronray_in(d, &["validate", scene]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{scene}: {err}");
        assert!(err.contains(&format!("{file}:1:")), "{scene}: not located: {err}");
    }
}

/// One texture named `x.png` and `./x.png` is decoded once (it was once
/// per spelling: 2.6 GB each for an 11000² PNG).
#[test]
fn one_texture_spelled_two_ways_is_decoded_once() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    std::fs::copy(root().join("scenes/golden/cornell.png"), d.join("x.png")).expect("copy");
    let text = format!(
        "Scene({} materials: {{ \"a\": Lambert(albedo: \"x.png\"), \"b\": Lambert(albedo: \"./x.png\"), \"c\": Lambert(albedo: \"sub/../x.png\") }}, objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"a\"), Sphere(center: (2, 0, 0), radius: 1, material: \"b\"), Sphere(center: (-2, 0, 0), radius: 1, material: \"c\")])",
        HEAD.replace("materials: { \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) },", "")
    );
    std::fs::create_dir_all(d.join("sub")).expect("mkdir");
    let l = load_str(&d.join("s.ron"), &text, &Overrides::default())
        .unwrap_or_else(|e| panic!("{}", common::message(&e)));
    assert_eq!(l.scene.textures.len(), 1, "one texture for three spellings");
}
