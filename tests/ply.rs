//! Stanford PLY meshes (`Mesh(file: "x.ply")`): the bunny written as PLY
//! (ASCII and both binary byte orders) renders as its OBJ does, PLY vertex
//! colours reach `VertexColor`, and wrong or hostile files are located
//! errors, never panics.

use crate::common;

use glam::Vec3A;
use ronray::load::{Overrides, load_str};
use ronray::math::Ray;

/// The bunny's vertices and triangles, read from its OBJ (`v` and `f` lines).
fn bunny() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let text = std::fs::read_to_string(common::root().join("assets/bunny.obj")).expect("bunny");
    let (mut v, mut f) = (Vec::new(), Vec::new());
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first() {
            Some(&"v") => v.push([1, 2, 3].map(|i| w[i].parse::<f32>().expect("number"))),
            Some(&"f") => f.push([1, 2, 3].map(|i| w[i].parse::<u32>().expect("index") - 1)),
            _ => {}
        }
    }
    (v, f)
}

/// `(v, f)` as PLY: `format` is `ascii`, `binary_little_endian` or
/// `binary_big_endian`. Vertices as `float`, faces as `uchar`-counted `int`
/// lists; an unused `confidence` property and a `comment` to read past.
fn ply(v: &[[f32; 3]], f: &[[u32; 3]], format: &str) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment written by tests/ply.rs\nelement vertex {}\nproperty float x\n\
         property float y\nproperty float z\nproperty float confidence\nelement face {}\n\
         property list uchar int vertex_indices\nend_header\n",
        v.len(),
        f.len()
    )
    .into_bytes();
    if format == "ascii" {
        let mut text = String::new();
        for p in v {
            text.push_str(&format!("{} {} {} 1\n", p[0], p[1], p[2]));
        }
        for t in f {
            text.push_str(&format!("3 {} {} {}\n", t[0], t[1], t[2]));
        }
        out.extend(text.into_bytes());
        return out;
    }
    let big = format == "binary_big_endian";
    let put = |out: &mut Vec<u8>, b: [u8; 4]| {
        if big {
            out.extend(b.iter().rev())
        } else {
            out.extend(b)
        }
    };
    for p in v {
        p.iter()
            .chain(&[1.0])
            .for_each(|x| put(&mut out, x.to_le_bytes()));
    }
    for t in f {
        out.push(3);
        t.iter().for_each(|&i| put(&mut out, (i as i32).to_le_bytes()));
    }
    out
}

fn scene(file: &str, material: &str) -> String {
    format!(
        "Scene(camera: (eye: (0, 1.2, 3.2), target: (0, 0.6, 0), fov_y_degrees: 35), \
         film: (width: 24, height: 24, spp: 4, seed: 3), integrator: Path(max_depth: 3), \
         materials: {{ \"clay\": Lambert(albedo: (0.8, 0.6, 0.5)), {material} }}, \
         lights: [Rect(center: (0.5, 3, 1), half_u: (0.6, 0, 0), half_v: (0, 0, 0.6), radiance: (10, 10, 10)), \
                  Environment(radiance: (0.1, 0.1, 0.1))], \
         objects: [Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: \"clay\"), \
                   Mesh(file: \"{file}\", material: \"clay\", transform: [Scale((0.1, 0.1, 0.1))])])"
    )
}

#[test]
fn the_bunny_as_ply_renders_as_its_obj() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (v, f) = bunny();
    assert_eq!((v.len(), f.len()), (1839, 3674));
    std::fs::copy(
        common::root().join("assets/bunny.obj"),
        dir.path().join("bunny.obj"),
    )
    .expect("copy");
    let reference = common::render_loaded(&common::load_in(
        dir.path(),
        &scene("bunny.obj", ""),
        &Overrides::default(),
    ));
    for format in ["ascii", "binary_little_endian", "binary_big_endian"] {
        let name = format!("bunny_{format}.PLY");
        std::fs::write(dir.path().join(&name), ply(&v, &f, format)).expect("write");
        let l = common::load_in(dir.path(), &scene(&name, ""), &Overrides::default());
        assert!(
            common::notes_text(&l).is_empty() || !common::notes_text(&l).contains("PLY"),
            "{}",
            common::notes_text(&l)
        );
        let img = common::render_loaded(&l);
        // Same triangles in the same order: the same image, to the bit for
        // the binary files (ASCII prints each float in its shortest form,
        // which reads back exactly too).
        assert_eq!(img.pixels, reference.pixels, "{format}");
    }
}

#[test]
fn ply_vertex_colours_reach_vertex_color_textures() {
    let dir = tempfile::tempdir().expect("temp dir");
    // A 2 × 2 floor at y = 0 whose corners are painted (sRGB uchar), under a
    // sky of radiance 1: a ray straight down reads the interpolated colour.
    let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
        property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\nelement face 1\n\
        property list uchar uint vertex_index\nend_header\n\
        -1 0 1 255 0 0 255\n1 0 1 255 0 0 255\n1 0 -1 0 0 255 255\n-1 0 -1 0 0 255 255\n4 0 1 2 3\n";
    std::fs::write(dir.path().join("floor.ply"), text).expect("write");
    let s = "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), integrator: Path(max_depth: 2), \
        materials: { \"paint\": Lambert(albedo: VertexColor(factor: (1, 1, 1))) }, \
        lights: [Environment(radiance: (1, 1, 1))], objects: [Mesh(file: \"floor.ply\", material: \"paint\")])";
    let l = common::load_in(dir.path(), s, &Overrides::default());
    let at = |z: f32| common::mean_li(&l, Ray::new(Vec3A::new(0.0, 1.0, z), Vec3A::NEG_Y), 300);
    let near = at(0.9); // mostly red: z = 1 is the red edge
    let far = at(-0.9);
    assert!(near.x > 0.8 && near.z < 0.1, "near the red edge: {near}");
    assert!(far.z > 0.8 && far.x < 0.1, "near the blue edge: {far}");
    let mid = at(0.0);
    // Halfway between 1 and 0 linear: 0.5 each.
    assert!(
        (mid.x - 0.5).abs() < 0.03 && (mid.z - 0.5).abs() < 0.03,
        "midway: {mid}"
    );
}

#[test]
fn wrong_ply_files_are_located_errors() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (v, f) = bunny();
    let good = ply(&v[..50], &f[..0], "binary_little_endian");
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("empty.ply", Vec::new(), "not a PLY"),
        ("no_faces.ply", good.clone(), "contains no faces"),
        (
            "points.ply",
            b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n".to_vec(),
            "point cloud",
        ),
        ("truncated.ply", ply(&v, &f, "binary_little_endian")[..5000].to_vec(), "PLY element"),
        (
            // Counted through 10¹² times before (a hang): fuzz/regressions/ply.
            "zero_property.ply",
            std::fs::read(common::root().join("fuzz/regressions/ply/binary_element_without_properties_counted_1e12"))
                .expect("regression"),
            "contains no faces",
        ),
        (
            "past_the_end.ply",
            ply(&v[..3], &[[0, 1, 7]], "ascii"),
            "uses vertex 7 but the file has 3",
        ),
    ];
    for (name, bytes, want) in cases {
        std::fs::write(dir.path().join(name), bytes).expect("write");
        let e = load_str(
            &dir.path().join("test.ron"),
            &scene(name, ""),
            &Overrides::default(),
        )
        .err()
        .unwrap_or_else(|| panic!("{name} loaded"));
        let m = common::message(&e);
        assert!(m.contains(want), "{name}: {m}");
        assert!(
            m.contains("test.ron:1:"),
            "{name}: the report locates the field: {m}"
        );
        assert!(
            m.contains("PLY mesh with a `vertex` element"),
            "{name}: the fix: {m}"
        );
    }
}

/// A binary PLY with its bytes changed at random, 400 times (header and
/// payload): every variant loads or is refused, none panics, and every one
/// that loads renders finite pixels.
#[test]
fn mangled_binary_plys_never_panic() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (v, f) = bunny();
    let good = ply(
        &v[..200],
        &f.iter()
            .copied()
            .filter(|t| t.iter().all(|&i| i < 200))
            .collect::<Vec<_>>(),
        "binary_little_endian",
    );
    let mut rng = ronray::math::Pcg32::new(17, 4);
    let (mut loaded, mut refused) = (0, 0);
    for round in 0..400 {
        let mut bytes = good.clone();
        for _ in 0..1 + round % 4 {
            let at = (rng.next_u32() as usize) % bytes.len();
            bytes[at] = match rng.next_u32() % 4 {
                0 => 0xff,
                1 => 0,
                2 => bytes[at] ^ (1 << (rng.next_u32() % 8)),
                _ => rng.next_u32() as u8,
            };
        }
        std::fs::write(dir.path().join("m.ply"), &bytes).expect("write");
        let o = Overrides {
            spp: Some(1),
            size: Some((8, 8)),
            ..Default::default()
        };
        match load_str(&dir.path().join("test.ron"), &scene("m.ply", ""), &o) {
            Ok(l) => {
                loaded += 1;
                common::render_loaded(&l);
            }
            Err(_) => refused += 1,
        }
    }
    // Most single-byte changes land in float payload and still load.
    assert!(loaded > 100 && refused > 10, "loaded {loaded}, refused {refused}");
}
