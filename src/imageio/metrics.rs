//! Image comparison metrics, all on linear RGB.
//!
//! - RMSE: √(mean over pixels and channels of (a − b)²).
//! - relMSE: mean of (a − b)² / (b² + 0.01), b the reference; robust to
//!   bright pixels (Rousselle et al. 2011).
//! - PSNR: 10·log10(1 / MSE), peak 1.

use super::Image;
use crate::math::Rgb;

#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    pub rmse: f64,
    pub rel_mse: f64,
    pub psnr: f64,
    pub mean_a: [f64; 3],
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
}
