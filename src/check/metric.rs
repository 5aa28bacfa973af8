//! The regression metric: each region of the render is tested against the
//! noise level measured in that region.
//!
//! Both images are cut into cells of [`COMPARE_FACTOR`]×[`COMPARE_FACTOR`]
//! pixels. Per cell and channel, the cell means differ by `d`, and the
//! spread of the cell's pixels gives the noise variance of that mean in each
//! image, `s²/n` (every pixel is an independent estimate: one random stream
//! per pixel and sample). The cell's statistic is
//! `d² / (s²_new/n + s²_golden/n + (0.01·(g + 0.01))²)`, a squared z-score
//! with a 1% relative floor (8-bit quantisation, noise-free regions). The
//! score is its largest mean over every [`WINDOW`]×[`WINDOW`] block of cells
//! (16×16 pixels, stride one cell, so a change on a block border is not
//! split in two). Two renders that differ only by noise average about 1 in
//! every window (less where edges and textures add to the spread, which
//! makes the test conservative there); a change the size of a small object
//! scores several times that. This is the per-pixel z-test of Mitsuba's
//! render tests, with the variance estimated from the images themselves and
//! pooled over a window so that one unlucky pixel does not fail a check.
//!
//! A whole-image mean (the previous metric, relative MSE) dilutes a small
//! wrong region by the image's area and cannot tell a noisy scene from a
//! changed one; it is kept in [`Score::whole`] for the summary only.

use crate::imageio::Image;

/// Side of a cell, in pixels.
pub const COMPARE_FACTOR: u32 = 4;
/// Side of the sliding window, in cells (16×16 pixels of the test render).
pub const WINDOW: u32 = 4;
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

/// Mean and unbiased variance of the pixels of one cell, per channel.
type Cell = [(f64, f64); 3];

fn cells(img: &Image, factor: u32) -> Vec<Cell> {
    let (w, h) = (img.width / factor, img.height / factor);
    let n = (factor * factor) as f64;
    let mut out = Vec::with_capacity((w * h) as usize);
    for y in 0..h {
        for x in 0..w {
            let px = |i: u32, c: usize| img.get(x * factor + i % factor, y * factor + i / factor)[c] as f64;
            out.push(std::array::from_fn(|c| {
                let mean = (0..factor * factor).map(|i| px(i, c)).sum::<f64>() / n;
                let var = (0..factor * factor)
                    .map(|i| (px(i, c) - mean).powi(2))
                    .sum::<f64>()
                    / (n - 1.0).max(1.0);
                (mean, var)
            }));
        }
    }
    out
}

/// Scores `new` against `golden` (sizes must match).
pub fn score(new: &Image, golden: &Image) -> Result<Score, String> {
    if (new.width, new.height) != (golden.width, golden.height) {
        return Err(format!(
            "image sizes differ: {}×{} vs {}×{}",
            new.width, new.height, golden.width, golden.height
        ));
    }
    let factor = COMPARE_FACTOR.min(new.width).min(new.height).max(1);
    let (a, g) = (cells(new, factor), cells(golden, factor));
    let (w, h) = ((new.width / factor) as usize, (new.height / factor) as usize);
    let n = (factor * factor) as f64;
    let mut whole = 0.0;
    let z: Vec<f64> = a
        .iter()
        .zip(&g)
        .map(|(ca, cg)| {
            let mut s = 0.0;
            for c in 0..3 {
                let d = ca[c].0 - cg[c].0;
                whole += d * d / (cg[c].0 * cg[c].0 + 0.01) / 3.0;
                let floor = (REL_FLOOR * (cg[c].0 + 0.01)).powi(2);
                s += d * d / ((ca[c].1 + cg[c].1) / n + floor);
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
    use crate::math::Rgb;

    /// Noise of a fixed level everywhere, and a 16×16 patch brightened by
    /// about four deviations of a cell mean: the whole-image figure barely
    /// moves, the window over the patch stands out.
    #[test]
    fn score_finds_a_small_wrong_region_against_noise() {
        let mut rng = crate::math::Pcg32::new(1, 2);
        let mut noisy = || {
            let mut img = Image::new(64, 64);
            for p in &mut img.pixels {
                *p = Rgb::splat(0.5 + 0.1 * (rng.next_f32() - 0.5));
            }
            img
        };
        let (g, a) = (noisy(), noisy());
        let quiet = score(&a, &g).expect("same size");
        assert!(quiet.worst < 2.5, "noise alone scores {}", quiet.worst);
        let mut b = a.clone();
        for y in 20..36 {
            for x in 40..56 {
                b.pixels[y * 64 + x] += Rgb::splat(0.05);
            }
        }
        let s = score(&b, &g).expect("same size");
        assert!(
            s.worst > 4.0 * quiet.worst,
            "patch scores {}, noise {}",
            s.worst,
            quiet.worst
        );
        assert!(s.whole < 0.001, "whole-image relMSE {} dilutes it", s.whole);
        assert!(
            (28..=40).contains(&s.at.0) && (8..=20).contains(&s.at.1),
            "{:?}",
            s.at
        );
        assert_eq!(score(&g, &g).expect("same").worst, 0.0);
        assert!(score(&a, &Image::new(8, 8)).is_err());
    }
}
