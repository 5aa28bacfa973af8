//! Unidirectional path tracing with next-event estimation and multiple
//! importance sampling (Veach 1997, ch. 9, power heuristic), as Mitsuba 3's
//! `path` integrator does, so renders converge to its references.
//!
//! Depth follows Mitsuba: `max_depth` counts path **segments** from the
//! camera — 1 shows emitters only, 2 is direct lighting, 3 adds one indirect
//! bounce; −1 is unlimited (Russian roulette ends paths). Russian roulette
//! starts once the path has `rr_depth` segments, continuing with probability
//! min(0.95, max(β)·η²) (η² undoes the radiance scaling of refraction so
//! roulette acts on flux).
//!
//! Emitters reached by a BSDF sample after a non-delta vertex are weighted
//! against light sampling; after a delta vertex (or from the camera) they
//! count fully, since light sampling cannot produce those paths. Each path
//! therefore counts every emitter exactly once. The environment is an
//! emitter like the others: a BSDF sample that escapes the scene is weighted
//! against the environment's own density (its luminance distribution), and
//! next-event estimation picks it by power like any light. A camera ray that
//! escapes sees the environment, or its background when it is not
//! `visible`.

use super::caustic::max_chain;
use super::{Counters, emitted, escaped, shadow_ray, spawn};
use crate::geometry::NO_LIGHT;
use crate::lights::LightPicker;
use crate::materials::Bxdf;
use crate::math::sampling::power_heuristic;
use crate::math::{Frame, Ray, Rgb};
use crate::sampler::Sampler;
use crate::scene::Scene;

/// Path-tracing estimator with next-event estimation and MIS; the module docs pin
/// down its depth convention.
#[derive(Clone, Copy, Debug)]
pub struct Path {
    /// Segments from the camera; `u32::MAX` when unlimited.
    pub max_depth: u32,
    /// Segments a path has before Russian roulette may end it.
    pub rr_depth: u32,
    /// Whether caustics seen directly are light-traced ([`super::caustic`])
    /// when the render can: the scene's wish.
    pub light_trace_caustics: bool,
    /// Set by the renderer for a render whose light-tracing pass runs: the
    /// paths that pass counts are dropped here (see [`super::caustic`]).
    pub split_caustics: bool,
}

impl Path {
    /// Radiance in W/(m²·sr) arriving along camera `ray`, one path's estimate;
    /// unbiased for unlimited depth.
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut Sampler, counters: &mut Counters) -> Rgb {
        let picker: &LightPicker = &scene.light_picker;
        let mut l = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        let mut eta_scale = 1.0f32;
        let mut ray = *ray;
        // Density of the last BSDF sample, and whether it was a delta lobe
        // (the camera ray counts as one: emitters it sees count fully).
        let mut prev_pdf = 0.0f32;
        let mut prev_delta = true;
        // The vertex the ray left from: light densities for MIS are seen from it.
        let mut prev_p = ray.o;
        // Its shading normal: a light tree's probabilities depend on both.
        let mut prev_n = glam::Vec3A::ZERO;
        let mut segments = 0u32;
        // The split with the caustic light tracer (`super::caustic`): whether
        // the path since its last non-delta vertex is one the tracer counts
        // (that vertex seen straight from the camera and left by a
        // non-delta sample), and the perfect-specular vertices since.
        let split = self.split_caustics && scene.caustics.is_some();
        let max_chain = max_chain(self.max_depth);
        let mut traced = false;
        let mut chain = 0u32;
        loop {
            counters.rays += 1;
            let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
                // The environment, reached by the previous BSDF sample.
                // After a non-delta vertex (never the camera ray) the radiance
                // and the MIS density share one mapping of the direction.
                match scene.environment() {
                    Some((i, env)) if !prev_delta => {
                        let (le, env_pdf) = env.le_and_pdf(ray.d);
                        if le != Rgb::ZERO {
                            let w =
                                power_heuristic(prev_pdf, picker.pmf(prev_p, prev_n, i as usize) * env_pdf);
                            l += beta * le * w;
                        }
                    }
                    _ => {
                        let le = escaped(scene, ray.d, segments == 0);
                        if le != Rgb::ZERO {
                            l += beta * le;
                        }
                    }
                }
                break;
            };
            segments += 1;

            // Emission reached by the previous BSDF sample.
            if hit.light != NO_LIGHT {
                let le = emitted(scene, &hit, ray.d);
                if le != Rgb::ZERO {
                    let w = if prev_delta {
                        let theirs = traced
                            && (1..=max_chain).contains(&chain)
                            && scene.caustics.as_ref().is_some_and(|c| c.covers(hit.light));
                        if theirs { 0.0 } else { 1.0 }
                    } else {
                        let light = &scene.lights[hit.light as usize];
                        let light_pdf =
                            picker.pmf(prev_p, prev_n, hit.light as usize) * light.pdf(prev_p, ray.d, &hit);
                        power_heuristic(prev_pdf, light_pdf)
                    };
                    l += beta * le * w;
                }
            }
            if segments >= self.max_depth {
                break;
            }

            let bsdf = scene.materials[hit.material as usize].bsdf(hit.uv, &scene.textures);
            let frame = Frame::from_normal(hit.ns);
            let wo = frame.to_local(-ray.d);

            // The numbers are drawn in a fixed order (light pick, light
            // point, BSDF lobe and direction), but the BSDF is sampled
            // before the shadow ray is traced: its direction does not depend
            // on the light, so its latency-bound chain (a division, a sine
            // polynomial, a square root) runs while the shadow ray
            // traverses instead of after it. Same numbers, same image.
            let delta = bsdf.is_delta();
            let (u_pick, u_light) = if delta {
                (0.0, glam::Vec2::ZERO)
            } else {
                (sampler.next_f32(), sampler.next_vec2())
            };
            let bs = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2());

            // Next-event estimation: one light, picked as the scene says (by
            // the light tree unless told otherwise).
            if !delta && let Some((li, pmf)) = picker.pick(hit.p, hit.ns, u_pick) {
                let light = &scene.lights[li];
                if let Some(ls) = light.sample(hit.p, u_light, &scene.geometry) {
                    let wi = frame.to_local(ls.wi);
                    let f = bsdf.eval(wo, wi) * wi.z.abs();
                    if f != Rgb::ZERO {
                        let (shadow, extent) = shadow_ray(&hit, &ls);
                        counters.rays += 1;
                        if !scene.occluded(&shadow, extent) {
                            let light_pdf = pmf * ls.pdf;
                            let w = if ls.delta {
                                1.0
                            } else {
                                power_heuristic(light_pdf, bsdf.pdf(wo, wi))
                            };
                            l += beta * f * ls.li * (w / light_pdf);
                        }
                    }
                }
            }

            if split {
                if delta {
                    chain += 1;
                } else {
                    chain = 0;
                    traced = segments == 1 && bs.is_some_and(|b| !b.delta);
                }
            }

            // Continue the path along the BSDF sample.
            let Some(bs) = bs else {
                break;
            };
            beta *= bs.weight;
            if beta == Rgb::ZERO {
                break;
            }
            eta_scale *= bs.eta * bs.eta;
            prev_pdf = bs.pdf;
            prev_delta = bs.delta;
            prev_p = hit.p;
            prev_n = hit.ns;
            ray = spawn(&hit, frame.to_world(bs.wi));

            if segments >= self.rr_depth {
                let q = (beta.max_element() * eta_scale).min(0.95);
                if sampler.next_f32() >= q {
                    break;
                }
                beta /= q;
            }
        }
        debug_assert!(l.is_finite(), "non-finite radiance {l}");
        l
    }
}
