//! glTF import end to end, on synthetic assets written by the tests (so
//! every feature has a small case whose answer is known) and on the shipped
//! Fox: transforms down a node hierarchy, instancing, sparse accessors,
//! interleaved views, texture transforms, MASK cut-outs, MikkTSpace against
//! stored tangents, a glTF box against the same box as OBJ, and malformed
//! assets as located errors.

use crate::common;

mod camera;
mod vertex_colors;

use glam::{Mat4, Quat, Vec3, Vec3A};
use ronray::frame::render_whole;
use ronray::imageio::Image;
use ronray::load::{LoadError, Overrides, load_str};
use ronray::math::Ray;
use serde_json::{Value, json};
use std::path::Path;

/// A glTF asset under construction: one binary buffer, views and accessors.
#[derive(Default)]
struct Asset {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Asset {
    fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let mut v = json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(s) = stride {
            v["byteStride"] = json!(s);
        }
        self.bin.extend_from_slice(bytes);
        self.views.push(v);
        self.views.len() - 1
    }

    fn floats(&mut self, data: &[f32], ty: &str) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|f| f.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let per = match ty {
            "SCALAR" => 1,
            "VEC2" => 2,
            "VEC3" => 3,
            _ => 4,
        };
        let mut a = json!({"bufferView": view, "componentType": 5126, "count": data.len() / per, "type": ty});
        if ty == "VEC3" {
            // glTF requires bounds on POSITION.
            let axis = |k: usize, f: fn(f32, f32) -> f32| data.iter().skip(k).step_by(3).copied().reduce(f);
            a["min"] = json!([0, 1, 2].map(|k| axis(k, f32::min)));
            a["max"] = json!([0, 1, 2].map(|k| axis(k, f32::max)));
        }
        self.accessor(a)
    }

    fn indices(&mut self, data: &[u16]) -> usize {
        let bytes: Vec<u8> = data.iter().flat_map(|f| f.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        self.accessor(
            json!({"bufferView": view, "componentType": 5123, "count": data.len(), "type": "SCALAR"}),
        )
    }

    fn accessor(&mut self, a: Value) -> usize {
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// The `.gltf` JSON with the buffer as a data URI, `rest` merged in.
    fn gltf(&self, rest: Value) -> String {
        let mut doc = json!({
            "asset": {"version": "2.0"},
            "buffers": [{"byteLength": self.bin.len(), "uri": format!("data:application/octet-stream;base64,{}", b64(&self.bin))}],
            "bufferViews": self.views,
            "accessors": self.accessors,
        });
        for (k, v) in rest.as_object().expect("an object") {
            doc[k] = v.clone();
        }
        doc.to_string()
    }

    /// The same as a `.glb`: JSON chunk, then the BIN chunk.
    fn glb(&self, rest: Value) -> Vec<u8> {
        let mut doc: Value = serde_json::from_str(&self.gltf(rest)).expect("json");
        doc["buffers"] = json!([{"byteLength": self.bin.len()}]);
        let mut json = doc.to_string().into_bytes();
        while !json.len().is_multiple_of(4) {
            json.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + json.len() + 8 + bin.len();
        let mut out = Vec::new();
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(json.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&json);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        out
    }
}

fn b64(data: &[u8]) -> String {
    const T: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in data.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(T[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// A 1×1 PNG of colour `rgba`, as a data URI.
fn png_uri(rgba: [u8; 4]) -> String {
    let mut bytes = Vec::new();
    let img = image::RgbaImage::from_pixel(1, 1, image::Rgba(rgba));
    img.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .expect("encode png");
    format!("data:image/png;base64,{}", b64(&bytes))
}

/// Writes `files` into a fresh folder and loads `scene` from it.
fn load(files: &[(&str, &[u8])], scene: &str) -> Result<ronray::load::Loaded, LoadError> {
    let dir = tempfile::tempdir().expect("tempdir");
    for (name, data) in files {
        std::fs::write(dir.path().join(name), data).expect("write");
    }
    let o = Overrides {
        spp: Some(2),
        size: Some((64, 64)),
        seed: Some(3),
        ..Default::default()
    };
    load_str(&dir.path().join("scene.ron"), scene, &o)
}

fn scene_with(objects: &str, materials: &str) -> String {
    format!(
        "Scene(
            camera: (eye: (0, 1, 6), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 3),
            materials: {{ \"grey\": Lambert(albedo: 0.5), {materials} }},
            lights: [Point(position: (2, 4, 5), intensity: (30, 30, 30))],
            objects: [{objects}],
        )"
    )
}

/// The start of a scene whose frames run `first..=last` at 24 fps,
/// drawing `frame`: what `scene_with(..).replacen("Scene(", ..)` puts in.
fn animated(first: i32, last: i32, frame: i32) -> String {
    format!("Scene(animation: (frames: ({first}, {last}), fps: 24, frame: {frame}),")
}

/// A unit right triangle in z = 0 (positions only), as asset parts.
fn triangle(a: &mut Asset) -> Value {
    let pos = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "VEC3");
    json!({"primitives": [{"attributes": {"POSITION": pos}}]})
}

/// The world point of `p` under the node chain, computed here from T·R·S.
fn trs(t: [f32; 3], r: Quat, s: [f32; 3]) -> Mat4 {
    Mat4::from_scale_rotation_translation(Vec3::from(s), r, Vec3::from(t))
}

#[test]
fn gltf_hierarchy_and_instances_put_vertices_where_the_node_matrices_say() {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    let r = Quat::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7);
    let parent = trs([0.5, -0.25, 0.0], r, [2.0, 0.5, 1.5]);
    let child = trs([1.0, 0.0, -1.0], Quat::from_rotation_y(0.4), [1.0, 1.0, 1.0]);
    // A column-major `matrix` node for the third instance.
    let third = Mat4::from_rotation_z(0.3) * Mat4::from_scale(Vec3::new(1.0, 3.0, 1.0));
    let q = r.to_array();
    let gltf = a.gltf(json!({
        "scene": 0,
        "scenes": [{"nodes": [0, 3]}],
        "nodes": [
            {"translation": [0.5, -0.25, 0.0], "rotation": q, "scale": [2.0, 0.5, 1.5], "mesh": 0, "children": [1]},
            {"translation": [1.0, 0.0, -1.0], "rotation": Quat::from_rotation_y(0.4).to_array(), "mesh": 0, "children": [2]},
            {"matrix": third.to_cols_array(), "mesh": 0},
            {"translation": [-2.0, 0.0, 0.0]},
        ],
        "meshes": [tri],
    }));
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf", material: "grey")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let geo = &loaded.scene.geometry;
    assert_eq!(geo.meshes.len(), 1, "one mesh for three nodes");
    assert_eq!(geo.instances.len(), 3, "three instances");
    let expected = [parent, parent * child, parent * child * third];
    let corners = [Vec3::ZERO, Vec3::X, Vec3::Y];
    for (inst, m) in geo.instances.iter().zip(expected) {
        let [a, b, c] = inst.world_triangle(0, &geo.meshes);
        let mut got = [a, b, c].map(Vec3::from);
        if m.determinant() < 0.0 {
            got.swap(1, 2);
        }
        // The mesh's BVH may keep the corners in any rotation; compare as a set.
        for want in corners.map(|p| m.transform_point3(p)) {
            let near = got
                .iter()
                .map(|g| (*g - want).length())
                .fold(f32::INFINITY, f32::min);
            assert!(near < 1e-5, "vertex {want} missing from {got:?} (nearest {near})");
        }
        // A ray at the centroid hits there.
        let centroid = (got[0] + got[1] + got[2]) / 3.0;
        let n = (got[1] - got[0]).cross(got[2] - got[0]).normalize();
        let o = centroid + n * 3.0;
        let hit = loaded
            .scene
            .intersect(&Ray::new(Vec3A::from(o), Vec3A::from(-n)), f32::INFINITY)
            .expect("the centroid is hit");
        assert!(
            (Vec3::from(hit.p) - centroid).length() < 1e-5,
            "hit {} vs centroid {centroid}",
            hit.p
        );
    }
}

/// Meshes placed once each by the same transform become one mesh under
/// one BVH (`merge_single_placements`); a mesh placed twice stays shared,
/// and one placed elsewhere stays apart. Each triangle keeps its own
/// material through the merge: rays down onto each part meet that part's
/// material, at the same point as before.
#[test]
fn gltf_parts_placed_together_share_one_mesh_and_keep_their_materials() {
    let mut a = Asset::default();
    // Four one-triangle meshes side by side along x (triangle k spans
    // x ∈ [3k, 3k + 1]), each with its own material.
    let meshes: Vec<Value> = (0..4)
        .map(|k| {
            let x = 3.0 * k as f32;
            let pos = a.floats(&[x, 0.0, 0.0, x + 1.0, 0.0, 0.0, x, 1.0, 0.0], "VEC3");
            json!({"primitives": [{"attributes": {"POSITION": pos}, "material": k}]})
        })
        .collect();
    let materials: Vec<Value> = (0..4)
        .map(|k| json!({"name": format!("m{k}"), "pbrMetallicRoughness": {"metallicFactor": 0.0}}))
        .collect();
    let gltf = a.gltf(json!({
        "scene": 0,
        // Meshes 0 and 1 at the identity, mesh 2 moved, mesh 3 placed twice.
        "scenes": [{"nodes": [0, 1, 2, 3, 4]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 1},
            {"mesh": 2, "translation": [0.0, 0.0, -1.0]},
            {"mesh": 3},
            {"mesh": 3, "translation": [0.0, 0.0, -2.0]},
        ],
        "meshes": meshes,
        "materials": materials,
    }));
    let overrides = (0..4)
        .map(|k| format!("\"m{k}\": \"c{k}\""))
        .collect::<Vec<_>>()
        .join(", ");
    let mats = (0..4)
        .map(|k| format!("\"c{k}\": Lambert(albedo: {})", 0.1 + 0.2 * k as f32))
        .collect::<Vec<_>>()
        .join(", ");
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(
            &format!(r#"Gltf(file: "a.gltf", materials: {{ {overrides} }})"#),
            &mats,
        ),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let geo = &loaded.scene.geometry;
    assert_eq!(geo.meshes.len(), 3, "meshes 0 and 1 joined; 2 and 3 apart");
    assert_eq!(geo.instances.len(), 4, "the joined pair, mesh 2, mesh 3 twice");
    assert_eq!(
        geo.meshes.iter().map(|m| m.triangle_count()).max(),
        Some(2),
        "the joined mesh holds both triangles"
    );
    let scene = &loaded.scene;
    // Each part from 5 units away (the second copy of mesh 3 from behind,
    // as the first hides it from the front).
    for (k, z, d) in [
        (0, 0.0, -1.0),
        (1, 0.0, -1.0),
        (2, -1.0, -1.0),
        (3, 0.0, -1.0),
        (3, -2.0, 1.0),
    ] {
        let o = Vec3A::new(3.0 * k as f32 + 0.25, 0.25, z - 5.0 * d);
        let hit = scene
            .intersect(&Ray::new(o, Vec3A::new(0.0, 0.0, d)), f32::INFINITY)
            .unwrap_or_else(|| panic!("the ray onto part {k} at z = {z} hits"));
        assert!((hit.t - 5.0).abs() < 1e-5, "part {k}: t = {}", hit.t);
        let albedo = scene.materials[hit.material as usize]
            .albedo(&ronray::materials::TexPoint::at(&hit), &scene.textures);
        assert!(
            (albedo.x - (0.1 + 0.2 * k as f32)).abs() < 1e-6,
            "part {k} at z = {z} keeps its material: albedo {albedo}"
        );
    }
}

#[test]
fn gltf_sparse_accessor_and_interleaved_view_are_read() {
    let mut a = Asset::default();
    // Interleaved position + normal, 24 bytes a vertex.
    let verts = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut bytes = Vec::new();
    for v in verts {
        for f in v.iter().chain(&[0.0, 0.0, 1.0]) {
            bytes.extend_from_slice(&f.to_le_bytes());
        }
    }
    let view = a.view(&bytes, Some(24));
    let pos = a.accessor(
        json!({"bufferView": view, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
        "min": [0, 0, 0], "max": [1, 1, 0]}),
    );
    let nrm = a.accessor(
        json!({"bufferView": view, "byteOffset": 12, "componentType": 5126, "count": 3, "type": "VEC3"}),
    );
    // Sparse: vertex 1 moves from (1, 0, 0) to (2, 0, 0).
    let idx = a.view(&1u16.to_le_bytes(), None);
    let val = a.view(
        &[2.0f32, 0.0, 0.0]
            .iter()
            .flat_map(|f| f.to_le_bytes())
            .collect::<Vec<_>>(),
        None,
    );
    let sparse = a.accessor(json!({"bufferView": view, "byteOffset": 0, "componentType": 5126, "count": 3, "type": "VEC3",
        "min": [0, 0, 0], "max": [2, 1, 0],
        "sparse": {"count": 1, "indices": {"bufferView": idx, "componentType": 5123}, "values": {"bufferView": val}}}));
    let _ = pos;
    let gltf = a.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": sparse, "NORMAL": nrm}}]}],
    }));
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf", material: "grey")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let mesh = &loaded.scene.geometry.meshes[0];
    let xs: Vec<f32> = mesh.positions.iter().map(|p| p.x).collect();
    assert_eq!(xs, vec![0.0, 2.0, 0.0], "sparse value replaced vertex 1");
    assert!(
        mesh.normals.iter().all(|n| *n == Vec3A::Z),
        "interleaved normals: {:?}",
        mesh.normals
    );
}

/// A quad (two triangles) at z = 0 spanning [−1, 1]², with UVs in set 1
/// (set 0 is zeros) and a material from `material`.
fn quad_asset(material: Value, tangents: bool, mirrored: bool) -> String {
    let mut a = Asset::default();
    let pos = a.floats(
        &[
            -1.0, -1.0, 0.0, 1.0, -1.0, 0.0, 1.0, 1.0, 0.0, -1.0, 1.0, 0.0, 3.0, -1.0, 0.0, 3.0, 1.0, 0.0,
        ],
        "VEC3",
    );
    let nrm = a.floats(&[0.0, 0.0, 1.0].repeat(6), "VEC3");
    // glTF UVs: v down. The right square mirrors the left in u.
    let uv1 = a.floats(
        &[0.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        "VEC2",
    );
    let uv0 = a.floats(&[0.0; 12], "VEC2");
    let idx: Vec<u16> = if mirrored {
        vec![0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2]
    } else {
        vec![0, 1, 2, 0, 2, 3]
    };
    let idx = a.indices(&idx);
    let mut attributes = json!({"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv0, "TEXCOORD_1": uv1});
    if tangents {
        // +u runs along +x on the left square and −x on the right one; glTF's
        // bitangent is w·(n × t) and runs along the image's up (+y here) on
        // both, so w = +1 on the left and −1 on the right. The shared middle
        // vertices (1, 2) cannot hold both: stored tangents need them split.
        let t = a.floats(&[1.0, 0.0, 0.0, 1.0].repeat(6), "VEC4");
        attributes["TANGENT"] = json!(t);
    }
    a.gltf(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": attributes, "indices": idx, "material": 0}]}],
        "materials": [material],
        "images": [{"uri": png_uri([128, 128, 255, 255])}, {"uri": png_uri([255, 0, 0, 77])}],
        "textures": [{"source": 0}, {"source": 1}],
    }))
}

#[test]
fn gltf_missing_tangent_gets_mikktspace_matching_stored_tangents() {
    let normal_mapped = json!({"name": "m", "normalTexture": {"index": 0, "texCoord": 1}});
    let gltf = quad_asset(normal_mapped.clone(), false, false);
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let mesh = &loaded.scene.geometry.meshes[0];
    assert_eq!(
        mesh.tangents.len(),
        mesh.positions.len(),
        "MikkTSpace tangents made"
    );
    // The second UV set was read (set 0 is all zeros).
    assert!(
        mesh.uvs.iter().any(|uv| uv.x > 0.5),
        "TEXCOORD_1 used: {:?}",
        mesh.uvs
    );
    let stored = quad_asset(normal_mapped, true, false);
    let with = load(
        &[("a.gltf", stored.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let m2 = &with.scene.geometry.meshes[0];
    for tri in 0..mesh.triangle_count() {
        for k in 0..3 {
            let (a, b) = (
                mesh.tangents[mesh.indices[tri][k] as usize],
                m2.tangents[m2.indices[tri][k] as usize],
            );
            assert!(
                (a - b).abs().max_element() < 1e-3,
                "triangle {tri} corner {k}: MikkTSpace {a} vs stored {b}"
            );
        }
    }
}

#[test]
fn gltf_mikktspace_flips_handedness_on_mirrored_uvs() {
    let normal_mapped = json!({"normalTexture": {"index": 0, "texCoord": 1}});
    let gltf = quad_asset(normal_mapped, false, true);
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let mesh = &loaded.scene.geometry.meshes[0];
    // The glTF convention written out: left square t = +x, w = +1; right
    // square t = −x, w = −1 (what an exporter stores for mirrored UVs).
    for (tri, corners) in mesh.indices.iter().enumerate() {
        let right = corners.iter().any(|&v| mesh.positions[v as usize].x > 1.5);
        for &v in corners {
            let t = mesh.tangents[v as usize];
            let want = if right {
                glam::Vec4::new(-1.0, 0.0, 0.0, -1.0)
            } else {
                glam::Vec4::new(1.0, 0.0, 0.0, 1.0)
            };
            assert!(
                (t - want).abs().max_element() < 1e-3,
                "triangle {tri}: {t} vs {want}"
            );
        }
    }
}

/// Issue 39, as for MTL `Ke`: an emissive strength of 1e38 made the
/// light's power infinite, silently. The emission is clamped to
/// `MAX_RADIANCE` with a note, and every light's power is finite.
#[test]
fn gltf_emission_above_the_limit_is_clamped_with_a_note() {
    let m = json!({"emissiveFactor": [1, 0.5, 0],
        "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 1e38}}});
    let mut gltf: Value = serde_json::from_str(&quad_asset(m, false, false)).expect("JSON");
    gltf["extensionsUsed"] = json!(["KHR_materials_emissive_strength"]);
    let loaded = load(
        &[("a.gltf", gltf.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let notes: Vec<&str> = loaded
        .warnings
        .diagnostics
        .iter()
        .map(|d| d.message.as_str())
        .collect();
    assert!(
        notes.iter().any(|n| n.contains("emissive strength")
            && n.contains("at most 1e12")
            && n.contains("read as [1000000000000, 1000000000000, 0]")),
        "{notes:#?}"
    );
    assert!(!loaded.scene.lights.is_empty(), "the emission was dropped");
    for l in &loaded.scene.lights {
        assert!(l.power().is_finite(), "a light's power is {:?}", l.power());
    }
}

/// A scene lit only by a glTF's emissive material renders lit, so the
/// "it will render black" warning must not say otherwise (it did: only
/// OBJ meshes were taken to maybe emit); with every material replaced by
/// a scene one that does not emit, the warning is right and stays.
#[test]
fn a_scene_lit_by_a_gltf_emitter_is_not_warned_black() {
    let m = json!({"emissiveFactor": [1, 0.5, 0]});
    let gltf = quad_asset(m, false, false);
    let scene = |object: &str| {
        format!(
            "Scene(
                camera: (eye: (0, 1, 6), target: (0, 0, 0), fov_y_degrees: 40),
                materials: {{ \"grey\": Lambert(albedo: 0.5) }},
                objects: [{object}],
            )"
        )
    };
    let black = |object: &str| {
        let loaded = load(&[("a.gltf", gltf.as_bytes())], &scene(object))
            .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
        let warned = notes_of(&loaded).iter().any(|n| n.contains("render black"));
        (warned, loaded.scene.lights.len())
    };
    let (warned, lights) = black(r#"Gltf(file: "a.gltf")"#);
    assert!(lights > 0, "the emissive quad is a light");
    assert!(!warned, "a scene lit by the glTF's emission was warned black");
    let (warned, lights) = black(r#"Gltf(file: "a.gltf", material: "grey")"#);
    assert_eq!(lights, 0);
    assert!(warned, "a scene with nothing emitting was not warned");
}

#[test]
fn gltf_mask_cuts_out_below_the_cutoff_only() {
    for (alpha, present) in [(0.3, false), (0.7, true)] {
        let m = json!({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, alpha]}, "alphaMode": "MASK", "alphaCutoff": 0.5});
        let gltf = quad_asset(m, false, false);
        let loaded = load(
            &[("a.gltf", gltf.as_bytes())],
            &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
        )
        .unwrap_or_else(|e| panic!("loads: {e}"));
        let ray = Ray::new(Vec3A::new(0.2, 0.1, 5.0), Vec3A::NEG_Z);
        assert_eq!(
            loaded.scene.intersect(&ray, f32::INFINITY).is_some(),
            present,
            "alpha {alpha} against cutoff 0.5"
        );
    }
}

#[test]
fn gltf_texture_transform_moves_the_lookup() {
    // Base colour from a 1×1 texture is constant, so the transform is
    // checked on the mapping itself: the extension's own example (offset
    // (0, 1), rotation π/2, scale ½) reads glTF uv (1, 0) at (0, ½) and
    // (0, 1) at (½, 1); in ronray's v-up UVs, (1, 1) → (0, ½), (0, 0) → (½, 0).
    let t = ronray::load::gltf::material::uv_transform([0.0, 1.0], std::f32::consts::FRAC_PI_2, [0.5, 0.5]);
    let a = t.0.expect("a transform");
    let close = |p: glam::Vec2, q: glam::Vec2| (p - q).length() < 1e-6;
    assert!(close(
        a.transform_point2(glam::Vec2::new(1.0, 1.0)),
        glam::Vec2::new(0.0, 0.5)
    ));
    assert!(close(
        a.transform_point2(glam::Vec2::new(0.0, 0.0)),
        glam::Vec2::new(0.5, 0.0)
    ));
    // And it reaches the material: the asset loads with the extension used.
    let m = json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1, "texCoord": 1,
        "extensions": {"KHR_texture_transform": {"offset": [0, 1], "rotation": 1.5707964, "scale": [0.5, 0.5]}}}}});
    let mut doc: Value = serde_json::from_str(&quad_asset(m, false, false)).expect("json");
    doc["extensionsUsed"] = json!(["KHR_texture_transform"]);
    load(
        &[("a.gltf", doc.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    // The normal map's transform too (the `gltf` crate hands its JSON
    // over unread: it was dropped, and the normal map kept its tiling while
    // the colour moved).
    let transform =
        json!({"KHR_texture_transform": {"offset": [0, 1], "rotation": 1.5707964, "scale": [0.5, 0.5]}});
    let m = json!({"normalTexture": {"index": 0, "texCoord": 1, "extensions": transform},
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 1, "texCoord": 1, "extensions": transform}}});
    let mut doc: Value = serde_json::from_str(&quad_asset(m, true, false)).expect("json");
    doc["extensionsUsed"] = json!(["KHR_texture_transform"]);
    let loaded = load(
        &[("a.gltf", doc.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    use ronray::materials::{Material, Perturb, Tex};
    let scene = &loaded.scene;
    let (k, colour) = scene
        .materials
        .iter()
        .enumerate()
        .find_map(|(k, m)| match m {
            Material::MetalPlastic(p) => match &p.base_color {
                Tex::Image(l) => Some((k, l.uv)),
                _ => None,
            },
            _ => None,
        })
        .expect("the asset's material");
    let Some(Perturb::NormalMap {
        map: Tex::Image(normal),
        ..
    }) = &scene.surfaces[k].normal
    else {
        panic!("no normal map on the asset's material");
    };
    assert!(colour.0.is_some(), "the colour's transform");
    assert_eq!(normal.uv, colour, "the normal map moves with the colour");
}

fn render(loaded: &ronray::load::Loaded) -> Vec<[u32; 3]> {
    let img: Image = render_whole(&loaded.scene, &loaded.view, &Default::default()).0;
    img.pixels
        .iter()
        .map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

/// A unit box's 8 corners and 12 counter-clockwise triangles.
fn unit_box() -> (Vec<[f32; 3]>, Vec<[u16; 3]>) {
    let p = (0..8)
        .map(|i| {
            [
                (i & 1) as f32 - 0.5,
                ((i >> 1) & 1) as f32 - 0.5,
                ((i >> 2) & 1) as f32 - 0.5,
            ]
        })
        .collect();
    let t = vec![
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [2, 6, 7],
        [2, 7, 3],
        [0, 4, 6],
        [0, 6, 2],
        [1, 3, 7],
        [1, 7, 5],
    ];
    (p, t)
}

#[test]
fn gltf_box_renders_byte_identical_to_the_same_box_as_obj() {
    let (p, t) = unit_box();
    let mut a = Asset::default();
    let pos = a.floats(&p.concat(), "VEC3");
    let idx = a.indices(&t.concat());
    let glb = a.glb(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
    }));
    let mut obj = String::new();
    for v in &p {
        obj += &format!("v {} {} {}\n", v[0], v[1], v[2]);
    }
    for f in &t {
        obj += &format!("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    let files: [(&str, &[u8]); 2] = [("box.glb", &glb), ("box.obj", obj.as_bytes())];
    let rot = r#"transform: [Rotate(axis: (0, 1, 0), degrees: 30)]"#;
    let from_gltf = load(
        &files,
        &scene_with(&format!(r#"Gltf(file: "box.glb", material: "grey", {rot})"#), ""),
    )
    .unwrap_or_else(|e| panic!("glb loads: {e}"));
    let ron_obj = scene_with(&format!(r#"Instance(mesh: "box", material: "grey", {rot})"#), "")
        .replace("objects:", "meshes: { \"box\": (file: \"box.obj\") },\n objects:");
    let from_obj = load(&files, &ron_obj).unwrap_or_else(|e| panic!("obj loads: {e}"));
    let (g, o) = (render(&from_gltf), render(&from_obj));
    assert!(g.iter().any(|p| p[0] != 0), "the box is lit");
    let differ = g.iter().zip(&o).filter(|(a, b)| a != b).count();
    assert_eq!(differ, 0, "{differ} of {} pixels differ", g.len());
}

#[test]
fn flat_normal_map_on_a_mesh_renders_byte_identical_to_no_map() {
    let obj = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n\
               f 1/1 4/4 3/3\nf 1/1 3/3 2/2\nf 1/1 2/2 5/5\nf 2/2 3/3 5/5\nf 3/3 4/4 5/5\nf 4/4 1/1 5/5\n";
    let files: [(&str, &[u8]); 1] = [("p.obj", obj.as_bytes())];
    let object = r#"Mesh(file: "p.obj", material: "m", transform: [Rotate(axis: (1, 0, 0), degrees: 20)])"#;
    let plain = load(&files, &scene_with(object, r#""m": Lambert(albedo: 0.6)"#)).expect("plain loads");
    let mapped = load(
        &files,
        &scene_with(
            object,
            r#""m": NormalMap(map: (0.5, 0.5, 1), material: Lambert(albedo: 0.6))"#,
        ),
    )
    .expect("mapped loads");
    assert!(
        !mapped.scene.geometry.meshes[0].tangents.is_empty(),
        "the mesh got tangents"
    );
    assert!(
        render(&plain) == render(&mapped),
        "a flat normal map changed the image"
    );
}

fn error_of(files: &[(&str, &[u8])]) -> String {
    match load(
        files,
        &scene_with(r#"Gltf(file: "a.gltf", material: "grey")"#, ""),
    ) {
        Ok(_) => panic!("a malformed asset loaded"),
        Err(LoadError::Invalid(r)) => r.render(false),
        Err(e) => panic!("not a located error: {e}"),
    }
}

#[test]
fn malformed_gltf_is_a_located_error() {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    let good = a.gltf(json!({"scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [tri]}));
    let mut doc: Value = serde_json::from_str(&good).expect("json");
    // Truncated buffer: says 36 bytes, holds 12.
    let mut t = doc.clone();
    t["buffers"][0]["uri"] = json!(format!(
        "data:application/octet-stream;base64,{}",
        b64(&a.bin[..12])
    ));
    let e = error_of(&[("a.gltf", t.to_string().as_bytes())]);
    assert!(
        e.contains("scene.ron:6:"),
        "located at the object's file line: {e}"
    );
    assert!(e.contains("truncated"), "names the truncation: {e}");
    // Out-of-range accessor: 30 elements in a 36-byte view.
    let mut t = doc.clone();
    t["accessors"][0]["count"] = json!(30);
    let e = error_of(&[("a.gltf", t.to_string().as_bytes())]);
    assert!(e.contains("run past"), "names the overrun: {e}");
    // A cycle in the node tree.
    let mut t = doc.clone();
    t["nodes"] = json!([{"mesh": 0, "children": [1]}, {"children": [0]}]);
    let e = error_of(&[("a.gltf", t.to_string().as_bytes())]);
    assert!(e.contains("cycle"), "names the cycle: {e}");
    // An unknown required extension.
    doc["extensionsUsed"] = json!(["EXT_from_the_future"]);
    doc["extensionsRequired"] = json!(["EXT_from_the_future"]);
    let e = error_of(&[("a.gltf", doc.to_string().as_bytes())]);
    assert!(e.contains("extensionsRequired"), "names the extension: {e}");
    // Not glTF at all.
    let e = error_of(&[("a.gltf", b"{\"asset\": 3")]);
    assert!(e.contains("invalid glTF"), "{e}");
}

/// A triangle with one morph target (its third corner 1 up in z): the
/// mesh's default weight 0.5 puts the corner at z = 0.5 without an
/// animation; an animation of the weight from 0 (0 s) to 1 (1 s) puts it
/// at z = 0.25 on the frame 0.25 s in; a second node placing the same
/// mesh without the animation stays at the default, so the morphed mesh is
/// its node's own.
#[test]
fn morph_targets_blend_by_the_weights_at_the_frame_time() {
    let mut a = Asset::default();
    let pos = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "VEC3");
    let up = a.floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], "VEC3");
    let times = a.floats(&[0.0, 1.0], "SCALAR");
    let w = a.floats(&[0.0, 1.0], "SCALAR");
    let gltf = a.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [5.0, 0.0, 0.0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "targets": [{"POSITION": up}]}], "weights": [0.5]}],
        "animations": [{
            "name": "rise",
            "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}],
            "samplers": [{"input": times, "output": w}],
        }],
    }));
    let corner_z = |extra: &str| -> Vec<f32> {
        let objects = format!(r#"Gltf(file: "a.gltf", material: "grey"{extra})"#);
        let scene = scene_with(&objects, "").replacen("Scene(", &animated(0, 48, 6), 1);
        let loaded =
            load(&[("a.gltf", gltf.as_bytes())], &scene).unwrap_or_else(|e| panic!("loads: {}", explain(e)));
        let geo = &loaded.scene.geometry;
        geo.instances
            .iter()
            .map(|i| {
                i.world_triangle(0, &geo.meshes)
                    .iter()
                    .map(|p| p.z)
                    .fold(f32::NEG_INFINITY, f32::max)
            })
            .collect()
    };
    let close = |got: f32, want: f32| assert!((got - want).abs() < 1e-6, "z {got}, expected {want}");
    let rest = corner_z("");
    assert_eq!(rest.len(), 2);
    close(rest[0], 0.5);
    close(rest[1], 0.5);
    let posed = corner_z(r#", animation: "rise""#);
    close(posed[0], 0.25); // frame 6 at 24 fps: 0.25 s
    close(posed[1], 0.5);
}

/// A skinned vertex with joints past the fourth (`JOINTS_1`) is skinned by
/// its first four, with a note saying the rest are not read.
/// Up to eight joints a vertex: `JOINTS_1`/`WEIGHTS_1` add to the first
/// four (a vertex split half and half between a joint of each set lands
/// half way; one weighed by the second set alone follows it), and a third
/// set is named in a note.
#[test]
fn a_second_set_of_joints_is_read_and_a_third_named_in_a_note() {
    let mut a = Asset::default();
    let pos = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "VEC3");
    // Set 0: vertex 0 half on joint 0, vertex 1 wholly on joint 0, vertex 2 nothing.
    let j0v = a.view(&[0; 12], None);
    let j0 = a.accessor(json!({"bufferView": j0v, "componentType": 5121, "count": 3, "type": "VEC4"}));
    let w0 = a.floats(
        &[0.5, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        "VEC4",
    );
    // Set 1: vertex 0 half on joint 1, vertex 2 wholly on joint 1.
    let j1v = a.view(&[1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0], None);
    let j1 = a.accessor(json!({"bufferView": j1v, "componentType": 5121, "count": 3, "type": "VEC4"}));
    let w1 = a.floats(
        &[0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
        "VEC4",
    );
    let none = a.floats(&[0.0; 12], "VEC4");
    let asset = |third: bool| {
        let mut attributes =
            json!({"POSITION": pos, "JOINTS_0": j0, "WEIGHTS_0": w0, "JOINTS_1": j1, "WEIGHTS_1": w1});
        if third {
            attributes["JOINTS_2"] = json!(j0);
            attributes["WEIGHTS_2"] = json!(none);
        }
        a.gltf(json!({
            "scenes": [{"nodes": [0, 1, 2]}],
            // The holding node is ignored; joint 1 is 10 up.
            "nodes": [{"mesh": 0, "skin": 0, "translation": [100, 0, 0]}, {}, {"translation": [0, 10, 0]}],
            "skins": [{"joints": [1, 2]}],
            "meshes": [{"primitives": [{"attributes": attributes}]}],
        }))
    };
    let load_asset = |gltf: &str| {
        load(
            &[("a.gltf", gltf.as_bytes())],
            &scene_with(r#"Gltf(file: "a.gltf", material: "grey")"#, ""),
        )
        .unwrap_or_else(|e| panic!("loads: {}", explain(e)))
    };
    let loaded = load_asset(&asset(false));
    let geo = &loaded.scene.geometry;
    let got: Vec<Vec3> = geo.instances[0]
        .world_triangle(0, &geo.meshes)
        .into_iter()
        .map(Vec3::from)
        .collect();
    let want = [
        Vec3::new(0.0, 5.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 11.0, 0.0),
    ];
    for w in want {
        assert!(
            got.iter().any(|g| (*g - w).length() < 1e-5),
            "{w} missing from {got:?}"
        );
    }
    assert!(
        !notes_of(&loaded).iter().any(|n| n.contains("JOINTS")),
        "{:?}",
        notes_of(&loaded)
    );
    let notes = notes_of(&load_asset(&asset(true)));
    assert!(notes.iter().any(|n| n.contains("JOINTS_2")), "{notes:?}");
}

/// Broken animations and skins are located errors at the object's file
/// (never a panic, never a silently wrong pose): key times that go back,
/// an output short of its keys, a vertex naming a joint the skin lacks,
/// `JOINTS_0` without `WEIGHTS_0`, fewer inverse bind matrices than joints,
/// and a cycle among the nodes a skin's joints hang from.
#[test]
fn malformed_animations_and_skins_are_located_errors() {
    let mut a = Asset::default();
    let pos = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "VEC3");
    let jv = a.view(&[0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], None);
    let joints = a.accessor(json!({"bufferView": jv, "componentType": 5121, "count": 3, "type": "VEC4"}));
    let bad_jv = a.view(&[0, 0, 0, 0, 7, 0, 0, 0, 0, 0, 0, 0], None);
    let bad_joints =
        a.accessor(json!({"bufferView": bad_jv, "componentType": 5121, "count": 3, "type": "VEC4"}));
    let weights = a.floats(
        &[1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
        "VEC4",
    );
    let ibm_bytes: Vec<u8> = Mat4::IDENTITY
        .to_cols_array()
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let ibm_view = a.view(&ibm_bytes, None);
    let ibm = a.accessor(json!({"bufferView": ibm_view, "componentType": 5126, "count": 1, "type": "MAT4"}));
    let back = a.floats(&[0.0, 2.0, 1.0], "SCALAR");
    let two = a.floats(&[0.0, 1.0], "SCALAR");
    let three_values = a.floats(&[0.0; 9], "VEC3");
    let two_values = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0], "VEC3");
    let one_value = a.floats(&[0.0; 3], "VEC3");
    let base = |attributes: Value, skin: Value, animations: Value| {
        a.gltf(json!({
            "scenes": [{"nodes": [0, 1]}],
            "nodes": [{"mesh": 0, "skin": 0}, {}],
            "skins": [skin],
            "meshes": [{"primitives": [{"attributes": attributes}]}],
            "animations": animations,
        }))
    };
    let good_attr = json!({"POSITION": pos, "JOINTS_0": joints, "WEIGHTS_0": weights});
    let good_skin = json!({"joints": [1], "inverseBindMatrices": ibm});
    let slide = |input: usize, output: usize| {
        json!([{"name": "a", "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                "samplers": [{"input": input, "output": output}]}])
    };
    let check = |doc: String, animation: bool, want: &str| {
        let extra = if animation { r#", animation: "a""# } else { "" };
        let objects = format!(r#"Gltf(file: "a.gltf", material: "grey"{extra})"#);
        let e = match load(&[("a.gltf", doc.as_bytes())], &scene_with(&objects, "")) {
            Ok(_) => panic!("loaded; expected an error with {want:?}"),
            Err(e) => explain(e),
        };
        assert!(
            e.contains("scene.ron:6:") && e.contains(want),
            "expected {want:?} at the file: {e}"
        );
    };
    // The good asset loads, posed.
    let good = base(good_attr.clone(), good_skin.clone(), slide(two, two_values));
    let objects = r#"Gltf(file: "a.gltf", material: "grey", animation: "a")"#;
    if let Err(e) = load(&[("a.gltf", good.as_bytes())], &scene_with(objects, "")) {
        panic!("the good asset: {}", explain(e));
    }
    check(
        base(good_attr.clone(), good_skin.clone(), slide(back, three_values)),
        true,
        "must increase",
    );
    check(
        base(good_attr.clone(), good_skin.clone(), slide(two, one_value)),
        true,
        "1 output values for 2 keys",
    );
    let bad = json!({"POSITION": pos, "JOINTS_0": bad_joints, "WEIGHTS_0": weights});
    check(base(bad, good_skin.clone(), json!([])), false, "names joint 7");
    let half = json!({"POSITION": pos, "JOINTS_0": joints});
    check(base(half, good_skin.clone(), json!([])), false, "one is missing");
    check(
        base(
            good_attr.clone(),
            json!({"joints": [1, 0], "inverseBindMatrices": ibm}),
            json!([]),
        ),
        false,
        "1 inverse bind matrices for 2 joints",
    );
    // A channel's target the `gltf` crate unwraps unchecked (a panic
    // before): a property that is none of the four, a node that is not.
    let aimed = |node: usize, path: &str| {
        json!([{"name": "a", "channels": [{"sampler": 0, "target": {"node": node, "path": path}}],
                "samplers": [{"input": two, "output": two_values}]}])
    };
    check(
        base(good_attr.clone(), good_skin.clone(), aimed(1, "translatio")),
        true,
        "channels[0].target.path",
    );
    check(
        base(good_attr.clone(), good_skin.clone(), aimed(9, "translation")),
        true,
        "node 9 does not exist",
    );
    let mut cyc: Value = serde_json::from_str(&base(good_attr, good_skin, json!([]))).expect("json");
    cyc["nodes"] = json!([{"mesh": 0, "skin": 0}, {"children": [2]}, {"children": [1]}]);
    check(cyc.to_string(), false, "cycle");
}

/// A load error as the user sees it.
fn explain(e: LoadError) -> String {
    match e {
        LoadError::Invalid(r) => r.render(false),
        e => e.to_string(),
    }
}

/// The notes of a load, as messages.
fn notes_of(loaded: &ronray::load::Loaded) -> Vec<String> {
    loaded
        .warnings
        .diagnostics
        .iter()
        .map(|d| d.message.clone())
        .collect()
}

/// The shipped Fox (skinned, three animations): without `animation` it
/// loads in its rest pose with a note naming the animations it could
/// play; with `"Walk"` its legs are somewhere else, and an animation it
/// does not have is an error at `animation` listing the three.
#[test]
fn fox_rests_without_an_animation_and_walks_with_one() {
    let fox = common::root().join("tests/fixtures/gltf/Fox.glb");
    let data = std::fs::read(&fox).expect("the Fox fixture");
    let with = |extra: &str, frame: i32| {
        let objects = format!(r#"Gltf(file: "Fox.glb", transform: [Scale((0.02, 0.02, 0.02))]{extra})"#);
        let scene = scene_with(&objects, "").replacen("Scene(", &animated(1, 48, frame), 1);
        load(&[("Fox.glb", &data)], &scene)
    };
    let rest = with("", 1).unwrap_or_else(|e| panic!("Fox loads: {}", explain(e)));
    let notes = notes_of(&rest);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("\"Survey\", \"Walk\", \"Run\"") && n.contains("rest pose")),
        "expected a note naming the animations, got {notes:?}"
    );
    let bounds = |l: &ronray::load::Loaded| l.scene.geometry.meshes[0].positions.clone();
    let p_rest = bounds(&rest);
    assert!(p_rest.len() > 100);
    let walk =
        |frame| with(r#", animation: "Walk""#, frame).unwrap_or_else(|e| panic!("Fox walks: {}", explain(e)));
    let (w1, w10) = (walk(1), walk(10));
    assert!(
        !notes_of(&w1).iter().any(|n| n.contains("rest pose")),
        "{:?}",
        notes_of(&w1)
    );
    let moved = |a: &[Vec3A], b: &[Vec3A]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| (*p - *q).length())
            .fold(0.0f32, f32::max)
    };
    let (a, b, c) = (p_rest.as_slice(), bounds(&w1), bounds(&w10));
    assert_eq!(a.len(), b.len());
    // Fox units (centimetres before the object's scale): the legs swing
    // by tens of them between frames, and every point stays near the fox.
    assert!(
        moved(a, &b) > 5.0,
        "walk frame 1 is the rest pose (moved {})",
        moved(a, &b)
    );
    assert!(
        moved(&b, &c) > 5.0,
        "frames 1 and 10 are one pose (moved {})",
        moved(&b, &c)
    );
    assert!(moved(a, &c) < 200.0, "a vertex flew off ({})", moved(a, &c));
    // Frame 10 again: the same pose, bit for bit.
    assert_eq!(bounds(&walk(10)), c, "posing is deterministic");
    let e = with(r#", animation: "Jump""#, 1)
        .err()
        .expect("no animation Jump");
    let msg = explain(e);
    assert!(
        msg.contains("animation") && msg.contains("\"Survey\", \"Walk\", \"Run\""),
        "{msg}"
    );
    assert!(Path::new(&fox).exists());
}

/// A triangle under a node whose translation is animated: at frame F of a
/// scene whose frames start at 1 (24 fps) it sits where the keys put it at
/// (F − 1)/24 s, LINEAR between keys, held past the last, wrapped with
/// `repeat`, and STEP holds each key.
#[test]
fn an_animated_node_moves_its_mesh_by_the_keys_at_the_frame_time() {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    // Keys at 0 s and 1 s: x from 0 to 2.
    let times = a.floats(&[0.0, 1.0], "SCALAR");
    let values = a.floats(&[0.0, 0.0, 0.0, 2.0, 0.0, 0.0], "VEC3");
    let doc = |interpolation: &str| {
        a.gltf(json!({
            "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0}],
            "meshes": [tri],
            "animations": [{
                "name": "slide",
                "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
                "samplers": [{"input": times, "output": values, "interpolation": interpolation}],
            }],
        }))
    };
    let x_at = |interpolation: &str, frame: i32, repeat: bool| -> f32 {
        let extra = if repeat { ", repeat: true" } else { "" };
        let objects = format!(r#"Gltf(file: "a.gltf", material: "grey", animation: "slide"{extra})"#);
        let scene = scene_with(&objects, "").replacen("Scene(", &animated(1, 200, frame), 1);
        let loaded = load(&[("a.gltf", doc(interpolation).as_bytes())], &scene)
            .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
        let geo = &loaded.scene.geometry;
        let [p, q, r] = geo.instances[0].world_triangle(0, &geo.meshes);
        p.x.min(q.x).min(r.x)
    };
    let close = |got: f32, want: f32| assert!((got - want).abs() < 1e-5, "x {got}, expected {want}");
    close(x_at("LINEAR", 1, false), 0.0);
    close(x_at("LINEAR", 13, false), 1.0); // 0.5 s
    close(x_at("LINEAR", 25, false), 2.0); // 1 s
    close(x_at("LINEAR", 49, false), 2.0); // 2 s: held
    close(x_at("LINEAR", 37, true), 1.0); // 1.5 s wraps to 0.5 s
    close(x_at("STEP", 13, false), 0.0);
    close(x_at("STEP", 25, false), 2.0);
    // `#0` names the same animation.
    let scene = scene_with(r##"Gltf(file: "a.gltf", material: "grey", animation: "#0")"##, "");
    assert!(load(&[("a.gltf", doc("LINEAR").as_bytes())], &scene).is_ok());
}

/// A node the animation moves is motion-blurred like a keyed instance:
/// with a half-frame shutter it moves from where the keys put it at the
/// opening to where they put it half a frame later; with the shutter
/// closed it holds still. A node whose animated scale is zero at the
/// frame drawn is left out of the picture, and is back once scaled up.
#[test]
fn animated_nodes_are_motion_blurred_and_scaled_to_nothing_is_hidden() {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    // x from 0 to 24 over 1 s: one unit per frame at 24 fps.
    let times = a.floats(&[0.0, 1.0], "SCALAR");
    let xs = a.floats(&[0.0, 0.0, 0.0, 24.0, 0.0, 0.0], "VEC3");
    // Scale 0 until 0.5 s, then 1 (STEP).
    let grow = a.floats(&[0.0, 0.0, 0.0, 1.0, 1.0, 1.0], "VEC3");
    let half = a.floats(&[0.0, 0.5], "SCALAR");
    let gltf = a.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"mesh": 0, "translation": [0.0, 5.0, 0.0]}],
        "meshes": [tri],
        "animations": [{"name": "go", "channels": [
            {"sampler": 0, "target": {"node": 0, "path": "translation"}},
            {"sampler": 1, "target": {"node": 1, "path": "scale"}},
        ], "samplers": [
            {"input": times, "output": xs},
            {"input": half, "output": grow, "interpolation": "STEP"},
        ]}],
    }));
    let at = |frame: i32, shutter: &str| {
        let scene = scene_with(r#"Gltf(file: "a.gltf", material: "grey", animation: "go")"#, "")
            .replacen("Scene(", &animated(0, 48, frame), 1)
            .replacen("fov_y_degrees: 40", &format!("fov_y_degrees: 40{shutter}"), 1);
        load(&[("a.gltf", gltf.as_bytes())], &scene).unwrap_or_else(|e| panic!("loads: {}", explain(e)))
    };
    // Frame 6 (0.25 s): the scaled node is hidden; the other moves.
    let blurred = at(6, ", shutter: (0, 0.5)");
    let geo = &blurred.scene.geometry;
    assert_eq!(geo.instances.len(), 1, "the node scaled to nothing is not placed");
    let m = geo.instances[0].motion().expect("the moving node is blurred");
    let x = |t: f32| m.placement_at(t).world_from_object.translation.x;
    assert!((x(6.0) - 6.0).abs() < 1e-4, "at the opening: {}", x(6.0));
    assert!((x(6.5) - 6.5).abs() < 1e-4, "at the closing: {}", x(6.5));
    assert!((x(6.25) - 6.25).abs() < 1e-4, "half way: {}", x(6.25));
    // Shutter closed: placed, still.
    let still = at(6, "");
    let geo = &still.scene.geometry;
    assert!(geo.instances[0].motion().is_none());
    assert!((geo.instances[0].world_from_object.translation.x - 6.0).abs() < 1e-4);
    // Frame 18 (0.75 s): the scaled node is back.
    assert_eq!(at(18, "").scene.geometry.instances.len(), 2);
}

/// A skinned strip of two triangles: the vertices weighted to the second
/// joint follow it when the animation turns that joint a quarter turn
/// about z, those weighted to the first stay, and a vertex split half and
/// half lands between (the blend of the two joint matrices). The node
/// holding the mesh is moved far away: skinned vertices ignore it, and a
/// second node with the same mesh and skin shares the one skinned mesh.
#[test]
fn a_skinned_mesh_follows_its_joints() {
    let mut a = Asset::default();
    // A quad from x = 0 to 2 in z = 0, split at x = 1.
    let pos = a.floats(
        &[
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 2.0, 1.0, 0.0,
        ],
        "VEC3",
    );
    let idx = a.indices(&[0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4]);
    let joints: Vec<u8> = [[0u8, 1, 0, 0]; 6].iter().flatten().copied().collect();
    let jv = a.view(&joints, None);
    let j = a.accessor(json!({"bufferView": jv, "componentType": 5121, "count": 6, "type": "VEC4"}));
    // x = 0: first joint; x = 1: half each; x = 2: second joint.
    let w = a.floats(
        &[
            1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0,
            0.0, 0.0, 1.0, 0.0, 0.0,
        ],
        "VEC4",
    );
    // Joint 1 sits at x = 1; its inverse bind matrix undoes that.
    let ibm: Vec<f32> = [Mat4::IDENTITY, Mat4::from_translation(Vec3::new(-1.0, 0.0, 0.0))]
        .iter()
        .flat_map(|m| m.to_cols_array())
        .collect();
    let ibm_view = a.view(
        &ibm.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>(),
        None,
    );
    let ibm = a.accessor(json!({"bufferView": ibm_view, "componentType": 5126, "count": 2, "type": "MAT4"}));
    let times = a.floats(&[0.0], "SCALAR");
    let turn = Quat::from_rotation_z(std::f32::consts::FRAC_PI_2);
    let rot = a.floats(&turn.to_array(), "VEC4");
    let gltf = a.gltf(json!({
        "scenes": [{"nodes": [0, 1, 3]}],
        "nodes": [
            {"children": [2]},
            {"mesh": 0, "skin": 0, "translation": [100.0, 0.0, 0.0]},
            {"translation": [1.0, 0.0, 0.0]},
            // The same mesh and skin again: the same triangles, built once.
            {"mesh": 0, "skin": 0, "translation": [0.0, -50.0, 0.0]},
        ],
        "skins": [{"joints": [0, 2], "inverseBindMatrices": ibm}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "JOINTS_0": j, "WEIGHTS_0": w}, "indices": idx}]}],
        "animations": [{
            "channels": [{"sampler": 0, "target": {"node": 2, "path": "rotation"}}],
            "samplers": [{"input": times, "output": rot}],
        }],
    }));
    let positions = |animation: &str| {
        let objects = format!(r#"Gltf(file: "a.gltf", material: "grey"{animation})"#);
        let loaded = load(&[("a.gltf", gltf.as_bytes())], &scene_with(&objects, ""))
            .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
        let geo = &loaded.scene.geometry;
        assert_eq!(
            geo.meshes.len(),
            1,
            "one skinned mesh for two nodes with one skin"
        );
        assert_eq!(geo.instances.len(), 2);
        let mut got: Vec<Vec3> = (0..geo.meshes[0].triangle_count() as u32)
            .flat_map(|t| geo.instances[0].world_triangle(t, &geo.meshes))
            .map(Vec3::from)
            .collect();
        got.sort_by(|p, q| p.to_array().partial_cmp(&q.to_array()).expect("numbers"));
        got.dedup_by(|p, q| (*p - *q).length() < 1e-5);
        got
    };
    let has = |got: &[Vec3], want: Vec3| {
        let near = got
            .iter()
            .map(|g| (*g - want).length())
            .fold(f32::INFINITY, f32::min);
        assert!(near < 1e-5, "{want} missing from {got:?}");
    };
    // At rest the joints are where the bind matrices say: the quad as stored.
    let rest = positions("");
    for p in [
        [0.0, 0.0],
        [1.0, 0.0],
        [2.0, 0.0],
        [0.0, 1.0],
        [1.0, 1.0],
        [2.0, 1.0],
    ] {
        has(&rest, Vec3::new(p[0], p[1], 0.0));
    }
    // Turned: joint 1's vertices (x = 2) swing about (1, 0) by 90°.
    let posed = positions(r##", animation: "#0""##);
    let bend = |p: Vec3| Vec3::new(1.0, 0.0, 0.0) + turn * (p - Vec3::new(1.0, 0.0, 0.0));
    has(&posed, Vec3::ZERO);
    has(&posed, Vec3::Y);
    has(&posed, bend(Vec3::new(2.0, 0.0, 0.0)));
    has(&posed, bend(Vec3::new(2.0, 1.0, 0.0)));
    // Half and half: the mean of the two joints' images.
    let x1 = Vec3::new(1.0, 1.0, 0.0);
    has(&posed, (x1 + bend(x1)) * 0.5);
}

/// A small valid `.glb` (a box), `.gltf` (a textured, normal-mapped,
/// sparse quad), an animated, skinned, morphed triangle (every
/// interpolation) and a floor with a light of each `KHR_lights_punctual`
/// kind, the glTF fuzz target's seeds.
fn seeds() -> Vec<(&'static str, Vec<u8>)> {
    let (p, t) = unit_box();
    let mut a = Asset::default();
    let pos = a.floats(&p.concat(), "VEC3");
    let idx = a.indices(&t.concat());
    let glb = a.glb(json!({
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "children": [1]}, {"mesh": 0, "scale": [1, 2, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos}, "indices": idx}]}],
    }));
    let m = json!({"normalTexture": {"index": 0, "texCoord": 1}, "alphaMode": "MASK",
        "pbrMetallicRoughness": {"baseColorTexture": {"index": 1}, "metallicRoughnessTexture": {"index": 0}}});
    vec![
        ("box.glb", glb),
        ("quad.gltf", quad_asset(m, true, true).into_bytes()),
        ("posed.gltf", posed_asset().into_bytes()),
        (
            "lit.gltf",
            lit_asset([json!({}), json!({}), json!({})]).into_bytes(),
        ),
        ("camera.gltf", camera::dolly_asset().into_bytes()),
    ]
}

/// A triangle with a morph target, skinned to two joints, and an
/// animation with a channel of each kind and every interpolation.
fn posed_asset() -> String {
    let mut a = Asset::default();
    let pos = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0], "VEC3");
    let up = a.floats(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], "VEC3");
    let jv = a.view(&[0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0], None);
    let joints = a.accessor(json!({"bufferView": jv, "componentType": 5121, "count": 3, "type": "VEC4"}));
    let weights = a.floats(
        &[1.0, 0.0, 0.0, 0.0, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0],
        "VEC4",
    );
    let times = a.floats(&[0.0, 0.5, 1.0], "SCALAR");
    let moves = a.floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 2.0, 0.0], "VEC3");
    let turns: Vec<f32> = [
        Quat::IDENTITY,
        Quat::from_rotation_z(1.0),
        Quat::from_rotation_x(2.0),
    ]
    .iter()
    .flat_map(|q| q.to_array())
    .collect();
    let turns = a.floats(&turns, "VEC4");
    // CUBICSPLINE: in-tangent, value, out-tangent per key.
    let mut scales = Vec::new();
    for v in [1.0f32, 2.0, 1.0] {
        scales.extend([0.0; 3]);
        scales.extend([v; 3]);
        scales.extend([0.0; 3]);
    }
    let scales = a.floats(&scales, "VEC3");
    let w = a.floats(&[0.0, 1.0, 0.5], "SCALAR");
    a.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0, "skin": 0}, {"children": [2]}, {"translation": [1.0, 0.0, 0.0]}],
        "skins": [{"joints": [1, 2]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "JOINTS_0": joints, "WEIGHTS_0": weights},
                                    "targets": [{"POSITION": up}]}], "weights": [0.0]}],
        "animations": [{"name": "all", "channels": [
            {"sampler": 0, "target": {"node": 1, "path": "translation"}},
            {"sampler": 1, "target": {"node": 2, "path": "rotation"}},
            {"sampler": 2, "target": {"node": 2, "path": "scale"}},
            {"sampler": 3, "target": {"node": 0, "path": "weights"}},
        ], "samplers": [
            {"input": times, "output": moves},
            {"input": times, "output": turns, "interpolation": "LINEAR"},
            {"input": times, "output": scales, "interpolation": "CUBICSPLINE"},
            {"input": times, "output": w, "interpolation": "STEP"},
        ]}],
    }))
}

#[test]
fn gltf_fuzz_seeds_are_committed_and_current() {
    let dir = common::root().join("fuzz/corpus/gltf");
    for (name, bytes) in seeds() {
        let path = dir.join(name);
        if std::env::var_os("RONRAY_WRITE_SEEDS").is_some() {
            std::fs::create_dir_all(&dir).expect("mkdir");
            std::fs::write(&path, &bytes).expect("write seed");
        }
        assert!(ronray::fuzzing::gltf(&bytes), "seed {name} imports");
        assert!(
            path.exists(),
            "{} missing: RONRAY_WRITE_SEEDS=1 cargo test --test integration gltf::",
            path.display()
        );
    }
}

#[test]
fn gltf_byte_mutations_never_panic() {
    // A few hundred single-byte corruptions of each seed, seeded: every
    // one must import or fail, never panic (the fuzz target, in small).
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    for (_, seed) in seeds() {
        for _ in 0..300 {
            let mut bytes = seed.clone();
            let at = (next() % bytes.len() as u64) as usize;
            bytes[at] = (next() & 0xff) as u8;
            let _ = ronray::fuzzing::gltf(&bytes);
        }
    }
}

/// `KHR_lights_punctual` lights with a floor (a triangle turned to face
/// +y, over x ∈ [0, 5], z ∈ [−5, 0]), as an asset: a point light
/// at (0, 3, 0), a spot on a node turned to shine down (−z turned a
/// quarter turn about x), a directional light turned likewise, each with
/// `extra` merged into its light, under a scene that moves the asset by
/// `transform`.
fn lit_asset(extra: [Value; 3]) -> String {
    let mut a = Asset::default();
    let mut lights = vec![
        json!({"type": "point", "color": [1.0, 0.5, 0.25], "intensity": 683.0, "range": 20.0}),
        json!({"type": "spot", "intensity": 1366.0, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}}),
        json!({"type": "directional", "color": [0.5, 0.5, 0.5], "intensity": 1366.0}),
    ];
    for (l, e) in lights.iter_mut().zip(extra) {
        for (k, v) in e.as_object().expect("an object") {
            l[k] = v.clone();
        }
    }
    let floor = triangle(&mut a);
    let down = [
        -std::f32::consts::FRAC_1_SQRT_2,
        0.0,
        0.0,
        std::f32::consts::FRAC_1_SQRT_2,
    ];
    a.gltf(json!({
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": lights}},
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0, "scale": [5, 5, 5], "rotation": down},
            {"translation": [0, 3, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
            {"translation": [1, 2, 0], "rotation": down, "scale": [4, 4, 4],
             "extensions": {"KHR_lights_punctual": {"light": 1}}},
            {"rotation": down, "extensions": {"KHR_lights_punctual": {"light": 2}}},
        ],
        "meshes": [floor],
    }))
}

/// An asset's point, spot and directional lights join the scene's lights
/// where their nodes and the object's transform put them, their candela
/// and lux over 683 lm/W, a spot's half-angles as `Spot`'s full cone; a
/// `range` is named in a note; a scene lit only by them is not warned
/// black, and renders lit.
#[test]
fn gltf_punctual_lights_are_placed_and_converted() {
    use ronray::lights::Light;
    let gltf = lit_asset([json!({}), json!({}), json!({})]);
    let scene = |lights: &str| {
        format!(
            "Scene(
                camera: (eye: (12, 6, 6), target: (12, 0, -2), fov_y_degrees: 40),
                integrator: Path(max_depth: 2),
                materials: {{ \"grey\": Lambert(albedo: 0.5) }},
                lights: [{lights}],
                objects: [Gltf(file: \"a.gltf\", material: \"grey\", transform: [Translate((10, 0, 0))])],
            )"
        )
    };
    let loaded =
        load(&[("a.gltf", gltf.as_bytes())], &scene("")).unwrap_or_else(|e| panic!("{}", explain(e)));
    let lights = &loaded.scene.lights;
    assert_eq!(lights.len(), 3, "three lights");
    let close = |a: Vec3A, b: Vec3A| (a - b).length() < 1e-4;
    match &lights[0] {
        Light::Point(p) => {
            assert!(close(p.position, Vec3A::new(10.0, 3.0, 0.0)), "{}", p.position);
            assert!(close(p.intensity, Vec3A::new(1.0, 0.5, 0.25)), "{}", p.intensity);
        }
        other => panic!("not a point light: {other:?}"),
    }
    match &lights[1] {
        Light::Spot(s) => {
            assert!(close(s.position, Vec3A::new(11.0, 2.0, 0.0)), "{}", s.position);
            assert!(close(s.direction, Vec3A::NEG_Y), "{}", s.direction);
            assert!(close(s.intensity, Vec3A::splat(2.0)));
            // Full intensity within 0.2 rad of the axis, none past 0.5.
            assert_eq!(s.falloff(0.19f32.cos()), 1.0);
            assert_eq!(s.falloff(0.51f32.cos()), 0.0);
            assert!(s.falloff(0.35f32.cos()) > 0.0 && s.falloff(0.35f32.cos()) < 1.0);
        }
        other => panic!("not a spot light: {other:?}"),
    }
    match &lights[2] {
        Light::Directional(d) => {
            assert!(close(d.direction, Vec3A::NEG_Y), "{}", d.direction);
            assert!(close(d.irradiance, Vec3A::ONE), "{}", d.irradiance);
        }
        other => panic!("not a directional light: {other:?}"),
    }
    let notes = notes_of(&loaded);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("3 KHR_lights_punctual light(s) placed")),
        "{notes:?}"
    );
    assert!(
        notes.iter().any(|n| n.contains("1 light(s) give a `range`")),
        "{notes:?}"
    );
    assert!(!notes.iter().any(|n| n.contains("render black")), "{notes:?}");
    // Lit by them alone: the floor under the sun is ρ/π · E = 0.5/π · 1 and
    // more (the point and the spot add to it).
    let img = render_whole(&loaded.scene, &loaded.view, &Default::default()).0;
    let mean = img.pixels.iter().map(|p| p.x).sum::<f32>() / img.pixels.len() as f32;
    assert!(mean > 0.02, "the asset's lights light nothing: mean {mean}");
    // Without its lights (a zero intensity each) the same scene is black
    // and warned so.
    let dark = lit_asset([
        json!({"intensity": 0}),
        json!({"intensity": 0}),
        json!({"intensity": 0}),
    ]);
    let loaded =
        load(&[("a.gltf", dark.as_bytes())], &scene("")).unwrap_or_else(|e| panic!("{}", explain(e)));
    assert!(notes_of(&loaded).iter().any(|n| n.contains("render black")));
}

/// A light with values outside the extension's ranges is a located error
/// naming the light and what is wrong; a node naming a light that does
/// not exist is refused; a light whose node is scaled to nothing has no
/// direction and is left out with a note.
#[test]
fn malformed_punctual_lights_are_located_errors() {
    for (extra, want) in [
        ([json!({"intensity": -1.0}), json!({}), json!({})], "intensity -1"),
        (
            [json!({"color": [1.0, -2.0, 0.0]}), json!({}), json!({})],
            "color",
        ),
        (
            [
                json!({}),
                json!({"spot": {"innerConeAngle": 0.6, "outerConeAngle": 0.5}}),
                json!({}),
            ],
            "spot cone angles",
        ),
        (
            [
                json!({}),
                json!({"spot": {"innerConeAngle": 0.1, "outerConeAngle": 2.0}}),
                json!({}),
            ],
            "spot cone angles",
        ),
        (
            [json!({}), json!({}), json!({"intensity": 1e30})],
            "past the limit",
        ),
    ] {
        let gltf = lit_asset(extra);
        let e = error_of(&[("a.gltf", gltf.as_bytes())]);
        assert!(e.contains("objects[0].file") || e.contains("file:"), "{e}");
        assert!(
            e.contains(want) && e.contains("KHR_lights_punctual light"),
            "{want}: {e}"
        );
    }
    // A node naming light 7 of three.
    let gltf = lit_asset([json!({}), json!({}), json!({})]).replace("{\"light\":2}", "{\"light\":7}");
    assert!(gltf.contains("\"light\":7"), "the replacement found its text");
    let e = error_of(&[("a.gltf", gltf.as_bytes())]);
    assert!(
        e.contains("nodes[3]") && e.contains("light") && e.contains("out of bounds"),
        "{e}"
    );
    // Scaled to nothing: no direction.
    let gltf = lit_asset([json!({}), json!({}), json!({})]).replace("\"scale\":[4,4,4]", "\"scale\":[0,0,0]");
    assert!(
        gltf.contains("\"scale\":[0,0,0]"),
        "the replacement found its text"
    );
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("{}", explain(e)));
    // The scene's own point light, the asset's point and directional.
    assert_eq!(loaded.scene.lights.len(), 3);
    let notes = notes_of(&loaded);
    assert!(notes.iter().any(|n| n.contains("has no direction")), "{notes:?}");
    // Placed beyond the scene's coordinate limit: left out with a note.
    let gltf = lit_asset([json!({}), json!({}), json!({})])
        .replace("\"translation\":[0,3,0]", "\"translation\":[0,3e20,0]");
    assert!(gltf.contains("3e20"), "the replacement found its text");
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("{}", explain(e)));
    assert_eq!(
        loaded.scene.lights.len(),
        3,
        "the scene's point light, the asset's spot and sun"
    );
    let notes = notes_of(&loaded);
    assert!(notes.iter().any(|n| n.contains("coordinate limit")), "{notes:?}");
}

/// `KHR_materials_transmission` becomes glass: a thin sheet without
/// `KHR_materials_volume` (the extension's thin-walled default), a solid's
/// boundary with one (rough above 0.05), tinted by the base colour, at
/// `KHR_materials_ior`; partly transmissive (metallic counts against it),
/// a blend of glass and the metallic–roughness model.
#[test]
fn gltf_transmission_is_glass_thin_unless_it_has_a_volume() {
    use ronray::materials::Bsdf;
    let mut a = Asset::default();
    let cases = [
        // (extensions, roughness, metallic)
        (
            json!({"KHR_materials_transmission": {"transmissionFactor": 1.0}}),
            0.0,
            0.0,
        ),
        (
            json!({"KHR_materials_transmission": {"transmissionFactor": 1.0},
                   "KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationColor": [0.5, 0.25, 1.0],
                                            "attenuationDistance": 2.0},
                   "KHR_materials_ior": {"ior": 1.33}}),
            0.0,
            0.0,
        ),
        (
            json!({"KHR_materials_transmission": {"transmissionFactor": 1.0},
                   "KHR_materials_volume": {"thicknessFactor": 0.5, "attenuationColor": [0.5, 0.5, 0.5],
                                            "attenuationDistance": 0.0}}),
            0.5,
            0.0,
        ),
        (
            json!({"KHR_materials_transmission": {"transmissionFactor": 0.3}}),
            0.0,
            0.0,
        ),
        (
            json!({"KHR_materials_transmission": {"transmissionFactor": 1.0}}),
            0.0,
            0.8,
        ),
    ];
    let meshes: Vec<Value> = (0..cases.len())
        .map(|k| {
            let x = 3.0 * k as f32;
            let pos = a.floats(&[x, 0.0, 0.0, x + 1.0, 0.0, 0.0, x, 1.0, 0.0], "VEC3");
            json!({"primitives": [{"attributes": {"POSITION": pos}, "material": k}]})
        })
        .collect();
    let materials: Vec<Value> = cases
        .iter()
        .enumerate()
        .map(|(k, (ext, rough, metal))| {
            json!({"name": format!("m{k}"), "extensions": ext,
                   "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.6, 0.3, 1.0],
                                            "roughnessFactor": rough, "metallicFactor": metal}})
        })
        .collect();
    let nodes: Vec<Value> = (0..cases.len()).map(|k| json!({"mesh": k})).collect();
    let gltf = a.gltf(json!({
        "extensionsUsed": ["KHR_materials_transmission", "KHR_materials_volume", "KHR_materials_ior"],
        "scenes": [{"nodes": (0..cases.len()).collect::<Vec<_>>()}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": materials,
    }));
    let loaded = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let scene = &loaded.scene;
    let bsdf_of = |k: usize| {
        let o = Vec3A::new(3.0 * k as f32 + 0.25, 0.25, 5.0);
        let hit = scene
            .intersect(&Ray::new(o, Vec3A::new(0.0, 0.0, -1.0)), f32::INFINITY)
            .unwrap_or_else(|| panic!("part {k} is hit"));
        scene.materials[hit.material as usize].bsdf(&ronray::materials::TexPoint::at(&hit), &scene.textures)
    };
    let tint = ronray::math::Rgb::new(0.9, 0.6, 0.3);
    // KHR_materials_volume's attenuation: σ = −ln(colour)/distance inside
    // the solid; none without a volume, none (and a note) for a distance
    // of 0, which is no length.
    let absorption_of = |k: usize| {
        let o = Vec3A::new(3.0 * k as f32 + 0.25, 0.25, 5.0);
        let hit = scene
            .intersect(&Ray::new(o, Vec3A::new(0.0, 0.0, -1.0)), f32::INFINITY)
            .unwrap_or_else(|| panic!("part {k} is hit"));
        scene
            .absorption
            .get(hit.material as usize)
            .copied()
            .flatten()
            .unwrap_or_default()
    };
    let sigma = absorption_of(1);
    let want = [2f32.ln() / 2.0, 4f32.ln() / 2.0, 0.0];
    assert!(
        (0..3).all(|c| (sigma[c] - want[c]).abs() < 1e-5),
        "absorption {sigma} against {want:?}"
    );
    assert_eq!(
        absorption_of(0),
        ronray::math::Rgb::ZERO,
        "a thin sheet absorbs nothing"
    );
    assert_eq!(absorption_of(2), ronray::math::Rgb::ZERO);
    let notes = loaded
        .warnings
        .diagnostics
        .iter()
        .map(|d| d.message.clone())
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        notes.contains("attenuationDistance 0 is no absorption"),
        "the unusable attenuation is noted: {notes}"
    );
    match bsdf_of(0) {
        Bsdf::Glass(g) => assert!(g.thin && g.ior == 1.5 && g.tint == tint, "{g:?}"),
        b => panic!("no volume: a thin sheet, not {b:?}"),
    }
    match bsdf_of(1) {
        Bsdf::Glass(g) => assert!(!g.thin && g.ior == 1.33 && g.tint == tint, "{g:?}"),
        b => panic!("a volume: a solid's boundary, not {b:?}"),
    }
    match bsdf_of(2) {
        Bsdf::RoughGlass(g) => assert!(g.ior == 1.5 && g.tint == tint, "{g:?}"),
        b => panic!("a rough volume: rough glass, not {b:?}"),
    }
    // Partly transmissive: a blend, glass on transmission × (1 − metallic)
    // of the hits (each ray's pick is its own: rays from 4,000 points).
    for (k, want) in [(3, 0.3), (4, 0.2)] {
        let (mut glass, n) = (0, 4_000);
        for i in 0..n {
            let o = Vec3A::new(
                3.0 * k as f32 + 0.05 + 0.4 * (i % 64) as f32 / 64.0,
                0.05 + 0.4 * (i / 64) as f32 / 64.0,
                5.0,
            );
            let hit = scene
                .intersect(&Ray::new(o, Vec3A::new(0.0, 0.0, -1.0)), f32::INFINITY)
                .unwrap_or_else(|| panic!("part {k} is hit"));
            match scene.materials[hit.material as usize]
                .bsdf(&ronray::materials::TexPoint::at(&hit), &scene.textures)
            {
                Bsdf::Glass(g) => {
                    assert!(g.thin && g.tint == tint, "{g:?}");
                    glass += 1;
                }
                Bsdf::MetalPlastic(_) => {}
                b => panic!("case {k}: glass or the metallic–roughness model, not {b:?}"),
            }
        }
        let share = glass as f32 / n as f32;
        // 4σ of a binomial share at n = 4,000 is under 0.03.
        assert!(
            (share - want).abs() < 0.03,
            "case {k}: glass on {share} of the hits, expected {want}"
        );
    }
}

/// A `KHR_mesh_quantization` asset (the form gltfpack and glTF-Transform
/// write for the web), required by the file: integer positions
/// dequantised by the node's scale, normalised `i8` normals and `u16`
/// texture coordinates, read as the floats they stand for.
#[test]
fn quantized_meshes_are_read() {
    let mut a = Asset::default();
    let u16s = |d: &[u16]| d.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let view = a.view(&u16s(&[0, 0, 0, 1000, 0, 0, 0, 1000, 0]), None);
    let pos = a.accessor(
        json!({"bufferView": view, "componentType": 5123, "count": 3, "type": "VEC3",
        "min": [0, 0, 0], "max": [1000, 1000, 0]}),
    );
    let view = a.view(&[0, 0, 127, 0, 0, 0, 127, 0, 0, 0, 127, 0], Some(4));
    let normal = a.accessor(
        json!({"bufferView": view, "componentType": 5120, "normalized": true,
        "count": 3, "type": "VEC3"}),
    );
    let view = a.view(&u16s(&[0, 0, 65535, 0, 0, 65535]), None);
    let uv = a.accessor(
        json!({"bufferView": view, "componentType": 5123, "normalized": true,
        "count": 3, "type": "VEC2"}),
    );
    let doc = a.gltf(json!({
        "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "scale": [0.002, 0.002, 0.002]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": pos, "NORMAL": normal, "TEXCOORD_0": uv}}]}],
    }));
    let loaded = load(
        &[("a.gltf", doc.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf", material: "grey")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let geo = &loaded.scene.geometry;
    let tri = geo.instances[0].world_triangle(0, &geo.meshes);
    for (got, want) in tri
        .iter()
        .zip([Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)])
    {
        assert!((Vec3::from(*got) - want).length() < 1e-5, "{got} against {want}");
    }
    let mesh = &geo.meshes[0];
    assert!(
        mesh.normals.iter().all(|n| (*n - Vec3A::Z).length() < 1e-6),
        "{:?}",
        mesh.normals
    );
    // glTF's v runs down; ronray stores 1 − v.
    let uvs: Vec<[f32; 2]> = mesh.uvs.iter().map(|v| v.to_array()).collect();
    assert_eq!(uvs, [[0.0, 1.0], [1.0, 1.0], [0.0, 0.0]]);
}

/// An `emissiveTexture` varies the light over the surface (it was its
/// mean colour everywhere): a quad whose emission map is red on its left
/// half and black on its right glows `emissiveFactor` × red on the left
/// and not at all on the right, and a surface the quad lights sees its
/// light come from the left half.
#[test]
fn gltf_emissive_texture_varies_the_light_over_the_surface() {
    let mut bytes = Vec::new();
    let img = image::RgbaImage::from_fn(2, 1, |x, _| {
        if x == 0 {
            image::Rgba([255, 0, 0, 255])
        } else {
            image::Rgba([0, 0, 0, 255])
        }
    });
    img.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .expect("encode png");
    let m = json!({"emissiveFactor": [2, 2, 2], "emissiveTexture": {"index": 1, "texCoord": 1},
        "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1], "metallicFactor": 1}});
    let mut gltf: Value = serde_json::from_str(&quad_asset(m, false, false)).expect("JSON");
    gltf["images"][1] = json!({"uri": format!("data:image/png;base64,{}", b64(&bytes))});
    let loaded = load(
        &[("a.gltf", gltf.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let seen = |x: f32| {
        let from = Vec3A::new(x, 0.0, 3.0);
        common::mean_li(&loaded, Ray::new(from, Vec3A::new(0.0, 0.0, -1.0)), 16)
    };
    let (left, right) = (seen(-0.5), seen(0.5));
    assert!(
        (left - Vec3A::new(2.0, 0.0, 0.0)).length() < 1e-3,
        "left half: {left}"
    );
    assert!(right.length() < 1e-3, "right half: {right}");
    // The light's power is its mean radiance × area × π: one red quad-half
    // (beside the scene's point light, 4π × 30 W/sr).
    let all = loaded
        .scene
        .lights
        .iter()
        .fold(ronray::math::Rgb::ZERO, |a, l| a + l.power());
    let total = all - ronray::math::Rgb::splat(4.0 * std::f32::consts::PI * 30.0);
    let want = 2.0 * 2.0 * std::f32::consts::PI; // 2 W/(m²·sr) × 2 m² lit × π
    assert!(
        (total.x - want).abs() < 0.05 * want && total.y.abs() < 1e-2,
        "the quad's power {total:?} against {want} in red"
    );
}

/// A `transmissionTexture` weighs the blend per point: the left half of
/// the quad (red 255 × factor 0.8) is glass on 80% of its hits, the right
/// half (red 0) never.
#[test]
fn gltf_transmission_texture_weighs_the_glass_per_point() {
    use ronray::materials::Bsdf;
    let mut bytes = Vec::new();
    // Eight texels: the bilinear lookup is flat over each half's middle.
    let img = image::RgbaImage::from_fn(8, 1, |x, _| image::Rgba([if x < 4 { 255 } else { 0 }, 0, 0, 255]));
    img.write_to(&mut std::io::Cursor::new(&mut bytes), image::ImageFormat::Png)
        .expect("encode png");
    let m = json!({"extensions": {"KHR_materials_transmission":
            {"transmissionFactor": 0.8, "transmissionTexture": {"index": 1, "texCoord": 1}}},
        "pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1], "metallicFactor": 0}});
    let mut gltf: Value = serde_json::from_str(&quad_asset(m, false, false)).expect("JSON");
    gltf["images"][1] = json!({"uri": format!("data:image/png;base64,{}", b64(&bytes))});
    gltf["extensionsUsed"] = json!(["KHR_materials_transmission"]);
    let loaded = load(
        &[("a.gltf", gltf.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let scene = &loaded.scene;
    let glass_share = |x0: f32| {
        let (mut glass, n) = (0, 4_000);
        for i in 0..n {
            let o = Vec3A::new(
                x0 + 0.5 * (i % 64) as f32 / 64.0,
                -0.25 + 0.5 * (i / 64) as f32 / 64.0,
                3.0,
            );
            let hit = scene
                .intersect(&Ray::new(o, Vec3A::new(0.0, 0.0, -1.0)), f32::INFINITY)
                .expect("the quad is hit");
            if matches!(
                scene.materials[hit.material as usize]
                    .bsdf(&ronray::materials::TexPoint::at(&hit), &scene.textures),
                Bsdf::Glass(_)
            ) {
                glass += 1;
            }
        }
        glass as f32 / n as f32
    };
    let (left, right) = (glass_share(-0.75), glass_share(0.25));
    assert!(
        (left - 0.8).abs() < 0.03,
        "left half: glass on {left} of the hits"
    );
    assert!(right == 0.0, "right half: glass on {right} of the hits");
}

/// A texture's sampler `wrapS`/`wrapT` reach the lookup (they were read as
/// repeat, with a note): clamp along u and mirror along v.
#[test]
fn gltf_sampler_wrap_modes_are_kept() {
    use ronray::materials::{Material, Tex, Wrap};
    let m = json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1, "texCoord": 1}}});
    let mut gltf: Value = serde_json::from_str(&quad_asset(m, false, false)).expect("JSON");
    gltf["samplers"] = json!([{"wrapS": 33071, "wrapT": 33648}]);
    gltf["textures"][1]["sampler"] = json!(0);
    let loaded = load(
        &[("a.gltf", gltf.to_string().as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let wraps: Vec<[Wrap; 2]> = loaded
        .scene
        .materials
        .iter()
        .filter_map(|m| match m {
            Material::MetalPlastic(p) => match &p.base_color {
                Tex::Image(l) => Some(l.wrap),
                _ => None,
            },
            _ => None,
        })
        .collect();
    assert_eq!(wraps, [[Wrap::Clamp, Wrap::Mirror]]);
    assert!(
        !notes_of(&loaded).iter().any(|n| n.contains("wrap")),
        "{:?}",
        notes_of(&loaded)
    );
}

/// An extension the asset uses and ronray does not read (here clear coat
/// and sheen) renders without it, named in one note; the ones it reads are
/// not named.
#[test]
fn extensions_used_but_not_read_are_named_in_a_note() {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    let gltf = a.gltf(json!({
        "extensionsUsed": ["KHR_texture_transform", "KHR_materials_clearcoat", "KHR_materials_sheen"],
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [tri],
        "materials": [{"extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 1.0}}}],
    }));
    let l = load(
        &[("a.gltf", gltf.as_bytes())],
        &scene_with(r#"Gltf(file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {e}"));
    let notes = notes_of(&l);
    let named: Vec<&String> = notes.iter().filter(|n| n.contains("not read")).collect();
    assert_eq!(named.len(), 1, "{notes:?}");
    assert!(
        named[0].contains("KHR_materials_clearcoat, KHR_materials_sheen")
            && !named[0].contains("KHR_texture_transform"),
        "{}",
        named[0]
    );
}
