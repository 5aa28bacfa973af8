//! An emissive sphere, sampled by the cone of directions it subtends.

use super::emission::{Emission, EmissionTexture};
use super::tree::LightBounds;
use super::{LightModel, LightOrigin, LightSample};
use crate::geometry::Sphere;
use crate::math::sampling::uniform_sphere;
use crate::math::trig::sin_cos_turns;
use crate::math::{Frame, Rgb};
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;
use std::sync::Arc;

/// A sphere emitting uniform radiance outward from its surface (and inward too
/// when `two_sided`); its surface is also a [`crate::geometry::Sphere`] in the
/// scene BVH.
#[derive(Clone, Debug)]
pub struct SphereLight {
    /// Centre, in world space.
    pub center: Vec3A,
    /// Radius in scene units, > 0.
    pub radius: f32,
    /// Emitted radiance, W/(m²·sr); a texture's average when `texture` is set.
    pub radiance: Rgb,
    /// The radiance over the sphere's UVs, when it varies.
    pub texture: Option<Arc<EmissionTexture>>,
    /// The sphere's UVs are Mitsuba's ([`Sphere::uv_mitsuba`]) rather than
    /// [`Sphere::uv`]: what `texture` is looked up with.
    pub mitsuba_uv: bool,
    /// Whether the inside emits too.
    pub two_sided: bool,
}

impl SphereLight {
    /// A one-sided sphere of constant `radiance`, y-up UVs.
    pub fn new(center: Vec3A, radius: f32, radiance: Rgb) -> Self {
        Self {
            center,
            radius,
            radiance,
            texture: None,
            mitsuba_uv: false,
            two_sided: false,
        }
    }

    /// This light emitting `e` over its UVs.
    pub fn with_emission(mut self, e: Emission) -> Self {
        self.radiance = e.radiance;
        self.texture = e.texture;
        self
    }

    /// Radiance at the point of outward unit normal `n`: its texture's value
    /// at that point's UVs (computed here, since hits on spheres of untextured
    /// materials skip them).
    #[inline]
    pub fn radiance_at(&self, n: Vec3A) -> Rgb {
        match &self.texture {
            None => self.radiance,
            Some(t) if self.mitsuba_uv => t.eval(Sphere::uv_mitsuba(n)),
            Some(t) => t.eval(Sphere::uv(n)),
        }
    }

    /// Radiance leaving a point of outward normal `n` toward `w`.
    #[inline]
    pub fn emitted(&self, n: Vec3A, w: Vec3A) -> Rgb {
        if self.two_sided || n.dot(w) > 0.0 {
            self.radiance_at(n)
        } else {
            Rgb::ZERO
        }
    }

    /// `sin²θmax` and `1 − cos θmax` of the cone the sphere subtends from `p`,
    /// or `None` when `p` is inside (or on) it.
    #[inline]
    fn cone(&self, p: Vec3A) -> Option<(f32, f32)> {
        super::sphere_cone(self.center, self.radius, p, 1.0 + 1e-5)
    }

    /// From outside, uniform over the cone of directions the sphere subtends (its
    /// visible cap: pdf 1/(2π(1 − cos θmax))); from inside a two-sided sphere,
    /// uniform by area (pdf d²/(|cos θl|·4πr²)); `None` from inside a one-sided
    /// one, which sends no light inward.
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        let Some((sin2_max, one_minus_cos)) = self.cone(p) else {
            return self.sample_inside(p, u);
        };
        // A direction in the cone at angle θ to the centre, uniform in cos θ.
        let (cos_t, sin2_t) = if sin2_max < 0.000_685_23 {
            let s2 = sin2_max * u.x;
            ((1.0 - s2).sqrt(), s2)
        } else {
            let c = 1.0 - one_minus_cos * u.x;
            (c, (1.0 - c * c).max(0.0))
        };
        // The angle α at the centre between the sphere point the direction meets
        // and the direction back to `p` (law of sines), then the point itself.
        let sin_max = sin2_max.sqrt();
        let cos_a = sin2_t / sin_max + cos_t * (1.0 - sin2_t / sin2_max).max(0.0).sqrt();
        let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
        // (sin φ, cos φ) of φ = 2π·u.y without libm's sinf and cosf.
        let (sin_p, cos_p) = sin_cos_turns(u.y);
        let to_p = (p - self.center).normalize();
        let f = Frame::from_normal(to_p);
        let n = f.to_world(Vec3A::new(sin_a * cos_p, sin_a * sin_p, cos_a));
        let q = self.center + n * self.radius;
        let d = q - p;
        let dist = d.length();
        if dist.is_nan() || dist <= 0.0 {
            return None;
        }
        Some(LightSample {
            wi: d / dist,
            dist,
            p: q,
            n,
            li: self.radiance_at(n),
            pdf: 1.0 / (2.0 * PI * one_minus_cos),
            delta: false,
        })
    }

    fn sample_inside(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        if !self.two_sided {
            return None;
        }
        let n = crate::math::sampling::uniform_sphere(u);
        let q = self.center + n * self.radius;
        let d = q - p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        let wi = d / dist;
        let cos_l = wi.dot(n).abs();
        if !(dist > 0.0 && cos_l > 0.0) {
            return None;
        }
        Some(LightSample {
            wi,
            dist,
            p: q,
            n,
            li: self.radiance_at(n),
            pdf: dist2 / (cos_l * self.area()),
            delta: false,
        })
    }

    /// Solid-angle density of [`Self::sample`] from `p` for a ray that reached
    /// the sphere along unit `wi` at distance `dist` with outward normal `n`.
    #[inline]
    pub fn pdf(&self, p: Vec3A, wi: Vec3A, dist: f32, n: Vec3A) -> f32 {
        match self.cone(p) {
            Some((_, one_minus_cos)) => 1.0 / (2.0 * PI * one_minus_cos),
            None if self.two_sided => {
                let cos_l = wi.dot(n).abs();
                if cos_l > 0.0 {
                    dist * dist / (cos_l * self.area())
                } else {
                    0.0
                }
            }
            None => 0.0,
        }
    }

    /// Surface area 4πr².
    pub fn area(&self) -> f32 {
        4.0 * PI * self.radius * self.radius
    }

    /// Φ = π·A·L, twice that when two-sided.
    pub fn power(&self) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * self.area() * self.radiance
    }
}

impl LightModel for SphereLight {
    /// The ball; normals in every direction.
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        let b = LightBounds::ball(self.center, self.radius);
        Some(LightBounds::surface(b, Vec3A::Z, -1.0, self.two_sided, phi))
    }
    /// One-sided spheres only: a two-sided one also lights its inside,
    /// which the tracer's aiming does not cover.
    fn emits_caustics(&self) -> bool {
        !self.two_sided
    }
    /// A point uniform over the sphere, emitting from its outside.
    #[inline]
    fn caustic_origin(&self, u: Vec2, pmf: f32) -> Option<LightOrigin> {
        let n = uniform_sphere(u);
        let area = 4.0 * PI * self.radius * self.radius;
        Some(LightOrigin {
            p: self.center + self.radius * n,
            n,
            le: self.radiance_at(n) * (area / pmf),
            two_sided: false,
        })
    }
}
