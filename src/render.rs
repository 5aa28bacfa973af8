//! Renders a runtime scene to a linear image, in parallel over tiles.
//!
//! Every camera sample draws from its own random stream (`SampleRng`) seeded by (pixel,
//! sample index, scene seed), and each pixel sums its samples exactly
//! ([`ExactSum`]: fixed point, so the grouping of the additions does not
//! matter). The image is therefore bit-identical whatever the thread count or
//! tile scheduling, and any rectangle of pixels ([`render_sums`]) or range of
//! samples rendered on its own holds exactly what the whole render holds
//! there when every pixel takes every sample (`allocation: Even`): pieces
//! rendered on many machines reassemble bit for bit (`crate::farm`). A
//! whole-frame render spread by noise (`crate::film::allocation`) renders
//! in two passes, the second's counts decided from the first's frame.

pub use crate::imageio::SampleSums;

use crate::camera::Projection;
use crate::film::FilterKind;
use crate::film::{Adaptive, PixelNoise, Plan};
use crate::imageio::{Image, PixelRect};
use crate::integrators::{Counters, Integrator, caustic};
use crate::math::rng::mix64;
use crate::math::{ExactSum, Rgb, SampleRng};
use crate::sampler::{PixelSampler, Sampler, SamplerKind};
use crate::scene::Scene;
use crate::view::{Allocation, View};
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

/// A tile finished by [`render_sums`], for progress reports.
#[derive(Clone, Copy, Debug)]
pub struct TileDone {
    /// The tile's pixels.
    pub rect: PixelRect,
    /// Tiles finished so far, this one included.
    pub done: usize,
    /// Tiles in the render.
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
    render_image(scene, view, opts, cancel, &|_| {})
}

/// As [`render_cancellable`], calling `on_tile` as each tile finishes (from
/// worker threads). Each tile's sums become means as soon as it finishes, so
/// the whole frame's exact sums are never held at once.
pub fn render_image(
    scene: &Scene,
    view: &View,
    opts: &RenderOptions,
    cancel: &AtomicBool,
    on_tile: &(dyn Fn(&TileDone) + Sync),
) -> (Image, RenderStats) {
    let (w, h) = (view.film.width, view.film.height);
    // A part of the samples is added to other parts' exact sums, which
    // needs fixed counts: only a render of all of them is adaptive or
    // spread by noise.
    let whole = opts.sample_range.is_none_or(|r| r == (0, view.film.spp));
    let adaptive = view.film.adaptive.filter(|_| whole);
    let work = Work::new(
        scene,
        view,
        opts,
        PixelRect::full(w, h),
        cancel,
        on_tile,
        adaptive,
    );
    let caustic_paths = light_trace_plan(scene, view, opts);
    let mut work = work;
    if caustic_paths.is_some()
        && let Integrator::Path(p) = &mut work.integrator
    {
        p.split_caustics = true;
    }
    let (mut pixels, mut stats) = match spread_plan(view, opts) {
        Some(plan) => work.spread(plan),
        None => work.run(Rgb::ZERO, |p| p.sum.mean(p.taken)),
    };
    if let Some((paths, max_chain)) = caustic_paths
        && !stats.cancelled
    {
        let start = Instant::now();
        let mut trace = || light_trace(scene, view, paths, max_chain, cancel, &mut pixels);
        let traced = match rayon::ThreadPoolBuilder::new()
            .num_threads(opts.threads.unwrap_or(0))
            .build()
        {
            Ok(pool) => pool.install(trace),
            Err(_) => trace(),
        };
        match traced {
            Some(counters) => stats.rays += counters.rays,
            None => stats.cancelled = true,
        }
        stats.elapsed += start.elapsed();
    }
    (
        Image {
            width: w,
            height: h,
            pixels,
        },
        stats,
    )
}

/// Light paths per camera sample the caustic light tracer takes
/// ([`light_trace`]). Its own noise is small: on `cornell_specular`
/// (256², 128 spp, two seeds) the noise off the light is 0.0387 without it
/// and 0.0309, 0.0307, 0.0306, 0.0306 with 1/32, 1/16, 1/8, 1/4 light paths
/// a sample; 1/16 costs 4% more instructions (callgrind, 64², 64 spp: 1.393
/// against 1.336 G), 3% more rays.
pub const LIGHT_PATHS_PER_SAMPLE: f64 = 0.0625;

/// How many light paths [`render_image`] traces for caustics seen directly
/// (`integrator: Path(caustics: LightTracing)`, the default), and the
/// longest specular chain they follow; `None` when it traces none: the scene
/// has no perfect mirror or smooth glass lit by a rectangle or sphere light,
/// the camera is not a pinhole, the filter is not `Box`, the render is part
/// of the samples (the splats land anywhere in the frame, so pieces and
/// passes could not add up), or it would take 2³² light paths or more.
pub fn light_trace_plan(scene: &Scene, view: &View, opts: &RenderOptions) -> Option<(u64, u32)> {
    let whole = opts.sample_range.is_none_or(|r| r == (0, view.film.spp));
    let Integrator::Path(p) = view.integrator else {
        return None;
    };
    let pinhole = view.camera.projection == Projection::Perspective && view.camera.aperture_radius <= 0.0;
    if !(whole
        && p.light_trace_caustics
        && scene.caustics.is_some()
        && pinhole
        && view.filter.kind == FilterKind::Box)
    {
        return None;
    }
    let samples = view.film.width as f64 * view.film.height as f64 * view.film.spp as f64;
    let paths = (samples * LIGHT_PATHS_PER_SAMPLE).ceil();
    // `ExactSum::mean` divides by a u32.
    (paths >= 1.0 && paths <= u32::MAX as f64).then_some((paths as u64, caustic::max_chain(p.max_depth)))
}

/// Light paths a chunk of [`light_trace`] traces: its unit of parallel work
/// and of random streams (chunk `k` draws from stream `k` of `SampleRng`), so the
/// image does not depend on the thread count.
const CHUNK: u64 = 4096;

/// Chunks traced between merges into the image: bounds the splats held at
/// once (at most `CHUNK` each).
const BATCH: u64 = 64;

/// The caustic light tracer ([`caustic`]): traces `paths` light paths of a
/// pinhole `view`'s scene and adds to each of `pixels` (row-major, the whole
/// film) the sum of its splats over `paths`; `None`, with `pixels`
/// untouched, when cancelled. Splats are summed exactly ([`ExactSum`]), so
/// the image is the same whatever the thread count. Memory: 48 bytes a
/// pixel for the sums beside the film's 16, below a render's peak
/// (`crate::memory`), and at most `BATCH · CHUNK` splats.
pub fn light_trace(
    scene: &Scene,
    view: &View,
    paths: u64,
    max_chain: u32,
    cancel: &AtomicBool,
    pixels: &mut [Rgb],
) -> Option<Counters> {
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
                let splats = (0..n)
                    .filter_map(|_| {
                        let y = caustic::trace(scene, em, max_chain, &mut sampler, &mut c)?;
                        caustic::splat(scene, &view.camera, w, h, &y, &mut c)
                    })
                    .collect();
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

/// The plan of [`render_image`]'s two passes when it spreads the samples by
/// noise (`film.allocation: ByNoise`), `None` when every pixel takes `spp`:
/// below 32 spp, with adaptive sampling, with the `Stratified` sampler
/// (whose strata are laid out for exactly `spp`), or for part of the
/// samples.
pub fn spread_plan(view: &View, opts: &RenderOptions) -> Option<Plan> {
    let whole = opts.sample_range.is_none_or(|r| r == (0, view.film.spp));
    match view.film.allocation {
        Allocation::ByNoise
            if whole && view.film.adaptive.is_none() && view.film.sampler != SamplerKind::Stratified =>
        {
            Plan::new(view.film.spp)
        }
        _ => None,
    }
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
    // The sums of pieces and passes must add up: every sample is taken.
    let work = Work::new(scene, view, opts, rect, cancel, on_tile, None);
    let (sums, stats) = work.run(ExactSum::ZERO, |p| p.sum);
    (SampleSums { rect, sums }, stats)
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

fn progress_bar(show: bool, tiles: usize, done: usize) -> indicatif::ProgressBar {
    if !show {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(tiles as u64);
    bar.set_position(done as u64);
    if let Ok(style) =
        indicatif::ProgressStyle::with_template("{spinner} rendering [{bar:40}] {percent}% eta {eta}")
    {
        bar.set_style(style.progress_chars("=> "));
    }
    bar
}

/// `tiles` of `rect` ordered by the samples their pixels take (pixel `i`,
/// row-major over `rect`, takes samples `from..upto[i]`), most first; tiles
/// with equal counts keep their order.
fn heaviest_first(mut tiles: Vec<PixelRect>, rect: PixelRect, from: u32, upto: &[u32]) -> Vec<PixelRect> {
    let samples = |t: &PixelRect| -> u64 {
        (t.y0..t.y1)
            .flat_map(|y| (t.x0..t.x1).map(move |x| (x, y)))
            .map(|(x, y)| u64::from(upto[rect.index(x, y)].saturating_sub(from)))
            .sum()
    };
    // `sort_by_cached_key` is stable.
    tiles.sort_by_cached_key(|t| std::cmp::Reverse(samples(t)));
    tiles
}

/// One render of the pixels in `rect`.
struct Work<'a> {
    scene: &'a Scene,
    view: &'a View,
    opts: &'a RenderOptions,
    rect: PixelRect,
    cancel: &'a AtomicBool,
    on_tile: &'a (dyn Fn(&TileDone) + Sync),
    /// Adaptive sampling's stopping rule, if this render uses it.
    adaptive: Option<Adaptive>,
    /// Which samples each pixel takes.
    samples: Samples<'a>,
    /// The sample count the pixel samplers are made for (the Sobol index's
    /// bits): the most any pixel takes.
    sampler_spp: u32,
    /// Whether to sum each pixel's squared samples (a spread render's first pass).
    squares: bool,
    /// This is pass `.0` of `.1`, for progress reports.
    pass: (usize, usize),
    /// The view's integrator, told when a light tracer takes its caustics.
    integrator: Integrator,
}

/// Which samples each pixel of a [`Work`] takes.
#[derive(Clone, Copy, Debug)]
enum Samples<'a> {
    /// Samples `first..first + count` of every pixel.
    Every { first: u32, count: u32 },
    /// Pixel `i` (row-major over the rect) takes samples `from..upto[i]`.
    UpTo { from: u32, upto: &'a [u32] },
}

/// One pixel's samples, summed, for [`Work::run`]'s `finish`.
struct PixelSums {
    x: u32,
    y: u32,
    sum: ExactSum,
    taken: u32,
    /// Per channel, the sum of the squared samples (when `Work::squares`).
    squares: [f64; 3],
}

impl PixelSums {
    /// The variance of one sample, summed over the channels (0 below two samples).
    fn variance(&self) -> f32 {
        if self.taken < 2 {
            return 0.0;
        }
        let n = self.taken as f64;
        let mean = self.sum.mean(self.taken).to_array();
        let v: f64 = (0..3)
            .map(|c| (self.squares[c] - n * mean[c] as f64 * mean[c] as f64).max(0.0))
            .sum();
        (v / (n - 1.0)) as f32
    }
}

impl<'a> Work<'a> {
    /// A render of the samples `opts.sample_range` (all by default) of the pixels in `rect`.
    fn new(
        scene: &'a Scene,
        view: &'a View,
        opts: &'a RenderOptions,
        rect: PixelRect,
        cancel: &'a AtomicBool,
        on_tile: &'a (dyn Fn(&TileDone) + Sync),
        adaptive: Option<Adaptive>,
    ) -> Self {
        let (first, count) = opts.sample_range.unwrap_or((0, view.film.spp));
        Work {
            scene,
            view,
            opts,
            rect,
            cancel,
            on_tile,
            adaptive,
            samples: Samples::Every { first, count },
            sampler_spp: view.film.spp,
            squares: false,
            pass: (0, 1),
            integrator: view.integrator,
        }
    }

    /// A render spread by noise (`crate::film::allocation`): `plan.first`
    /// samples everywhere, then each pixel up to its count; the pixels' means.
    fn spread(mut self, plan: Plan) -> (Vec<Rgb>, RenderStats) {
        let start = Instant::now();
        self.sampler_spp = plan.cap;
        self.samples = Samples::Every {
            first: 0,
            count: plan.first,
        };
        self.squares = true;
        self.pass = (0, 2);
        let (first, s1) = self.run(([0.0f32; 3], 0.0f32), |p| {
            (p.sum.mean(p.taken).to_array(), p.variance())
        });
        if s1.cancelled {
            return (first.iter().map(|f| Rgb::from_array(f.0)).collect(), s1);
        }
        let variance: Vec<f32> = first.iter().map(|f| f.1).collect();
        let (w, h) = (self.rect.width() as usize, self.rect.height() as usize);
        let upto = plan.counts(w, h, &variance);
        drop(variance);
        let second = Work {
            samples: Samples::UpTo {
                from: plan.first,
                upto: &upto,
            },
            squares: false,
            pass: (1, 2),
            ..self
        };
        let rect = second.rect;
        let n1 = plan.first as f32;
        // A weighted mean of the two passes' means; skipped tiles (on
        // cancel) keep the first pass's.
        let (pixels, s2) = second.run(Rgb::NAN, |p| {
            let m1 = Rgb::from_array(first[rect.index(p.x, p.y)].0);
            if p.taken == 0 {
                return m1;
            }
            let n2 = p.taken as f32;
            (m1 * n1 + p.sum.mean(p.taken) * n2) / (n1 + n2)
        });
        let pixels = pixels
            .into_iter()
            .zip(&first)
            .map(|(p, f)| if p.is_nan() { Rgb::from_array(f.0) } else { p })
            .collect();
        let stats = RenderStats {
            // Both passes and the allocation between them.
            elapsed: start.elapsed(),
            samples: s1.samples + s2.samples,
            rays: s1.rays + s2.rays,
            cancelled: s2.cancelled,
        };
        (pixels, stats)
    }

    /// Renders every tile on the options' thread pool, turns each pixel's
    /// exact sum and sample count into a `T` as its tile finishes (`empty`
    /// for pixels of tiles skipped on cancel), and returns them row-major
    /// over `rect`.
    fn run<T: Copy + Send>(
        &self,
        empty: T,
        finish: impl Fn(&PixelSums) -> T + Sync,
    ) -> (Vec<T>, RenderStats) {
        let start = Instant::now();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(self.opts.threads.unwrap_or(0))
            .build();
        let work = || self.tiles(start, &finish);
        let (rendered, counters) = match pool {
            Ok(pool) => pool.install(work),
            Err(_) => work(),
        };
        let rect = self.rect;
        let mut out = vec![empty; rect.area() as usize];
        for (tile, px) in rendered {
            for (i, p) in px.into_iter().enumerate() {
                let (x, y) = (
                    tile.x0 + i as u32 % tile.width(),
                    tile.y0 + i as u32 / tile.width(),
                );
                out[rect.index(x, y)] = p;
            }
        }
        let stats = RenderStats {
            elapsed: start.elapsed(),
            samples: counters.samples,
            rays: counters.rays,
            cancelled: self.cancel.load(Ordering::Relaxed),
        };
        (out, stats)
    }

    /// The order tiles are handed out in: reading order, or, when pixels
    /// take different sample counts, the most samples first, so the pass
    /// ends on small tiles rather than with one thread on a heavy one
    /// (longest-processing-time-first scheduling). The image does not
    /// depend on the order: every pixel's samples are its own.
    fn schedule(&self, tiles: Vec<PixelRect>) -> Vec<PixelRect> {
        match self.samples {
            Samples::UpTo { from, upto } => heaviest_first(tiles, self.rect, from, upto),
            Samples::Every { .. } => tiles,
        }
    }

    /// Each tile's pixels, finished; a tile skipped on cancel has none.
    fn tiles<T: Send>(
        &self,
        start: Instant,
        finish: &(impl Fn(&PixelSums) -> T + Sync),
    ) -> (Vec<(PixelRect, Vec<T>)>, Counters) {
        let film = self.view.film;
        let tiles = self.schedule(tiles_of(self.rect));
        let (pass, passes) = self.pass;
        let bar = progress_bar(self.opts.progress, passes * tiles.len(), pass * tiles.len());
        let finished = AtomicUsize::new(pass * tiles.len());
        // One tile per job: rayon otherwise hands each thread a run of tiles
        // it cannot split once started, and a spread render's second pass,
        // whose tiles differ by up to 8× in samples, left one of two threads
        // idle for a fifth of the pass (cornell, 256², 121 spp: 1.61 of 2
        // cores busy in that pass against 1.97 in the even first pass).
        let rendered: Vec<(PixelRect, Vec<T>, Counters)> = tiles
            .par_iter()
            .with_max_len(1)
            .map(|&tile| {
                let mut counters = Counters::default();
                let mut px = Vec::with_capacity(tile.area() as usize);
                let mut pixel = PixelSampler::with_splits(
                    film.sampler,
                    self.sampler_spp,
                    self.integrator.splits(),
                    film.seed,
                );
                if self.cancel.load(Ordering::Relaxed) {
                    return (tile, px, counters);
                }
                for y in tile.y0..tile.y1 {
                    for x in tile.x0..tile.x1 {
                        let (s0, spp) = match self.samples {
                            Samples::Every { first, count } => (first, count),
                            Samples::UpTo { from, upto } => {
                                (from, upto[self.rect.index(x, y)].saturating_sub(from))
                            }
                        };
                        let mut sum = ExactSum::ZERO;
                        let mut squares = [0.0f64; 3];
                        let mut noise = PixelNoise::default();
                        let mut taken = spp;
                        pixel.set_pixel(x, y, s0..s0 + spp);
                        for s in s0..s0 + spp {
                            let mut sampler = pixel.sample(s);
                            let (ray, weight) = self.view.camera_ray(x, y, &mut sampler);
                            let li = self.integrator.li(self.scene, &ray, &mut sampler, &mut counters);
                            // A non-finite sample (a numerical bug, caught by
                            // debug asserts) must not poison the pixel in release.
                            let c = if li.is_finite() {
                                if weight == 1.0 { li } else { li * weight }
                            } else {
                                Rgb::ZERO
                            };
                            sum.add_sample(c);
                            if self.squares {
                                for (q, v) in squares.iter_mut().zip(c.to_array()) {
                                    *q += v as f64 * v as f64;
                                }
                            }
                            if let Some(a) = &self.adaptive {
                                noise.add(c);
                                if a.converged(&noise) {
                                    taken = s - s0 + 1;
                                    break;
                                }
                            }
                        }
                        counters.samples += taken as u64;
                        px.push(finish(&PixelSums {
                            x,
                            y,
                            sum,
                            taken,
                            squares,
                        }));
                    }
                }
                bar.inc(1);
                (self.on_tile)(&TileDone {
                    rect: tile,
                    done: finished.fetch_add(1, Ordering::Relaxed) + 1,
                    total: passes * tiles.len(),
                    elapsed: start.elapsed(),
                });
                (tile, px, counters)
            })
            .collect();
        bar.finish_and_clear();
        let mut total = Counters::default();
        let tiles = rendered
            .into_iter()
            .map(|(tile, px, c)| {
                total.rays += c.rays;
                total.samples += c.samples;
                (tile, px)
            })
            .collect();
        (tiles, total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_tiles_go_out_heaviest_first_and_every_tile_once() {
        // 40 × 24 pixels: 3 × 2 tiles, the right and bottom ones partial.
        let rect = PixelRect {
            x0: 0,
            y0: 0,
            x1: 40,
            y1: 24,
        };
        let tiles = tiles_of(rect);
        assert_eq!(tiles.len(), 6);
        // Samples 8.. of each pixel: more toward the right, and a hot spot in
        // the bottom-left tile.
        let upto: Vec<u32> = (0..rect.area())
            .map(|i| {
                let (x, y) = ((i % 40) as u32, (i / 40) as u32);
                if x < 4 && y > 20 { 200 } else { 8 + x }
            })
            .collect();
        let order = heaviest_first(tiles.clone(), rect, 8, &upto);
        let upto = &upto;
        let load = |t: &PixelRect| -> u64 {
            (t.y0..t.y1)
                .flat_map(|y| (t.x0..t.x1).map(move |x| upto[rect.index(x, y)] as u64 - 8))
                .sum()
        };
        let loads: Vec<u64> = order.iter().map(load).collect();
        assert!(
            loads.windows(2).all(|w| w[0] >= w[1]),
            "not heaviest first: {loads:?}"
        );
        let mut seen = order.clone();
        seen.sort_by_key(|t| (t.y0, t.x0));
        assert_eq!(seen, tiles, "every tile exactly once");
        // Loads in proportion to the tiles' areas (256, 256, 128, 128, 128,
        // 64 pixels), which already decrease: ties keep reading order.
        let flat = vec![8 + 4; rect.area() as usize];
        assert_eq!(heaviest_first(tiles.clone(), rect, 8, &flat), tiles);
    }
}
