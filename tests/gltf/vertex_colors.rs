//! glTF `COLOR_0`: a primitive's vertex colours multiply its material's
//! base colour (glTF 2.0 §3.9.2). A quad painted one colour c under a
//! uniform sky renders as the same quad unpainted with base colour
//! factor × c; another primitive with the same material and no `COLOR_0`
//! keeps the factor; colours stored as normalised bytes with alpha below 1
//! are read and their alpha named in a note.

use super::{Asset, load, notes_of};
use glam::Vec3A;
use ronray::math::Ray;
use serde_json::{Value, json};

/// A floor quad at y = 0 over x ∈ [x0, x0 + 2], z ∈ [−1, 1], facing +y.
fn quad(a: &mut Asset, x0: f32) -> (usize, usize) {
    let x1 = x0 + 2.0;
    let pos = a.floats(
        &[x0, 0.0, 1.0, x1, 0.0, 1.0, x1, 0.0, -1.0, x0, 0.0, -1.0],
        "VEC3",
    );
    let idx = a.indices(&[0, 1, 2, 0, 2, 3]);
    (pos, idx)
}

fn material(factor: [f32; 3]) -> Value {
    json!({"pbrMetallicRoughness": {
        "baseColorFactor": [factor[0], factor[1], factor[2], 1.0],
        "metallicFactor": 0.0, "roughnessFactor": 1.0
    }})
}

/// Mean radiance of rays straight down at (x, z).
fn seen(l: &ronray::load::Loaded, x: f32, z: f32) -> Vec3A {
    crate::common::mean_li(l, Ray::new(Vec3A::new(x, 1.0, z), Vec3A::NEG_Y), 2000)
}

const SCENE: &str = "Scene(camera: (eye: (1, 4, 4), target: (1, 0, 0), fov_y_degrees: 40), \
     integrator: Path(max_depth: 2), lights: [Environment(radiance: (1, 1, 1))], \
     objects: [Gltf(file: \"a.gltf\")])";

#[test]
fn color_0_multiplies_the_base_colour_of_its_primitives_only() {
    let factor = [0.8, 0.6, 0.9];
    let c = [0.25f32, 0.7, 0.5];
    // Painted: the left quad has COLOR_0 = c (floats, RGB); the right one
    // wears the same material without colours.
    let mut a = Asset::default();
    let (pos0, idx0) = quad(&mut a, -1.0);
    let colors = a.floats(&c.repeat(4), "VEC3");
    let (pos1, idx1) = quad(&mut a, 2.0);
    let painted = a.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos0, "COLOR_0": colors}, "indices": idx0, "material": 0},
            {"attributes": {"POSITION": pos1}, "indices": idx1, "material": 0},
        ]}],
        "materials": [material(factor)],
    }));
    let painted = load(&[("a.gltf", painted.as_bytes())], SCENE).unwrap_or_else(|e| panic!("loads: {e}"));
    // The reference: both quads unpainted, the left one's factor × c.
    let mut b = Asset::default();
    let (pos0, idx0) = quad(&mut b, -1.0);
    let (pos1, idx1) = quad(&mut b, 2.0);
    let product = [factor[0] * c[0], factor[1] * c[1], factor[2] * c[2]];
    let plain = b.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [
            {"attributes": {"POSITION": pos0}, "indices": idx0, "material": 0},
            {"attributes": {"POSITION": pos1}, "indices": idx1, "material": 1},
        ]}],
        "materials": [material(product), material(factor)],
    }));
    let plain = load(&[("a.gltf", plain.as_bytes())], SCENE).unwrap_or_else(|e| panic!("loads: {e}"));
    for (x, z) in [(0.0, 0.0), (-0.5, 0.6), (0.7, -0.8), (3.0, 0.0), (2.4, -0.5)] {
        let (got, want) = (seen(&painted, x, z), seen(&plain, x, z));
        assert!(
            (got - want).abs().max_element() < 0.01 + 0.02 * want.max_element(),
            "at ({x}, {z}): {got} painted against {want}"
        );
    }
    // The painted quad is darker than the plain one in every channel but
    // none is lost: c is not 1 anywhere.
    let (left, right) = (seen(&painted, 0.0, 0.0), seen(&painted, 3.0, 0.0));
    assert!(
        left.x < 0.5 * right.x && left.y < right.y,
        "{left} against {right}"
    );
}

#[test]
fn byte_colours_with_alpha_are_read_and_their_alpha_noted() {
    let mut a = Asset::default();
    let (pos, idx) = quad(&mut a, -1.0);
    // Normalised bytes: (255, 0, 0, 128) on every corner.
    let view = a.view(&[255u8, 0, 0, 128].repeat(4), None);
    let colors = a.accessor(
        json!({"bufferView": view, "componentType": 5121, "normalized": true, "count": 4, "type": "VEC4"}),
    );
    let gltf = a.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "COLOR_0": colors}, "indices": idx}]}],
    }));
    let l = load(&[("a.gltf", gltf.as_bytes())], SCENE).unwrap_or_else(|e| panic!("loads: {e}"));
    let notes = notes_of(&l).join("\n");
    assert!(notes.contains("COLOR_0's alpha is below 1"), "{notes}");
    // glTF's default material is white metal; red vertex colours leave
    // green and blue black.
    let v = seen(&l, 0.2, 0.1);
    assert!(v.x > 0.2 && v.y < 1e-3 && v.z < 1e-3, "{v}");
}
