//! Parallelogram `corner + s·u + t·v`, s,t ∈ `[0, 1]`; also the shape of area
//! lights.

use super::Hit;
use crate::accel::Aabb;
use crate::math::Ray;
use crate::math::float_error::{error_along, gamma_offset};
use glam::{Vec2, Vec3A};

/// A parallelogram in world space, hit from both sides; an area light's emitting
/// surface is one too.
#[derive(Clone, Copy, Debug)]
pub struct Quad {
    /// One corner, in world space.
    pub corner: Vec3A,
    /// First edge from `corner`; `s` runs along it.
    pub u: Vec3A,
    /// Second edge from `corner`; `t` runs along it.
    pub v: Vec3A,
    /// `normalize(u × v)`.
    pub n: Vec3A,
    /// Dual basis of `(u, v)` in the plane: `p · du` and `p · dv` are the
    /// `(s, t)` of an in-plane offset `p`, precomputed because the division
    /// and cross products were most of the cost of a quad test.
    du: Vec3A,
    dv: Vec3A,
    /// Index into the scene's materials.
    pub material: u32,
    /// Area light index or `NO_LIGHT`.
    pub light: u32,
}

impl Quad {
    /// The parallelogram `corner + s·u + t·v`; `u` and `v` must not be parallel.
    /// `light` is the area light it is, or `NO_LIGHT`.
    pub fn new(corner: Vec3A, u: Vec3A, v: Vec3A, material: u32, light: u32) -> Self {
        let uxv = u.cross(v);
        let inv = 1.0 / uxv.length_squared();
        Self {
            corner,
            u,
            v,
            n: uxv.normalize(),
            du: v.cross(uxv) * inv,
            dv: uxv.cross(u) * inv,
            material,
            light,
        }
    }

    /// The dual basis `(du, dv)`: `p · du`, `p · dv` are the `(s, t)` of an
    /// in-plane offset `p` (for [`super::shape_lanes`]).
    pub(crate) fn dual(&self) -> (Vec3A, Vec3A) {
        (self.du, self.dv)
    }

    /// Area in square scene units, `|u × v|`.
    pub fn area(&self) -> f32 {
        self.u.cross(self.v).length()
    }

    /// Plane hit, then the (s, t) coordinates from the edge vectors.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
        let denom = self.n.dot(ray.d);
        if denom.abs() < 1e-12 {
            return None;
        }
        // Range check on the numerator first: most planes a ray meets lie
        // behind its best hit, and the division would only be waited on.
        let t = (self.corner - ray.o).dot(self.n) / denom;
        if !(t > 1e-5 && t < t_max) {
            return None;
        }
        // Solve d = s·u + r·v: (d × v)·(u × v) = d · (v × (u × v)), etc.
        let d = ray.at(t) - self.corner;
        let (s, r) = (d.dot(self.du), d.dot(self.dv));
        ((0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&r)).then_some((t, Vec2::new(s, r)))
    }

    /// Shading record for a hit at distance `t` found by [`Quad::intersect`]; `uv` is
    /// `(s, t)` in `[0, 1]²`.
    pub fn hit(&self, ray: &Ray, t: f32) -> Hit {
        let uv = self
            .intersect(ray, f32::INFINITY)
            .map_or(Vec2::ZERO, |(_, uv)| uv);
        self.hit_at(ray, t, uv)
    }

    /// Shading record for a hit at distance `t` whose `(s, t)` coordinates
    /// `uv` [`Quad::intersect`] already returned: the scene's closest-hit
    /// query keeps them rather than intersecting the quad a second time.
    ///
    /// The point is rebuilt from `(s, t)` as `corner + s·u + t·v`, not taken
    /// as `o + t·d`: its distance from the quad's plane is then one product
    /// and two sums of terms no larger than `|corner|`, `|s·u|` and `|t·v|`
    /// (γ(3)), whatever the ray's length; γ(5) leaves room for `n` being
    /// perpendicular to `u` and `v` only to its own rounding.
    #[inline]
    pub fn hit_at(&self, _ray: &Ray, t: f32, uv: Vec2) -> Hit {
        let (su, tv) = (self.u * uv.x, self.v * uv.y);
        let p = self.corner + su + tv;
        Hit {
            t,
            p,
            p_error: error_along(
                self.n,
                gamma_offset(5) * (self.corner.abs() + su.abs() + tv.abs()),
            ),
            ng: self.n,
            ns: self.n,
            uv,
            material: self.material,
            light: self.light,
            color: glam::Vec3A::ONE,
        }
    }

    /// World-space bounds of the four corners.
    pub fn bounds(&self) -> Aabb {
        let c = self.corner;
        Aabb::from_points(&[c, c + self.u, c + self.v, c + self.u + self.v])
    }
}
