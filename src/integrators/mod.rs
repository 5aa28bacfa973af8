//! Light-transport estimators. Each returns the radiance (W/(m²·sr)) arriving
//! at the camera along one ray.

pub mod caustic;
pub mod direct;
pub mod path;
pub mod sky_visibility;
pub mod whitted;

pub use direct::Direct;
pub use path::Path;
pub use whitted::Whitted;

use crate::geometry::{Hit, NO_LIGHT};
use crate::lights::LightSample;
use crate::math::{Ray, Rgb, ray_epsilon};
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
    Ray::new(offset_origin(hit.p, hit.ng, w), w)
}

/// `p` moved off its surface (normal `n`) by [`ray_epsilon`] to the side
/// `w` points into. The offset is along the normal, so the moved point is off
/// the surface's plane by the full margin whatever the angle of `w`.
#[inline]
pub(crate) fn offset_origin(p: Vec3A, n: Vec3A, w: Vec3A) -> Vec3A {
    let off = n * ray_epsilon(p);
    if n.dot(w) >= 0.0 { p + off } else { p - off }
}

/// The shadow ray from `hit` to the point `ls` sampled on a light, and its
/// extent: the segment between the two points, each moved off its own
/// surface (pbrt-v4's `SpawnRayTo` between two interactions).
///
/// Direction and extent are measured from the moved origin to the moved
/// target, so the segment lies on the open side of both surfaces' planes and
/// cannot touch either, at any angle and any distance from the origin. (Before
/// this, the direction and extent were those of the unmoved points: at
/// grazing angles the ray then crossed the light's own plane before its
/// extent ended, and a floor beyond about 60° from a quad light went black.)
/// Delta lights have no surface (`ls.n` is zero); their point is the target.
/// The extent stops a relative 1e-4 short of the target. A sample at infinite
/// distance (the environment) gives an unbounded ray from the moved origin.
#[inline]
pub fn shadow_ray(hit: &Hit, ls: &LightSample) -> (Ray, f32) {
    let o = offset_origin(hit.p, hit.ng, ls.wi);
    if ls.dist == f32::INFINITY {
        return (Ray::new(o, ls.wi), f32::INFINITY);
    }
    let target = if ls.n == Vec3A::ZERO {
        ls.p
    } else {
        offset_origin(ls.p, ls.n, o - ls.p)
    };
    let d = target - o;
    let len = d.length();
    if !(len > 0.0 && len.is_finite()) {
        // The two ends coincide: nothing can lie between them.
        return (Ray::new(o, ls.wi), 0.0);
    }
    (Ray::new(o, d / len), len * (1.0 - 1e-4))
}
