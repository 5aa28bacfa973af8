//! The one tile loop: renders the pixels of a [`Plan`]'s rect under the
//! sampling policy it chose ([`Sampling`]), in parallel over tiles.
//!
//! Every camera sample draws from its own random stream (`SampleRng`)
//! seeded by (pixel, sample index, scene seed), and each pixel sums its
//! samples exactly ([`ExactSum`]: fixed point, so the grouping of the
//! additions does not matter). The image is therefore bit-identical whatever
//! the thread count or tile scheduling, and any rectangle of pixels or range
//! of samples rendered on its own holds exactly what the whole render holds
//! there when every pixel takes every sample: pieces rendered on many
//! machines reassemble bit for bit (`crate::farm`). The loop reads the
//! plan's integrator and never changes it.

use super::options::RenderOptions;
use super::plan::{Plan, Sampling};
use super::stats::{RenderStats, TileDone};
use crate::film::{Adaptive, PixelNoise, Spread};
use crate::geometry::Hit;
use crate::imageio::sample_sums::two_pass_mean;
use crate::imageio::{PixelRect, SampleSums};
use crate::integrators::{Counters, Integrator};
use crate::math::{ExactSum, Rgb, SampleSum};
use crate::sampler::PixelSampler;
use crate::scene::Scene;
use crate::view::View;
use rayon::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Instant;

const TILE: u32 = 16;

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
/// row-major over `rect`, takes samples `ranges[i].0..ranges[i].1`), most
/// first; tiles with equal counts keep their order.
fn heaviest_first(mut tiles: Vec<PixelRect>, rect: PixelRect, ranges: &[(u32, u32)]) -> Vec<PixelRect> {
    let samples = |t: &PixelRect| -> u64 {
        (t.y0..t.y1)
            .flat_map(|y| (t.x0..t.x1).map(move |x| (x, y)))
            .map(|(x, y)| {
                let (a, b) = ranges[rect.index(x, y)];
                u64::from(b.saturating_sub(a))
            })
            .sum()
    };
    // `sort_by_cached_key` is stable.
    tiles.sort_by_cached_key(|t| std::cmp::Reverse(samples(t)));
    tiles
}

/// One render of the pixels in `rect`.
pub(super) struct Work<'a> {
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
    /// Samples from this index on are summed apart (`PixelSums::late`): a
    /// spread piece keeps its two passes' sums apart.
    late_from: u32,
    /// This is pass `.0` of `.1`, for progress reports.
    pass: (usize, usize),
    /// The plan's integrator (told whether a light tracer takes its caustics).
    integrator: Integrator,
}

/// Which samples each pixel of a [`Work`] takes.
#[derive(Clone, Copy, Debug)]
enum Samples<'a> {
    /// Samples `first..first + count` of every pixel.
    Every { first: u32, count: u32 },
    /// Pixel `i` (row-major over the rect) takes samples
    /// `ranges[i].0..ranges[i].1`.
    Ranges(&'a [(u32, u32)]),
}

/// A spread render's first pass: each pixel's mean and variance
/// (row-major over the frame), each pixel's count, and what it cost.
type FirstPass = (Vec<([f32; 3], f32)>, Vec<u32>, RenderStats);

/// One pixel's samples, summed, for [`Work::run`]'s `finish`.
struct PixelSums {
    x: u32,
    y: u32,
    sum: ExactSum,
    /// The sum of the samples from `Work::late_from` on (not in `sum`).
    late: ExactSum,
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
    /// The render of `plan`'s pixels with an even count per pixel, or
    /// adaptive when the plan says so (see [`Work::render`] for all three).
    fn new(
        scene: &'a Scene,
        view: &'a View,
        plan: &Plan,
        opts: &'a RenderOptions,
        cancel: &'a AtomicBool,
        on_tile: &'a (dyn Fn(&TileDone) + Sync),
    ) -> Self {
        let (samples, adaptive) = match plan.sampling {
            Sampling::Even { first, count } => (Samples::Every { first, count }, None),
            Sampling::Adaptive(a) => (
                Samples::Every {
                    first: 0,
                    count: view.film.spp,
                },
                Some(a),
            ),
            // Set up by `spread` itself.
            Sampling::Spread(_) => (
                Samples::Every {
                    first: 0,
                    count: view.film.spp,
                },
                None,
            ),
        };
        Work {
            scene,
            view,
            opts,
            rect: plan.rect,
            cancel,
            on_tile,
            adaptive,
            samples,
            sampler_spp: view.film.spp,
            squares: false,
            late_from: u32::MAX,
            pass: (0, 1),
            integrator: plan.integrator,
        }
    }

    /// Each pixel's exact sum (a piece or a pass: even counts, or a piece
    /// spread by noise as the whole frame is).
    pub(super) fn sums(
        scene: &'a Scene,
        view: &'a View,
        plan: &Plan,
        opts: &'a RenderOptions,
        cancel: &'a AtomicBool,
        on_tile: &'a (dyn Fn(&TileDone) + Sync),
    ) -> (SampleSums, RenderStats) {
        let work = Self::new(scene, view, plan, opts, cancel, on_tile);
        match plan.sampling {
            Sampling::Spread(s) => work.spread_piece(s, plan.samples),
            Sampling::Even { .. } | Sampling::Adaptive(_) => {
                debug_assert!(matches!(plan.sampling, Sampling::Even { .. }));
                let (sums, stats) = work.run(ExactSum::ZERO, |p| p.sum);
                let rect = plan.rect;
                (
                    SampleSums {
                        rect,
                        sums,
                        spread: None,
                    },
                    stats,
                )
            }
        }
    }

    /// Each pixel's mean under the plan's sampling policy, row-major over
    /// the plan's rect.
    pub(super) fn means(
        scene: &'a Scene,
        view: &'a View,
        plan: &Plan,
        opts: &'a RenderOptions,
        cancel: &'a AtomicBool,
        on_tile: &'a (dyn Fn(&TileDone) + Sync),
    ) -> (Vec<Rgb>, RenderStats) {
        let work = Self::new(scene, view, plan, opts, cancel, on_tile);
        match plan.sampling {
            Sampling::Spread(s) => work.spread(s),
            Sampling::Even { .. } | Sampling::Adaptive(_) => work.run(Rgb::ZERO, |p| p.sum.mean(p.taken)),
        }
    }

    /// The first pass of a render spread by noise, over the whole frame
    /// whatever `self.rect` is: `plan.first` samples of every pixel, each
    /// pixel's mean and variance (row-major over the frame), and the count
    /// of samples each pixel then takes (`crate::film::allocation`).
    fn first_pass(&self, plan: Spread) -> FirstPass {
        let f = self.view.film;
        let full = PixelRect::full(f.width, f.height);
        let first = Work {
            rect: full,
            samples: Samples::Every {
                first: 0,
                count: plan.first,
            },
            sampler_spp: plan.cap,
            squares: true,
            late_from: u32::MAX,
            pass: (0, 2),
            ..*self
        };
        let (pixels, stats) = first.run(([0.0f32; 3], 0.0f32), |p| {
            (p.sum.mean(p.taken).to_array(), p.variance())
        });
        if stats.cancelled {
            return (pixels, Vec::new(), stats);
        }
        let variance: Vec<f32> = pixels.iter().map(|f| f.1).collect();
        let upto = plan.counts(full.width() as usize, full.height() as usize, &variance);
        (pixels, upto, stats)
    }

    /// A render spread by noise (`crate::film::allocation`): `plan.first`
    /// samples everywhere, then each pixel up to its count; the pixels' means.
    fn spread(mut self, plan: Spread) -> (Vec<Rgb>, RenderStats) {
        let start = Instant::now();
        self.sampler_spp = plan.cap;
        let (first, upto, s1) = self.first_pass(plan);
        if s1.cancelled {
            return (first.iter().map(|f| Rgb::from_array(f.0)).collect(), s1);
        }
        let ranges: Vec<(u32, u32)> = upto.iter().map(|&u| (plan.first, u)).collect();
        drop(upto);
        let second = Work {
            samples: Samples::Ranges(&ranges),
            squares: false,
            pass: (1, 2),
            ..self
        };
        let rect = second.rect;
        // A weighted mean of the two passes' means; skipped tiles (on
        // cancel) keep the first pass's.
        let (pixels, s2) = second.run(Rgb::NAN, |p| {
            let m1 = Rgb::from_array(first[rect.index(p.x, p.y)].0);
            two_pass_mean(m1, plan.first, &p.sum, p.taken)
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

    /// A piece of a render spread by noise: the whole frame's first pass
    /// (every piece repeats it: the counts depend on the noise of pixels
    /// outside the piece, and on the frame's total), then the piece's
    /// share of each of its pixels' samples. Samples `a..b` of the frame's
    /// `spp` become samples `a·n/spp..b·n/spp` of a pixel that takes `n`,
    /// so pieces splitting `0..spp` split every pixel's samples, and the
    /// assembled sums are exactly the whole render's.
    fn spread_piece(mut self, plan: Spread, (a, b): (u32, u32)) -> (SampleSums, RenderStats) {
        let start = Instant::now();
        let spp = u64::from(plan.spp.max(1));
        self.sampler_spp = plan.cap;
        let (_, upto, s1) = self.first_pass(plan);
        let rect = self.rect;
        let mut out = SampleSums::new_spread(rect, plan.first);
        if s1.cancelled {
            return (out, s1);
        }
        let full = PixelRect::full(self.view.film.width, self.view.film.height);
        let part = |n: u32, k: u32| (u64::from(n) * u64::from(k) / spp) as u32;
        let ranges: Vec<(u32, u32)> = (rect.y0..rect.y1)
            .flat_map(|y| (rect.x0..rect.x1).map(move |x| (x, y)))
            .map(|(x, y)| {
                let n = upto[full.index(x, y)];
                (part(n, a), part(n, b))
            })
            .collect();
        drop(upto);
        let second = Work {
            samples: Samples::Ranges(&ranges),
            squares: false,
            late_from: plan.first,
            pass: (1, 2),
            ..self
        };
        let (pixels, s2) = second.run((ExactSum::ZERO, ExactSum::ZERO, 0u32), |p| {
            (p.sum, p.late, p.taken)
        });
        if let Some(spread) = &mut out.spread {
            for (i, (sum, late, taken)) in pixels.into_iter().enumerate() {
                out.sums[i] = sum;
                spread.late[i] = late;
                spread.counts[i] = taken;
            }
        }
        let stats = RenderStats {
            elapsed: start.elapsed(),
            samples: s1.samples + s2.samples,
            rays: s1.rays + s2.rays,
            cancelled: s1.cancelled || s2.cancelled,
        };
        (out, stats)
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
            Samples::Ranges(ranges) => heaviest_first(tiles, self.rect, ranges),
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
                // The path tracer without media takes first hits found
                // for it (see the sample loop).
                let paired = match &self.integrator {
                    Integrator::Path(p) if self.scene.media.is_none() => Some(p),
                    _ => None,
                };
                for y in tile.y0..tile.y1 {
                    for x in tile.x0..tile.x1 {
                        let (s0, spp) = match self.samples {
                            Samples::Every { first, count } => (first, count),
                            Samples::Ranges(ranges) => {
                                let (a, b) = ranges[self.rect.index(x, y)];
                                (a, b.saturating_sub(a))
                            }
                        };
                        let mut sum = SampleSum::ZERO;
                        let mut late = SampleSum::ZERO;
                        let mut squares = [0.0f64; 3];
                        let mut noise = PixelNoise::default();
                        let mut taken = spp;
                        pixel.set_pixel(x, y, s0..s0 + spp);
                        // One sample's radiance into the pixel's sums;
                        // `true` when the pixel has converged at it.
                        let mut add = |s: u32, li: Rgb, weight: f32| {
                            // A non-finite sample (a numerical bug, caught by
                            // debug asserts) must not poison the pixel in release.
                            let c = if li.is_finite() {
                                if weight == 1.0 { li } else { li * weight }
                            } else {
                                Rgb::ZERO
                            };
                            if s < self.late_from {
                                sum.add_sample(c);
                            } else {
                                late.add_sample(c);
                            }
                            if self.squares {
                                for (q, v) in squares.iter_mut().zip(c.to_array()) {
                                    *q += v as f64 * v as f64;
                                }
                            }
                            if let Some(a) = &self.adaptive {
                                noise.add(c);
                                if a.converged(&noise) {
                                    taken = s - s0 + 1;
                                    return true;
                                }
                            }
                            false
                        };
                        let end = s0 + spp;
                        let mut s = s0;
                        while s < end {
                            // Two samples at a time when the path tracer
                            // takes a first hit found for it: the two
                            // searches run back to back, and the processor
                            // overlaps them.
                            if let Some(path) = paired
                                && s + 1 < end
                            {
                                let (mut sa, mut sb) = (pixel.sample(s), pixel.sample(s + 1));
                                let (ra, wa) = self.view.camera_ray(x, y, &mut sa);
                                let (rb, wb) = self.view.camera_ray(x, y, &mut sb);
                                let (mut ha, mut hb) = (Hit::default(), Hit::default());
                                let fa = self.scene.intersect_into(&ra, f32::INFINITY, &mut ha);
                                let fb = self.scene.intersect_into(&rb, f32::INFINITY, &mut hb);
                                let la =
                                    path.li_first_found(self.scene, &ra, (fa, &ha), &mut sa, &mut counters);
                                if add(s, la, wa) {
                                    break;
                                }
                                let lb =
                                    path.li_first_found(self.scene, &rb, (fb, &hb), &mut sb, &mut counters);
                                if add(s + 1, lb, wb) {
                                    break;
                                }
                                s += 2;
                                continue;
                            }
                            let mut sampler = pixel.sample(s);
                            let (ray, weight) = self.view.camera_ray(x, y, &mut sampler);
                            let li = self.integrator.li(self.scene, &ray, &mut sampler, &mut counters);
                            if add(s, li, weight) {
                                break;
                            }
                            s += 1;
                        }
                        counters.samples += taken as u64;
                        px.push(finish(&PixelSums {
                            x,
                            y,
                            sum: sum.total(),
                            late: late.total(),
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
        let upto: Vec<(u32, u32)> = (0..rect.area())
            .map(|i| {
                let (x, y) = ((i % 40) as u32, (i / 40) as u32);
                (8, if x < 4 && y > 20 { 200 } else { 8 + x })
            })
            .collect();
        let order = heaviest_first(tiles.clone(), rect, &upto);
        let upto = &upto;
        let load = |t: &PixelRect| -> u64 {
            (t.y0..t.y1)
                .flat_map(|y| (t.x0..t.x1).map(move |x| upto[rect.index(x, y)].1 as u64 - 8))
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
        let flat = vec![(8, 8 + 4); rect.area() as usize];
        assert_eq!(heaviest_first(tiles.clone(), rect, &flat), tiles);
    }
}
