//! Light sources. Units: point and spot lights give radiant intensity in
//! W/sr, area lights and the environment emitted radiance in W/(m²·sr), per
//! linear-RGB channel.
//!
//! | light | what emits | next-event estimation samples |
//! |---|---|---|
//! | `Point`, `Spot` | a point (delta) | its position |
//! | `Directional` | parallel light from infinitely far (a sun; delta) | its direction, with an unbounded shadow ray |
//! | `Quad` | a `Quad`/`Rect` light, or an emissive `Quad`/`Rect` object | rectangles uniformly in solid angle (spherical rectangles), other parallelograms by area |
//! | `Sphere` | an emissive sphere | uniformly in the cone it subtends |
//! | `Mesh` | the emissive triangles of a placed mesh (one material slot), moving with a keyed instance | by area: a triangle by an alias table, then a uniform point (placed at the path's time when it moves) |
//! | `Sdf` | an emissive implicit surface | uniformly in its bounding sphere's cone, then marched |
//! | `Environment` | the sky at infinity (at most one) | an image by its bilinear luminance × sin θ; a constant sky by the cosine about the shading normal |
//!
//! Every light but points, spots and directional lights is also reached by BSDF sampling (a
//! surface in the BVH, or a ray that misses everything); the path tracer
//! weighs the two strategies by MIS, so each emitter counts once.
//!
//! Which light a next-event estimate samples is chosen per shading point by
//! a light tree (`tree.rs`, the default), or by power or uniformly
//! (`power.rs`).

pub mod alias;
pub mod caustic;
pub mod directional;
pub mod emission;
pub mod env_map;
pub mod env_table;
pub mod environment;
pub mod irradiance;
pub mod mesh;
pub mod point;
pub mod power;
pub mod quad;
pub mod sdf;
pub mod sphere;
pub mod spherical_rect;
pub mod spot;
pub mod tree;

#[cfg(test)]
mod moving_tests;
#[cfg(test)]
mod tests;

pub use caustic::CausticEmitters;
pub use directional::DirectionalLight;
pub use emission::Emission;
pub use env_map::EnvMap;
pub use environment::{EnvSampling, EnvironmentLight};
pub use mesh::MeshLight;
pub use point::PointLight;
pub use power::{LightPicker, Selection};
pub use quad::QuadLight;
pub use sdf::SdfLight;
pub use sphere::SphereLight;
pub use spot::SpotLight;
pub use tree::LightTree;

use crate::geometry::{Geometry, Hit};
use crate::math::Rgb;
use crate::sampler::Draw;
use glam::{Vec2, Vec3A};
use tree::LightBounds;

/// A light source of the runtime scene, in world space; a closed set, so an `enum`
/// forwarded by `match`.
#[derive(Clone, Debug)]
pub enum Light {
    /// Isotropic point light (a delta light).
    Point(PointLight),
    /// Point light limited to a cone (a delta light).
    Spot(SpotLight),
    /// Parallel light from infinitely far away (a delta light: a sun).
    Directional(DirectionalLight),
    /// One-sided parallelogram area light; its surface is also a
    /// [`crate::geometry::Quad`] in the scene BVH.
    Quad(QuadLight),
    /// An emissive sphere (also a [`crate::geometry::Sphere`] in the BVH).
    Sphere(SphereLight),
    /// Emissive triangles of a placed mesh.
    Mesh(MeshLight),
    /// An emissive implicit surface.
    Sdf(SdfLight),
    /// The environment, at infinity.
    Environment(Box<EnvironmentLight>),
}

/// What every light answers beyond sampling and emission, written beside
/// its model: a new light is its description (`desc/light.rs`), its loader
/// entry (`load/light.rs` or the emitting object's) and its model file, plus
/// one line in [`Light`], one in `forward_light!` and one in each of
/// [`Light::sample`], [`Light::emitted`] and [`Light::pdf`] (whose arguments
/// differ by kind). The defaults are those of most lights.
pub trait LightModel {
    /// What the light tree knows of it (`tree.rs`), `phi` being its power
    /// (luminance, W); `None` for a light without a position (the sky).
    fn bounds(&self, phi: f32) -> Option<LightBounds>;
    /// True for lights without area (point, spot, directional): sampled
    /// exactly, never hit by rays.
    fn is_delta(&self) -> bool {
        false
    }
    /// Whether the caustic light tracer (`integrators/caustic.rs`) starts
    /// paths on it; [`LightModel::caustic_origin`] then gives their start.
    fn emits_caustics(&self) -> bool {
        false
    }
    /// Where a caustic light path starts for `u` ∈ [0, 1)², the light
    /// having been picked with probability `pmf`; `None` when
    /// [`LightModel::emits_caustics`] is false.
    fn caustic_origin(&self, _u: Vec2, _pmf: f32) -> Option<LightOrigin> {
        None
    }
    /// The sky, when this light is it.
    fn as_environment(&self) -> Option<&EnvironmentLight> {
        None
    }
    /// The directional light, when this light is one.
    fn as_directional(&self) -> Option<&DirectionalLight> {
        None
    }
}

/// The start of a light path: a point, its emitting normal, the emitted
/// radiance over the point's density (`L_e / (pmf · p_A)`), and whether the
/// back emits too.
#[derive(Clone, Copy, Debug)]
pub struct LightOrigin {
    /// A point on the light.
    pub p: Vec3A,
    /// Unit normal of its emitting side.
    pub n: Vec3A,
    /// `L_e / (pmf · p_A)`, W/(m²·sr) over the area density.
    pub le: Rgb,
    /// Whether the back emits too.
    pub two_sided: bool,
}

/// Forwards one [`LightModel`] method to the variant (the match is the
/// checklist).
macro_rules! forward_light {
    ($self:ident, $l:ident => $call:expr) => {
        match $self {
            Light::Point($l) => $call,
            Light::Spot($l) => $call,
            Light::Directional($l) => $call,
            Light::Quad($l) => $call,
            Light::Sphere($l) => $call,
            Light::Mesh($l) => $call,
            Light::Sdf($l) => $call,
            Light::Environment($l) => $call,
        }
    };
}

/// Light arriving at a shading point from one sampled point of a light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light.
    pub wi: Vec3A,
    /// Distance from the shading point to the sampled point; infinite for the
    /// environment (its shadow ray is unbounded).
    pub dist: f32,
    /// The sampled point on the light.
    pub p: Vec3A,
    /// Unit surface normal at `p` on the emitting side, or zero for lights
    /// without a surface (points, spots): shadow rays stop short of a
    /// surface by leaving it along this normal (`integrators::shadow_ray`).
    pub n: Vec3A,
    /// Incident radiance (area lights, environment) or `I/r²` (delta lights),
    /// to be divided by `pdf`.
    pub li: Rgb,
    /// Solid-angle density of `wi`; 1 for delta lights.
    pub pdf: f32,
    /// True for point and spot lights: `wi` is the only direction the light arrives
    /// from, so BSDF sampling can never hit it and MIS does not apply.
    pub delta: bool,
}

impl Light {
    /// Samples light arriving at world-space point `p`, `u` ∈ [0, 1)² choosing the
    /// point on an area light or the direction toward the environment; `None` if
    /// no light reaches `p` (behind an area light, outside a spot's cone, or at
    /// the light's own position). `n` is the unit normal at `p` on the side
    /// light is wanted from, or zero for every side (a transmitting surface):
    /// only the environment reads it, and `draw`, whether `u` is stratified
    /// across the pixel's samples (a sky map then keeps its strata, see
    /// `env_table.rs`). `geo` is for SDF emitters, which are marched.
    #[inline]
    pub fn sample(&self, p: Vec3A, n: Vec3A, u: Vec2, draw: Draw, geo: &Geometry) -> Option<LightSample> {
        match self {
            Light::Point(l) => l.sample(p),
            Light::Spot(l) => l.sample(p),
            Light::Directional(l) => l.sample(p, u),
            Light::Quad(l) => l.sample(p, u),
            Light::Sphere(l) => l.sample(p, u),
            Light::Mesh(l) => l.sample(p, u),
            Light::Sdf(l) => l.sample(p, u, geo),
            Light::Environment(l) => l.sample(p, n, u, draw),
        }
    }

    /// Radiance the surface at `hit` (this light's surface) emits toward `w`
    /// (unit, leaving the surface); zero for lights without a surface.
    #[inline]
    pub fn emitted(&self, hit: &Hit, w: Vec3A) -> Rgb {
        match self {
            Light::Quad(l) => l.emitted(hit.uv, w),
            Light::Sphere(l) => l.emitted(hit.ng, w),
            Light::Mesh(l) => l.emitted(hit.ng, hit.uv, w),
            Light::Sdf(l) => l.emitted(hit.ng, w),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Environment(_) => Rgb::ZERO,
        }
    }

    /// Solid-angle density with which [`Light::sample`] from `p` draws the
    /// direction `wi` of a ray that reached this light's surface at `hit`
    /// (for MIS); 0 for lights without a surface.
    #[inline]
    pub fn pdf(&self, p: Vec3A, wi: Vec3A, hit: &Hit) -> f32 {
        match self {
            Light::Quad(l) => l.pdf(p, wi, hit.t),
            Light::Sphere(l) => l.pdf(p, wi, hit.t, hit.ng),
            Light::Mesh(l) => l.pdf(wi, hit.t, hit.ng),
            Light::Sdf(l) => l.pdf(p),
            Light::Point(_) | Light::Spot(_) | Light::Directional(_) | Light::Environment(_) => 0.0,
        }
    }

    /// Total emitted power in W per channel (for the environment, the power
    /// through the scene's bounding disk; for an SDF, that of its bounding
    /// sphere): what light selection weighs.
    pub fn power(&self) -> Rgb {
        match self {
            Light::Point(l) => l.power(),
            Light::Spot(l) => l.power(),
            Light::Directional(l) => l.power(),
            Light::Quad(l) => l.power(),
            Light::Sphere(l) => l.power(),
            Light::Mesh(l) => l.power(),
            Light::Sdf(l) => l.power(),
            Light::Environment(l) => l.power(),
        }
    }

    /// Where a light without area (point, spot) sits; `None` for the others.
    #[inline]
    pub fn point_source(&self) -> Option<Vec3A> {
        match self {
            Light::Point(l) => Some(l.position),
            Light::Spot(l) => Some(l.position),
            Light::Directional(_)
            | Light::Quad(_)
            | Light::Sphere(_)
            | Light::Mesh(_)
            | Light::Sdf(_)
            | Light::Environment(_) => None,
        }
    }

    /// Radiant intensity (W/sr) a point or spot light sends along unit
    /// direction `d`; zero for lights with area and the sky.
    #[inline]
    pub fn intensity_toward(&self, d: Vec3A) -> Rgb {
        match self {
            Light::Point(l) => l.intensity,
            Light::Spot(l) => l.intensity * l.falloff(d.dot(l.direction)),
            Light::Directional(_)
            | Light::Quad(_)
            | Light::Sphere(_)
            | Light::Mesh(_)
            | Light::Sdf(_)
            | Light::Environment(_) => Rgb::ZERO,
        }
    }

    /// The directional light, when this light is one.
    #[inline]
    pub fn as_directional(&self) -> Option<&DirectionalLight> {
        forward_light!(self, l => l.as_directional())
    }

    /// True for lights without area (point, spot, directional): sampled
    /// exactly, never hit by rays.
    #[inline]
    pub fn is_delta(&self) -> bool {
        forward_light!(self, l => l.is_delta())
    }

    /// What the light tree knows of it (see [`LightModel::bounds`]).
    pub fn bounds(&self, phi: f32) -> Option<LightBounds> {
        forward_light!(self, l => l.bounds(phi))
    }

    /// Whether the caustic light tracer starts paths on it.
    pub fn emits_caustics(&self) -> bool {
        forward_light!(self, l => l.emits_caustics())
    }

    /// Where a caustic light path starts (see [`LightModel::caustic_origin`]).
    #[inline]
    pub fn caustic_origin(&self, u: Vec2, pmf: f32) -> Option<LightOrigin> {
        forward_light!(self, l => l.caustic_origin(u, pmf))
    }

    /// The sky, when this light is it.
    #[inline]
    pub fn as_environment(&self) -> Option<&EnvironmentLight> {
        forward_light!(self, l => l.as_environment())
    }
}

/// `radiance` leaving a surface of normal `n` toward `w`: from the side `n`
/// points to, or from both sides when `two_sided`. The rule every emitting
/// shape follows (SDFs call it; quads, spheres and meshes, which may carry an
/// emission texture, test the side themselves).
#[inline]
pub(crate) fn sided(radiance: Rgb, two_sided: bool, n: Vec3A, w: Vec3A) -> Rgb {
    if two_sided || n.dot(w) > 0.0 {
        radiance
    } else {
        Rgb::ZERO
    }
}

/// `sin²θmax` and `1 − cos θmax` of the cone a sphere subtends from `p`, or
/// `None` when `p` is within `margin` times its squared radius of the centre
/// (inside). The difference is computed by its series for small cones, where
/// `1 − cos` would cancel (pbrt-v4 `Sphere::Sample`, below sin² 1.5°).
#[inline]
pub(crate) fn sphere_cone(center: Vec3A, radius: f32, p: Vec3A, margin: f32) -> Option<(f32, f32)> {
    let dc2 = (p - center).length_squared();
    let r2 = radius * radius;
    if dc2 <= r2 * margin {
        return None;
    }
    let sin2_max = r2 / dc2;
    let one_minus_cos = if sin2_max < 0.000_685_23 {
        0.5 * sin2_max
    } else {
        1.0 - (1.0 - sin2_max).max(0.0).sqrt()
    };
    Some((sin2_max, one_minus_cos))
}
