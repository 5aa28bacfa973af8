//! Skinned meshes (glTF 2.0 §3.7.3): each vertex moves with up to eight
//! joints (two sets of four), `p' = Σ wᵢ · Jⱼᵢ · p`, where a joint's matrix is its posed world
//! transform times its inverse bind matrix. The result is in the asset's
//! space: the transform of the node that holds the mesh is ignored, as
//! the specification says. Normals go through the inverse transpose of
//! the blended matrix, tangents through the matrix itself (their sign
//! flips with a mirroring blend).
//!
//! The skinning is done once at load, at the pose `animation.rs` gives;
//! the mesh's BVH is then built over the moved vertices like any other.

use super::accessor::{Buffers, read_f32};
use crate::geometry::Mesh;
use glam::{Mat3A, Mat4, Vec3A, Vec4};
use gltf::Document;
use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Semantic;

/// Joints a vertex follows at most: two sets of four (`JOINTS_0`/`WEIGHTS_0`
/// and `JOINTS_1`/`WEIGHTS_1`), what exporters write for rigs with more
/// than four influences (Blender's "influence limit" above 4).
pub const MAX_INFLUENCES: usize = 8;

/// A vertex's joints (indices into the skin's `joints`) and their weights;
/// unused slots weigh 0.
pub type Influence = ([u32; MAX_INFLUENCES], [f32; MAX_INFLUENCES]);

/// The `JOINTS_k` / `WEIGHTS_k` sets 0 and 1 of primitive `p` (`n`
/// vertices), or `None` when it has no set 0. Sets past the second are not
/// read (`primitive.rs` says so in a note).
pub fn influences(
    doc: &Document,
    buffers: &Buffers,
    p: &gltf::Primitive,
    n: usize,
) -> Result<Option<Vec<Influence>>, String> {
    let Some(first) = set(doc, buffers, p, n, 0)? else {
        return Ok(None);
    };
    let second = set(doc, buffers, p, n, 1)?;
    Ok(Some(
        first
            .into_iter()
            .enumerate()
            .map(|(v, (j0, w0))| {
                let (j1, w1) = second.as_ref().map_or(([0; 4], [0.0; 4]), |s| s[v]);
                let mut j = [0; MAX_INFLUENCES];
                let mut w = [0.0; MAX_INFLUENCES];
                j[..4].copy_from_slice(&j0);
                j[4..].copy_from_slice(&j1);
                w[..4].copy_from_slice(&w0);
                w[4..].copy_from_slice(&w1);
                (j, w)
            })
            .collect(),
    ))
}

/// One set of a vertex's joints and weights: four of each.
type Set = ([u32; 4], [f32; 4]);

/// Set `k` of joints and weights: `None` when the primitive has neither;
/// an error when it has one without the other, a normalised `JOINTS_k`, a
/// count other than `n`, or a negative or non-finite weight.
fn set(
    doc: &Document,
    buffers: &Buffers,
    p: &gltf::Primitive,
    n: usize,
    k: u32,
) -> Result<Option<Vec<Set>>, String> {
    let (joints, weights) = match (p.get(&Semantic::Joints(k)), p.get(&Semantic::Weights(k))) {
        (None, None) => return Ok(None),
        (Some(j), Some(w)) => (j, w),
        _ => {
            return Err(format!(
                "JOINTS_{k} and WEIGHTS_{k} come together; one is missing"
            ));
        }
    };
    if joints.normalized() {
        return Err(format!("JOINTS_{k} cannot be normalised"));
    }
    let (jn, wn) = (format!("JOINTS_{k}"), format!("WEIGHTS_{k}"));
    let j: Vec<[f32; 4]> = read_f32(
        doc,
        buffers,
        joints.index(),
        Dimensions::Vec4,
        &[DataType::U8, DataType::U16],
        &jn,
    )?;
    let w: Vec<[f32; 4]> = read_f32(
        doc,
        buffers,
        weights.index(),
        Dimensions::Vec4,
        &[DataType::F32, DataType::U8, DataType::U16],
        &wn,
    )?;
    if j.len() != n || w.len() != n {
        return Err(format!(
            "{jn} has {} and {wn} {} elements for {n} positions",
            j.len(),
            w.len()
        ));
    }
    if let Some(v) = w
        .iter()
        .position(|w| !w.iter().all(|x| x.is_finite() && *x >= 0.0))
    {
        return Err(format!("{wn} {v} is negative or not a number"));
    }
    Ok(Some(
        j.into_iter()
            .zip(w)
            .map(|(j, w)| (j.map(|x| x as u32), w))
            .collect(),
    ))
}

/// Moves `mesh`'s vertices by skin `skin` posed with the world transforms
/// `worlds` (every node's); `influences` is per vertex. `fallback` places
/// a vertex no joint weighs (the node's own transform).
pub fn deform(
    doc: &Document,
    buffers: &Buffers,
    skin: usize,
    worlds: &[Mat4],
    mesh: &mut Mesh,
    influences: &[Influence],
    fallback: Mat4,
) -> Result<(), String> {
    let at = format!("skins[{skin}]");
    let s = doc
        .skins()
        .nth(skin)
        .ok_or_else(|| format!("{at} does not exist"))?;
    let nodes: Vec<usize> = s.joints().map(|j| j.index()).collect();
    let ibm: Vec<Mat4> = match s.inverse_bind_matrices() {
        Some(a) => read_f32::<16>(
            doc,
            buffers,
            a.index(),
            Dimensions::Mat4,
            &[DataType::F32],
            "inverseBindMatrices",
        )
        .map_err(|e| format!("{at}: {e}"))?
        .iter()
        .map(Mat4::from_cols_array)
        .collect(),
        None => vec![Mat4::IDENTITY; nodes.len()],
    };
    if ibm.len() < nodes.len() {
        return Err(format!(
            "{at}: {} inverse bind matrices for {} joints",
            ibm.len(),
            nodes.len()
        ));
    }
    let joints: Vec<Mat4> = nodes
        .iter()
        .zip(&ibm)
        .map(|(&n, b)| worlds.get(n).map(|w| *w * *b))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("{at}: a joint is not a node of the asset"))?;
    if influences.len() != mesh.positions.len() {
        return Err(format!(
            "{at}: {} joint influences for {} vertices",
            influences.len(),
            mesh.positions.len()
        ));
    }
    for (v, (js, ws)) in influences.iter().enumerate() {
        let total: f32 = ws.iter().sum();
        let m = if total > 0.0 {
            let mut m = Mat4::ZERO;
            for (&j, &w) in js.iter().zip(ws) {
                if w == 0.0 {
                    continue;
                }
                let jm = joints.get(j as usize).ok_or_else(|| {
                    format!("{at}: vertex {v} names joint {j}; the skin has {}", joints.len())
                })?;
                m += *jm * (w / total);
            }
            m
        } else {
            fallback
        };
        if !m.is_finite() {
            return Err(format!("{at}: vertex {v}'s joint matrix is not finite"));
        }
        let p = m.transform_point3a(mesh.positions[v]);
        if !p.is_finite() {
            return Err(format!("{at}: vertex {v} moves to a point that is not finite"));
        }
        mesh.positions[v] = p;
        let linear = Mat3A::from_mat4(m);
        if let Some(n) = mesh.normals.get_mut(v) {
            let moved = linear.inverse().transpose() * *n;
            *n = if moved.is_finite() {
                moved.normalize_or_zero()
            } else {
                Vec3A::ZERO
            };
        }
        if let Some(t) = mesh.tangents.get_mut(v) {
            let xyz = (linear * Vec3A::from(t.truncate())).normalize_or(Vec3A::X);
            let w = if linear.determinant() < 0.0 { -t.w } else { t.w };
            *t = Vec4::new(xyz.x, xyz.y, xyz.z, w);
        }
    }
    Ok(())
}
