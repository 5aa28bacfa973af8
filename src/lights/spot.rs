//! Spot light: a point light restricted to a circular cone, with a smooth
//! falloff band (pbrt-v4 `SpotLight`). The cone is circular by construction:
//! intensity depends only on the angle to the axis.

use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::math::Rgb;
use glam::Vec3A;
use std::f32::consts::PI;

/// A point light restricted to a circular cone around `direction`, with a smooth
/// falloff band at its edge.
#[derive(Clone, Copy, Debug)]
pub struct SpotLight {
    /// Position in world space.
    pub position: Vec3A,
    /// Unit axis of the cone.
    pub direction: Vec3A,
    /// Intensity on the axis, W/sr.
    pub intensity: Rgb,
    /// cos of the half-angle where light stops.
    pub cos_total: f32,
    /// cos of the half-angle where the falloff starts (≥ `cos_total`).
    pub cos_falloff: f32,
}

impl SpotLight {
    /// `cone_degrees` and `falloff_degrees` are full angles; the falloff
    /// band is the outer part of the cone.
    pub fn new(
        position: Vec3A,
        direction: Vec3A,
        intensity: Rgb,
        cone_degrees: f32,
        falloff_degrees: f32,
    ) -> Self {
        let cos_total = (0.5 * cone_degrees).to_radians().cos();
        let inner = (cone_degrees - falloff_degrees).max(0.0);
        let cos_falloff = (0.5 * inner).to_radians().cos().max(cos_total);
        Self {
            position,
            direction: direction.normalize(),
            intensity,
            cos_total,
            cos_falloff,
        }
    }

    /// Angular falloff: 1 inside the inner cone, smoothstep to 0 at the edge.
    #[inline]
    pub fn falloff(&self, cos_theta: f32) -> f32 {
        if self.cos_falloff <= self.cos_total {
            return if cos_theta >= self.cos_total { 1.0 } else { 0.0 };
        }
        let t = ((cos_theta - self.cos_total) / (self.cos_falloff - self.cos_total)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    }

    /// The light reaching world-space point `p`: `I·falloff/r²`, pdf 1; `None`
    /// outside the cone or at the light's position.
    pub fn sample(&self, p: Vec3A) -> Option<LightSample> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        if dist2 == 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        let wi = d / dist;
        let f = self.falloff((-wi).dot(self.direction));
        if f == 0.0 {
            return None;
        }
        Some(LightSample {
            wi,
            dist,
            p: self.position,
            n: Vec3A::ZERO,
            li: self.intensity * f / dist2,
            pdf: 1.0,
            delta: true,
        })
    }

    /// Φ = I·2π·[(1 − cos θfalloff) + (cos θfalloff − cos θtotal)/2]: the
    /// smoothstep band integrates to exactly half its solid angle.
    pub fn power(&self) -> Rgb {
        self.intensity * 2.0 * PI * ((1.0 - self.cos_falloff) + 0.5 * (self.cos_falloff - self.cos_total))
    }
}

impl LightModel for SpotLight {
    /// The cone where the spot emits at all: θo + θe = its total
    /// half-angle. Its weight is π × its intensity inside the cone (see
    /// `tree::light_bounds`): its power `phi` over the solid angle
    /// [`SpotLight::power`] spreads it on, times π.
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        let cone = 2.0 * ((1.0 - self.cos_falloff) + 0.5 * (self.cos_falloff - self.cos_total));
        let weight = if cone > 0.0 { phi / cone } else { 0.0 };
        Some(LightBounds {
            bounds: LightBounds::ball(self.position, 0.0),
            w: self.direction.normalize_or(Vec3A::Z),
            phi: if weight.is_finite() { weight } else { 0.0 },
            cos_theta_o: 1.0,
            cos_theta_e: self.cos_total,
            two_sided: false,
        })
    }
    fn is_delta(&self) -> bool {
        true
    }
    /// Its caustics are light traced from its position
    /// (`integrators/caustic.rs`): the path tracer can never find them (no
    /// BSDF sample reaches a point).
    fn emits_caustics(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spot_power_matches_integrated_intensity() {
        let s = SpotLight::new(Vec3A::ZERO, Vec3A::NEG_Y, Rgb::ONE, 60.0, 20.0);
        // ∫ I(ω) dω over the sphere, by quadrature in θ (the cone is circular).
        let n = 200_000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let theta = (i as f64 + 0.5) / n as f64 * std::f64::consts::PI;
            sum += s.falloff(theta.cos() as f32) as f64 * theta.sin() * 2.0 * std::f64::consts::PI;
        }
        let integral = sum * std::f64::consts::PI / n as f64;
        let closed = s.power().x as f64;
        assert!(
            (integral - closed).abs() / closed < 1e-3,
            "quadrature {integral} vs closed form {closed}"
        );
    }

    #[test]
    fn spot_is_circular() {
        let s = SpotLight::new(Vec3A::new(0.0, 2.0, 0.0), Vec3A::NEG_Y, Rgb::ONE, 40.0, 10.0);
        // Points at the same angle off-axis in different azimuths get equal light.
        let a = s.sample(Vec3A::new(0.5, 0.0, 0.0)).map(|l| l.li.x);
        let b = s.sample(Vec3A::new(0.0, 0.0, 0.5)).map(|l| l.li.x);
        let c = s.sample(Vec3A::new(-0.3536, 0.0, 0.3536)).map(|l| l.li.x);
        assert!(a.is_some() && a == b, "{a:?} vs {b:?}");
        assert!(
            (a.unwrap_or(0.0) - c.unwrap_or(1.0)).abs() < 1e-4,
            "{a:?} vs {c:?}"
        );
    }
}
