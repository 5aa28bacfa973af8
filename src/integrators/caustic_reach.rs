//! Which lights the caustic light tracer leaves to the path tracer: those
//! whose light paths almost never reach the film.
//!
//! The light tracer aims at the bounding spheres of the perfect mirrors and
//! smooth glass, and the sky's beams cross their disks
//! (`lights/caustic.rs`). When a specular object is far larger than what
//! the camera sees — a glass dome or sphere around the whole scene, a vast
//! mirror — nearly every light path lands off the film, on nothing, or
//! where the eye cannot see it. The path tracer drops the caustic paths the
//! light tracer takes, so those paths then went almost unsampled: a camera
//! inside a glass sphere of radius 10,000 under the sky map saw its floor
//! at 2% of its brightness at 256 spp (0.03 against 1.37 with the path
//! tracer alone, which finds the sky through that glass easily).
//!
//! So before rendering, each light the tracer emits from is tried alone:
//! [`PILOT_PATHS`] light paths from it (fewer when there are many lights:
//! [`PILOT_BUDGET`] in all, at least 16 a light; a scene with more than
//! 1,024 such lights is not tried), and the share that splats onto the
//! whole frame (lands in the picture, in sight of the eye). A light whose
//! share is under [`MIN_REACH`] is left to the path tracer
//! ([`CausticEmitters::without`]): its caustics are then found as with
//! `caustics: PathOnly`, and the other lights keep theirs. Point, spot and
//! directional lights are kept whatever their share: nothing else finds
//! their caustics. Only the noise depends on the choice, never the expected
//! image.
//!
//! Deterministic: a fixed seed, one thread, the whole frame whatever piece
//! or pass is rendered (the scene is judged once, at load).

use super::Counters;
use super::caustic::{splat, trace_from};
use crate::camera::{Camera, Projection};
use crate::lights::CausticEmitters;
use crate::math::SampleRng;
use crate::sampler::Sampler;
use crate::scene::Scene;

/// Light paths tried per light.
pub const PILOT_PATHS: u32 = 256;

/// Light paths tried in all, at most (a few milliseconds).
pub const PILOT_BUDGET: u32 = 16_384;

/// The least share of a light's paths that must reach the film for the
/// light tracer to keep it (see the module docs).
pub const MIN_REACH: f32 = 1.0 / 64.0;

/// Drops from `scene`'s caustic emitters the lights whose light paths
/// (specular chains up to `max_chain`) reach the `w` × `h` film of `camera`
/// less often than [`MIN_REACH`] (module docs). Nothing changes for a
/// camera the light tracer does not splat onto (not a pinhole).
pub fn keep_lights_that_reach(scene: &mut Scene, camera: &Camera, (w, h): (u32, u32), max_chain: u32) {
    let pinhole = camera.projection == Projection::Perspective && camera.aperture_radius <= 0.0;
    let Some(em) = scene.caustics.as_ref().filter(|_| pinhole) else {
        return;
    };
    if em.emitters().len() > (PILOT_BUDGET / 16) as usize {
        return;
    }
    let drop: Vec<u32> = reach(scene, em, camera, (w, h), max_chain)
        .iter()
        .filter(|&&(li, share)| share < MIN_REACH && !scene.lights[li as usize].is_delta())
        .map(|&(li, _)| li)
        .collect();
    if !drop.is_empty() {
        scene.caustics = em.without(&drop);
    }
}

/// Each emitter of `em` and the share of its pilot paths (module docs),
/// traced from it alone, that splat onto the `w` × `h` film of `camera`.
pub fn reach(
    scene: &Scene,
    em: &CausticEmitters,
    camera: &Camera,
    (w, h): (u32, u32),
    max_chain: u32,
) -> Vec<(u32, f32)> {
    let n = em.emitters().len().max(1) as u32;
    let paths = (PILOT_BUDGET / n).clamp(16, PILOT_PATHS);
    let mut counters = Counters::default();
    em.emitters()
        .iter()
        .map(|&li| {
            // One stream per light: a light's share does not depend on the others.
            let mut sampler = Sampler::independent(SampleRng::new(0x7265_6163_6821, u64::from(li)));
            let landed = (0..paths)
                .filter(|_| {
                    trace_from(scene, em, li, 1.0, max_chain, &mut sampler, &mut counters)
                        .and_then(|y| splat(scene, camera, w, h, &y, &mut counters))
                        .is_some()
                })
                .count();
            (li, landed as f32 / paths as f32)
        })
        .collect()
}
