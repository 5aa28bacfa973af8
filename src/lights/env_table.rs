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
//! its corners, from a [`PiecewiseConstant2d`], then the point inside it
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
//! the CDF tables (~5 bytes a pixel); the corner weights live in the map's
//! pixels, beside their radiance (`env_map.rs`, 4 bytes a pixel), so the
//! table's functions take the map.

use super::env_map::{EnvMap, Footprint};
use crate::math::piecewise::PiecewiseConstant2d;
use glam::Vec2;
use rayon::prelude::*;

/// See the module docs.
#[derive(Clone, Debug)]
pub struct EnvTable {
    width: usize,
    /// Rows of pixels (H); cells have `max(H − 1, 1)` rows.
    height: usize,
    /// Chooses the cell, by the mean of its corners.
    cells: PiecewiseConstant2d,
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

impl EnvTable {
    /// The table of `map`, rows in parallel; writes the map's pixel
    /// weights first ([`EnvMap::fill_weights`]).
    pub fn new(map: &mut EnvMap) -> Self {
        map.fill_weights();
        let (w, h) = (map.width as usize, map.height as usize);
        let corners = |k: usize| map.texels[k][3];
        // A map of one row: its cells are that row against itself.
        let rows = (h - 1).max(1);
        let cells = PiecewiseConstant2d::new(w, rows, |j, out| {
            let (r0, r1) = (j * w, (j + 1).min(h - 1) * w);
            for (i, o) in out.iter_mut().enumerate() {
                let i1 = if i + 1 == w { 0 } else { i + 1 };
                *o = 0.25 * (corners(r0 + i) + corners(r0 + i1) + corners(r1 + i) + corners(r1 + i1));
            }
        });
        // Σ of the cell means, the integral of the interpolant over the
        // cells (in cell units), in f64.
        let sum: f64 = (0..rows)
            .into_par_iter()
            .map(|j| {
                let (r0, r1) = (j * w, (j + 1).min(h - 1) * w);
                (0..w)
                    .map(|i| {
                        let i1 = if i + 1 == w { 0 } else { i + 1 };
                        0.25 * (corners(r0 + i) + corners(r0 + i1) + corners(r1 + i) + corners(r1 + i1))
                            as f64
                    })
                    .sum::<f64>()
            })
            .sum();
        let inv_mean = (w * rows) as f64 / sum;
        Self {
            width: w,
            height: h,
            cells,
            inv_mean: if inv_mean.is_finite() && sum > 0.0 {
                inv_mean as f32
            } else {
                0.0
            },
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
    pub fn sample(&self, map: &EnvMap, u: Vec2) -> (Vec2, f32, Footprint) {
        let (q, cell_pdf) = self.cells.sample(u);
        let (w, rows) = (self.width as f32, self.rows() as f32);
        // The cell, and where in it: uniform, as the inversion left it.
        let (x, y) = (q.x * w, q.y * rows);
        let (i, j) = (
            (x as usize).min(self.width - 1),
            (y as usize).min(self.rows() - 1),
        );
        let (fx, fy) = ((x - i as f32).clamp(0.0, 1.0), (y - j as f32).clamp(0.0, 1.0));
        let mut at = self.cell(i, j, Vec2::ZERO);
        let c = map.weights(&at);
        let by = sample_linear(fy, c[0] + c[1], c[2] + c[3]);
        let bx = sample_linear(fx, (1.0 - by) * c[0] + by * c[2], (1.0 - by) * c[1] + by * c[3]);
        let f = Vec2::new(bx, by);
        let pdf = if self.inv_mean > 0.0 {
            bilerp(c, f) * self.inv_mean
        } else {
            cell_pdf * bilinear_pdf(f, c)
        };
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

    /// Density of [`Self::sample`] at the point of `at` (the footprint
    /// [`EnvMap::footprint`] gives for its image coordinates) of `map`.
    #[inline]
    pub fn pdf_at(&self, map: &EnvMap, at: &Footprint) -> f32 {
        let c = map.weights(at);
        if self.inv_mean > 0.0 {
            bilerp(c, at.f) * self.inv_mean
        } else {
            1.0
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
        let cell = Vec2::new((i as f32 + 0.5) / w, (j as f32 + 0.5) / rows);
        self.cells.pdf(cell) * bilinear_pdf(Vec2::new(fx, fy), c)
    }

    /// Heap bytes of the tables (the weights are the map's).
    pub fn bytes(&self) -> usize {
        self.cells.bytes()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;
    use std::f32::consts::PI;

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
        for _ in 0..20_000 {
            let (uv, pdf, _) = t.sample(&m, rng.next_vec2());
            assert!(pdf > 0.0);
            let again = t.pdf(&m, uv);
            assert!((again - pdf).abs() <= 2e-3 * pdf, "{uv}: {pdf} vs {again}");
        }
        let n = 400_000;
        let sum: f64 = (0..n).map(|_| t.pdf(&m, rng.next_vec2()) as f64).sum();
        assert!((sum / n as f64 - 1.0).abs() < 0.01, "∫ pdf = {}", sum / n as f64);
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
            let (mut lo, mut hi) = (1.0f32, 0.0f32);
            for _ in 0..2000 {
                let (uv, pdf, _) = t.sample(&m, rng.next_vec2());
                assert!((t.pdf(&m, uv) - pdf).abs() <= 2e-3 * pdf, "{w}×{h} at {uv}");
                lo = lo.min(uv.y);
                hi = hi.max(uv.y);
            }
            assert!(lo < 0.1 && hi > 0.9, "{w}×{h}: v from {lo} to {hi}");
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
        let (mut lo, mut hi) = (f32::INFINITY, 0.0f32);
        for _ in 0..10_000 {
            let (uv, pdf, _) = t.sample(&m, rng.next_vec2());
            let l = m.lookup(uv).x;
            let weight = l * (PI * uv.y).sin() / pdf;
            lo = lo.min(weight);
            hi = hi.max(weight);
        }
        assert!(hi / lo < 1.1, "weights from {lo} to {hi}");
    }
}
