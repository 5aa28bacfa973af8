//! The caustic light-tracing pass of a whole frame ([`crate::integrators::caustic`]):
//! light paths through perfect mirrors and smooth glass splatted onto a
//! pinhole camera's film, added to the tile loop's image. The plan decides
//! whether it runs and how many paths it traces ([`super::plan::LightTrace`]).

use super::plan::LightTrace;
use crate::integrators::{Counters, caustic};
use crate::math::rng::mix64;
use crate::math::{ExactSum, Rgb, SampleRng};
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::view::View;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};

/// Light paths a chunk of [`light_trace`] traces: its unit of parallel work
/// and of random streams (chunk `k` draws from stream `k` of `SampleRng`), so the
/// image does not depend on the thread count.
const CHUNK: u64 = 4096;

/// Chunks traced between merges into the image: bounds the splats held at
/// once (at most `CHUNK` × [`caustic::MAX_SEGMENTS`] each).
const BATCH: u64 = 64;

/// The caustic light tracer ([`caustic`]): traces `paths` light paths of a
/// pinhole `view`'s scene and adds to each of `pixels` (row-major, the whole
/// film) the sum of its splats over `paths`; `None`, with `pixels`
/// untouched, when cancelled. Splats are summed exactly ([`ExactSum`]), so
/// the image is the same whatever the thread count. Memory: 48 bytes a
/// pixel for the sums beside the film's 16, below a render's peak
/// (`crate::memory`), and at most `BATCH · CHUNK` light paths' splats.
pub(super) fn light_trace(
    scene: &Scene,
    view: &View,
    trace: LightTrace,
    cancel: &AtomicBool,
    pixels: &mut [Rgb],
) -> Option<Counters> {
    let LightTrace {
        paths,
        max_chain,
        max_depth,
    } = trace;
    let em = scene.caustics.as_ref()?;
    let (w, h) = (view.film.width, view.film.height);
    let mut sums = vec![ExactSum::ZERO; w as usize * h as usize];
    let mut counters = Counters::default();
    let chunks = paths.div_ceil(CHUNK);
    let seed = mix64(view.film.seed ^ 0x6c69_6768_745f_7472);
    let mut k0 = 0;
    while k0 < chunks {
        if cancel.load(Ordering::Relaxed) {
            return None;
        }
        let k1 = (k0 + BATCH).min(chunks);
        let batch: Vec<(Vec<(u32, Rgb)>, Counters)> = (k0..k1)
            .into_par_iter()
            .map(|k| {
                let mut sampler = Sampler::independent(SampleRng::new(seed, k));
                let mut c = Counters::default();
                let n = CHUNK.min(paths - k * CHUNK);
                let mut splats = Vec::new();
                for _ in 0..n {
                    let Some(mut v) = caustic::trace(scene, em, max_chain, &mut sampler, &mut c) else {
                        continue;
                    };
                    // The caustic's own surface, then (from a point, spot
                    // or directional light) every later one it lights.
                    loop {
                        splats.extend(caustic::splat(scene, &view.camera, w, h, &v, &mut c));
                        match caustic::bounce(scene, &v, max_depth, &mut sampler, &mut c) {
                            Some(next) => v = next,
                            None => break,
                        }
                    }
                }
                (splats, c)
            })
            .collect();
        for (splats, c) in batch {
            counters.rays += c.rays;
            for (i, v) in splats {
                sums[i as usize].add_sample(v);
            }
        }
        k0 = k1;
    }
    let n = u32::try_from(paths).ok()?;
    for (p, s) in pixels.iter_mut().zip(&sums) {
        *p += s.mean(n);
    }
    Some(counters)
}
