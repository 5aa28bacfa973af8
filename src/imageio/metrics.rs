//! Image comparison metrics, all on linear RGB.
//!
//! - RMSE: √(mean over pixels and channels of (a − b)²).
//! - relMSE: mean of (a − b)² / (b² + 0.01), b the reference; robust to
//!   bright pixels (Rousselle et al. 2011).
//! - PSNR: 10·log10(1 / MSE), peak 1.

use super::Image;
use crate::math::Rgb;

/// Error figures of an image `a` against a reference `b` (see the module docs for the
/// formulas).
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Root-mean-square error, in linear RGB units.
    pub rmse: f64,
    /// Relative MSE, `mean((a − b)² / (b² + 0.01))`: what `ronray check` compares
    /// with a scene's tolerance.
    pub rel_mse: f64,
    /// Peak signal-to-noise ratio in dB (peak 1); infinite for identical images.
    pub psnr: f64,
    /// Mean of `a` per channel over every pixel (the mask does not apply): a
    /// brightness check.
    pub mean_a: [f64; 3],
    /// Mean of `b` per channel over every pixel.
    pub mean_b: [f64; 3],
    /// Pixels compared (after the mask).
    pub pixels: usize,
}

/// Compares `a` against reference `b`; pixels where `skip[i]` is true are
/// left out of the error (not of the means). Sizes must match.
pub fn compare(a: &Image, b: &Image, skip: Option<&[bool]>) -> Result<Comparison, String> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!(
            "image sizes differ: {}×{} vs {}×{}",
            a.width, a.height, b.width, b.height
        ));
    }
    let mut se = 0.0f64;
    let mut rel = 0.0f64;
    let mut n = 0usize;
    let mut ma = [0.0f64; 3];
    let mut mb = [0.0f64; 3];
    for (i, (pa, pb)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        for c in 0..3 {
            ma[c] += pa[c] as f64;
            mb[c] += pb[c] as f64;
        }
        if skip.is_some_and(|s| s.get(i).copied().unwrap_or(false)) {
            continue;
        }
        n += 1;
        for c in 0..3 {
            let d = (pa[c] - pb[c]) as f64;
            se += d * d;
            rel += d * d / ((pb[c] as f64).powi(2) + 0.01);
        }
    }
    let total = a.pixels.len().max(1) as f64;
    let mse = se / (3 * n.max(1)) as f64;
    Ok(Comparison {
        rmse: mse.sqrt(),
        rel_mse: rel / (3 * n.max(1)) as f64,
        psnr: if mse > 0.0 {
            10.0 * (1.0 / mse).log10()
        } else {
            f64::INFINITY
        },
        mean_a: ma.map(|m| m / total),
        mean_b: mb.map(|m| m / total),
        pixels: n,
    })
}

/// One square block of an image pair, for judging an image region by region:
/// a whole-image figure dilutes a wrong region (a far floor rendered black
/// moved the whole-image RMSE of a test scene by less than its noise).
#[derive(Clone, Debug, PartialEq)]
pub struct Block {
    /// Top-left pixel of the block.
    pub x: usize,
    /// Top row of the block.
    pub y: usize,
    /// Pixels in the block (fewer than `size²` on the right and bottom edges).
    pub pixels: usize,
    /// Mean of `a` per channel over the block.
    pub mean_a: [f64; 3],
    /// Mean of `b` per channel over the block.
    pub mean_b: [f64; 3],
    /// Per-channel sum over the block's pixels of (a − b)².
    pub sum_sq_diff: [f64; 3],
}

/// `a` and `b` cut into `size × size` blocks, row by row from the top left.
pub fn blocks(a: &Image, b: &Image, size: usize) -> Result<Vec<Block>, String> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!(
            "image sizes differ: {}×{} vs {}×{}",
            a.width, a.height, b.width, b.height
        ));
    }
    let size = size.max(1);
    let (w, h) = (a.width as usize, a.height as usize);
    let mut out = Vec::new();
    for y0 in (0..h).step_by(size) {
        for x0 in (0..w).step_by(size) {
            let mut blk = Block {
                x: x0,
                y: y0,
                pixels: 0,
                mean_a: [0.0; 3],
                mean_b: [0.0; 3],
                sum_sq_diff: [0.0; 3],
            };
            for y in y0..(y0 + size).min(h) {
                for x in x0..(x0 + size).min(w) {
                    let (pa, pb) = (a.pixels[y * w + x], b.pixels[y * w + x]);
                    blk.pixels += 1;
                    for c in 0..3 {
                        blk.mean_a[c] += pa[c] as f64;
                        blk.mean_b[c] += pb[c] as f64;
                        blk.sum_sq_diff[c] += ((pa[c] - pb[c]) as f64).powi(2);
                    }
                }
            }
            let n = blk.pixels as f64;
            blk.mean_a = blk.mean_a.map(|m| m / n);
            blk.mean_b = blk.mean_b.map(|m| m / n);
            out.push(blk);
        }
    }
    Ok(out)
}

/// Per-pixel absolute error as a false-colour image (black → red → yellow →
/// white), scaled so `max_error` is white.
pub fn heatmap(a: &Image, b: &Image, max_error: f32) -> Image {
    let mut out = Image::new(a.width, a.height);
    for (o, (pa, pb)) in out.pixels.iter_mut().zip(a.pixels.iter().zip(&b.pixels)) {
        let e = ((*pa - *pb).abs().max_element() / max_error.max(1e-12)).clamp(0.0, 1.0);
        // Piecewise ramp, then back to linear so the PNG encoder's sRGB
        // curve shows the intended colours.
        let c = Rgb::new(
            (3.0 * e).min(1.0),
            (3.0 * e - 1.0).clamp(0.0, 1.0),
            (3.0 * e - 2.0).clamp(0.0, 1.0),
        );
        *o = c.to_array().map(super::srgb_decode).into();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compare_identical_is_zero_and_mask_excludes() {
        let mut a = Image::new(2, 1);
        let b = a.clone();
        let c = compare(&a, &b, None).expect("same size");
        assert_eq!(c.rmse, 0.0);
        a.pixels[0] = Rgb::splat(1.0);
        let c = compare(&a, &b, None).expect("same size");
        assert!((c.rmse - (0.5f64).sqrt()).abs() < 1e-9, "rmse {}", c.rmse);
        let c = compare(&a, &b, Some(&[true, false])).expect("same size");
        assert_eq!(c.rmse, 0.0, "masked pixel must not count");
        assert!(compare(&a, &Image::new(1, 1), None).is_err());
    }

    #[test]
    fn blocks_cover_every_pixel_once_and_keep_the_means() {
        let mut a = Image::new(5, 3);
        for (i, p) in a.pixels.iter_mut().enumerate() {
            *p = Rgb::splat(i as f32);
        }
        let b = Image::new(5, 3);
        let bl = blocks(&a, &b, 2).expect("same size");
        // 3 columns × 2 rows of blocks, edge blocks smaller.
        assert_eq!(bl.len(), 6);
        assert_eq!(bl.iter().map(|b| b.pixels).sum::<usize>(), 15);
        assert_eq!((bl[2].x, bl[2].y, bl[2].pixels), (4, 0, 2));
        // Block (0,0) holds pixels 0, 1, 5, 6.
        assert_eq!(bl[0].mean_a[0], 3.0);
        assert_eq!(bl[0].sum_sq_diff[1], 0.0 + 1.0 + 25.0 + 36.0);
        let total: f64 = bl.iter().map(|b| b.mean_a[0] * b.pixels as f64).sum();
        assert_eq!(total, (0..15).sum::<i32>() as f64);
        assert!(blocks(&a, &Image::new(1, 1), 2).is_err());
    }
}
