//! Triangle meshes (from Wavefront OBJ), stored indexed.

use super::{Hit, NO_LIGHT, triangle};
use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Vec2, Vec3A};

#[derive(Clone, Debug, Default)]
pub struct Mesh {
    pub positions: Vec<Vec3A>,
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals (same indexing as `positions`), or empty.
    pub normals: Vec<Vec3A>,
    /// Per-vertex texture coordinates, or empty.
    pub uvs: Vec<Vec2>,
    pub material: u32,
}

impl Mesh {
    #[inline]
    fn corners(&self, tri: u32) -> (Vec3A, Vec3A, Vec3A) {
        let [a, b, c] = self.indices[tri as usize];
        (
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        )
    }

    #[inline]
    pub fn intersect(&self, tri: u32, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
        let (a, b, c) = self.corners(tri);
        triangle::intersect(a, b, c, ray, t_max)
    }

    pub fn hit(&self, tri: u32, ray: &Ray, t: f32) -> Hit {
        let (a, b, c) = self.corners(tri);
        let bc = triangle::intersect(a, b, c, ray, f32::INFINITY).map_or(Vec2::ZERO, |(_, bc)| bc);
        let w = Vec3A::new(1.0 - bc.x - bc.y, bc.x, bc.y);
        // Counter-clockwise winding faces outward.
        let ng = (b - a).cross(c - a).normalize();
        let [ia, ib, ic] = self.indices[tri as usize].map(|i| i as usize);
        let mut ns = ng;
        if !self.normals.is_empty() {
            let n = self.normals[ia] * w.x + self.normals[ib] * w.y + self.normals[ic] * w.z;
            if n.length_squared() > 0.0 {
                // Keep the shading normal on the geometric normal's side.
                ns = n.normalize();
                if ns.dot(ng) < 0.0 {
                    ns = -ns;
                }
            }
        }
        let uv = if self.uvs.is_empty() {
            bc
        } else {
            self.uvs[ia] * w.x + self.uvs[ib] * w.y + self.uvs[ic] * w.z
        };
        Hit {
            t,
            p: a * w.x + b * w.y + c * w.z,
            ng,
            ns,
            uv,
            material: self.material,
            light: NO_LIGHT,
        }
    }

    pub fn tri_bounds(&self, tri: u32) -> Aabb {
        let (a, b, c) = self.corners(tri);
        Aabb::from_points(&[a, b, c])
    }

    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }
}
