//! Renders a runtime scene to a linear image, in parallel over tiles.
//!
//! Every camera sample draws from its own PCG32 stream seeded by (pixel,
//! sample index, scene seed), and each pixel sums its samples exactly
//! ([`ExactSum`]: fixed point, so the grouping of the additions does not
//! matter). The image is therefore bit-identical whatever the thread count or
//! tile scheduling, and any rectangle of pixels ([`render_sums`]) or range of
//! samples rendered on its own holds exactly what the whole render holds
//! there: pieces rendered on many machines reassemble bit for bit
//! (`crate::farm`).

use crate::imageio::{Image, PixelRect};
use crate::integrators::Counters;
use crate::math::ExactSum;
use crate::sampler::Sampler;
use crate::scene::Scene;
use crate::view::View;
use glam::Vec2;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
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
    /// progressive refinement and sample splits; `None` renders all of the
    /// scene's samples.
    pub sample_range: Option<(u32, u32)>,
}

#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    pub elapsed: Duration,
    pub samples: u64,
    pub rays: u64,
    pub cancelled: bool,
}

impl RenderStats {
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

/// Per-pixel sample sums over a rectangle of the frame: what a render
/// produces before the division by the sample count, and what pieces of a
/// frame add up.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleSums {
    pub rect: PixelRect,
    /// Row-major over `rect`.
    pub sums: Vec<ExactSum>,
}

impl SampleSums {
    pub fn new(rect: PixelRect) -> Self {
        Self {
            rect,
            sums: vec![ExactSum::ZERO; rect.area() as usize],
        }
    }

    /// The sum at pixel (x, y) in image coordinates.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> ExactSum {
        self.sums[self.rect.index(x, y)]
    }

    /// Adds `other`'s sums at the pixels it covers, which must lie inside.
    pub fn add(&mut self, other: &SampleSums) {
        debug_assert!(self.rect.contains(&other.rect));
        let r = other.rect;
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let i = self.rect.index(x, y);
                self.sums[i].add(&other.get(x, y));
            }
        }
    }

    /// The mean over `n` samples per pixel, as an image of `rect`'s size.
    pub fn mean(&self, n: u32) -> Image {
        Image {
            width: self.rect.width(),
            height: self.rect.height(),
            pixels: self.sums.iter().map(|s| s.mean(n)).collect(),
        }
    }
}

/// A tile finished by [`render_sums`], for progress reports.
#[derive(Clone, Copy, Debug)]
pub struct TileDone {
    pub rect: PixelRect,
    /// Tiles finished so far, this one included.
    pub done: usize,
    pub total: usize,
    /// Since the render started.
    pub elapsed: Duration,
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
    let full = PixelRect::full(view.film.width, view.film.height);
    let (sums, stats) = render_sums(scene, view, opts, full, cancel, &|_| {});
    let spp = opts.sample_range.map_or(view.film.spp, |(_, n)| n);
    (sums.mean(spp), stats)
}

/// Progressive refinement without rounding drift: `sums` holds per-pixel
/// sample sums over `[0, first)` where `opts.sample_range` is `(first, n)`,
/// and on return the sums over `[0, first + n)`. The sums are exact, so
/// `sums.mean(first + n)` is exactly [`render`]'s image at that sample
/// count. A cancelled pass leaves `sums` untouched.
pub fn render_accumulate(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    sums: &mut SampleSums,
) -> RenderStats {
    let (pass, stats) = render_sums(scene, view, opts, sums.rect, cancel, &|_| {});
    if !stats.cancelled {
        sums.add(&pass);
    }
    stats
}

/// Per-pixel sample sums of the pixels in `rect` (which must lie inside the
/// film) over `opts.sample_range`: exactly the sums the whole render has
/// there. `on_tile` is called as each tile finishes, from worker threads.
pub fn render_sums(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    rect: PixelRect,
    cancel: &AtomicBool,
    on_tile: &(dyn Fn(&TileDone) + Sync),
) -> (SampleSums, RenderStats) {
    debug_assert!(PixelRect::full(view.film.width, view.film.height).contains(&rect));
    let start = Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(opts.threads.unwrap_or(0))
        .build();
    let work = || render_tiles(scene, view, opts, rect, cancel, on_tile, start);
    let (sums, counters, samples) = match pool {
        Ok(pool) => pool.install(work),
        Err(_) => work(),
    };
    let stats = RenderStats {
        elapsed: start.elapsed(),
        samples,
        rays: counters.rays,
        cancelled: cancel.load(Ordering::Relaxed),
    };
    (sums, stats)
}

/// The tiles of `rect`, `TILE` pixels square, in reading order.
fn tiles_of(rect: PixelRect) -> Vec<PixelRect> {
    (rect.y0..rect.y1)
        .step_by(TILE as usize)
        .flat_map(|y0| {
            (rect.x0..rect.x1)
                .step_by(TILE as usize)
                .map(move |x0| PixelRect {
                    x0,
                    y0,
                    x1: (x0 + TILE).min(rect.x1),
                    y1: (y0 + TILE).min(rect.y1),
                })
        })
        .collect()
}

fn progress_bar(show: bool, tiles: usize) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(tiles as u64);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent}% eta {eta}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// Per-pixel sample sums over `rect`.
fn render_tiles(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    rect: PixelRect,
    cancel: &AtomicBool,
    on_tile: &(dyn Fn(&TileDone) + Sync),
    start: Instant,
) -> (SampleSums, Counters, u64) {
    let film = view.film;
    let (w, h) = (film.width, film.height);
    let tiles = tiles_of(rect);
    let bar = progress_bar(opts.progress, tiles.len());
    let finished = AtomicUsize::new(0);
    let (s0, spp) = opts.sample_range.unwrap_or((0, film.spp));
    let aspect = w as f32 / h as f32;
    let rendered: Vec<(PixelRect, Vec<ExactSum>, Counters)> = tiles
        .par_iter()
        .map(|&tile| {
            let mut counters = Counters::default();
            let mut px = Vec::with_capacity(tile.area() as usize);
            if cancel.load(Ordering::Relaxed) {
                return (tile, px, counters);
            }
            for y in tile.y0..tile.y1 {
                for x in tile.x0..tile.x1 {
                    let mut sum = ExactSum::ZERO;
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
                            sum.add_sample(li);
                        }
                    }
                    px.push(sum);
                }
            }
            bar.inc(1);
            on_tile(&TileDone {
                rect: tile,
                done: finished.fetch_add(1, Ordering::Relaxed) + 1,
                total: tiles.len(),
                elapsed: start.elapsed(),
            });
            (tile, px, counters)
        })
        .collect();
    bar.finish_and_clear();
    let mut sums = SampleSums::new(rect);
    let mut total = Counters::default();
    for (tile, px, c) in rendered {
        total.rays += c.rays;
        // A tile skipped on cancel has no pixels; its sums stay zero.
        for (i, p) in px.into_iter().enumerate() {
            let (x, y) = (
                tile.x0 + i as u32 % tile.width(),
                tile.y0 + i as u32 / tile.width(),
            );
            let k = rect.index(x, y);
            sums.sums[k] = p;
        }
    }
    (sums, total, rect.area() * spp as u64)
}
