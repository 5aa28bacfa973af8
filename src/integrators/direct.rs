//! Direct lighting: emission seen by the camera plus one bounce of light from
//! every light, estimated by light sampling with shadow rays.

use super::{Counters, emitted, spawn};
use crate::materials::Bxdf;
use crate::math::{Frame, Pcg32, Ray, Rgb};
use crate::scene::Scene;

#[derive(Clone, Copy, Debug)]
pub struct Direct {
    /// Shadow rays per area light per camera sample (the seed report's
    /// `_nbLightSamples`); point lights always take one.
    pub light_samples: u32,
}

impl Direct {
    pub fn li(&self, scene: &Scene, ray: &Ray, rng: &mut Pcg32, counters: &mut Counters) -> Rgb {
        counters.rays += 1;
        let Some(hit) = scene.intersect(ray, f32::INFINITY) else {
            return Rgb::ZERO;
        };
        let mut l = emitted(scene, &hit, ray.d);
        let bsdf = scene.materials[hit.material as usize].bsdf(hit.uv, &scene.textures);
        let frame = Frame::from_normal(hit.ns);
        let wo = frame.to_local(-ray.d);
        for light in &scene.lights {
            let n = if matches!(light, crate::lights::Light::Point(_)) {
                1
            } else {
                self.light_samples
            };
            let mut sum = Rgb::ZERO;
            for _ in 0..n {
                let Some(ls) = light.sample(hit.p, rng.next_vec2()) else {
                    continue;
                };
                let wi = frame.to_local(ls.wi);
                let f = bsdf.eval(wo, wi);
                if f == Rgb::ZERO {
                    continue;
                }
                let shadow = spawn(&hit, ls.wi);
                counters.rays += 1;
                let t_max = (ls.dist - (shadow.o - hit.p).length()) * (1.0 - 1e-4);
                if !scene.occluded(&shadow, t_max) {
                    sum += f * ls.li * wi.z.abs() / ls.pdf;
                }
            }
            l += sum / n as f32;
        }
        debug_assert!(l.is_finite(), "non-finite radiance {l}");
        l
    }
}
