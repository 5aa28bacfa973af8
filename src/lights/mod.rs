//! Light sources. Units: point and spot lights give radiant intensity in
//! W/sr, area lights emitted radiance in W/(m²·sr), per linear-RGB channel.

pub mod point;
pub mod power;
pub mod quad;
pub mod spot;

pub use point::PointLight;
pub use power::LightPicker;
pub use quad::QuadLight;
pub use spot::SpotLight;

use crate::math::Rgb;
use glam::{Vec2, Vec3A};

#[derive(Clone, Copy, Debug)]
pub enum Light {
    Point(PointLight),
    Spot(SpotLight),
    Quad(QuadLight),
}

/// Light arriving at a shading point from one sampled point of a light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light.
    pub wi: Vec3A,
    /// Distance from the shading point to the sampled point.
    pub dist: f32,
    /// The sampled point on the light.
    pub p: Vec3A,
    /// Unit surface normal at `p` on the emitting side, or zero for lights
    /// without a surface (points, spots): shadow rays stop short of a
    /// surface by leaving it along this normal (`integrators::shadow_ray`).
    pub n: Vec3A,
    /// Incident radiance (area lights) or `I/r²` (delta lights), to be
    /// divided by `pdf`.
    pub li: Rgb,
    /// Solid-angle density of `wi`; 1 for delta lights.
    pub pdf: f32,
    pub delta: bool,
}

impl Light {
    #[inline]
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        match self {
            Light::Point(l) => l.sample(p),
            Light::Spot(l) => l.sample(p),
            Light::Quad(l) => l.sample(p, u),
        }
    }

    /// Total emitted power in W per channel.
    pub fn power(&self) -> Rgb {
        match self {
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Quad(l) => l.power(),
        }
    }

    pub fn is_delta(&self) -> bool {
        !matches!(self, Light::Quad(_))
    }
}
