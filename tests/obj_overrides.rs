//! OBJ material overrides (`materials: { "key": "scene material" }` on a
//! `Mesh` or `Instance`) say which part they recolour, and an MTL file that
//! defines a name twice is refused (issue 46, falsehood 5).

use crate::common;

use common::ronray_in;
use ronray::load::{LoadError, load};
use std::path::Path;

/// Two boxes as McGuire's Cornell box has them: group `box` wears MTL
/// material `wall`, group `left` wears MTL material `box`.
const OBJ: &str = "mtllib parts.mtl\n\
    o box\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\n\
    o left\nv 2 0 0\nv 3 0 0\nv 2 1 0\nusemtl box\nf 4 5 6\n";
const MTL: &str = "newmtl wall\nKd 0.8 0.8 0.8\nnewmtl box\nKd 0.8 0.1 0.1\n";

fn folder(overrides: &str, mtl: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = format!(
        r#"Scene(
    camera: (eye: (1.5, 0.5, 4), target: (1.5, 0.5, 0), fov_y_degrees: 40),
    film: (width: 8, height: 8, spp: 1),
    materials: {{ "blue": Lambert(albedo: (0.1, 0.1, 0.8)) }},
    lights: [Point(position: (1, 1, 3), intensity: (5, 5, 5))],
    objects: [
        Mesh(file: "parts.obj", materials: {{ {overrides} }}),
    ],
)
"#
    );
    std::fs::write(dir.path().join("scene.ron"), scene).expect("write");
    std::fs::write(dir.path().join("parts.obj"), OBJ).expect("write");
    std::fs::write(dir.path().join("parts.mtl"), mtl).expect("write");
    dir
}

fn errors(dir: &Path) -> String {
    match load(&dir.join("scene.ron")) {
        Ok(_) => String::new(),
        Err(LoadError::Invalid(r)) => r.render(false),
        Err(e) => e.to_string(),
    }
}

/// The material of each of the two slots after loading.
fn slot_materials(dir: &Path) -> Vec<u32> {
    let l = load(&dir.join("scene.ron")).unwrap_or_else(|e| panic!("{e}"));
    l.scene.geometry.instances[0].materials.to_vec()
}

#[test]
fn obj_override_key_naming_a_group_and_a_material_is_an_error() {
    let dir = folder(r#""box": "blue""#, MTL);
    let text = errors(dir.path());
    assert!(
        text.contains("group `box`") && text.contains("material `box`"),
        "a key that hits two parts names both:\n{text}"
    );
    assert!(
        text.contains("group:box") && text.contains("material:box"),
        "and offers the prefixed keys:\n{text}"
    );
}

#[test]
fn obj_override_prefixes_pick_the_group_or_the_material() {
    let blue = 0;
    let by_group = slot_materials(folder(r#""group:box": "blue""#, MTL).path());
    assert_eq!(by_group[0], blue, "group `box` is blue: {by_group:?}");
    assert_ne!(
        by_group[1], blue,
        "group `left` keeps its MTL material: {by_group:?}"
    );
    let by_material = slot_materials(folder(r#""material:box": "blue""#, MTL).path());
    assert_ne!(by_material[0], blue, "{by_material:?}");
    assert_eq!(
        by_material[1], blue,
        "the group wearing `box` is blue: {by_material:?}"
    );
    let text = errors(folder(r#""group:wall": "blue""#, MTL).path());
    assert!(text.contains("no group `wall`"), "{text}");
}

#[test]
fn mtl_defining_a_material_twice_is_an_error() {
    let twice = format!("{MTL}newmtl box\nKd 0.1 0.8 0.1\n");
    let text = errors(folder("", &twice).path());
    assert!(
        text.contains("`box`") && text.contains("twice") && text.contains("parts.mtl"),
        "{text}"
    );
}

#[test]
fn validate_verbose_lists_an_obj_groups_and_materials() {
    let dir = folder("", MTL);
    let o = ronray_in(dir.path(), &["validate", "-v", "scene.ron"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{out}{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("parts.mtl"), "the MTL file is listed:\n{out}");
    assert!(
        out.contains("groups: `box` (material `wall`), `left` (material `box`)"),
        "{out}"
    );
}
