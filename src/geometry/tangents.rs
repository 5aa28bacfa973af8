//! Per-vertex tangents by MikkTSpace, the convention glTF 2.0 names for
//! assets that give no `TANGENT` ("client implementations should calculate
//! tangents using … MikkTSpace") and the one Blender and Substance bake
//! normal maps in, so a map baked there lines up here.
//!
//! The algorithm is `bevy_mikktspace` (a safe Rust port of Morten
//! Mikkelsen's reference code, byte-identical to it on x86, no
//! dependencies; the `mikktspace` crate would pull nalgebra 0.26 or glam
//! 0.15 beside ours). MikkTSpace gives one tangent per triangle *corner*;
//! where two corners of one vertex disagree (a UV seam, a mirrored half)
//! the vertex is split so that [`Mesh::tangents`] stays per vertex like
//! the normals and UVs.

use super::mesh::Mesh;
use bevy_mikktspace::{Geometry, TangentSpace};
use glam::{Vec3A, Vec4};
use std::collections::HashMap;

/// Fills `mesh.tangents` by MikkTSpace (splitting vertices whose corners
/// get different tangents). Needs UVs; without normals the face normals
/// are used. Returns the number of vertices added by splits. Must run
/// before [`Mesh::prepare`] (it may add vertices, never reorders triangles).
pub fn generate(mesh: &mut Mesh) -> usize {
    if mesh.uvs.len() != mesh.positions.len() || mesh.indices.is_empty() {
        return 0;
    }
    let mut corners = Corners {
        out: vec![Vec4::new(1.0, 0.0, 0.0, 1.0); 3 * mesh.indices.len()],
        mesh,
    };
    // The error type has no variants: generation cannot fail.
    let _ = bevy_mikktspace::generate_tangents(&mut corners);
    let out = std::mem::take(&mut corners.out);
    split(mesh, &out)
}

/// Gives each vertex its corners' tangent, duplicating a vertex for each
/// further tangent its corners carry.
fn split(mesh: &mut Mesh, corner_tangents: &[Vec4]) -> usize {
    let n = mesh.positions.len();
    let mut tangents: Vec<Option<Vec4>> = vec![None; n];
    let mut extra: HashMap<(u32, [u32; 4]), u32> = HashMap::new();
    let mut added = 0;
    for (t, tri) in mesh.indices.iter_mut().enumerate() {
        for (k, v) in tri.iter_mut().enumerate() {
            let tan = corner_tangents[3 * t + k];
            let i = *v as usize;
            match tangents[i] {
                None => tangents[i] = Some(tan),
                Some(old) if old == tan => {}
                Some(_) => {
                    let key = (*v, tan.to_array().map(f32::to_bits));
                    let copy = *extra.entry(key).or_insert_with(|| {
                        added += 1;
                        tangents.push(Some(tan));
                        mesh.positions.push(mesh.positions[i]);
                        mesh.uvs.push(mesh.uvs[i]);
                        if !mesh.normals.is_empty() {
                            mesh.normals.push(mesh.normals[i]);
                        }
                        (tangents.len() - 1) as u32
                    });
                    *v = copy;
                }
            }
        }
    }
    mesh.tangents = tangents
        .into_iter()
        .map(|t| t.unwrap_or(Vec4::new(1.0, 0.0, 0.0, 1.0)))
        .collect();
    added
}

/// The mesh seen through MikkTSpace's interface, collecting one tangent
/// per corner.
struct Corners<'a> {
    mesh: &'a Mesh,
    out: Vec<Vec4>,
}

impl Corners<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face][vert] as usize
    }
}

impl Geometry for Corners<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len()
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        match self.mesh.normals.get(self.vertex(face, vert)) {
            Some(n) => n.to_array(),
            None => {
                let (a, b, c) = self.mesh.corners(face as u32);
                (b - a).cross(c - a).normalize_or(Vec3A::Z).to_array()
            }
        }
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        self.mesh.uvs[self.vertex(face, vert)].to_array()
    }

    fn set_tangent(&mut self, tangent_space: Option<TangentSpace>, face: usize, vert: usize) {
        if let Some(ts) = tangent_space {
            self.out[3 * face + vert] = Vec4::from_array(ts.tangent_encoded());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// A quad in the xy plane (normal +z) of two triangles; the right half's
    /// UVs mirror the left's in u, sharing the middle vertices.
    fn mirrored_strip() -> Mesh {
        let p = |x: f32, y: f32| Vec3A::new(x, y, 0.0);
        let mut m = Mesh::default();
        m.positions = vec![
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
            p(2.0, 0.0),
            p(2.0, 1.0),
        ];
        m.uvs = vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(0.0, 0.0),
            Vec2::new(0.0, 1.0),
        ];
        m.normals = vec![Vec3A::Z; 6];
        m.indices = vec![[0, 1, 2], [0, 2, 3], [1, 4, 5], [1, 5, 2]];
        m.slot_count = 1;
        m
    }

    #[test]
    fn mikktspace_follows_u_and_flips_handedness_where_uvs_mirror() {
        let mut m = mirrored_strip();
        let added = generate(&mut m);
        // The two shared middle vertices get a second tangent each.
        assert_eq!(added, 2, "expected the seam's two vertices split");
        assert_eq!(m.tangents.len(), m.positions.len());
        for (t, tri) in m.indices.iter().enumerate() {
            let right = t >= 2;
            for &v in tri {
                let tan = m.tangents[v as usize];
                let want = if right {
                    Vec4::new(-1.0, 0.0, 0.0, -1.0)
                } else {
                    Vec4::new(1.0, 0.0, 0.0, 1.0)
                };
                assert!(
                    (tan - want).abs().max_element() < 1e-5,
                    "triangle {t} vertex {v}: {tan} vs {want}"
                );
            }
        }
    }

    #[test]
    fn mesh_without_uvs_gets_no_tangents() {
        let mut m = mirrored_strip();
        m.uvs.clear();
        assert_eq!(generate(&mut m), 0);
        assert!(m.tangents.is_empty());
    }
}
