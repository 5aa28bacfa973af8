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

/// A light source of the runtime scene, in world space; a closed set, so an `enum`
/// forwarded by `match`.
#[derive(Clone, Copy, Debug)]
pub enum Light {
    /// Isotropic point light (a delta light).
    Point(PointLight),
    /// Point light limited to a cone (a delta light).
    Spot(SpotLight),
    /// One-sided parallelogram area light; its surface is also a
    /// [`crate::geometry::Quad`] in the scene BVH.
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
    /// True for point and spot lights: `wi` is the only direction the light arrives
    /// from, so BSDF sampling can never hit it and MIS does not apply.
    pub delta: bool,
}

impl Light {
    /// Samples light arriving at world-space point `p`, `u` ∈ [0, 1)² choosing the
    /// point on an area light; `None` if no light reaches `p` (behind an area light,
    /// outside a spot's cone, or at the light's own position).
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

    /// True for lights without area (point, spot): sampled exactly, never hit by
    /// rays.
    pub fn is_delta(&self) -> bool {
        !matches!(self, Light::Quad(_))
    }
}
