//! Adaptive sampling: a pixel stops taking samples once its value is known
//! well enough (`film.noise_threshold`), so the samples go where the noise
//! is — caustics, glossy highlights, the sun's reflections — instead of
//! flat walls that converged long before. Production renderers do this by
//! default (Cycles' "noise threshold", RenderMan's pixel variance); the
//! research renderers ronray's references come from do not.
//!
//! The rule is local to the pixel and uses only its own samples, in order,
//! so a pixel's sample count — and hence the image — is the same whatever
//! the thread count, the tiling or the crop. After `min_spp` samples, and
//! then every [`CHECK_EVERY`] samples, the pixel computes the standard
//! error of its mean luminance (sample variance / n, square-rooted) and
//! stops once it is at most `threshold × max(mean, white)`: a relative
//! error for pixels brighter than display white (`2^−exposure`, what a PNG
//! shows as 1.0), an absolute one below it, so near-black pixels do not
//! chase a relative error nobody can see. The scene's `spp` stays the most
//! any pixel takes.
//!
//! Caveats, documented in `docs/film.md`: the estimate sees only the samples a
//! pixel took, so a pixel whose first `min_spp` samples all missed a rare
//! bright path (a caustic seen through glass) may stop early — raise
//! `min_spp` for such scenes; the stopping rule makes the estimate very
//! slightly biased (by far less than the noise it stops at); and render-farm
//! pieces render every sample, since their exact sums must add up across
//! machines.

use crate::math::{Rgb, luminance};

/// Samples between two convergence checks after the first `min_spp`: the
/// check is cheap, but stopping at multiples of 8 keeps a `Sobol` pixel's
/// points in whole strata of its net.
pub const CHECK_EVERY: u32 = 8;

/// The stopping rule of one render (`film.noise_threshold`, `film.min_spp`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Adaptive {
    /// Largest standard error of a pixel's mean luminance, relative to
    /// `max(mean, white)`, at which it stops.
    pub threshold: f32,
    /// Samples every pixel takes before it may stop.
    pub min_spp: u32,
    /// Display white in scene-linear units: `2^−exposure`.
    pub white: f32,
}

/// Running luminance moments of one pixel's samples (f64: exact enough
/// that the order-fixed sums give the same decision on every machine).
#[derive(Clone, Copy, Debug, Default)]
pub struct PixelNoise {
    n: u32,
    sum: f64,
    sum_sq: f64,
}

impl PixelNoise {
    /// Records one sample (its weighted radiance, as the film adds it).
    #[inline]
    pub fn add(&mut self, c: Rgb) {
        let y = luminance(c) as f64;
        self.n += 1;
        self.sum += y;
        self.sum_sq += y * y;
    }

    /// Samples recorded.
    pub fn count(&self) -> u32 {
        self.n
    }

    /// Standard error of the mean luminance, and the mean.
    fn error_and_mean(&self) -> (f64, f64) {
        let n = self.n as f64;
        let mean = self.sum / n;
        let var = ((self.sum_sq - self.sum * mean) / (n - 1.0)).max(0.0);
        ((var / n).sqrt(), mean)
    }
}

impl Adaptive {
    /// Whether a pixel with these samples may stop now.
    #[inline]
    pub fn converged(&self, p: &PixelNoise) -> bool {
        let n = p.count();
        if n < self.min_spp.max(2) || !(n - self.min_spp).is_multiple_of(CHECK_EVERY) {
            return false;
        }
        let (err, mean) = p.error_and_mean();
        err <= self.threshold as f64 * mean.abs().max(self.white as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rule(threshold: f32, min_spp: u32) -> Adaptive {
        Adaptive {
            threshold,
            min_spp,
            white: 1.0,
        }
    }

    #[test]
    fn constant_pixels_stop_at_min_spp_and_not_before() {
        let a = rule(0.01, 16);
        let mut p = PixelNoise::default();
        for i in 1..=16 {
            p.add(Rgb::splat(0.7));
            assert_eq!(a.converged(&p), i == 16, "sample {i}");
        }
    }

    #[test]
    fn checks_only_every_few_samples_after_min_spp() {
        // Alternating 0 and 2.2: the error is about mean/√n, within 20% of
        // the mean from 25 samples on, so the first check that passes is at 32.
        let a = rule(0.2, 16);
        let mut p = PixelNoise::default();
        let mut stops = Vec::new();
        for i in 1..=48u32 {
            p.add(Rgb::splat(if i % 2 == 0 { 0.0 } else { 2.2 }));
            if a.converged(&p) {
                stops.push(i);
            }
        }
        assert_eq!(stops, [32, 40, 48]);
    }

    #[test]
    fn noisy_pixels_keep_sampling() {
        let a = rule(0.01, 16);
        let mut p = PixelNoise::default();
        for i in 0..1024u32 {
            // A firefly every 32 samples: error far above 1% of the mean.
            p.add(Rgb::splat(if i % 32 == 0 { 50.0 } else { 0.5 }));
            assert!(!a.converged(&p), "stopped at {}", i + 1);
        }
    }

    #[test]
    fn dark_pixels_use_the_absolute_floor() {
        // Mean 0.001 with an error of ~2e-4: 20% relative, but far below
        // 1% of display white, so it stops.
        let a = rule(0.01, 16);
        let mut p = PixelNoise::default();
        for i in 0..16 {
            p.add(Rgb::splat(if i % 2 == 0 { 0.0002 } else { 0.0018 }));
        }
        assert!(a.converged(&p));
        // The same pixel with display white at 1/1024 (exposure +10) is bright.
        let bright = Adaptive {
            white: 1.0 / 1024.0,
            ..a
        };
        assert!(!bright.converged(&p));
    }
}
