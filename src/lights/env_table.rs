//! Importance sampling of an equirectangular map in proportion to its
//! *bilinearly interpolated* luminance × sin θ, as Mitsuba 3's `envmap`
//! does (its `Hierarchical2D` over the interpolant), not a piecewise
//! constant per pixel.
//!
//! Why: the map is looked up bilinearly, so inside one pixel's cell the
//! radiance of a small sun falls from its peak to the sky's. A piecewise-
//! constant density there gives weights `L/pdf` from 0 to ~2× their mean,
//! and on an open scene under a 0.5° sun ronray was 1.5× noisier per sample
//! than Mitsuba (`tests/open_scenes.rs`' sun scenes, issue 37). Sampling the
//! interpolant makes `L/pdf` nearly constant: the cell (between four
//! neighbouring pixel centres) is chosen by its mean weight, the average of
//! its corners (by CDFs or alias tables, see below), then the point inside it
//! from the bilinear patch of the corners (pbrt-v4's `SampleBilinear`,
//! <https://pbr-book.org/4ed/Monte_Carlo_Integration/Sampling_Using_the_Inversion_Method#Bilinear%20Functions>):
//! a linear marginal in v, a linear conditional in u. The product of the
//! two is exactly the interpolant's density, so [`EnvTable::pdf`] agrees
//! with what [`EnvTable::sample`] draws.
//!
//! Cells follow the lookup's grid (`environment.rs`): pixel centres at
//! `u = (i + ½)/W` (wrapping across the seam) and `v = j/(H − 1)`, so there
//! are `W × (H − 1)` cells. Corner weights are `luminance × sin θ_j` of the
//! pixel, zero at the poles; every point the interpolated image lights
//! (away from the poles' measure-zero rows) has a non-zero density. Memory:
//! the CDFs with their guide tables (~5 bytes a cell) and the alias tables
//! (8 bytes a cell); the corner weights live in the map's
//! pixels, beside their radiance (`env_map.rs`, 4 bytes a pixel), so the
//! table's functions take the map.
//!
//! # Alias tables for independent numbers, CDFs for stratified ones
//! The cell is found by inverting a marginal CDF over rows and a
//! conditional CDF in the row (binary searches narrowed by guide tables,
//! as pbrt-v4's `PiecewiseConstant2D`), or by two alias tables (Walker–Vose,
//! `alias.rs`): one over the rows, then the row's own. Both give each cell
//! exactly its probability (the density, [`EnvTable::pdf_at`], is the
//! same); they differ in which numbers `u` lead to it.
//!
//! - Each search is a chain of dependent loads into tables of half a
//!   megabyte and more, and on `env_spheres` (one sky sample per vertex)
//!   those chains were 11% of the wall time: with the alias tables, one
//!   load each, it renders in 758–781 ms against 867–879 ms (seven and
//!   nine alternated runs, 256², 64 spp, `Independent`).
//! - An alias table is not monotone in `u`: stratified numbers (`Sobol`'s
//!   first draws, `Stratified`) reach the cells in proportion but no
//!   longer ordered across the sky. Alias tables for every draw raised the
//!   error of `env_spheres` with `Sobol` at 48 spp by 17% (0.0334 → 0.0390
//!   off the light pixels, four seeds): the first vertex's light sample
//!   is stratified over the sun's disc, and the penumbrae lost it.
//!
//! So the caller says which numbers it has ([`Draw`], from the sampler):
//! stratified draws take the CDFs, independent ones the alias tables.
//! `Sobol` keeps its error (0.0337 at 48 spp, four seeds) and is 2.5% faster
//! (its later vertices' draws are independent); `Independent` renders
//! gain the whole 12%. The point in the cell takes what the choice leaves
//! of `u` (15 bits and more on maps up to 512 cells a row, 11 at 8,192).

use super::alias::{Bin, fill_bins, pick};
use super::env_map::{EnvMap, Footprint};
use crate::cpu::prefetch_line;
use crate::math::piecewise::PiecewiseConstant2d;
use crate::sampler::Draw;
use glam::Vec2;
use rayon::prelude::*;

/// See the module docs.
#[derive(Clone, Debug)]
pub struct EnvTable {
    width: usize,
    /// Rows of pixels (H); cells have `max(H − 1, 1)` rows.
    height: usize,
    /// Chooses the cell by the mean of its corners, monotone in the
    /// numbers: for stratified draws.
    cells: PiecewiseConstant2d,
    /// Chooses the cell row, by the sum of its cells' means (alias table):
    /// for independent draws.
    row_bins: Vec<Bin>,
    /// Row `j`'s cells at `j·W..(j + 1)·W`: the alias table that chooses
    /// a cell of the row by the mean of its corners.
    cell_bins: Vec<Bin>,
    /// `W·(H − 1) / Σ cell means`: the density at a point is its
    /// interpolated corner weight times this (0 for a map without light,
    /// which is sampled uniformly).
    inv_mean: f32,
}

/// `x` ∈ [0, 1) with density ∝ `(1 − x) a + x b` (pbrt-v4's `SampleLinear`).
#[inline]
fn sample_linear(u: f32, a: f32, b: f32) -> f32 {
    if u == 0.0 && a == 0.0 {
        return 0.0;
    }
    let x = u * (a + b) / (a + ((1.0 - u) * a * a + u * b * b).sqrt());
    x.min(1.0 - f32::EPSILON / 2.0)
}

/// Density at `p` ∈ [0, 1]² of the bilinear patch of corners `w`
/// ((0,0), (1,0), (0,1), (1,1)); uniform (1) for a patch of zeros.
#[inline]
fn bilinear_pdf(p: Vec2, w: [f32; 4]) -> f32 {
    let sum = w[0] + w[1] + w[2] + w[3];
    if sum <= 0.0 {
        return 1.0;
    }
    4.0 * ((1.0 - p.x) * (1.0 - p.y) * w[0]
        + p.x * (1.0 - p.y) * w[1]
        + (1.0 - p.x) * p.y * w[2]
        + p.x * p.y * w[3])
        / sum
}

/// The bilinear patch of corners `w` ((0,0), (1,0), (0,1), (1,1)) at `p`.
#[inline]
fn bilerp(w: [f32; 4], p: Vec2) -> f32 {
    let top = w[0] + (w[1] - w[0]) * p.x;
    let bottom = w[2] + (w[3] - w[2]) * p.x;
    top + (bottom - top) * p.y
}

/// `weights` scaled to a mean of 1 (their sum is `sum`), as the alias
/// table wants them; all alike when they hold nothing.
fn scaled(mut weights: Vec<f64>, sum: f64) -> Vec<f64> {
    let n = weights.len() as f64;
    for x in weights.iter_mut() {
        *x = if sum > 0.0 && sum.is_finite() {
            *x * n / sum
        } else {
            1.0
        };
    }
    weights
}

impl EnvTable {
    /// The table of `map`, rows in parallel; writes the map's pixel
    /// weights first ([`EnvMap::fill_weights`]).
    pub fn new(map: &mut EnvMap) -> Self {
        map.fill_weights();
        let (w, h) = (map.width as usize, map.height as usize);
        let corners = |k: usize| map.texels[k][3];
        // A map of one row: its cells are that row against itself.
        let rows = (h - 1).max(1);
        // Cell (i, j)'s mean weight, the average of its corners (0 where
        // that is not a positive number).
        let mean = |i: usize, j: usize| {
            let (r0, r1) = (j * w, (j + 1).min(h - 1) * w);
            let i1 = if i + 1 == w { 0 } else { i + 1 };
            let m = 0.25 * (corners(r0 + i) + corners(r0 + i1) + corners(r1 + i) + corners(r1 + i1));
            if m.is_finite() && m > 0.0 { m } else { 0.0 }
        };
        // Each row's alias table over its cells, and the row's sum, in f64.
        let mut cell_bins = vec![Bin::default(); w * rows];
        let row_sums: Vec<f64> = cell_bins
            .par_chunks_mut(w)
            .enumerate()
            .map(|(j, bins)| {
                let means: Vec<f64> = (0..w).map(|i| mean(i, j) as f64).collect();
                let sum: f64 = means.iter().sum();
                fill_bins(scaled(means, sum), bins);
                sum
            })
            .collect();
        // Σ of the cell means, the integral of the interpolant over the
        // cells (in cell units).
        let sum: f64 = row_sums.iter().sum();
        let mut row_bins = vec![Bin::default(); rows];
        fill_bins(scaled(row_sums, sum), &mut row_bins);
        let inv_mean = ((w * rows) as f64 / sum) as f32;
        // No light (or weights too small for the density's f32): every cell
        // alike (each bin keeps its own entry, and names itself as its
        // alias for a number that rounds to the bin's top).
        let uniform = !(sum > 0.0 && inv_mean.is_finite());
        if uniform {
            fill_bins(vec![1.0; rows], &mut row_bins);
            for bins in cell_bins.chunks_mut(w) {
                fill_bins(vec![1.0; w], bins);
            }
        }
        let cells = PiecewiseConstant2d::new(w, rows, |j, out| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = if uniform { 1.0 } else { mean(i, j) };
            }
        });
        Self {
            width: w,
            height: h,
            cells,
            row_bins,
            cell_bins,
            inv_mean: if uniform { 0.0 } else { inv_mean },
        }
    }

    /// The footprint of cell `(i, j)`'s corners, at `f` inside it.
    #[inline]
    fn cell(&self, i: usize, j: usize, f: Vec2) -> Footprint {
        Footprint {
            i: [i as u32, if i + 1 == self.width { 0 } else { i as u32 + 1 }],
            j: [j as u32, (j + 1).min(self.height - 1) as u32],
            f,
        }
    }

    /// Cell rows.
    #[inline]
    fn rows(&self) -> usize {
        (self.height - 1).max(1)
    }

    /// Image coordinates `(u, v)` ∈ [0, 1)² of `map` (the one the table was
    /// built from) for `u` ∈ [0, 1)², their density with respect to area on
    /// [0, 1)², and their footprint (for the radiance there without a
    /// second search).
    #[inline]
    pub fn sample(&self, map: &EnvMap, u: Vec2, draw: Draw) -> (Vec2, f32, Footprint) {
        // The cell, and where in it: uniform, as the choice left it.
        let (w, rows) = (self.width, self.rows());
        let (i, j, fx, fy) = match draw {
            Draw::Independent => {
                let (j, fy) = pick(&self.row_bins, u.y);
                let (i, fx) = pick(&self.cell_bins[j * w..(j + 1) * w], u.x);
                (i, j, fx, fy)
            }
            Draw::Stratified => {
                let (q, _) = self.cells.sample(u);
                let (x, y) = (q.x * w as f32, q.y * rows as f32);
                let (i, j) = ((x as usize).min(w - 1), (y as usize).min(rows - 1));
                (
                    i,
                    j,
                    (x - i as f32).clamp(0.0, 1.0),
                    (y - j as f32).clamp(0.0, 1.0),
                )
            }
        };
        let mut at = self.cell(i, j, Vec2::ZERO);
        let c = map.weights(&at);
        let by = sample_linear(fy, c[0] + c[1], c[2] + c[3]);
        let bx = sample_linear(fx, (1.0 - by) * c[0] + by * c[2], (1.0 - by) * c[1] + by * c[3]);
        let f = Vec2::new(bx, by);
        let pdf = if self.inv_mean > 0.0 {
            bilerp(c, f) * self.inv_mean
        } else {
            bilinear_pdf(f, c)
        };
        let (w, rows) = (w as f32, rows as f32);
        // Cells start half a pixel in; the last wraps across the seam.
        let mut uu = (i as f32 + 0.5 + bx) / w;
        if uu >= 1.0 {
            uu -= 1.0;
        }
        // (A map of one row is constant in v: its one cell row spans it all.)
        let vv = (j as f32 + by) / rows;
        at.f = f;
        (
            Vec2::new(uu.clamp(0.0, 1.0 - f32::EPSILON), vv.clamp(0.0, 1.0)),
            pdf,
            at,
        )
    }

    /// Asks for the cache lines an independent draw `u` will read in
    /// [`Self::sample`]: the cell's alias bin and, for the cell the bin
    /// keeps, the map's two rows of corner weights. The row is chosen from
    /// a table of a few hundred bins, in cache; the cells' table (8 bytes a
    /// cell) and the map (16 a pixel) are megabytes, and the sample read
    /// them one after the other: the bin's load was a third of
    /// `env_spheres`' light sample (perf). Called when the numbers are
    /// drawn, so the misses overlap the BSDF's sampling. Changes nothing
    /// but timing.
    #[inline]
    pub fn prefetch(&self, map: &EnvMap, u: Vec2) {
        let (j, _) = pick(&self.row_bins, u.y);
        let w = self.width;
        let i = ((u.x * w as f32) as usize).min(w - 1);
        let at = self.cell(i, j, Vec2::ZERO);
        prefetch_line(self.cell_bins.as_ptr().wrapping_add(j * w + i).cast());
        for r in at.j {
            prefetch_line(map.texels.as_ptr().wrapping_add(r as usize * w + i).cast());
        }
    }

    /// Density of [`Self::sample`] at the point of `at` (the footprint
    /// [`EnvMap::footprint`] gives for its image coordinates) of `map`.
    #[inline]
    pub fn pdf_at(&self, map: &EnvMap, at: &Footprint) -> f32 {
        let c = map.weights(at);
        if self.inv_mean > 0.0 {
            bilerp(c, at.f) * self.inv_mean
        } else {
            bilinear_pdf(at.f, c)
        }
    }

    /// Density of [`Self::sample`] at image coordinates `uv` of `map`, by
    /// its own grid walk: the tests' check of [`Self::pdf_at`]'s agreement
    /// with what is sampled (the renderer goes through the lookup's
    /// footprint).
    #[cfg(test)]
    pub fn pdf(&self, map: &EnvMap, uv: Vec2) -> f32 {
        let (w, rows) = (self.width as f32, self.rows() as f32);
        let mut x = uv.x * w - 0.5;
        if x < 0.0 {
            x += w;
        }
        let i = (x as usize).min(self.width - 1);
        let fx = (x - i as f32).clamp(0.0, 1.0);
        let y = (uv.y * rows).clamp(0.0, rows);
        let j = (y as usize).min(self.rows() - 1);
        let fy = (y - j as f32).clamp(0.0, 1.0);
        let c = map.weights(&self.cell(i, j, Vec2::ZERO));
        if self.inv_mean > 0.0 {
            return bilerp(c, Vec2::new(fx, fy)) * self.inv_mean;
        }
        bilinear_pdf(Vec2::new(fx, fy), c)
    }

    /// Heap bytes of the tables (the weights are the map's).
    pub fn bytes(&self) -> usize {
        self.cells.bytes() + std::mem::size_of::<Bin>() * (self.row_bins.len() + self.cell_bins.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;
    use std::f32::consts::PI;

    const DRAWS: [Draw; 2] = [Draw::Stratified, Draw::Independent];

    fn map(w: u32, h: u32, f: impl Fn(u32, u32) -> f32) -> EnvMap {
        let mut rgb = Vec::new();
        for j in 0..h {
            for i in 0..w {
                let l = f(i, j);
                rgb.extend_from_slice(&[l, l, l]);
            }
        }
        EnvMap::from_rgb(w, h, &rgb)
    }

    #[test]
    fn sample_linear_inverts_a_linear_density() {
        for (a, b) in [(1.0, 1.0), (0.0, 1.0), (1.0, 0.0), (0.2, 3.0)] {
            // CDF of (1−x)a + xb normalised, at the sampled point, is u.
            for k in 0..100 {
                let u = (k as f32 + 0.5) / 100.0;
                let x = sample_linear(u, a, b);
                let cdf = (a * x + 0.5 * (b - a) * x * x) / (0.5 * (a + b));
                assert!((cdf - u).abs() < 1e-4, "a {a} b {b} u {u}: cdf {cdf}");
            }
        }
    }

    /// `prefetch` reads only the rows' table, at the cell the numbers
    /// start from, for every size of map down to one pixel and numbers at
    /// the ends of [0, 1): it is called on every independent draw, before
    /// the light is even picked, so it must never index out of range.
    #[test]
    fn prefetch_takes_any_numbers_on_any_map() {
        let top = 1.0 - f32::EPSILON / 2.0;
        for (w, h) in [(1, 1), (1, 5), (7, 1), (2, 2), (64, 32)] {
            let mut m = map(w, h, |i, j| 1.0 + (i * 3 + j) as f32);
            let t = EnvTable::new(&mut m);
            for u in [0.0, 0.5, top] {
                for v in [0.0, 0.5, top] {
                    t.prefetch(&m, Vec2::new(u, v));
                }
            }
        }
    }

    #[test]
    fn samples_agree_with_the_pdf_and_the_pdf_integrates_to_one() {
        let mut rng = Pcg32::new(3, 9);
        let m = map(37, 19, |i, j| {
            if (i * 7 + j * 3) % 5 == 0 {
                4.0
            } else {
                0.1 + (i % 3) as f32
            }
        });
        let mut m = m;
        let t = EnvTable::new(&mut m);
        for draw in DRAWS {
            for _ in 0..20_000 {
                let (uv, pdf, _) = t.sample(&m, rng.next_vec2(), draw);
                assert!(pdf > 0.0);
                let again = t.pdf(&m, uv);
                assert!(
                    (again - pdf).abs() <= 2e-3 * pdf,
                    "{draw:?} {uv}: {pdf} vs {again}"
                );
            }
        }
        let n = 400_000;
        let sum: f64 = (0..n).map(|_| t.pdf(&m, rng.next_vec2()) as f64).sum();
        assert!((sum / n as f64 - 1.0).abs() < 0.01, "∫ pdf = {}", sum / n as f64);
    }

    /// Each cell is drawn as often as its mean weight says (the alias
    /// tables' and the CDFs' frequencies, not only their density's
    /// agreement with the sampled points), empty cells never, and the
    /// number left over for the point in the cell is uniform.
    #[test]
    fn cells_are_drawn_in_proportion_to_their_means() {
        for draw in DRAWS {
            cells_drawn_in_proportion(draw);
        }
    }

    fn cells_drawn_in_proportion(draw: Draw) {
        let (w, h) = (9u32, 7u32);
        let mut m = map(w, h, |i, j| match (i, j) {
            (0..=2, 0..=2) => 0.0,
            (4, 3) => 60.0,
            _ => 0.5 + ((i * 5 + j * 3) % 7) as f32,
        });
        let t = EnvTable::new(&mut m);
        let (w, rows) = (w as usize, (h - 1) as usize);
        let mean = |i: usize, j: usize| {
            let c = m.weights(&t.cell(i, j, Vec2::ZERO));
            0.25 * (c[0] + c[1] + c[2] + c[3]) as f64
        };
        let total: f64 = (0..rows)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| mean(i, j))
            .sum();
        let mut counts = vec![0u32; w * rows];
        let mut rng = Pcg32::new(21, 4);
        let n = 600_000;
        let mut f_sum = Vec2::ZERO;
        for _ in 0..n {
            let (_, pdf, at) = t.sample(&m, rng.next_vec2(), draw);
            assert!(pdf > 0.0);
            counts[at.j[0] as usize * w + at.i[0] as usize] += 1;
            f_sum += at.f;
        }
        for j in 0..rows {
            for i in 0..w {
                let want = mean(i, j) / total;
                let got = counts[j * w + i] as f64 / n as f64;
                // Four standard deviations of a binomial count.
                let sigma = (want * (1.0 - want) / n as f64).sqrt();
                assert!(
                    (got - want).abs() <= 4.0 * sigma + 1e-7,
                    "{draw:?} cell ({i}, {j}): {got} vs {want}"
                );
                if want == 0.0 {
                    assert_eq!(counts[j * w + i], 0, "empty cell ({i}, {j}) drawn");
                }
            }
        }
        // Inside their cells the points spread (the bilinear warp of a
        // uniform pair): means well inside (0, 1).
        let f_mean = f_sum / n as f32;
        assert!(
            f_mean.min_element() > 0.3 && f_mean.max_element() < 0.7,
            "{f_mean}"
        );
    }

    /// A small sun: weights `L sin θ / pdf` of samples nearly equal (they
    /// ranged 0 to ~2× with a density constant per pixel).
    /// Maps of one row or one column: still a density over the whole
    /// square that matches what is sampled.
    #[test]
    fn one_row_and_one_column_maps_cover_the_square() {
        let mut rng = Pcg32::new(5, 5);
        for (w, h) in [(1, 1), (1, 7), (9, 1)] {
            let mut m = map(w, h, |i, j| 1.0 + (i + 2 * j) as f32);
            let t = EnvTable::new(&mut m);
            let n = 100_000;
            let sum: f64 = (0..n).map(|_| t.pdf(&m, rng.next_vec2()) as f64).sum();
            assert!(
                (sum / n as f64 - 1.0).abs() < 0.02,
                "{w}×{h}: ∫ pdf = {}",
                sum / n as f64
            );
            for draw in DRAWS {
                let (mut lo, mut hi) = (1.0f32, 0.0f32);
                for _ in 0..2000 {
                    let (uv, pdf, _) = t.sample(&m, rng.next_vec2(), draw);
                    assert!((t.pdf(&m, uv) - pdf).abs() <= 2e-3 * pdf, "{w}×{h} at {uv}");
                    lo = lo.min(uv.y);
                    hi = hi.max(uv.y);
                }
                assert!(lo < 0.1 && hi > 0.9, "{draw:?} {w}×{h}: v from {lo} to {hi}");
            }
        }
    }

    #[test]
    fn a_small_suns_samples_carry_nearly_equal_weights() {
        let (w, h) = (360u32, 181u32);
        let m = map(w, h, |i, j| {
            if (i == 100 || i == 101) && (j == 60 || j == 61) {
                1e4
            } else {
                0.0
            }
        });
        let mut m = m;
        let t = EnvTable::new(&mut m);
        let mut rng = Pcg32::new(1, 1);
        for draw in DRAWS {
            let (mut lo, mut hi) = (f32::INFINITY, 0.0f32);
            for _ in 0..10_000 {
                let (uv, pdf, _) = t.sample(&m, rng.next_vec2(), draw);
                let l = m.lookup(uv).x;
                let weight = l * (PI * uv.y).sin() / pdf;
                lo = lo.min(weight);
                hi = hi.max(weight);
            }
            assert!(hi / lo < 1.1, "{draw:?}: weights from {lo} to {hi}");
        }
    }
}
