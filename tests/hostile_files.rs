//! Files that are not what a scene says they are (issue 13): a FIFO or a
//! device as OBJ or MTL, an OBJ at the edge of `f32`, non-ASCII text in an
//! include or a JSON scene, one texture spelled two ways, a batch with one
//! hostile scene. None may block, abort, panic or cost a summary.

use crate::common;

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

/// Issue 39: a sky map whose EXR header lies about its size. The decoder
/// sized its buffers from the header, so a few hundred bytes claiming
/// 100,000² pixels aborted the process (SIGABRT) and 16,000² took 3 GB.
/// Both are refused, located, before anything is allocated.
#[test]
fn a_sky_map_whose_header_lies_about_its_size_is_refused_before_allocating() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().expect("tmp");
    let small = dir.path().join("small.exr");
    // One 4×2 tile: a header that also claims one N×N tile keeps the
    // offset table (one chunk) consistent with the file.
    let encoding = Encoding {
        compression: Compression::Uncompressed,
        blocks: Blocks::Tiles(Vec2(4, 2)),
        line_order: LineOrder::Increasing,
    };
    Image::from_encoded_channels(
        (4, 2),
        encoding,
        SpecificChannels::rgb(|_p: Vec2<usize>| (0.5f32, 0.5f32, 0.5f32)),
    )
    .write()
    .to_file(&small)
    .expect("a small EXR");
    let bytes = std::fs::read(&small).expect("read");
    // Both windows (`<name>\0box2i\0`, size 16, xMin yMin xMax yMax as
    // i32 LE) and the tile size (`tiles\0tiledesc\0`, size 9, x y as u32).
    let find = |b: &[u8], name: &[u8]| {
        b.windows(name.len())
            .position(|w| w == name)
            .expect("the attribute")
            + name.len()
            + 4
    };
    let patch = |side: i32| {
        let mut b = bytes.clone();
        for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
            let at = find(&b, name);
            b[at + 8..at + 12].copy_from_slice(&(side - 1).to_le_bytes());
            b[at + 12..at + 16].copy_from_slice(&(side - 1).to_le_bytes());
        }
        let at = find(&b, b"tiles\0tiledesc\0");
        b[at..at + 4].copy_from_slice(&side.to_le_bytes());
        b[at + 4..at + 8].copy_from_slice(&side.to_le_bytes());
        b
    };
    for (side, expect) in [(100_000, "above the limit"), (16_000, "truncated or corrupt")] {
        let lying = dir.path().join(format!("lying{side}.exr"));
        std::fs::write(&lying, patch(side)).expect("write");
        assert!(std::fs::metadata(&lying).expect("meta").len() < 2000);
        let text = format!(
            "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), \
             film: (width: 8, height: 8, spp: 1), lights: [Environment(map: \"{}\")], objects: [])",
            lying.file_name().and_then(|n| n.to_str()).expect("name")
        );
        let e = load_str(&dir.path().join("s.ron"), &text, &Overrides::default()).err();
        let shown = e.as_ref().map(common::message).unwrap_or_default();
        assert!(shown.contains(expect), "{side}²: {shown}");
    }
}

/// Issue 39: one NaN texel in a sky map darkened the whole image by 11%
/// (it reached the importance tables and the irradiance), and negative or
/// infinite texels gave wrong images, all without a word. They are read
/// as 0 with a note that names the map and what was wrong.
#[test]
fn broken_texels_in_a_sky_map_are_repaired_with_a_note() {
    use exr::prelude::*;
    let dir = tempfile::tempdir().expect("tmp");
    let write = |name: &str, bad: [f32; 3]| {
        write_rgb_file(dir.path().join(name), 16, 8, |x, y| {
            if (x, y) == (5, 2) {
                (bad[0], bad[1], bad[2])
            } else {
                (1.0f32, 0.9f32, 0.8f32)
            }
        })
        .expect("an EXR");
    };
    write("clean.exr", [1.0, 0.9, 0.8]);
    write("nan.exr", [f32::NAN, 0.9, 0.8]);
    write("broken.exr", [f32::INFINITY, -3.0, f32::NAN]);
    let scene = |map: &str| {
        format!(
            "Scene(camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 50), \
             film: (width: 16, height: 16, spp: 16), \
             materials: {{ \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }}, \
             lights: [Environment(map: \"{map}\")], \
             objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])"
        )
    };
    let mean = |map: &str| {
        let l = common::load_in(dir.path(), &scene(map), &Overrides::default());
        let img = common::render_loaded(&l);
        let notes: Vec<String> = l.warnings.diagnostics.iter().map(|d| d.message.clone()).collect();
        let m = img.pixels.iter().map(common::sum).sum::<f64>() / img.pixels.len() as f64;
        (m, notes.join("\n"))
    };
    let (clean, quiet) = mean("clean.exr");
    assert!(!quiet.contains("read as 0"), "{quiet}");
    let (nan, said) = mean("nan.exr");
    assert!(
        said.contains("lights[0].map: nan.exr has 1 NaN channel value, read as 0"),
        "{said}"
    );
    assert!(
        (nan / clean - 1.0).abs() < 0.02,
        "NaN texel: mean {nan} against {clean}"
    );
    let (broken, said) = mean("broken.exr");
    assert!(
        said.contains("1 NaN channel value, 1 infinite channel value, 1 negative channel value"),
        "{said}"
    );
    assert!(
        broken.is_finite() && (broken / clean - 1.0).abs() < 0.02,
        "mean {broken} against {clean}"
    );
}
