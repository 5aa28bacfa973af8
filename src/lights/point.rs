//! Isotropic point light.

use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::math::Rgb;
use glam::Vec3A;
use std::f32::consts::PI;

/// Isotropic point light: the same intensity in every direction.
#[derive(Clone, Copy, Debug)]
pub struct PointLight {
    /// Position in world space.
    pub position: Vec3A,
    /// Radiant intensity, W/sr.
    pub intensity: Rgb,
}

impl PointLight {
    /// The light reaching world-space point `p`: `I/r²` from the light's position,
    /// pdf 1; `None` at the light's own position.
    pub fn sample(&self, p: Vec3A) -> Option<LightSample> {
        let d = self.position - p;
        let dist2 = d.length_squared();
        if dist2 == 0.0 {
            return None;
        }
        let dist = dist2.sqrt();
        Some(LightSample {
            wi: d / dist,
            dist,
            p: self.position,
            n: Vec3A::ZERO,
            li: self.intensity / dist2,
            pdf: 1.0,
            delta: true,
        })
    }

    /// Φ = 4π I.
    pub fn power(&self) -> Rgb {
        4.0 * PI * self.intensity
    }
}

impl LightModel for PointLight {
    /// A point emitting in every direction; its weight is π × its
    /// intensity, a quarter of its power (see `tree::light_bounds`).
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        Some(LightBounds {
            bounds: LightBounds::ball(self.position, 0.0),
            w: Vec3A::Z,
            phi: 0.25 * phi,
            cos_theta_o: -1.0,
            cos_theta_e: 0.0,
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
