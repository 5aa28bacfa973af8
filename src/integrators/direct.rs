//! Direct lighting: emission seen by the camera plus one bounce of light from
//! every light. Each light is sampled with shadow rays, and as many BSDF
//! samples look for the same lights; the two are weighed by the power
//! heuristic (Veach's MIS, as pbrt-v4's and Mitsuba 3's `direct`), so a
//! glossy lobe facing a large light or a bright sky is found by the BSDF
//! and a small light by light sampling. Point and spot lights (deltas) are
//! found by light sampling alone.

use super::interior::Interior;
use super::{Counters, emitted, escaped, shadow_ray, spawn};
use crate::geometry::{Hit, NO_LIGHT};
use crate::materials::{Bsdf, Bxdf};
use crate::math::sampling::power_heuristic;
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
        let bsdf = scene.materials[hit.material as usize]
            .bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
        let frame = Frame::from_normal(hit.ns);
        // A camera inside coloured glass (`super::interior`).
        let kept = Interior::OUTSIDE.to_hit(scene, &hit, ray.d);
        let l = kept
            * (emitted(scene, &hit, ray.d)
                + all_lights(
                    scene,
                    &hit,
                    Interior::OUTSIDE,
                    &bsdf,
                    &frame,
                    frame.to_local(-ray.d),
                    self.light_samples,
                    sampler,
                    counters,
                ));
        debug_assert!(l.is_finite(), "non-finite radiance {l}");
        l
    }
}

/// Reflected radiance from every light (N shadow rays per area light and for
/// the environment, one per point or spot light, and N BSDF samples that
/// count where they reach an area light or the sky, weighed by MIS), the
/// shading step shared by `Direct` and `Whitted`. `inside`: the absorbing
/// solid the ray that reached `hit` was in (`super::interior`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn all_lights(
    scene: &Scene,
    hit: &Hit,
    inside: Interior,
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
    let side = bsdf.light_side(hit.ns, wo.z);
    let mut any_area = false;
    for light in &scene.lights {
        let delta = light.is_delta();
        any_area |= !delta;
        let n = if delta { 1 } else { light_samples };
        let mut sum = Rgb::ZERO;
        for _ in 0..n {
            let (u, draw) = sampler.next_vec2_draw();
            let Some(ls) = light.sample(hit.p, side, u, draw, &scene.geometry) else {
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
                let w = if ls.delta {
                    1.0
                } else {
                    power_heuristic(ls.pdf, bsdf.pdf(wo, wi))
                };
                let kept = inside.beyond(scene, hit, ls.wi).over(scene, ls.dist);
                sum += f * ls.li * kept * (wi.z.abs() * w / ls.pdf);
            }
        }
        l += sum / n as f32;
    }
    if any_area && light_samples > 0 {
        let mut sum = Rgb::ZERO;
        for _ in 0..light_samples {
            let Some(bs) = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2()) else {
                continue;
            };
            if bs.delta {
                continue;
            }
            let ray = spawn(hit, frame.to_world(bs.wi));
            counters.rays += 1;
            let beyond = inside.beyond(scene, hit, ray.d);
            let (le, light_pdf) = match scene.intersect(&ray, f32::INFINITY) {
                Some(h) if h.light != NO_LIGHT => {
                    let light = &scene.lights[h.light as usize];
                    (
                        emitted(scene, &h, ray.d) * beyond.to_hit(scene, &h, ray.d),
                        light.pdf(hit.p, ray.d, &h),
                    )
                }
                Some(_) => continue,
                None => match scene.environment() {
                    Some((_, env)) => {
                        let (le, pdf) = env.le_and_pdf(ray.d, side);
                        (le * beyond.over(scene, f32::INFINITY), pdf)
                    }
                    None => continue,
                },
            };
            if le != Rgb::ZERO {
                sum += bs.weight * le * power_heuristic(bs.pdf, light_pdf);
            }
        }
        l += sum / light_samples as f32;
    }
    l
}
