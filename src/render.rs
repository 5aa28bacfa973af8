//! Renders a runtime scene to a linear image, in parallel over tiles.
//!
//! Every camera sample draws from its own PCG32 stream seeded by (pixel,
//! sample index, scene seed), and each pixel sums its samples in order, so the
//! image is bit-identical whatever the thread count or tile scheduling.

use crate::imageio::Image;
use crate::integrators::Counters;
use crate::math::Rgb;
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::view::View;
use glam::Vec2;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

const TILE: u32 = 16;

/// How to render; the scene says what.
#[derive(Clone, Debug, Default)]
pub struct RenderOptions {
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr (only shown on a terminal).
    pub progress: bool,
    /// Render only samples `first_sample..first_sample + spp`, for
    /// progressive refinement; `None` renders all of the scene's samples.
    pub sample_range: Option<(u32, u32)>,
}

/// What a render cost, for the summary line and benchmarks.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    /// Wall-clock time of the render.
    pub elapsed: Duration,
    /// Camera samples taken (pixels × samples per pixel, fewer if cancelled).
    pub samples: u64,
    /// Rays traced, camera, bounce and shadow rays together.
    pub rays: u64,
    /// True if the render stopped early because it was cancelled.
    pub cancelled: bool,
}

impl RenderStats {
    /// One line for the terminal: seconds, millions of samples and of rays per
    /// second.
    pub fn summary(&self) -> String {
        let s = self.elapsed.as_secs_f64().max(1e-9);
        format!(
            "{:.2} s, {:.2} M samples/s, {:.2} M rays/s",
            s,
            self.samples as f64 / s / 1e6,
            self.rays as f64 / s / 1e6
        )
    }
}

/// Renders the whole image; the returned pixels are the mean over the
/// rendered samples.
pub fn render(scene: &Scene, view: &View, opts: &RenderOptions) -> (Image, RenderStats) {
    render_cancellable(scene, view, opts, &AtomicBool::new(false))
}

/// As [`render`], but gives up early (returning `cancelled: true`) once
/// `cancel` is set; tiles already started finish first.
pub fn render_cancellable(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    cancel: &AtomicBool,
) -> (Image, RenderStats) {
    let start = Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build();
    let work = || render_tiles(scene, view, opts, cancel, None);
    let (mut image, counters, samples) = match pool {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    };
    let spp = opts.sample_range.map_or(view.film.spp, |(_, n)| n);
    for p in &mut image.pixels {
        *p /= spp as f32;
    }
    let stats = RenderStats {
        elapsed: start.elapsed(),
        samples,
        rays: counters.rays,
        cancelled: cancel.load(Ordering::Relaxed),
    };
    (image, stats)
}

/// Progressive refinement without rounding drift: `sums` holds per-pixel
/// sample sums over `[0, first)` where `opts.sample_range` is `(first, n)`,
/// and on return the sums over `[0, first + n)`, each pixel's samples added
/// in order as [`render`] adds them. Dividing by `first + n` therefore gives
/// exactly [`render`]'s image at that sample count. A cancelled pass leaves
/// `sums` untouched.
pub fn render_accumulate(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    sums: &mut Image,
) -> RenderStats {
    debug_assert_eq!((sums.width, sums.height), (view.film.width, view.film.height));
    let start = Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build();
    let work = || render_tiles(scene, view, opts, cancel, Some(&*sums));
    let (image, counters, samples) = match pool {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    };
    let cancelled = cancel.load(Ordering::Relaxed);
    if !cancelled {
        *sums = image;
    }
    RenderStats {
        elapsed: start.elapsed(),
        samples,
        rays: counters.rays,
        cancelled,
    }
}

/// Per-pixel sample sums, continuing from `prefix` when given.
fn render_tiles(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    prefix: Option<&Image>,
) -> (Image, Counters, u64) {
    let film = view.film;
    let (w, h) = (film.width, film.height);
    let tiles: Vec<(u32, u32)> = (0..h.div_ceil(TILE))
        .flat_map(|ty| (0..w.div_ceil(TILE)).map(move |tx| (tx, ty)))
        .collect();
    let bar = if opts.progress {
        let bar = indicatif::ProgressBar::new(tiles.len() as u64);
        if let Ok(style) =
            indicatif::ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent}% eta {eta}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar
    } else {
        indicatif::ProgressBar::hidden()
    };
    let (s0, spp) = opts.sample_range.unwrap_or((0, film.spp));
    let aspect = w as f32 / h as f32;
    let rendered: Vec<(u32, u32, Vec<Rgb>, Counters)> = tiles
        .par_iter()
        .map(|&(tx, ty)| {
            let mut counters = Counters::default();
            let (x0, y0) = (tx * TILE, ty * TILE);
            let (x1, y1) = ((x0 + TILE).min(w), (y0 + TILE).min(h));
            let mut px = Vec::with_capacity(((x1 - x0) * (y1 - y0)) as usize);
            if cancel.load(Ordering::Relaxed) {
                return (tx, ty, px, counters);
            }
            for y in y0..y1 {
                for x in x0..x1 {
                    let mut sum = prefix.map_or(Rgb::ZERO, |p| p.get(x, y));
                    for s in s0..s0 + spp {
                        let mut sampler = Sampler::new(film.sampler, x, y, s, film.spp, film.seed);
                        let jitter = sampler.next_vec2();
                        let film_pos =
                            Vec2::new((x as f32 + jitter.x) / w as f32, (y as f32 + jitter.y) / h as f32);
                        let ray = view.camera.ray(film_pos, aspect, sampler.next_vec2());
                        let li = view.integrator.li(scene, &ray, &mut sampler, &mut counters);
                        // A non-finite sample (a numerical bug, caught by
                        // debug asserts) must not poison the pixel in release.
                        if li.is_finite() {
                            sum += li;
                        }
                    }
                    px.push(sum);
                }
            }
            bar.inc(1);
            (tx, ty, px, counters)
        })
        .collect();
    bar.finish_and_clear();
    let mut image = Image::new(w, h);
    let mut total = Counters::default();
    for (tx, ty, px, c) in rendered {
        total.rays += c.rays;
        let (x0, y0) = (tx * TILE, ty * TILE);
        let tw = (x0 + TILE).min(w) - x0;
        for (i, p) in px.into_iter().enumerate() {
            let (x, y) = (x0 + i as u32 % tw, y0 + i as u32 / tw);
            image.pixels[(y * w + x) as usize] = p;
        }
    }
    (image, total, w as u64 * h as u64 * spp as u64)
}
