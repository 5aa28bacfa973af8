//! Light-transport estimators. Each returns the radiance (W/(m²·sr)) arriving
//! at the camera along one ray.

pub mod direct;
pub mod path;
pub mod whitted;

pub use direct::Direct;
pub use path::Path;
pub use whitted::Whitted;

use crate::geometry::{Hit, NO_LIGHT};
use crate::lights::Light;
use crate::math::{Ray, Rgb, ray_epsilon};
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::Vec3A;

#[derive(Clone, Copy, Debug)]
pub enum Integrator {
    Direct(Direct),
    Whitted(Whitted),
    Path(Path),
}

/// Per-thread counters, summed for the render summary.
#[derive(Clone, Copy, Debug, Default)]
pub struct Counters {
    pub rays: u64,
}

impl Integrator {
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
    match &scene.lights[hit.light as usize] {
        Light::Quad(q) => q.emitted(-ray_dir),
        _ => Rgb::ZERO,
    }
}

/// A ray leaving `hit` toward `w`, nudged off the surface along the
/// geometric normal on `w`'s side so it cannot re-hit its own surface.
#[inline]
pub(crate) fn spawn(hit: &Hit, w: Vec3A) -> Ray {
    let off = hit.ng * ray_epsilon(hit.p);
    let o = if hit.ng.dot(w) >= 0.0 {
        hit.p + off
    } else {
        hit.p - off
    };
    Ray::new(o, w)
}

/// Shadow-ray extent toward a point `dist` away from `hit.p`, stopping just
/// short of the light's own surface.
#[inline]
pub(crate) fn shadow_extent(hit: &Hit, shadow: &Ray, dist: f32) -> f32 {
    (dist - (shadow.o - hit.p).length()) * (1.0 - 1e-4)
}
