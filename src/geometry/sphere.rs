//! Analytic sphere.

use super::Hit;
use crate::accel::Aabb;
use crate::math::Ray;
use crate::math::float_error::{error_along, gamma_offset};
use crate::math::trig::turns_lanes;
use glam::{Vec2, Vec3A, Vec4};
use std::f32::consts::PI;

/// An analytic sphere in world space.
#[derive(Clone, Copy, Debug)]
pub struct Sphere {
    /// Centre, in world space.
    pub center: Vec3A,
    /// Radius in scene units, > 0.
    pub radius: f32,
    /// Index into the scene's materials.
    pub material: u32,
    /// Index of the light this sphere is (an emissive sphere), or [`NO_LIGHT`](super::NO_LIGHT).
    pub light: u32,
    /// UVs as Mitsuba's `sphere` ([`Sphere::uv_mitsuba`]) rather than
    /// [`Sphere::uv`].
    pub mitsuba_uv: bool,
}

impl Sphere {
    /// Nearest root of |o + t d − c|² = r² in (ε, t_max). Uses the
    /// numerically stable form of the quadratic (pbrt-v4 §6.8.5 style: the
    /// discriminant from the vector between the ray and the centre's
    /// projection avoids cancellation for distant spheres).
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let oc = ray.o - self.center;
        let a = ray.d.length_squared();
        let b = oc.dot(ray.d);
        // Distance² from centre to the ray's line, computed without cancellation.
        let l = oc - (b / a) * ray.d;
        let disc = self.radius * self.radius - l.length_squared();
        if disc < 0.0 {
            return None;
        }
        let q = -b - b.signum() * (a * disc).sqrt();
        let (t0, t1) = {
            let x = q / a;
            let y = if q != 0.0 {
                (oc.length_squared() - self.radius * self.radius) / q
            } else {
                x
            };
            (x.min(y), x.max(y))
        };
        let eps = 1e-4 * self.radius.max(1e-3);
        if t0 > eps && t0 < t_max {
            Some(t0)
        } else if t1 > eps && t1 < t_max {
            Some(t1)
        } else {
            None
        }
    }

    /// Shading record at `p` (projected back onto the surface), with the spherical
    /// UVs of [`Sphere::uv`].
    pub fn hit(&self, p: Vec3A, t: f32) -> Hit {
        let mut h = self.hit_without_uv(p, t);
        h.uv = if self.mitsuba_uv {
            Self::uv_mitsuba(h.ng)
        } else {
            Self::uv(h.ng)
        };
        h
    }

    /// [`Sphere::hit`] with `uv` left zero, for untextured materials: the
    /// `atan2` and `acos` were 4% of a render of the specular Cornell box.
    ///
    /// `p` is re-projected onto the sphere, so its error does not depend on
    /// how far the ray came: the radius vector `n·r` is off by the
    /// normalisation's few roundings of `r` (γ(5)·|n·r|, pbrt-v4's bound
    /// for its reprojection), the sum with the centre by one more rounding
    /// of the result (taken as γ(5)·|p| too, for margin).
    pub fn hit_without_uv(&self, p: Vec3A, t: f32) -> Hit {
        // Normalised without dividing by the radius first: one division
        // less on the chain every shading step waits on.
        let n = (p - self.center).normalize();
        let radial = n * self.radius;
        let p = self.center + radial;
        Hit {
            t,
            p,
            p_error: error_along(n, gamma_offset(5) * (radial.abs() + p.abs())),
            ng: n,
            ns: n,
            uv: Vec2::ZERO,
            material: self.material,
            light: self.light,
            color: glam::Vec3A::ONE,
        }
    }

    /// Spherical coordinates of unit normal `n`, y up: u around the axis,
    /// v from the bottom.
    ///
    /// Both angles by [`turns_lanes`] (the polynomial the sky's lookup uses,
    /// as fast as libm's `atanf` and `acosf` here, in two lanes of one
    /// computation so that their latency chains overlap), θ as atan2(sin θ, cos θ),
    /// which unlike `acos` keeps its precision near the poles (acos(1 − ε)
    /// moves in steps of ~3·10⁻⁴ rad there).
    pub fn uv(n: Vec3A) -> Vec2 {
        let a = turns_lanes(
            Vec4::new(n.z, (n.x * n.x + n.z * n.z).sqrt(), 0.0, 0.0),
            Vec4::new(n.x, n.y, 1.0, 1.0),
        );
        Vec2::new(0.5 + a.x, 1.0 - a.y)
    }

    /// Mitsuba's spherical coordinates of unit normal `n`: the poles on the
    /// z axis (v = 0 at +z), u = atan2(y, x)/2π in [0, 1) (0 along +x, ¼
    /// along +y). Angles as in [`Sphere::uv`].
    pub fn uv_mitsuba(n: Vec3A) -> Vec2 {
        let a = turns_lanes(
            Vec4::new(n.y, (n.x * n.x + n.y * n.y).sqrt(), 0.0, 0.0),
            Vec4::new(n.x, n.z, 1.0, 1.0),
        );
        let mut u = a.x;
        if u < 0.0 {
            u += 1.0;
        }
        Vec2::new(u, a.y)
    }

    /// ∂p/∂u and ∂p/∂v at unit normal `n`, for the UVs this sphere uses.
    pub fn derivatives(&self, n: Vec3A) -> (Vec3A, Vec3A) {
        let r = self.radius;
        if self.mitsuba_uv {
            // φ = atan2(y, x), θ = acos(z): ∂p/∂u = 2πr(−y, x, 0),
            // ∂p/∂v = πr(z cos φ, z sin φ, −sin θ).
            let rho = (n.x * n.x + n.y * n.y).sqrt();
            let (cos_phi, sin_phi) = if rho > 0.0 {
                (n.x / rho, n.y / rho)
            } else {
                (1.0, 0.0)
            };
            (
                2.0 * PI * r * Vec3A::new(-n.y, n.x, 0.0),
                PI * r * Vec3A::new(n.z * cos_phi, n.z * sin_phi, -rho),
            )
        } else {
            // φ = atan2(z, x), θ' = acos(y), u = ½ + φ/2π, v = 1 − θ'/π.
            let rho = (n.x * n.x + n.z * n.z).sqrt();
            let (cos_phi, sin_phi) = if rho > 0.0 {
                (n.x / rho, n.z / rho)
            } else {
                (1.0, 0.0)
            };
            (
                2.0 * PI * r * Vec3A::new(-n.z, 0.0, n.x),
                -PI * r * Vec3A::new(n.y * cos_phi, -rho, n.y * sin_phi),
            )
        }
    }

    /// World-space bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb {
            min: self.center - Vec3A::splat(self.radius),
            max: self.center + Vec3A::splat(self.radius),
        }
    }
}
