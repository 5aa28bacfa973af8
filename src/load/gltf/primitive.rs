//! One glTF mesh → one ronray [`Mesh`], each primitive a material slot.
//!
//! Primitive modes that make triangles (`TRIANGLES`, `TRIANGLE_STRIP`,
//! `TRIANGLE_FAN`) are read; points and lines are skipped with a note.
//! Attributes: `POSITION` (required), `NORMAL`, `TANGENT`, the UV set the
//! material's textures read (`TEXCOORD_0` or `_1`, v flipped to ronray's
//! v-up), `COLOR_0` (linear RGB; its alpha is not read, with a note: the
//! materials of primitives that have it multiply their base colour by it,
//! `Tex::Vertex`). Tangents
//! come from the file, else MikkTSpace when the material has a normal map
//! (per primitive, before the primitives are merged, so seams between
//! primitives do not weld).

use super::accessor::{Buffers, read_f32, read_indices};
use super::material::Mapped;
use super::skin::{self, Influence};
use crate::geometry::Mesh;
use glam::{Vec2, Vec3A, Vec4};
use gltf::Document;
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::{Mode, Semantic};

/// A built mesh, its slots' materials, and (when asked for a skinned
/// mesh) each vertex's joint influences.
pub type Built = (Mesh, Vec<Mapped>, Option<Vec<Influence>>);

/// Builds mesh `index`; `material` maps a primitive's glTF material to the
/// scene's. `weights` blends the primitives' morph targets into their
/// base shape. With `skinned`, each vertex's `JOINTS_0`/`WEIGHTS_0` come
/// back too (zero weights where a primitive has none). Errors name the
/// primitive. The scene materials of primitives with `COLOR_0` go to
/// `painted`.
#[allow(clippy::too_many_arguments)]
pub fn build(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    weights: Option<&[f32]>,
    skinned: bool,
    material: &mut dyn FnMut(Option<gltf::Material>) -> Mapped,
    painted: &mut Vec<u32>,
    notes: &mut Vec<String>,
) -> Result<Built, String> {
    let m = doc
        .meshes()
        .nth(index)
        .ok_or_else(|| format!("meshes[{index}] does not exist"))?;
    let mut mesh = Mesh::default();
    let mut slots = Vec::new();
    let mut influences: Vec<Influence> = Vec::new();
    for p in m.primitives() {
        let at = format!("meshes[{index}].primitives[{}]", p.index());
        let mode = p.mode();
        if !matches!(mode, Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan) {
            notes.push(format!("{at}: mode {mode:?} makes no triangles; skipped"));
            continue;
        }
        let mapped = material(p.material().index().map(|_| p.material()));
        let part =
            read_primitive(doc, buffers, &p, mapped, mode, weights).map_err(|e| format!("{at}: {e}"))?;
        if part.colors {
            painted.push(mapped.index);
        }
        if part.translucent_colors {
            notes.push(format!(
                "{at}: COLOR_0's alpha is below 1 but is not read (only its RGB tints the base colour)"
            ));
        }
        if skinned {
            if p.get(&Semantic::Joints(2)).is_some() {
                notes.push(format!(
                    "{at}: JOINTS_2/WEIGHTS_2 and later (joints past the eighth) are not read: each \
                     vertex follows its first eight, their weights rescaled to sum to 1"
                ));
            }
            let n = part.mesh.positions.len();
            match skin::influences(doc, buffers, &p, n).map_err(|e| format!("{at}: {e}"))? {
                Some(v) => influences.extend(v),
                None => influences.extend(std::iter::repeat_n(
                    ([0; skin::MAX_INFLUENCES], [0.0; skin::MAX_INFLUENCES]),
                    n,
                )),
            }
        }
        append(&mut mesh, part.mesh, slots.len() as u32);
        slots.push(mapped);
    }
    mesh.slot_count = slots.len().max(1) as u32;
    Ok((mesh, slots, skinned.then_some(influences)))
}

struct Part {
    mesh: Mesh,
    colors: bool,
    translucent_colors: bool,
}

fn read_primitive(
    doc: &Document,
    buffers: &Buffers,
    p: &gltf::Primitive,
    mapped: Mapped,
    mode: Mode,
    weights: Option<&[f32]>,
) -> Result<Part, String> {
    // Floats, and the integers `KHR_mesh_quantization` allows (normalised
    // or not, as the accessor says; the node's transform dequantises).
    let any_int = [
        DataType::F32,
        DataType::I8,
        DataType::U8,
        DataType::I16,
        DataType::U16,
    ];
    let signed = [DataType::F32, DataType::I8, DataType::I16];
    let color_types = [DataType::F32, DataType::U8, DataType::U16];
    let pos = p.get(&Semantic::Positions).ok_or("no POSITION attribute")?;
    let positions: Vec<[f32; 3]> =
        read_f32(doc, buffers, pos.index(), Dimensions::Vec3, &any_int, "POSITION")?;
    // As OBJ vertices: a position that is no number is refused, not built
    // into the BVH (the `gltf` fuzz target's NaN vertex).
    if let Some((k, p)) = positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.iter().all(|x| x.is_finite()))
    {
        return Err(format!(
            "POSITION {k} is not finite: ({}, {}, {})",
            p[0], p[1], p[2]
        ));
    }
    let n = positions.len();
    let same = |len: usize, what: &str| {
        if len == n {
            Ok(())
        } else {
            Err(format!("{what} has {len} elements for {n} positions"))
        }
    };
    let mut mesh = Mesh::default();
    mesh.positions = positions.iter().map(|&p| Vec3A::from(p)).collect();
    if let Some(a) = p.get(&Semantic::Normals) {
        let v: Vec<[f32; 3]> = read_f32(doc, buffers, a.index(), Dimensions::Vec3, &signed, "NORMAL")?;
        same(v.len(), "NORMAL")?;
        mesh.normals = v.iter().map(|&n| Vec3A::from(n).normalize_or_zero()).collect();
    }
    let uv_set = mapped.uv_set;
    if let Some(a) = p.get(&Semantic::TexCoords(uv_set)) {
        let what = format!("TEXCOORD_{uv_set}");
        let v: Vec<[f32; 2]> = read_f32(doc, buffers, a.index(), Dimensions::Vec2, &any_int, &what)?;
        same(v.len(), &what)?;
        // glTF's v runs down the image; ronray's up.
        mesh.uvs = v.iter().map(|&[u, v]| Vec2::new(u, 1.0 - v)).collect();
    }
    if let Some(a) = p.get(&Semantic::Tangents) {
        let v: Vec<[f32; 4]> = read_f32(doc, buffers, a.index(), Dimensions::Vec4, &signed, "TANGENT")?;
        same(v.len(), "TANGENT")?;
        mesh.tangents = v
            .iter()
            .map(|&t| {
                let w = if t[3] < 0.0 { -1.0 } else { 1.0 };
                Vec4::new(t[0], t[1], t[2], w)
            })
            .collect();
    }
    let (mut colors, mut translucent_colors) = (false, false);
    if let Some(a) = p.get(&Semantic::Colors(0)) {
        let dims = a.dimensions();
        if !matches!(dims, Dimensions::Vec3 | Dimensions::Vec4) {
            return Err(format!("COLOR_0 is {dims:?}, expected Vec3 or Vec4"));
        }
        let rgba: Vec<[f32; 4]> = match dims {
            Dimensions::Vec3 => read_f32::<3>(doc, buffers, a.index(), dims, &color_types, "COLOR_0")?
                .into_iter()
                .map(|[r, g, b]| [r, g, b, 1.0])
                .collect(),
            _ => read_f32::<4>(doc, buffers, a.index(), dims, &color_types, "COLOR_0")?,
        };
        same(rgba.len(), "COLOR_0")?;
        // Linear already (glTF 2.0 §3.7.2.1); a float outside [0, 1] or
        // not finite is clamped, as the normalised integers are by nature.
        let unit = |x: f32| if x.is_finite() { x.clamp(0.0, 1.0) } else { 1.0 };
        mesh.colors = rgba
            .iter()
            .map(|&[r, g, b, _]| Vec3A::new(unit(r), unit(g), unit(b)))
            .collect();
        translucent_colors = rgba.iter().any(|c| c[3] < 1.0);
        colors = true;
    }
    let list: Vec<u32> = match p.indices() {
        Some(a) => read_indices(doc, buffers, a.index())?,
        None => (0..n as u32).collect(),
    };
    if let Some((k, &bad)) = list.iter().enumerate().find(|&(_, &v)| v as usize >= n) {
        return Err(format!("index {bad} (element {k}) is past the {n} vertices"));
    }
    mesh.indices = triangles(&list, mode);
    if let Some(w) = weights {
        morph(doc, buffers, p, w, &mut mesh)?;
    }
    if mapped.normal_mapped && mesh.tangents.is_empty() && !mesh.uvs.is_empty() {
        crate::geometry::tangents::generate(&mut mesh);
    }
    Ok(Part {
        mesh,
        colors,
        translucent_colors,
    })
}

/// Adds `weights[i]` times morph target `i`'s displacements to the base
/// shape (glTF 2.0 §3.7.2.2), positions, normals and tangents alike; the
/// normals and tangents are renormalised after. Weights past the targets
/// are ignored.
fn morph(
    doc: &Document,
    buffers: &Buffers,
    p: &gltf::Primitive,
    weights: &[f32],
    mesh: &mut Mesh,
) -> Result<(), String> {
    let n = mesh.positions.len();
    // Float, or normalised signed integers (KHR_mesh_quantization).
    let types = [DataType::F32, DataType::I8, DataType::I16];
    let read = |a: gltf::Accessor, what: String| -> Result<Vec<Vec3A>, String> {
        let d: Vec<[f32; 3]> = read_f32(doc, buffers, a.index(), Dimensions::Vec3, &types, &what)?;
        if d.len() != n {
            return Err(format!("{what} has {} elements for {n} positions", d.len()));
        }
        Ok(d.into_iter().map(Vec3A::from).collect())
    };
    for (i, (t, &w)) in p.morph_targets().zip(weights).enumerate() {
        if w == 0.0 {
            continue;
        }
        if let Some(a) = t.positions() {
            for (x, d) in mesh
                .positions
                .iter_mut()
                .zip(read(a, format!("targets[{i}].POSITION"))?)
            {
                *x += w * d;
            }
        }
        if let Some(a) = t.normals().filter(|_| !mesh.normals.is_empty()) {
            for (x, d) in mesh
                .normals
                .iter_mut()
                .zip(read(a, format!("targets[{i}].NORMAL"))?)
            {
                *x += w * d;
            }
        }
        if let Some(a) = t.tangents().filter(|_| !mesh.tangents.is_empty()) {
            for (x, d) in mesh
                .tangents
                .iter_mut()
                .zip(read(a, format!("targets[{i}].TANGENT"))?)
            {
                *x += (w * d).extend(0.0);
            }
        }
    }
    if let Some(k) = mesh.positions.iter().position(|x| !x.is_finite()) {
        return Err(format!("morphed POSITION {k} is not finite"));
    }
    for x in &mut mesh.normals {
        *x = x.normalize_or_zero();
    }
    for x in &mut mesh.tangents {
        let xyz = Vec3A::from(x.truncate()).normalize_or(Vec3A::X);
        *x = xyz.extend(x.w);
    }
    Ok(())
}

/// Triangles of an index list in `mode`, counter-clockwise (glTF's front).
fn triangles(list: &[u32], mode: Mode) -> Vec<[u32; 3]> {
    match mode {
        Mode::TriangleStrip => (2..list.len())
            .map(|i| {
                // Every other triangle of a strip is wound the other way.
                if i % 2 == 0 {
                    [list[i - 2], list[i - 1], list[i]]
                } else {
                    [list[i - 1], list[i - 2], list[i]]
                }
            })
            .collect(),
        Mode::TriangleFan => (2..list.len()).map(|i| [list[0], list[i - 1], list[i]]).collect(),
        _ => list.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
    }
}

/// Appends `part` to `mesh` as slot `slot`. Arrays that one side lacks are
/// filled (zero normals mean "use the face", zero UVs, +x tangents) so the
/// merged arrays stay per vertex.
fn append(mesh: &mut Mesh, part: Mesh, slot: u32) {
    let base = mesh.positions.len() as u32;
    let (had, adds) = (base as usize, part.positions.len());
    fill(&mut mesh.normals, part.normals, had, adds, Vec3A::ZERO);
    fill(&mut mesh.uvs, part.uvs, had, adds, Vec2::ZERO);
    fill(
        &mut mesh.tangents,
        part.tangents,
        had,
        adds,
        Vec4::new(1.0, 0.0, 0.0, 1.0),
    );
    fill(&mut mesh.colors, part.colors, had, adds, Vec3A::ONE);
    mesh.positions.extend(part.positions);
    mesh.indices
        .extend(part.indices.iter().map(|t| t.map(|v| v + base)));
    mesh.slots.extend(std::iter::repeat_n(slot, part.indices.len()));
}

/// `dst` (covering `had` vertices, or empty) extended by `src` (covering
/// `adds`, or empty), padding with `zero` where only one side has data.
fn fill<T: Copy>(dst: &mut Vec<T>, src: Vec<T>, had: usize, adds: usize, zero: T) {
    if dst.is_empty() && src.is_empty() {
        return;
    }
    if dst.is_empty() {
        dst.resize(had, zero);
    }
    if src.is_empty() {
        dst.extend(std::iter::repeat_n(zero, adds));
    } else {
        dst.extend(src);
    }
}
