//! Light-transport estimators. Each returns the radiance (W/(m²·sr)) arriving
//! at the camera along one ray.

pub mod caustic;
pub mod caustic_reach;
pub mod direct;
mod interior;
pub mod path;
pub mod sky_visibility;
#[cfg(test)]
mod spawn_tests;
pub mod vol_path;
pub mod whitted;

pub use direct::Direct;
pub use path::Path;
pub use whitted::Whitted;

use crate::geometry::{Hit, NO_LIGHT};
use crate::lights::LightSample;
use crate::math::float_error::{error_along, gamma_offset, offset_along_normal};
use crate::math::{Ray, Rgb};
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::Vec3A;

/// The light-transport estimator a render uses; a closed set, so an `enum` forwarded
/// by `match` rather than a trait object.
#[derive(Clone, Copy, Debug)]
pub enum Integrator {
    /// Emission plus one bounce of light (see [`direct`]).
    Direct(Direct),
    /// Direct lighting plus perfect specular chains (see [`whitted`]).
    Whitted(Whitted),
    /// Path tracing with next-event estimation and MIS (see [`path`]).
    Path(Path),
}

/// Per-thread counters, summed for the render summary.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counters {
    /// Rays traced (camera, bounce and shadow rays), for the rays/s figure.
    pub rays: u64,
    /// Camera samples taken (adaptive sampling takes fewer than `spp`).
    pub samples: u64,
}

impl Integrator {
    /// Continuations per camera sample (path splitting): what the pixel
    /// samplers make room for.
    pub fn splits(&self) -> u32 {
        match self {
            Integrator::Path(p) => p.splits.max(1),
            _ => 1,
        }
    }

    /// Radiance in W/(m²·sr) arriving at the camera along `ray` (a camera ray in
    /// world space), one sample of the chosen estimator; `sampler` must be set to
    /// this pixel and sample.
    #[inline]
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut Sampler, counters: &mut Counters) -> Rgb {
        match self {
            Integrator::Direct(d) => d.li(scene, ray, sampler, counters),
            Integrator::Whitted(w) => w.li(scene, ray, sampler, counters),
            Integrator::Path(p) => p.li(scene, ray, sampler, counters),
        }
    }
}

/// Radiance emitted by the surface at `hit` toward `-ray_dir`.
#[inline]
pub(crate) fn emitted(scene: &Scene, hit: &Hit, ray_dir: Vec3A) -> Rgb {
    if hit.light == NO_LIGHT {
        return Rgb::ZERO;
    }
    scene.lights[hit.light as usize].emitted(hit, -ray_dir)
}

/// Radiance arriving along a ray of direction `d` that missed everything: the
/// environment's, or black without one. A camera ray (`camera`) sees the
/// background instead when the environment is not `visible`; rays after a
/// bounce (reflections, refractions) always see the environment.
#[inline]
pub(crate) fn escaped(scene: &Scene, d: Vec3A, camera: bool) -> Rgb {
    match scene.environment() {
        Some((_, env)) if camera => env.seen_by_camera(d),
        Some((_, env)) => env.le(d),
        None => Rgb::ZERO,
    }
}

/// A ray leaving `hit` toward `w`, its origin moved off the surface along
/// the geometric normal on `w`'s side so it cannot re-hit its own surface.
#[inline]
pub fn spawn(hit: &Hit, w: Vec3A) -> Ray {
    Ray::new(offset_origin(hit.p, hit.ng, hit.p_error, w), w)
}

/// `p` moved off its surface (unit normal `n`) by `d`, the bound on how far
/// the true surface may lie from `p` along `n` (`Hit::p_error`), to the side
/// `w` points into, and rounded one ulp further (pbrt-v4's
/// `OffsetRayOrigin`). The offset is along the normal, so the moved point is
/// off the surface's plane by the full margin whatever the angle of `w`.
///
/// The margin is each hit's own rounding error rather than an epsilon that
/// scales with `|p|` (`1e-4·(1 + |p|)`, before issue 44): at 1,000 units from
/// the origin that epsilon was 0.1, more than the gap between a floor and a
/// sphere resting on it near their contact, so shadow rays started beyond
/// the sphere and bright rings lit the contact shadows.
#[inline]
pub(crate) fn offset_origin(p: Vec3A, n: Vec3A, d: f32, w: Vec3A) -> Vec3A {
    offset_along_normal(p, n, d, w)
}

/// Error bound along `n` of a point `p` sampled on a light, which a
/// [`LightSample`] does not carry: a few roundings of `|p|` (γ(7), as for a
/// point rebuilt from a triangle's or a quad's parametrisation), at least
/// `4 × 2.5e-5`, the march threshold of scene SDFs (`MIN_EPS`), because an
/// SDF emitter's sample lies on the level set its march stopped at.
#[inline]
pub(crate) fn light_point_error(p: Vec3A, n: Vec3A) -> f32 {
    error_along(n, Vec3A::splat(1e-4) + gamma_offset(7) * p.abs())
}

/// The shadow ray from `hit` to the point `ls` sampled on a light, and its
/// extent: the segment between the two points, each moved off its own
/// surface by its own error bound (pbrt-v4's `SpawnRayTo` between two
/// interactions).
///
/// Direction and extent are measured from the moved origin to the moved
/// target, so the segment lies on the open side of both surfaces' planes and
/// cannot touch either, at any angle and any distance from the origin. (Before
/// this, the direction and extent were those of the unmoved points: at
/// grazing angles the ray then crossed the light's own plane before its
/// extent ended, and a floor beyond about 60° from a quad light went black.)
/// Delta lights have no surface (`ls.n` is zero); their point is the target.
/// The extent stops a relative 1e-4 short of the target (pbrt's
/// `ShadowEpsilon`). A sample at infinite distance (the environment) gives an
/// unbounded ray from the moved origin.
#[inline]
pub fn shadow_ray(hit: &Hit, ls: &LightSample) -> (Ray, f32) {
    let o = offset_origin(hit.p, hit.ng, hit.p_error, ls.wi);
    if ls.dist == f32::INFINITY {
        return (Ray::new(o, ls.wi), f32::INFINITY);
    }
    let target = if ls.n == Vec3A::ZERO {
        ls.p
    } else {
        offset_origin(ls.p, ls.n, light_point_error(ls.p, ls.n), o - ls.p)
    };
    let d = target - o;
    let len = d.length();
    if !(len > 0.0 && len.is_finite()) {
        // The two ends coincide: nothing can lie between them.
        return (Ray::new(o, ls.wi), 0.0);
    }
    (Ray::new(o, d / len), len * (1.0 - 1e-4))
}
