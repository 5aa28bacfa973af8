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
    pub fn hit(&self, corners: [Vec3A; 3], t: f32, bc: Vec2) -> Hit {
        let mut out = Hit::default();
        self.hit_into(corners, t, bc, &mut out);
        out
    }

    /// [`FlatShade::hit`] written into `out` field by field. Built as a
    /// value and then assigned, the record went through the stack: its
    /// four-byte fields (`t`, `p_error`, `uv`) were stored one by one and
    /// copied out by sixteen-byte loads across them, which store
    /// forwarding cannot serve (a third of the closest-hit record's cycles
    /// on the Cornell box as one OBJ, perf).
    #[inline(always)]
    pub fn hit_into(&self, [a, b, c]: [Vec3A; 3], t: f32, bc: Vec2, out: &mut Hit) {
        let w = Vec3A::new(1.0 - bc.x - bc.y, bc.x, bc.y);
        let (pa, pb, pc) = (a * w.x, b * w.y, c * w.z);
        let p_err = gamma_offset(7) * (pa.abs() + pb.abs() + pc.abs());
        let ng = Vec3A::from(self.ng);
        out.t = t;
        out.p = pa + pb + pc;
        out.p_error = error_along(ng, p_err);
        out.ng = ng;
        out.ns = ng;
        // A mesh without UVs reads its barycentrics as UVs.
        out.uv = bc;
        out.material = self.material;
        out.light = self.light;
        out.color = glam::Vec3A::ONE;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `hit_into` writes every field of the record: over a record full of
    /// other values it leaves what `hit` returns, bit for bit (a field
    /// added to `Hit` and forgotten here would keep the old value).
    #[test]
    fn hit_into_writes_the_whole_record() {
        let corners = [
            Vec3A::new(0.1, 0.2, 0.3),
            Vec3A::new(1.5, 0.2, 0.3),
            Vec3A::new(0.1, 1.7, -0.4),
        ];
        let f = FlatShade::new(corners, 3, 7);
        let (t, bc) = (2.5, Vec2::new(0.25, 0.5));
        let mut out = Hit {
            t: -1.0,
            p: Vec3A::splat(9.0),
            p_error: 9.0,
            ng: Vec3A::splat(9.0),
            ns: Vec3A::splat(9.0),
            uv: Vec2::splat(9.0),
            material: 99,
            light: 99,
            color: Vec3A::splat(9.0),
        };
        f.hit_into(corners, t, bc, &mut out);
        let want = f.hit(corners, t, bc);
        // Every field, by its bits (a debug print lists them all).
        assert_eq!(format!("{out:?}"), format!("{want:?}"));
        assert_eq!((out.material, out.light, out.uv), (3, 7, bc));
    }
}
