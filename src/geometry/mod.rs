//! Shapes the renderer intersects. A closed set, so `enum Shape` with a
//! hand-written `match`; each variant is small (a triangle is a mesh index and
//! a triangle index) so the primitive array stays cache friendly.

pub mod mesh;
pub mod obj;
pub mod plane;
pub mod quad;
pub mod sdf;
pub mod sdf_object;
pub mod sphere;
pub mod triangle;

pub use mesh::Mesh;
pub use plane::Plane;
pub use quad::Quad;
pub use sdf_object::SdfObject;
pub use sphere::Sphere;

use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Vec2, Vec3A};

/// Marks "no area light" in [`Shape`] emitter fields.
pub const NO_LIGHT: u32 = u32::MAX;

#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// Implicit surface `i` of `Scene::sdfs`.
    Sdf(u32),
    Sphere(Sphere),
    Quad(Quad),
    /// Triangle `tri` of mesh `mesh`.
    Triangle {
        mesh: u32,
        tri: u32,
    },
    Plane(Plane),
}

/// A ray–surface intersection with what shading needs.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub p: Vec3A,
    /// Unit geometric normal, on the side the shape defines as outside
    /// (not flipped toward the ray).
    pub ng: Vec3A,
    /// Unit shading normal (interpolated for smooth meshes), same side as `ng`.
    pub ns: Vec3A,
    pub uv: Vec2,
    pub material: u32,
    /// Index of the area light this surface is, or [`NO_LIGHT`].
    pub light: u32,
}

impl Shape {
    /// Distance to the first intersection in `(0, t_max)`.
    #[inline]
    pub fn intersect_t(&self, ray: &Ray, t_max: f32, meshes: &[Mesh], sdfs: &[SdfObject]) -> Option<f32> {
        match self {
            Shape::Sdf(i) => sdfs[*i as usize].intersect(ray, t_max),
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Quad(q) => q.intersect(ray, t_max).map(|(t, _)| t),
            Shape::Triangle { mesh, tri } => {
                meshes[*mesh as usize].intersect(*tri, ray, t_max).map(|(t, _)| t)
            }
            Shape::Plane(p) => p.intersect(ray, t_max),
        }
    }

    /// Full hit record for a `t` returned by [`Shape::intersect_t`].
    pub fn hit(&self, ray: &Ray, t: f32, meshes: &[Mesh], sdfs: &[SdfObject]) -> Hit {
        let p = ray.at(t);
        match self {
            Shape::Sdf(i) => sdfs[*i as usize].hit(ray, t),
            Shape::Sphere(s) => s.hit(p, t),
            Shape::Quad(q) => q.hit(ray, t),
            Shape::Triangle { mesh, tri } => meshes[*mesh as usize].hit(*tri, ray, t),
            Shape::Plane(pl) => pl.hit(p, t),
        }
    }

    /// `None` for unbounded shapes (planes), which live outside the BVH.
    pub fn bounds(&self, meshes: &[Mesh], sdfs: &[SdfObject]) -> Option<Aabb> {
        match self {
            Shape::Sdf(i) => sdfs[*i as usize].bounds(),
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Quad(q) => Some(q.bounds()),
            Shape::Triangle { mesh, tri } => Some(meshes[*mesh as usize].tri_bounds(*tri)),
            Shape::Plane(_) => None,
        }
    }
}
