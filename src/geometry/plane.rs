//! Infinite plane. Unbounded, so it is tested outside the BVH.

use super::{Hit, NO_LIGHT};
use crate::math::float_error::{error_along, gamma_offset};
use crate::math::{Frame, Ray};
use glam::{Vec2, Vec3A};

/// An infinite plane in world space, hit from both sides.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3A,
    /// Unit normal: the side the plane faces.
    pub normal: Vec3A,
    /// Index into the scene's materials.
    pub material: u32,
}

impl Plane {
    /// Distance along `ray` to the plane in `(1e-5, t_max)`, from either side; `None`
    /// for rays parallel to it.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let denom = self.normal.dot(ray.d);
        if denom.abs() < 1e-12 {
            return None;
        }
        let t = (self.point - ray.o).dot(self.normal) / denom;
        (t > 1e-5 && t < t_max).then_some(t)
    }

    /// Shading record at `p`; UVs are coordinates in the plane's own frame, one unit
    /// per scene unit, so textures repeat once per unit.
    ///
    /// `p` (the ray's `o + t·d`) is projected into the plane's frame and
    /// rebuilt as `point + a·s + b·t`, whose distance from the plane is a few
    /// roundings of `|point|`, `|a·s|` and `|b·t|` (γ(7): the products, two
    /// sums and the frame's own error against the normal) however far the
    /// ray travelled.
    pub fn hit(&self, p: Vec3A, t: f32) -> Hit {
        // UVs: coordinates in the plane's own frame, one unit per scene unit.
        let f = Frame::from_normal(self.normal);
        let d = p - self.point;
        let uv = Vec2::new(d.dot(f.s), d.dot(f.t));
        let (a, b) = (f.s * uv.x, f.t * uv.y);
        let p = self.point + a + b;
        Hit {
            t,
            p,
            p_error: error_along(
                self.normal,
                gamma_offset(7) * (self.point.abs() + a.abs() + b.abs()),
            ),
            ng: self.normal,
            ns: self.normal,
            uv,
            material: self.material,
            light: NO_LIGHT,
            color: glam::Vec3A::ONE,
        }
    }
}
