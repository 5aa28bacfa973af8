//! One triangle of a small mesh placed directly in the scene BVH.
//!
//! Going through an instance costs a ray transform, a second traversal
//! setup and a second stack, which a 12-triangle Cornell block does not
//! repay (flattening made the Cornell render 7% faster). Meshes of at most [`FLATTEN_MAX`] triangles that are
//! baked into world space (a scene's `Mesh` object, not a shared
//! `Instance`) therefore put each triangle in the top level, and keep their
//! [`super::Instance`] only for shading (normals, UVs, material slots) —
//! and not even for that when the mesh has neither vertex normals nor UVs:
//! such a triangle carries its whole shading record (`flat_shade.rs`).
//! Handing the top level whole four-triangle leaves instead was measured
//! slower: their boxes are much looser than single triangles'.

use super::flat_shade::FlatShade;
use super::triangle::{WatertightRay4, corners_of_rows, rows_of_corners};
use super::{Geometry, Hit, MeshHit};
use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Vec2, Vec3A, Vec4};

/// Meshes up to this many triangles are flattened into the scene BVH.
///
/// 64 covered the Cornell blocks; 256 also takes in the ground planes and
/// low-poly props of real scenes, whose instance box overlaps everything
/// on it, so most rays paid for two traversals. Measured (callgrind, 64²,
/// 16 spp, one thread; wall time 256², 64 spp, two threads, three
/// alternated runs): the bunny on a 200-triangle grid floor under a
/// rectangle light −5.5% instructions, 0.79 → 0.72–0.76 s; fifteen
/// 240-triangle balls on a floor −15%, 0.66–0.71 → 0.59–0.64 s. At 4,096
/// (the bunny flattened) the bunny scene cost 74% more instructions: the
/// pairing at load is quadratic, and single-triangle leaves are no match
/// for a mesh BVH's four-triangle blocks on thousands of triangles.
pub const FLATTEN_MAX: usize = 256;

/// A triangle of a small baked mesh, as its own entry in the scene BVH.
#[derive(Clone, Copy, Debug)]
pub struct MeshTriangle {
    /// World-space corners (the mesh is baked, so they are its own), one
    /// row per axis ([`rows_of_corners`]): the layout of
    /// [`WatertightRay4::single`].
    rows: [Vec4; 3],
    /// The instance that shades it, and the triangle's index in its mesh.
    pub instance: u32,
    /// Index of the triangle in that instance's mesh.
    pub tri: u32,
    /// Its whole shading record when the mesh has neither vertex normals
    /// nor UVs (`flat_shade.rs`); `None`: through the instance.
    flat: Option<FlatShade>,
}

impl MeshTriangle {
    /// Triangle `tri` of `instance`'s mesh, with world-space corners `p`.
    pub fn new(p: [Vec3A; 3], instance: u32, tri: u32) -> Self {
        Self {
            rows: rows_of_corners(p),
            instance,
            tri,
            flat: None,
        }
    }

    /// This triangle shaded from `flat` alone, which must be what its
    /// instance gives (a static, untransformed mesh without vertex normals
    /// or UVs).
    pub fn with_flat(self, flat: FlatShade) -> Self {
        Self {
            flat: Some(flat),
            ..self
        }
    }

    /// World-space corners.
    pub fn corners(&self) -> [Vec3A; 3] {
        corners_of_rows(&self.rows)
    }

    /// Watertight intersection with `wt` in `(0, t_max)`: the distance and the
    /// barycentrics of the second and third corners.
    #[inline(always)]
    pub fn intersect(&self, wt: &WatertightRay4, t_max: f32) -> Option<(f32, Vec2)> {
        wt.single(&self.rows, t_max)
    }

    /// Shading record for a hit found by [`MeshTriangle::intersect`].
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t: f32, bc: Vec2, geo: &Geometry) -> Hit {
        let mut out = Hit::default();
        self.hit_into(ray, t, bc, geo, &mut out);
        out
    }

    /// [`MeshTriangle::hit`] written into `out` (see [`FlatShade::hit_into`]).
    /// Inline: see [`super::MeshQuad::hit_into`].
    #[inline(always)]
    pub fn hit_into(&self, ray: &Ray, t: f32, bc: Vec2, geo: &Geometry, out: &mut Hit) {
        match &self.flat {
            Some(f) => f.hit_into(self.corners(), t, bc, out),
            None => *out = self.hit_through_instance(ray, t, bc, geo),
        }
    }

    #[inline(never)]
    fn hit_through_instance(&self, ray: &Ray, t: f32, bc: Vec2, geo: &Geometry) -> Hit {
        let h = MeshHit { t, tri: self.tri, bc };
        geo.instances[self.instance as usize].hit(ray, h, &geo.meshes)
    }

    /// World-space bounds of the three corners.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.corners())
    }
}
