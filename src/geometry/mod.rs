//! Shapes the renderer intersects. A closed set, so `enum Shape` with a
//! hand-written `match`; each variant is small (a triangle is a mesh index and
//! a triangle index) so the primitive array stays cache friendly.
//!
//! Triangles are not shapes of their own: a mesh carries its own BVH and the
//! scene BVH sees one [`Shape::Instance`] per placed mesh (two-level BVH, see
//! `instance.rs`), so a million-triangle mesh is one entry at the top level;
//! only very small baked meshes put their triangles in the top level
//! (`mesh_triangle.rs`).

pub mod flat_shade;
pub mod instance;
pub mod mesh;
pub mod mesh_quad;
pub mod mesh_triangle;
pub mod moving;
pub mod obj;
pub mod plane;
pub mod ply;
pub mod quad;
pub mod ray_sets;
pub mod sdf;
pub mod sdf_object;
pub mod shape_lanes;
pub mod sphere;
pub mod tangents;
pub mod triangle;

pub use instance::Instance;
pub use mesh::{Mesh, MeshHit, TangentFrame};
pub use mesh_quad::MeshQuad;
pub use mesh_triangle::MeshTriangle;
pub use plane::Plane;
pub use quad::Quad;
pub use sdf_object::SdfObject;
pub use sphere::Sphere;

use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Vec2, Vec3A};
use triangle::WatertightRay4;

/// Marks "no area light" in [`Shape`] emitter fields.
pub const NO_LIGHT: u32 = u32::MAX;

/// One entry of the scene's BVH (or of its unbounded list): a small value or an index
/// into [`Geometry`] for shapes that own big data.
#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// Implicit surface `i` of `Geometry::sdfs`.
    Sdf(u32),
    /// An analytic sphere, in world space.
    Sphere(Sphere),
    /// A parallelogram, in world space; area lights are quads too.
    Quad(Quad),
    /// Instance `i` of [`Geometry::instances`]: a mesh and its transform.
    Instance(u32),
    /// An infinite plane; unbounded, so it is tested outside the BVH.
    Plane(Plane),
    /// A triangle of a small mesh, flattened into the scene BVH.
    Triangle(MeshTriangle),
    /// Two triangles of a small mesh that share an edge (an OBJ quad),
    /// flattened into the scene BVH as one entry.
    MeshQuad(MeshQuad),
}

/// Meshes and their placements, shared by every [`Shape::Instance`].
#[derive(Clone, Debug, Default)]
pub struct Geometry {
    /// Triangle meshes, each with its own BVH, in object space (world space for a
    /// baked `Mesh` object, whose instance is the identity).
    pub meshes: Vec<Mesh>,
    /// Placements of the meshes: a mesh index, its transform and its materials.
    pub instances: Vec<Instance>,
    /// Implicit surfaces, referred to by [`Shape::Sdf`].
    pub sdfs: Vec<SdfObject>,
}

/// A ray–surface intersection with what shading needs.
#[derive(Clone, Copy, Debug, Default)]
pub struct Hit {
    /// Ray parameter of the hit: distance along the ray in units of its direction's
    /// length (world units for the unit-length rays integrators trace).
    pub t: f32,
    /// World-space hit point.
    pub p: Vec3A,
    /// How far the true surface may lie from `p` along `ng`: the shape's
    /// per-axis rounding-error bound of `p` projected on the normal
    /// (`float_error::error_along`). Rays leave the hit moved along `ng` by
    /// this much (`integrators::spawn`), so the bound must cover how `p` was
    /// computed: shapes reconstruct `p` from their own parametrisation
    /// rather than take `o + t·d`, whose error grows with the distance to
    /// the ray's origin (a far camera).
    pub p_error: f32,
    /// Unit geometric normal, on the side the shape defines as outside
    /// (not flipped toward the ray).
    pub ng: Vec3A,
    /// Unit shading normal (interpolated for smooth meshes), same side as `ng`.
    pub ns: Vec3A,
    /// Surface texture coordinates, for textured materials.
    pub uv: Vec2,
    /// Index into the scene's materials.
    pub material: u32,
    /// Index of the area light this surface is, or [`NO_LIGHT`].
    pub light: u32,
    /// The mesh's vertex colour at the hit (linear RGB), white where it has
    /// none: filled by `Scene::intersect` only for materials that read it
    /// (a `Vertex` texture), left as it was otherwise.
    pub color: crate::math::Rgb,
}

impl Shape {
    /// Distance to the first intersection in `(0, t_max)`.
    #[inline]
    pub fn intersect_t(&self, ray: &Ray, t_max: f32, geo: &Geometry) -> Option<f32> {
        match self {
            Shape::Sdf(i) => geo.sdfs[*i as usize].intersect(ray, t_max),
            Shape::Sphere(s) => s.intersect(ray, t_max),
            Shape::Quad(q) => q.intersect(ray, t_max).map(|(t, _)| t),
            Shape::Instance(i) => geo.instances[*i as usize]
                .closest(ray, t_max, &geo.meshes)
                .map(|h| h.t),
            Shape::Plane(p) => p.intersect(ray, t_max),
            Shape::Triangle(tr) => tr.intersect(&WatertightRay4::new(ray), t_max).map(|(t, _)| t),
            Shape::MeshQuad(q) => q.intersect(&WatertightRay4::new(ray), t_max).map(|(t, _, _)| t),
        }
    }

    /// Whether the shape is hit in `(0, t_max)`.
    #[inline]
    pub fn occludes(&self, ray: &Ray, t_max: f32, geo: &Geometry) -> bool {
        match self {
            Shape::Instance(i) => geo.instances[*i as usize].occluded(ray, t_max, &geo.meshes),
            Shape::Sdf(i) => geo.sdfs[*i as usize].occluded(ray, t_max),
            s => s.intersect_t(ray, t_max, geo).is_some(),
        }
    }

    /// Full hit record for a `t` returned by [`Shape::intersect_t`]. An
    /// instance re-traces its mesh (callers on the hot path keep the
    /// [`MeshHit`] instead, see `Scene::intersect`).
    pub fn hit(&self, ray: &Ray, t: f32, geo: &Geometry) -> Hit {
        let p = ray.at(t);
        match self {
            Shape::Sdf(i) => geo.sdfs[*i as usize].hit(ray, t),
            Shape::Sphere(s) => s.hit(p, t),
            Shape::Quad(q) => q.hit(ray, t),
            Shape::Instance(i) => {
                let inst = &geo.instances[*i as usize];
                let h = inst.closest(ray, t * (1.0 + 1e-5) + f32::MIN_POSITIVE, &geo.meshes);
                let h = h.unwrap_or(MeshHit {
                    t,
                    tri: 0,
                    bc: Vec2::ZERO,
                });
                inst.hit(ray, h, &geo.meshes)
            }
            Shape::Plane(pl) => pl.hit(p, t),
            Shape::Triangle(tr) => {
                let wt = WatertightRay4::new(ray);
                let bc = tr
                    .intersect(&wt, t * (1.0 + 1e-5) + f32::MIN_POSITIVE)
                    .map_or(Vec2::ZERO, |(_, bc)| bc);
                tr.hit(ray, t, bc, geo)
            }
            Shape::MeshQuad(q) => {
                let wt = WatertightRay4::new(ray);
                let (k, bc) = q
                    .intersect(&wt, t * (1.0 + 1e-5) + f32::MIN_POSITIVE)
                    .map_or((0, Vec2::ZERO), |(_, k, bc)| (k, bc));
                q.hit(ray, t, k, bc, geo)
            }
        }
    }

    /// `None` for unbounded shapes (planes), which live outside the BVH.
    pub fn bounds(&self, geo: &Geometry) -> Option<Aabb> {
        match self {
            Shape::Sdf(i) => geo.sdfs[*i as usize].bounds(),
            Shape::Sphere(s) => Some(s.bounds()),
            Shape::Quad(q) => Some(q.bounds()),
            Shape::Instance(i) => Some(geo.instances[*i as usize].bounds(&geo.meshes)),
            Shape::Plane(_) => None,
            Shape::Triangle(tr) => Some(tr.bounds()),
            Shape::MeshQuad(q) => Some(q.bounds()),
        }
    }
}

// The flattened triangles' shading records (`flat_shade.rs`) fit in the
// room the largest shape already takes: the scene's shape list is no larger.
const _: () = assert!(size_of::<Shape>() <= 128);
