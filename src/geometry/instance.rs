//! A mesh placed in the world: the top level of the two-level BVH.
//!
//! The scene BVH holds one box per instance; a ray that reaches it is moved
//! into the mesh's space (`object_from_world`, direction not renormalised so
//! `t` is the same in both spaces) and traced through the mesh's own BVH.
//! A thousand instances of one mesh cost one mesh plus a thousand of these
//! (pbrt-v4's `TransformedPrimitive`/`BVHAggregate` split,
//! <https://pbr-book.org/4ed/Primitives_and_Intersection_Acceleration/Object_Instancing_and_Primitives_in_Motion>).

use super::mesh::{Mesh, MeshHit};
use super::moving::InstanceMotion;
use super::{Hit, NO_LIGHT};
use crate::accel::Aabb;
use crate::math::Ray;
use crate::math::float_error::{error_along, transform_point_error};
use glam::{Affine3A, Mat3A, Vec3A};

/// A mesh placed in the world by an affine transform, with its own material mapping;
/// many instances can share one mesh and its BVH.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Index into [`Geometry::meshes`](super::Geometry::meshes).
    pub mesh: u32,
    /// Object-to-world transform: where this copy of the mesh goes.
    pub world_from_object: Affine3A,
    /// The inverse transform, which moves world rays into the mesh's space.
    pub object_from_world: Affine3A,
    /// Inverse transpose of the linear part, for normals.
    normal_from_object: Mat3A,
    /// Skips the transforms for meshes baked into world space.
    identity: bool,
    /// Scene material of each of the mesh's slots.
    pub materials: Box<[u32]>,
    /// Light of each of the mesh's slots (an emissive group), or
    /// [`NO_LIGHT`]; empty when nothing in the instance emits.
    pub lights: Box<[u32]>,
    /// Keys, when the instance moves while the shutter is open; the
    /// transforms above are then its placement at the shutter's opening.
    motion: Option<Box<InstanceMotion>>,
}

impl Instance {
    /// `world_from_object` must be invertible (validation checks it).
    pub fn new(mesh: u32, world_from_object: Affine3A, materials: Box<[u32]>) -> Self {
        let object_from_world = world_from_object.inverse();
        Self {
            mesh,
            world_from_object,
            object_from_world,
            normal_from_object: world_from_object.matrix3.inverse().transpose(),
            identity: world_from_object == Affine3A::IDENTITY,
            materials,
            lights: Box::default(),
            motion: None,
        }
    }

    /// This instance moving by `motion`. Its lights, if it emits, must be
    /// built in the mesh's space with the same motion
    /// ([`crate::lights::MeshLight::with_motion`]), so that they are
    /// sampled where the instance is at each time.
    pub fn with_motion(mut self, motion: InstanceMotion) -> Self {
        self.identity = false;
        self.motion = Some(Box::new(motion));
        self
    }

    /// Whether the instance leaves its mesh where it is (the identity, not
    /// moving): a baked mesh's.
    pub fn is_identity(&self) -> bool {
        self.identity
    }

    /// Whether the instance moves while the shutter is open.
    pub fn moves(&self) -> bool {
        self.motion.is_some()
    }

    /// Its motion, when it moves while the shutter is open.
    pub fn motion(&self) -> Option<&InstanceMotion> {
        self.motion.as_deref()
    }

    /// `world_from_object` and `normal_from_object` at the time traced: the
    /// static transforms, or the motion's at the thread's clock.
    #[inline]
    fn to_world(&self) -> (Affine3A, Mat3A) {
        match &self.motion {
            Some(m) => {
                let p = m.now();
                (p.world_from_object, p.normal_from_object)
            }
            None => (self.world_from_object, self.normal_from_object),
        }
    }

    /// The placement at the time traced (moving instances only).
    #[cold]
    #[inline(never)]
    fn moving_local(&self, m: &InstanceMotion, ray: &Ray) -> Ray {
        let p = m.now();
        Ray::new(
            p.object_from_world.transform_point3a(ray.o),
            p.object_from_world.transform_vector3a(ray.d),
        )
    }

    #[inline(always)]
    fn local(&self, ray: &Ray) -> Ray {
        if self.identity {
            *ray
        } else if let Some(m) = &self.motion {
            self.moving_local(m, ray)
        } else {
            Ray::new(
                self.object_from_world.transform_point3a(ray.o),
                self.object_from_world.transform_vector3a(ray.d),
            )
        }
    }

    /// Closest hit of a world-space `ray` with the mesh in `(0, t_max)`; `t` is the
    /// same in both spaces because the direction is not renormalised.
    #[inline]
    pub fn closest(&self, ray: &Ray, t_max: f32, meshes: &[Mesh]) -> Option<MeshHit> {
        meshes[self.mesh as usize].closest(&self.local(ray), t_max)
    }

    /// Whether the mesh blocks a world-space `ray` in `(0, t_max)`; a shadow ray
    /// stops at the first hit found.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32, meshes: &[Mesh]) -> bool {
        meshes[self.mesh as usize].occluded(&self.local(ray), t_max)
    }

    /// World-space shading record. The point's error bound is the mesh's
    /// carried through `world_from_object` with the transform's own
    /// rounding (pbrt-v4's `Transform` of a `Point3fi`), then measured along
    /// the world normal.
    pub fn hit(&self, ray: &Ray, h: MeshHit, meshes: &[Mesh]) -> Hit {
        let mesh = &meshes[self.mesh as usize];
        let mut hit = mesh.hit(h.tri, h.t, h.bc);
        let slot = mesh.slot(h.tri) as usize;
        hit.material = self.materials.get(slot).copied().unwrap_or(0);
        hit.light = self.lights.get(slot).copied().unwrap_or(NO_LIGHT);
        if !self.identity {
            let (world_from_object, normal_from_object) = self.to_world();
            let p_err = mesh.point_error(h.tri, h.bc);
            let p_err = transform_point_error(&world_from_object, hit.p, p_err);
            hit.p = world_from_object.transform_point3a(hit.p);
            hit.ng = (normal_from_object * hit.ng).normalize_or(hit.ng);
            hit.ns = (normal_from_object * hit.ns).normalize_or(hit.ng);
            hit.p_error = error_along(hit.ng, p_err);
        }
        // A point on the world-space ray is more accurate far from the origin.
        debug_assert!(hit.p.is_finite() && ray.at(h.t).is_finite());
        hit
    }

    /// The mesh's tangent at hit `h` (see [`Mesh::tangent`]) in world
    /// space: `xyz` carried by `world_from_object` at the time traced
    /// (tangents are vectors in the surface), `w` negated by a mirroring
    /// transform (the bitangent is `w·(n × t)` and the cross product of
    /// transformed vectors turns).
    pub fn tangent(&self, h: MeshHit, frame: super::TangentFrame, meshes: &[Mesh]) -> Option<glam::Vec4> {
        let t = meshes.get(self.mesh as usize)?.tangent(h.tri, h.bc, frame)?;
        if self.identity {
            return Some(t);
        }
        let m = self.to_world().0.matrix3;
        let xyz = m * Vec3A::from(t.truncate());
        let w = if m.determinant() < 0.0 { -t.w } else { t.w };
        Some(glam::Vec3::from(xyz).extend(w))
    }

    /// Triangle `tri` of the mesh in world space, wound so that `(b − a) ×
    /// (c − a)` points to the side [`Instance::hit`] reports as outside (a
    /// mirroring transform would otherwise turn it inward).
    pub fn world_triangle(&self, tri: u32, meshes: &[Mesh]) -> [Vec3A; 3] {
        let (a, b, c) = meshes[self.mesh as usize].corners(tri);
        let m = &self.world_from_object;
        let [a, b, c] = [a, b, c].map(|p| m.transform_point3a(p));
        if m.matrix3.determinant() < 0.0 {
            [a, c, b]
        } else {
            [a, b, c]
        }
    }

    /// World bounds: the mesh box's eight corners transformed; for a
    /// moving instance, the box they sweep over the shutter.
    pub fn bounds(&self, meshes: &[Mesh]) -> Aabb {
        let b = meshes[self.mesh as usize].bounds();
        if b.is_empty() {
            return b;
        }
        if let Some(m) = &self.motion {
            let (lo, hi) = m
                .track
                .bounds(b.min.into(), b.max.into(), m.shutter.0, m.shutter.1);
            return Aabb::EMPTY.grow_point(lo.into()).grow_point(hi.into());
        }
        (0..8).fold(Aabb::EMPTY, |acc, i| {
            let c = Vec3A::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            acc.grow_point(self.world_from_object.transform_point3a(c))
        })
    }
}
