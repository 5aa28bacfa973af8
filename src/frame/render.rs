//! The frame wing's entry point: [`render`] runs a [`Plan`] (the tile loop,
//! then the caustic light-tracing pass when the plan has one) and returns
//! the plan's kind of pixels: means for a whole frame, exact sums for a
//! piece or a watch pass.

use super::options::RenderOptions;
use super::plan::Plan;
use super::stats::{RenderStats, TileDone};
use super::tiles::Work;
use crate::imageio::{Image, SampleSums};
use crate::scene::Scene;
use crate::view::View;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// What a render produced: what its plan asked for.
#[derive(Clone, Debug, PartialEq)]
pub enum Pixels {
    /// A whole frame: each pixel's mean, light-traced caustics added.
    Means(Image),
    /// A piece or a watch pass: each pixel's exact sum over the plan's
    /// samples, to be added to other pieces' or passes' sums.
    Sums(SampleSums),
}

/// Renders `plan`. Gives up early (`cancelled: true`) once `cancel` is set;
/// tiles already started finish first. `on_tile` is called as each tile
/// finishes, from worker threads. A whole frame's tile sums become means as
/// each tile finishes, so its exact sums are never held at once.
pub fn render(
    scene: &Scene,
    view: &View,
    plan: &Plan,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    on_tile: &(dyn Fn(&TileDone) + Sync),
) -> (Pixels, RenderStats) {
    if plan.keeps_sums() {
        let (sums, stats) = Work::sums(scene, view, plan, opts, cancel, on_tile);
        return (Pixels::Sums(sums), stats);
    }
    let (mut pixels, mut stats) = Work::means(scene, view, plan, opts, cancel, on_tile);
    if let Some(trace) = plan.light_trace
        && !stats.cancelled
    {
        let start = Instant::now();
        let mut run = || super::caustics::light_trace(scene, view, trace, cancel, &mut pixels);
        let traced = match rayon::ThreadPoolBuilder::new()
            .num_threads(opts.threads.unwrap_or(0))
            .build()
        {
            Ok(pool) => pool.install(run),
            Err(_) => run(),
        };
        match traced {
            Some(counters) => stats.rays += counters.rays,
            None => stats.cancelled = true,
        }
        stats.elapsed += start.elapsed();
    }
    let (width, height) = (plan.rect.width(), plan.rect.height());
    (
        Pixels::Means(Image {
            width,
            height,
            pixels,
        }),
        stats,
    )
}

/// The whole frame as the scene describes it ([`Plan::whole`]), not
/// cancellable: what tests, `check` and benchmarks call.
pub fn render_whole(scene: &Scene, view: &View, opts: &RenderOptions) -> (Image, RenderStats) {
    let plan = Plan::whole(scene, view);
    match render(scene, view, &plan, opts, &AtomicBool::new(false), &|_| {}) {
        (Pixels::Means(image), stats) => (image, stats),
        // A whole frame's plan keeps no sums; were it to, its mean is the image.
        (Pixels::Sums(sums), stats) => (sums.mean(plan.samples.1), stats),
    }
}
