//! An emissive implicit surface. Its area and a way to pick points on it
//! uniformly are unknown, so it is sampled by direction instead: uniformly
//! over the cone its bounding sphere subtends (over the whole sphere of
//! directions from inside that sphere), then the SDF is marched along the
//! direction to find the point that emits. Directions that miss it carry
//! no light. The density depends on the direction only, so a BSDF sample
//! that reaches the surface knows it exactly for MIS.
//!
//! A point of the emitter does not light the emitter itself through this
//! strategy (the march from the surface stops at once); BSDF sampling in
//! `Path` still finds such light.

use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::geometry::Geometry;
use crate::math::sampling::{UNIFORM_SPHERE_PDF, uniform_sphere};
use crate::math::{Frame, Ray, Rgb, ray_epsilon};
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// An emissive [`crate::geometry::SdfObject`], sampled through its bounding sphere.
#[derive(Clone, Copy, Debug)]
pub struct SdfLight {
    /// Index into [`Geometry::sdfs`].
    pub sdf: u32,
    /// Centre of the bounding sphere, world space.
    pub center: Vec3A,
    /// Radius of the bounding sphere.
    pub radius: f32,
    /// Emitted radiance, W/(m²·sr).
    pub radiance: Rgb,
    /// Whether the inside (against the gradient) emits too.
    pub two_sided: bool,
}

impl SdfLight {
    /// Radiance leaving a point of outward normal `n` toward `w`.
    #[inline]
    pub fn emitted(&self, n: Vec3A, w: Vec3A) -> Rgb {
        super::sided(self.radiance, self.two_sided, n, w)
    }

    /// `1 − cos θmax` of the bounding sphere's cone from `p`; `None` inside it.
    #[inline]
    fn one_minus_cos(&self, p: Vec3A) -> Option<f32> {
        super::sphere_cone(self.center, self.radius, p, 1.0).map(|(_, c)| c)
    }

    /// A direction toward the bounding sphere, and the emitting point the
    /// direction meets; `None` when it meets none or its back.
    pub fn sample(&self, p: Vec3A, u: Vec2, geo: &Geometry) -> Option<LightSample> {
        let (wi, pdf) = match self.one_minus_cos(p) {
            Some(omc) => {
                let cos_t = 1.0 - omc * u.x;
                let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
                let phi = 2.0 * PI * u.y;
                let f = Frame::from_normal((self.center - p).normalize());
                let w = f.to_world(Vec3A::new(sin_t * phi.cos(), sin_t * phi.sin(), cos_t));
                (w.normalize(), 1.0 / (2.0 * PI * omc))
            }
            None => (uniform_sphere(u), UNIFORM_SPHERE_PDF),
        };
        let obj = &geo.sdfs[self.sdf as usize];
        let o = p + wi * ray_epsilon(p);
        let ray = Ray::new(o, wi);
        let t = obj.intersect(&ray, f32::INFINITY)?;
        let hit = obj.hit(&ray, t);
        let li = self.emitted(hit.ng, -wi);
        if li == Rgb::ZERO {
            return None;
        }
        let dist = (hit.p - p).length();
        Some(LightSample {
            wi,
            dist,
            p: hit.p,
            n: hit.ng,
            li,
            pdf,
            delta: false,
        })
    }

    /// Solid-angle density of [`Self::sample`] drawing `wi` from `p`.
    #[inline]
    pub fn pdf(&self, p: Vec3A) -> f32 {
        match self.one_minus_cos(p) {
            Some(omc) => 1.0 / (2.0 * PI * omc),
            None => UNIFORM_SPHERE_PDF,
        }
    }

    /// Power for light selection only: that of the bounding sphere's surface
    /// emitting `radiance` (an upper bound for a convex shape).
    pub fn power(&self) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * 4.0 * PI * self.radius * self.radius * self.radiance
    }
}

impl LightModel for SdfLight {
    /// Its bounding ball; normals in every direction.
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        let b = LightBounds::ball(self.center, self.radius);
        Some(LightBounds::surface(b, Vec3A::Z, -1.0, self.two_sided, phi))
    }
}
