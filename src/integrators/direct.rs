//! Direct lighting: emission seen by the camera plus one bounce of light from
//! every light, estimated by light sampling with shadow rays.

use super::{Counters, emitted, escaped, shadow_ray};
use crate::geometry::Hit;
use crate::materials::{Bsdf, Bxdf};
use crate::math::{Frame, Ray, Rgb};
use crate::sampler::Sampler;
use crate::scene::Scene;

/// Direct-lighting estimator: emission seen by the camera plus every light's
/// contribution at the first hit, by light sampling only.
#[derive(Clone, Copy, Debug)]
pub struct Direct {
    /// Shadow rays per area light (and for the environment) per camera sample
    /// (the seed report's `_nbLightSamples`); point and spot lights always take
    /// one.
    pub light_samples: u32,
}

impl Direct {
    /// Radiance in W/(m²·sr) arriving along camera `ray`: emission at the first hit
    /// plus the light it reflects directly from every light.
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut Sampler, counters: &mut Counters) -> Rgb {
        counters.rays += 1;
        let Some(hit) = scene.intersect(ray, f32::INFINITY) else {
            return escaped(scene, ray.d, true);
        };
        let bsdf = scene.materials[hit.material as usize].bsdf(hit.uv, &scene.textures);
        let frame = Frame::from_normal(hit.ns);
        let l = emitted(scene, &hit, ray.d)
            + all_lights(
                scene,
                &hit,
                &bsdf,
                &frame,
                frame.to_local(-ray.d),
                self.light_samples,
                sampler,
                counters,
            );
        debug_assert!(l.is_finite(), "non-finite radiance {l}");
        l
    }
}

/// Reflected radiance from every light (N shadow rays per area light and for
/// the environment, one per point or spot light), the shading step shared by
/// `Direct` and `Whitted`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn all_lights(
    scene: &Scene,
    hit: &Hit,
    bsdf: &Bsdf,
    frame: &Frame,
    wo: glam::Vec3A,
    light_samples: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Rgb {
    let mut l = Rgb::ZERO;
    if bsdf.is_delta() {
        return l;
    }
    for light in &scene.lights {
        let n = if light.is_delta() { 1 } else { light_samples };
        let mut sum = Rgb::ZERO;
        for _ in 0..n {
            let Some(ls) = light.sample(hit.p, sampler.next_vec2(), &scene.geometry) else {
                continue;
            };
            let wi = frame.to_local(ls.wi);
            let f = bsdf.eval(wo, wi);
            if f == Rgb::ZERO {
                continue;
            }
            let (shadow, extent) = shadow_ray(hit, &ls);
            counters.rays += 1;
            if !scene.occluded(&shadow, extent) {
                sum += f * ls.li * wi.z.abs() / ls.pdf;
            }
        }
        l += sum / n as f32;
    }
    l
}
