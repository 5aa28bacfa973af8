//! The shading record of a flattened triangle (`mesh_triangle.rs`,
//! `mesh_quad.rs`) whose mesh has neither vertex normals nor UVs: its
//! geometric normal, material and light, fixed at load.
//!
//! Through the instance, a hit of such a triangle loaded the instance, its
//! mesh, the triangle's indices and its three positions, one after the
//! other, then normalised a cross product (a square root and a division):
//! a chain of dependent loads and long-latency operations that the next
//! ray waited on. The Cornell box as one OBJ (`bench/cornell_mesh`, every
//! shape a flattened pair) spent 9.6% of its time in `Instance::hit`
//! (perf). With the three numbers stored beside the corners, the record
//! is the corners' barycentric sum and its error bound, computed with the
//! operations of [`super::mesh::Mesh::hit`] in its order, so every hit is
//! bit for bit the one the instance gives.

use super::Hit;
#[cfg(doc)]
use super::NO_LIGHT;
use crate::math::float_error::{error_along, gamma_offset};
use glam::{Vec2, Vec3A};

/// What a hit of one flattened, flat-shaded, untextured triangle needs
/// beyond its corners.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlatShade {
    /// Unit geometric normal, counter-clockwise winding outward (what
    /// `Mesh::hit` computes).
    ng: [f32; 3],
    /// Scene material of the triangle's slot.
    material: u32,
    /// Light of the triangle's slot, or [`NO_LIGHT`].
    light: u32,
}

impl FlatShade {
    /// The record of a triangle with corners `[a, b, c]` in its mesh's
    /// order, shaded by `material` and emitting as `light` ([`NO_LIGHT`]:
    /// dark).
    pub fn new([a, b, c]: [Vec3A; 3], material: u32, light: u32) -> Self {
        let ng = (b - a).cross(c - a).normalize_or(Vec3A::Z);
        Self {
            ng: ng.into(),
            material,
            light,
        }
    }

    /// The hit at distance `t` and barycentrics `bc` (of corners `b` and
    /// `c`, the mesh's order) of the triangle with corners `[a, b, c]`.
    #[inline]
    pub fn hit(&self, [a, b, c]: [Vec3A; 3], t: f32, bc: Vec2) -> Hit {
        let w = Vec3A::new(1.0 - bc.x - bc.y, bc.x, bc.y);
        let (pa, pb, pc) = (a * w.x, b * w.y, c * w.z);
        let p_err = gamma_offset(7) * (pa.abs() + pb.abs() + pc.abs());
        let ng = Vec3A::from(self.ng);
        Hit {
            t,
            p: pa + pb + pc,
            p_error: error_along(ng, p_err),
            ng,
            ns: ng,
            // A mesh without UVs reads its barycentrics as UVs.
            uv: bc,
            material: self.material,
            light: self.light,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::mesh_quad::{MeshQuad, pairing};
    use crate::geometry::mesh_triangle::MeshTriangle;
    use crate::geometry::{Geometry, Instance, Mesh, NO_LIGHT};
    use crate::math::Ray;
    use crate::math::rng::Pcg32;
    use glam::Affine3A;

    /// Every field of two hit records, bit for bit.
    fn same(a: &Hit, b: &Hit) -> bool {
        let bits = |v: Vec3A| v.to_array().map(f32::to_bits);
        a.t.to_bits() == b.t.to_bits()
            && bits(a.p) == bits(b.p)
            && a.p_error.to_bits() == b.p_error.to_bits()
            && bits(a.ng) == bits(b.ng)
            && bits(a.ns) == bits(b.ns)
            && a.uv.to_array().map(f32::to_bits) == b.uv.to_array().map(f32::to_bits)
            && (a.material, a.light) == (b.material, b.light)
    }

    /// A skewed, non-planar quad far from the origin as two triangles in
    /// two slots (the second emitting), each corner order rotated as an
    /// OBJ file may write it: the flat records give exactly the hits the
    /// instance gives, for the pair and for each triangle on its own.
    #[test]
    fn flat_records_are_the_instances_bit_for_bit() {
        let o = Vec3A::new(123.4, -56.7, 8.9);
        let q = [
            o,
            o + Vec3A::new(1.3, 0.1, -0.02),
            o + Vec3A::new(1.1, 0.9, 0.005),
            o + Vec3A::new(-0.1, 1.2, 0.01),
        ];
        let mut rng = Pcg32::new(7, 3);
        for (ra, rb) in [(0, 0), (1, 2), (2, 1)] {
            let rot = |t: [usize; 3], r: usize| [t[r % 3], t[(r + 1) % 3], t[(r + 2) % 3]];
            let (ta, tb) = (rot([0, 1, 2], ra), rot([0, 2, 3], rb));
            let mut mesh = Mesh::default();
            mesh.positions = q.to_vec();
            mesh.indices = vec![ta.map(|i| i as u32), tb.map(|i| i as u32)];
            mesh.slots = vec![0, 1];
            mesh.slot_count = 2;
            let mut instance = Instance::new(0, Affine3A::IDENTITY, vec![3, 5].into_boxed_slice());
            instance.lights = vec![NO_LIGHT, 7].into_boxed_slice();
            let geo = Geometry {
                meshes: vec![mesh],
                instances: vec![instance],
                sdfs: Vec::new(),
            };
            let corners = |t: [usize; 3]| t.map(|i| q[i]);
            let flat =
                |tri: usize, t: [usize; 3]| FlatShade::new(corners(t), [3, 5][tri], [NO_LIGHT, 7][tri]);
            let (v, rots) = pairing(corners(ta), corners(tb)).expect("the two halves pair");
            let pair = MeshQuad::new(v, 0, [0, 1], rots).expect("small indices");
            let flat_pair = pair.with_flat([flat(0, ta), flat(1, tb)]);
            let singles = [(0, ta), (1, tb)].map(|(tri, t)| {
                let s = MeshTriangle::new(corners(t), 0, tri as u32);
                (s, s.with_flat(flat(tri, t)))
            });
            let ray = Ray::new(o + Vec3A::new(0.5, 0.5, 3.0), Vec3A::NEG_Z);
            for _ in 0..200 {
                let bc = Vec2::new(rng.next_f32(), rng.next_f32()) * 0.5;
                let t = 1.0 + rng.next_f32();
                for k in 0..2 {
                    let (a, b) = (
                        pair.hit(&ray, t, k, bc, &geo),
                        flat_pair.hit(&ray, t, k, bc, &geo),
                    );
                    assert!(
                        same(&a, &b),
                        "pair, rotations ({ra}, {rb}), triangle {k}: {a:?} != {b:?}"
                    );
                    let (s, f) = &singles[k as usize];
                    let (a, b) = (s.hit(&ray, t, bc, &geo), f.hit(&ray, t, bc, &geo));
                    assert!(same(&a, &b), "single triangle {k}: {a:?} != {b:?}");
                }
            }
        }
    }
}
