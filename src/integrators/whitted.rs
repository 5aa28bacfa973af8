//! Whitted-style recursive ray tracing, the seed report's integrator: direct
//! lighting at diffuse and glossy hits, and perfect reflection and
//! refraction at mirrors and glass, up to `max_depth` specular bounces.
//!
//! At glass the choice between the reflected and the refracted ray is made
//! at random with probability F (as the BSDF samples it) instead of tracing
//! both: the same expected image, a path instead of a tree.

use super::direct::all_lights;
use super::interior::Interior;
use super::{Counters, emitted, escaped, spawn};
use crate::materials::Bxdf;
use crate::math::{Frame, Ray, Rgb};
use crate::sampler::Sampler;
use crate::scene::Scene;

/// Whitted-style estimator: direct lighting at diffuse and glossy hits, perfect
/// reflection and refraction followed through mirrors and glass.
#[derive(Clone, Copy, Debug)]
pub struct Whitted {
    /// Specular bounces followed after the camera ray.
    pub max_depth: u32,
    /// Shadow rays per area light at each diffuse or glossy hit; point and spot
    /// lights take one.
    pub light_samples: u32,
}

impl Whitted {
    /// Radiance in W/(m²·sr) arriving along camera `ray`, following one specular
    /// chain of at most `max_depth` bounces.
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut Sampler, counters: &mut Counters) -> Rgb {
        let mut l = Rgb::ZERO;
        let mut beta = Rgb::ONE;
        let mut ray = *ray;
        // The absorbing solid the ray is in (coloured glass).
        let mut inside = Interior::OUTSIDE;
        for depth in 0..=self.max_depth {
            counters.rays += 1;
            let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
                // Past a mirror or glass the environment counts fully: light
                // sampling cannot reach it through a delta bounce.
                l += beta * inside.over(scene, f32::INFINITY) * escaped(scene, ray.d, depth == 0);
                break;
            };
            beta *= inside.to_hit(scene, &hit, ray.d);
            let bsdf = scene.materials[hit.material as usize]
                .bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
            let frame = Frame::from_normal(hit.ns);
            let wo = frame.to_local(-ray.d);
            l += beta * emitted(scene, &hit, ray.d);
            if !bsdf.is_delta() {
                l += beta
                    * all_lights(
                        scene,
                        &hit,
                        inside,
                        &bsdf,
                        &frame,
                        wo,
                        self.light_samples,
                        sampler,
                        counters,
                    );
                break;
            }
            if depth == self.max_depth {
                break;
            }
            let Some(bs) = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2()) else {
                break;
            };
            beta *= bs.weight;
            ray = spawn(&hit, frame.to_world(bs.wi));
            inside = inside.beyond(scene, &hit, ray.d);
        }
        l
    }
}
