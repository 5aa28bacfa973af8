//! Every OBJ of the third-party corpus (`tests/fixtures/obj-corpus/`, see its
//! SOURCES.md) loads and renders through a small generated scene, and broken
//! OBJ files — generated here — fail with a located error, never a panic.

mod common;

use common::message;
use ronray::frame::{RenderOptions, render_whole};
use ronray::geometry::obj::load_obj_data;
use ronray::load::{LoadError, Overrides, load_str};
use std::path::{Path, PathBuf};

fn corpus() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/obj-corpus")
}

fn objs(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).expect("corpus folder") {
        let p = e.expect("entry").path();
        if p.is_dir() {
            objs(&p, out);
        } else if p.extension().is_some_and(|e| e == "obj") {
            out.push(p);
        }
    }
}

/// A scene beside `obj` looking at its bounding box, lit from the camera.
fn scene_for(obj: &Path, extra: &str) -> String {
    let mesh = load_obj_data(obj).map(|d| d.mesh);
    let (c, r) = match &mesh {
        Ok(m) => {
            let b = m.bounds();
            (b.centroid(), 0.5 * b.extent().length().max(1e-3))
        }
        Err(_) => (glam::Vec3A::ZERO, 1.0),
    };
    let eye = c + glam::Vec3A::new(0.3, 0.4, 1.0).normalize() * 3.0 * r;
    format!(
        r#"Scene(
    camera: (eye: ({}, {}, {}), target: ({}, {}, {}), fov_y_degrees: 40),
    film: (width: 32, height: 32, spp: 1),
    materials: {{ "red": Lambert(albedo: (0.6, 0.1, 0.1)) }},
    lights: [Point(position: ({}, {}, {}), intensity: ({i}, {i}, {i}))],
    objects: [Mesh(file: "{}"{extra})],
)"#,
        eye.x,
        eye.y,
        eye.z,
        c.x,
        c.y,
        c.z,
        eye.x,
        eye.y,
        eye.z,
        obj.file_name().and_then(|n| n.to_str()).expect("utf-8 name"),
        i = 10.0 * r * r,
    )
}

fn load(obj: &Path, extra: &str) -> Result<ronray::load::Loaded, LoadError> {
    let scene = obj.with_file_name("generated.ron");
    load_str(&scene, &scene_for(obj, extra), &Overrides::default())
}

#[test]
fn obj_corpus_loads_and_renders() {
    let mut files = Vec::new();
    objs(&corpus(), &mut files);
    files.sort();
    assert_eq!(files.len(), 11, "corpus files found: {files:?}");
    for f in &files {
        let loaded = load(f, "").unwrap_or_else(|e| panic!("{} failed: {}", f.display(), message(&e)));
        let (img, _) = render_whole(&loaded.scene, &loaded.view, &RenderOptions::default());
        assert!(
            img.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0),
            "{}: non-finite or negative pixels",
            f.display()
        );
        // MTL colours may be black (Kd 0); in red the mesh must show.
        let red = load(f, r#", material: "red""#).expect("loads with an override");
        let (img, _) = render_whole(&red.scene, &red.view, &RenderOptions::default());
        let lit = img.pixels.iter().filter(|p| p.max_element() > 0.0).count();
        assert!(lit > 0, "{}: the mesh is not visible in the image", f.display());
    }
}

#[test]
fn obj_corpus_groups_materials_and_overrides() {
    let cornell = corpus().join("Akuna/CornellBox-Original.obj");
    let d = load_obj_data(&cornell).expect("Akuna Cornell box loads");
    assert_eq!(d.mesh.triangle_count(), 36);
    assert_eq!(d.materials.len(), 8);
    assert!(
        d.groups.iter().any(|g| g.name == "shortBox"),
        "groups: {:?}",
        d.groups
    );
    // Dangling `vn` indices: the normals are dropped, nothing panics.
    let ogre = load_obj_data(&corpus().join("raytracer-skius/ogre/controlmesh.obj")).expect("ogre loads");
    assert_eq!(ogre.mesh.triangle_count(), 2654);
    assert!(ogre.mesh.normals.is_empty(), "dangling normals must be dropped");
    // A group override and an MTL-name override are accepted…
    load(
        &cornell,
        r#", materials: { "group:shortBox": "red", "leftWall": "red" }"#,
    )
    .expect("known groups");
    // …a bare key naming the group `shortBox` and the MTL material
    // `shortBox` another group wears would recolour both boxes (issue 46)…
    let e = load(&cornell, r#", materials: { "shortBox": "red" }"#)
        .err()
        .expect("a key that names two things");
    let m = message(&e);
    assert!(
        m.contains("group:shortBox") && m.contains("material:shortBox"),
        "got: {m}"
    );
    // …an unknown one is a located error with a suggestion.
    let e = load(&cornell, r#", materials: { "shortBx": "red" }"#)
        .err()
        .expect("unknown group");
    let m = message(&e);
    assert!(
        m.contains("objects[0].materials.shortBx") && m.contains("did you mean `shortBox`?"),
        "got: {m}"
    );
    let e = load(&cornell, r#", material: "rde""#)
        .err()
        .expect("unknown material");
    assert!(
        message(&e).contains("did you mean `red`?"),
        "got: {}",
        message(&e)
    );
}

#[test]
fn obj_broken_files_fail_cleanly() {
    let dir = tempfile::tempdir().expect("temp dir");
    let good = std::fs::read(corpus().join("tinyobjloader/models/cornell_box.obj")).expect("read");
    let mut garbage: Vec<u8> = (0..4096u32)
        .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
        .collect();
    garbage.extend_from_slice(b"\nf 1 2 3\n");
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty", Vec::new()),
        ("truncated", good[..good.len() / 2].to_vec()),
        ("garbage", garbage),
        ("nan", b"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n".to_vec()),
        ("inf", b"v 0 0 0\nv 1 0 0\nv 0 1e39 0\nf 1 2 3\n".to_vec()),
        (
            "huge_index",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4000000000\n".to_vec(),
        ),
        (
            "overflow_index",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n".to_vec(),
        ),
        (
            "negative_past_start",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -9\n".to_vec(),
        ),
        ("zero_index", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n".to_vec()),
        ("only_vertices", b"v 0 0 0\nv 1 0 0\n".to_vec()),
        ("degenerate", b"v 0 0 0\nv 0 0 0\nv 0 0 0\nf 1 2 3\n".to_vec()),
        (
            "bad_normals",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn nan 0 1\nf 1//1 2//1 3//7\n".to_vec(),
        ),
        (
            "missing_mtl",
            b"mtllib nowhere.mtl\nusemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n".to_vec(),
        ),
    ];
    for (name, bytes) in cases {
        let obj = dir.path().join(format!("{name}.obj"));
        std::fs::write(&obj, &bytes).expect("write");
        match load(&obj, "") {
            Ok(loaded) => {
                // Whatever loads must render.
                let (img, _) = render_whole(&loaded.scene, &loaded.view, &RenderOptions::default());
                assert!(
                    img.pixels.iter().all(|p| p.is_finite()),
                    "{name}: non-finite pixels"
                );
            }
            Err(e) => {
                let m = message(&e);
                assert!(
                    m.contains("objects[0].file") && m.contains(&format!("{name}.obj")),
                    "{name}: error must name the field and the file, got: {m}"
                );
            }
        }
    }
}

/// McGuire's Cornell box gets its light from the MTL file alone: the
/// `light` material's `Ke 17 12 4` makes its group emit, with no light in
/// the scene file (and no "no light" warning).
#[test]
fn mtl_ke_lights_the_cornell_box_with_no_light_in_the_scene() {
    use ronray::lights::Light;
    let dir = corpus().join("Akuna");
    let text = |extra: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 3.4), target: (0, 1, 0), fov_y_degrees: 40),
            film: (width: 32, height: 32, spp: 16),
            integrator: Path(max_depth: 8, rr_depth: 5),
            materials: {{ "red": Lambert(albedo: (0.6, 0.1, 0.1)) }},
            objects: [Mesh(file: "CornellBox-Original.obj"{extra})],
        )"#
        )
    };
    let loaded = common::load_in(&dir, &text(""), &Overrides::default());
    assert!(
        loaded.warnings.diagnostics.is_empty(),
        "{}",
        loaded.warnings.render(false)
    );
    let radiances: Vec<_> = loaded
        .scene
        .lights
        .iter()
        .map(|l| match l {
            Light::Mesh(m) => (m.radiance, m.area()),
            // The lamp is one rectangle of two triangles: a quad light
            // (`MeshLight::as_parallelogram`).
            Light::Quad(q) => (q.radiance, q.area),
            other => panic!("expected an emissive mesh, got {other:?}"),
        })
        .collect();
    assert_eq!(radiances.len(), 1, "one emissive group: {radiances:?}");
    let (radiance, area) = radiances[0];
    assert_eq!(radiance.to_array(), [17.0, 12.0, 4.0]);
    assert!((area - 0.47 * 0.38).abs() < 1e-4, "the light's area {area}");
    let img = common::render_loaded(&loaded);
    let mean = img.pixels.iter().map(|p| p.x).sum::<f32>() / img.pixels.len() as f32;
    assert!(mean > 0.1, "the box is lit by its own light: mean red {mean}");
    // Replacing the light's material replaces its emission too.
    let dark = common::load_in(
        &dir,
        &text(r#", materials: { "light": "red" }"#),
        &Overrides::default(),
    );
    assert!(dark.scene.lights.is_empty(), "an overridden group keeps no Ke");
    // An object's `emission` wins over Ke for every group.
    let all = common::load_in(
        &dir,
        &text(r#", emission: (radiance: (1, 1, 1), two_sided: true)"#),
        &Overrides::default(),
    );
    assert_eq!(all.scene.lights.len(), 8, "every group of the box emits");
}
