//! Parallelogram area light, one-sided (a `Quad`/`Rect` light) or two-sided
//! (an emissive `Quad`/`Rect` object that asks for it).

use super::LightSample;
use crate::math::Rgb;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// One-sided parallelogram `corner + s·u + t·v`, s,t ∈ [0, 1], emitting uniform
/// radiance from the side `u × v` points to.
#[derive(Clone, Copy, Debug)]
pub struct QuadLight {
    /// One corner, in world space.
    pub corner: Vec3A,
    /// First edge from `corner`.
    pub u: Vec3A,
    /// Second edge from `corner`.
    pub v: Vec3A,
    /// Emitting side: `normalize(u × v)`.
    pub n: Vec3A,
    /// Area in m² (square scene units), `|u × v|`.
    pub area: f32,
    /// Emitted radiance, W/(m²·sr).
    pub radiance: Rgb,
    /// Whether the back (against `n`) emits too.
    pub two_sided: bool,
}

impl QuadLight {
    /// The light spanned by `u` and `v` from `corner` (not parallel), emitting
    /// `radiance` in W/(m²·sr) toward `u × v`.
    pub fn new(corner: Vec3A, u: Vec3A, v: Vec3A, radiance: Rgb) -> Self {
        let c = u.cross(v);
        Self {
            corner,
            u,
            v,
            n: c.normalize(),
            area: c.length(),
            radiance,
            two_sided: false,
        }
    }

    /// Radiance leaving the light toward direction `w` (from the light).
    #[inline]
    pub fn emitted(&self, w: Vec3A) -> Rgb {
        if self.two_sided || self.n.dot(w) > 0.0 {
            self.radiance
        } else {
            Rgb::ZERO
        }
    }

    /// Uniform by area, converted to solid angle: pdf = d² / (cos θl · A).
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        let q = self.corner + u.x * self.u + u.y * self.v;
        let d = q - p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        let wi = d / dist;
        let cos_l = self.facing(-wi.dot(self.n));
        if cos_l <= 0.0 || dist2 == 0.0 {
            return None;
        }
        Some(LightSample {
            wi,
            dist,
            p: q,
            n: self.n,
            li: self.radiance,
            pdf: dist2 / (cos_l * self.area),
            delta: false,
        })
    }

    /// Solid-angle density of hitting this light at distance `dist` along
    /// `wi` (for MIS); matches [`QuadLight::sample`].
    pub fn pdf(&self, wi: Vec3A, dist: f32) -> f32 {
        let cos_l = self.facing(-wi.dot(self.n));
        if cos_l <= 0.0 {
            0.0
        } else {
            dist * dist / (cos_l * self.area)
        }
    }

    /// The cosine at the light of a direction whose cosine to `n` is `cos_n`:
    /// itself one-sided (≤ 0 means the back), its magnitude two-sided.
    #[inline]
    fn facing(&self, cos_n: f32) -> f32 {
        if self.two_sided { cos_n.abs() } else { cos_n }
    }

    /// Φ = π A L for a one-sided Lambertian emitter, twice that two-sided.
    pub fn power(&self) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * self.area * self.radiance
    }
}
