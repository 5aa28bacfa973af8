//! How much of the sky the scene's surfaces actually see, measured once
//! before rendering, so light selection does not send shadow rays to a sky
//! that walls hide.
//!
//! The light tree weighs the environment by its *unoccluded* irradiance at
//! each shading point (`lights/irradiance.rs`). Under an open sky that is
//! close; in a room lit through a window it is many times too high, and the
//! sky took most of the shadow rays while the window let in a few percent
//! of the light (1.06× uniform selection's noise in `tests/open_scenes.rs`'
//! room). The visibility `V` here is a ratio estimate over the points the
//! camera sees first (a 32 × 32 grid of pixel centres): the sky's
//! irradiance on them with shadow rays over the same estimate without,
//!
//!   V = Σ_p Σ_k w_k · unoccluded(p, d_k) / Σ_p Σ_k w_k,   w_k = L(d_k) |cos θ_k| / pdf(d_k),
//!
//! with four directions `d_k` per point drawn as next-event estimation
//! draws them. The tree then weighs the sky by `V · π E(n)`. A global
//! factor cannot follow a scene that is half indoors, half out: the
//! mixture's uniform share (`lights/tree.rs`) keeps every light sampled
//! wherever the estimate is wrong.
//!
//! Deterministic: a fixed seed, the full frame whatever piece or tile is
//! rendered, one thread: the same scene gives the same `V`, and the same
//! image whatever the scheduling. Costs 4,096 shadow rays and 1,024 camera
//! rays.

use super::shadow_ray;
use crate::camera::Camera;
use crate::materials::Bxdf;
use crate::math::{Pcg32, luminance};
use crate::sampler::Draw;
use crate::scene::Scene;
use glam::Vec2;

/// Grid of probe pixels per side, and shadow rays per probe.
const GRID: u32 = 32;
const RAYS: u32 = 4;
/// The smallest visibility reported: a sky seen through a keyhole still
/// keeps a little weight (beside the mixture's uniform share).
const MIN_VISIBILITY: f32 = 1.0 / 256.0;

/// The fraction of the sky's irradiance that reaches the surfaces `camera`
/// sees (image aspect `aspect`), in [1/256, 1]; 1 without an environment,
/// or when the camera sees no surface.
pub fn sky_visibility(scene: &Scene, camera: &Camera, aspect: f32) -> f32 {
    let Some((_, env)) = scene.environment() else {
        return 1.0;
    };
    let mut rng = Pcg32::new(0x5c1e_5ee5, 37);
    let (mut seen, mut all) = (0.0f64, 0.0f64);
    for j in 0..GRID {
        for i in 0..GRID {
            let film = Vec2::new((i as f32 + 0.5) / GRID as f32, (j as f32 + 0.5) / GRID as f32);
            let ray = camera.ray(film, aspect, Vec2::splat(0.5));
            let Some(hit) = scene.intersect(&ray, f32::INFINITY) else {
                continue;
            };
            let Some(material) = scene.materials.get(hit.material as usize) else {
                continue;
            };
            let bsdf = material.bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
            if bsdf.is_delta() {
                continue;
            }
            let wo_z = (-ray.d).dot(hit.ns);
            let side = bsdf.light_side(hit.ns, wo_z);
            for _ in 0..RAYS {
                let Some(ls) = env.sample(hit.p, side, rng.next_vec2(), Draw::Independent) else {
                    continue;
                };
                let cos = ls.wi.dot(hit.ns).abs();
                let w = luminance(ls.li) * cos / ls.pdf;
                if !(w.is_finite() && w > 0.0) || (side != glam::Vec3A::ZERO && ls.wi.dot(side) <= 0.0) {
                    continue;
                }
                all += f64::from(w);
                let (shadow, extent) = shadow_ray(&hit, &ls);
                if !scene.occluded(&shadow, extent) {
                    seen += f64::from(w);
                }
            }
        }
    }
    if all > 0.0 {
        ((seen / all) as f32).clamp(MIN_VISIBILITY, 1.0)
    } else {
        1.0
    }
}
