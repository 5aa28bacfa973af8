//! The regression metric: each region of the render is tested against the
//! noise of the sampling that made it.
//!
//! Both images are cut into cells of [`COMPARE_FACTOR`]×[`COMPARE_FACTOR`]
//! pixels. Per cell and channel, the cell means differ by `d`. Its noise is
//! measured from the sampling itself, not from the images' content: renders
//! of the scene with other seeds give each pixel's variance
//! ([`variance_of`], kept beside the golden image), and a cell mean's
//! variance `v` is the sum of its pixels' over `n²` (every pixel is an
//! independent estimate: one random stream per pixel and sample). The
//! cell's statistic is `d² / (2v + (0.01·(g + 0.01))²)`, the squared z-score
//! of the difference of two independent renders, with a 1% relative floor
//! (8-bit quantisation, noise-free regions). Two guards keep rare bright
//! samples from failing a check:
//!
//! - `v` is raised to the mean of its 3×3 neighbourhood of cells where that
//!   is larger, so a cell where the variance renders happened to draw no
//!   bright sample does not look noise-free;
//! - in each cell the largest pixel difference is clamped to the second
//!   largest: one firefly moves one pixel, a changed object several.
//!
//! The score is the largest mean of the statistic over every
//! [`WINDOW`]×[`WINDOW`] block of cells (8×8 pixels, stride one cell, so a
//! change on a block border is not split in two). Noise alone averages about
//! 1 per window and, at the worst window of a 64-pixel render, 1.5–4.5
//! (`tests/check.rs`); a small sphere 3 pixels across recoloured or halved
//! scores 13 and more.
//!
//! This is the per-pixel z-test of Mitsuba's render tests (reference mean
//! and variance images), pooled over a cell and a window so that one unlucky
//! pixel does not fail a check. The previous metric took each cell's pixel
//! spread for its noise: the edges of a small object then hid that object's
//! change (issue 46).
//!
//! A whole-image mean (relative MSE) dilutes a small wrong region by the
//! image's area and cannot tell a noisy scene from a changed one; it is kept
//! in [`Score::whole`] for the summary only.

use crate::imageio::Image;
use crate::math::Rgb;

/// Side of a cell, in pixels.
pub const COMPARE_FACTOR: u32 = 4;
/// Side of the sliding window, in cells (8×8 pixels).
pub const WINDOW: u32 = 2;
/// Relative floor of the noise standard deviation.
const REL_FLOOR: f64 = 0.01;

/// How far a render is from its golden image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Score {
    /// Largest window mean of the squared z-scores: what is judged.
    pub worst: f64,
    /// Top-left pixel of the worst window.
    pub at: (u32, u32),
    /// Whole-image relative MSE, `mean((a − g)² / (g² + 0.01))` over the
    /// cells' means, for information.
    pub whole: f64,
}

/// Each pixel's variance from renders that differ only in their seed: the
/// unbiased sample variance per channel (`(a − b)²/2` for two), an estimate
/// of one render's.
pub fn variance_of(renders: &[Image]) -> Result<Image, String> {
    let Some(first) = renders.first() else {
        return Err("no renders to measure noise from".into());
    };
    for r in renders {
        same_size(first, r)?;
    }
    let k = renders.len() as f32;
    let mut out = first.clone();
    for (i, o) in out.pixels.iter_mut().enumerate() {
        let mean = renders.iter().fold(Rgb::ZERO, |s, r| s + r.pixels[i]) / k;
        let squares = renders.iter().fold(Rgb::ZERO, |s, r| {
            let d = r.pixels[i] - mean;
            s + d * d
        });
        *o = squares / (k - 1.0).max(1.0);
    }
    Ok(out)
}

fn same_size(a: &Image, b: &Image) -> Result<(), String> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!(
            "image sizes differ: {}×{} vs {}×{}",
            a.width, a.height, b.width, b.height
        ));
    }
    Ok(())
}

/// One cell and channel: the mean difference (its largest pixel difference
/// clamped to the second largest), the golden's mean, and the variance of
/// one render's cell mean.
#[derive(Clone, Copy, Default)]
struct Cell {
    d: f64,
    g: f64,
    v: f64,
}

fn cells(new: &Image, golden: &Image, variance: &Image, factor: u32) -> Vec<[Cell; 3]> {
    let (w, h) = (new.width / factor, new.height / factor);
    let n = (factor * factor) as f64;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let at = |i: u32| (x * factor + i % factor, y * factor + i / factor);
            out.push(std::array::from_fn(|c| {
                let mut deltas: Vec<f64> = (0..factor * factor)
                    .map(|i| {
                        let (px, py) = at(i);
                        new.get(px, py)[c] as f64 - golden.get(px, py)[c] as f64
                    })
                    .collect();
                let mut order: Vec<usize> = (0..deltas.len()).collect();
                order.sort_by(|&a, &b| deltas[b].abs().total_cmp(&deltas[a].abs()));
                if let [top, second, ..] = order[..] {
                    deltas[top] = deltas[top].signum() * deltas[second].abs();
                }
                let sum = |img: &Image| {
                    (0..factor * factor)
                        .map(|i| img.get(at(i).0, at(i).1)[c] as f64)
                        .sum::<f64>()
                };
                Cell {
                    d: deltas.iter().sum::<f64>() / n,
                    g: sum(golden) / n,
                    v: sum(variance) / (n * n),
                }
            }));
        }
    }
    out
}

/// Each cell's variance raised to the mean of its 3×3 neighbourhood where
/// that is larger.
fn pooled(cells: &mut [[Cell; 3]], w: usize, h: usize) {
    let own: Vec<[f64; 3]> = cells.iter().map(|c| c.map(|x| x.v)).collect();
    for y in 0..h {
        for x in 0..w {
            let (mut s, mut k) = ([0.0; 3], 0.0);
            for yy in y.saturating_sub(1)..(y + 2).min(h) {
                for xx in x.saturating_sub(1)..(x + 2).min(w) {
                    k += 1.0;
                    for (c, v) in s.iter_mut().enumerate() {
                        *v += own[yy * w + xx][c];
                    }
                }
            }
            for (c, cell) in cells[y * w + x].iter_mut().enumerate() {
                cell.v = cell.v.max(s[c] / k);
            }
        }
    }
}

/// Scores `new` against `golden`, `variance` the per-pixel variance of one
/// render at the same settings ([`variance_of`]). All three must have the
/// same size.
pub fn score(new: &Image, golden: &Image, variance: &Image) -> Result<Score, String> {
    same_size(new, golden)?;
    same_size(new, variance)?;
    let factor = COMPARE_FACTOR.min(new.width).min(new.height).max(1);
    let (w, h) = ((new.width / factor) as usize, (new.height / factor) as usize);
    let mut cells = cells(new, golden, variance, factor);
    pooled(&mut cells, w, h);
    let mut whole = 0.0;
    let z: Vec<f64> = cells
        .iter()
        .map(|cell| {
            let mut s = 0.0;
            for &Cell { d, g, v } in cell {
                whole += d * d / (g * g + 0.01) / 3.0;
                let floor = (REL_FLOOR * (g + 0.01)).powi(2);
                s += d * d / (2.0 * v + floor);
            }
            s / 3.0
        })
        .collect();
    let whole = whole / z.len().max(1) as f64;
    // Window sums from a summed-area table.
    let mut sat = vec![0.0f64; (w + 1) * (h + 1)];
    for y in 0..h {
        for x in 0..w {
            sat[(y + 1) * (w + 1) + x + 1] =
                z[y * w + x] + sat[y * (w + 1) + x + 1] + sat[(y + 1) * (w + 1) + x] - sat[y * (w + 1) + x];
        }
    }
    let (ww, wh) = ((WINDOW as usize).min(w).max(1), (WINDOW as usize).min(h).max(1));
    let mut best = Score {
        worst: 0.0,
        at: (0, 0),
        whole,
    };
    for y in 0..=h.saturating_sub(wh) {
        for x in 0..=w.saturating_sub(ww) {
            let s =
                sat[(y + wh) * (w + 1) + x + ww] - sat[y * (w + 1) + x + ww] - sat[(y + wh) * (w + 1) + x]
                    + sat[y * (w + 1) + x];
            let mean = s / (ww * wh) as f64;
            if mean > best.worst {
                best.worst = mean;
                best.at = (x as u32 * factor, y as u32 * factor);
            }
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `k` renders of a flat grey 64×64 image with pixel noise of standard
    /// deviation 0.05, each from its own stream.
    fn renders(k: u64) -> Vec<Image> {
        (0..k)
            .map(|s| {
                let mut rng = crate::math::Pcg32::new(s, 2);
                let mut img = Image::new(64, 64);
                // Uniform on ±√3·σ has deviation σ.
                let mut x = || 0.5 + 0.05 * 3f32.sqrt() * (2.0 * rng.next_f32() - 1.0);
                for p in &mut img.pixels {
                    *p = Rgb::new(x(), x(), x());
                }
                img
            })
            .collect()
    }

    /// Noise alone scores about 1 per window and stays low at the worst;
    /// nine pixels (a small object) changed by six deviations fail; one
    /// firefly does not.
    #[test]
    fn score_catches_a_few_pixels_and_forgives_one_firefly() {
        let r = renders(6);
        let variance = variance_of(&r[2..]).expect("same sizes");
        let (golden, new) = (&r[0], &r[1]);
        let quiet = score(new, golden, &variance).expect("same size");
        assert!(quiet.worst < 5.0, "noise alone scores {}", quiet.worst);
        let mut changed = new.clone();
        for y in 20..23 {
            for x in 40..43 {
                changed.pixels[y * 64 + x] += Rgb::new(0.0, 0.3, -0.3);
            }
        }
        let s = score(&changed, golden, &variance).expect("same size");
        assert!(
            s.worst > 8.0,
            "nine changed pixels score {} (noise {})",
            s.worst,
            quiet.worst
        );
        assert!(
            (32..=40).contains(&s.at.0) && (16..=20).contains(&s.at.1),
            "{:?}",
            s.at
        );
        let mut firefly = new.clone();
        firefly.pixels[30 * 64 + 30] = Rgb::splat(50.0);
        let f = score(&firefly, golden, &variance).expect("same size");
        assert!(f.worst < 5.0, "one firefly scores {}", f.worst);
        assert_eq!(score(golden, golden, &variance).expect("same").worst, 0.0);
        assert!(score(new, &Image::new(8, 8), &variance).is_err());
    }

    #[test]
    fn variance_of_two_is_half_the_squared_difference() {
        let (mut a, mut b) = (Image::new(1, 1), Image::new(1, 1));
        a.pixels[0] = Rgb::new(1.0, 0.0, 2.0);
        b.pixels[0] = Rgb::new(0.0, 0.0, 4.0);
        let v = variance_of(&[a, b]).expect("same size");
        assert_eq!(v.pixels[0], Rgb::new(0.5, 0.0, 2.0));
    }
}
