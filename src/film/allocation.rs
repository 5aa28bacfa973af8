//! Samples spread by noise (`film.allocation: ByNoise`, the default): a
//! render of `spp` samples per pixel takes half of them everywhere, then
//! spends the other half where that first pass saw noise.
//!
//! For a fixed number of samples the image's mean squared error
//! Σᵢ σᵢ²/nᵢ is smallest when each pixel's count nᵢ is proportional to the
//! standard deviation σᵢ of one of its samples (Neyman allocation, the
//! optimum of stratified sampling theory: Cochran, *Sampling Techniques*,
//! 3rd ed., §5.5). That assumes σᵢ known; here it is estimated from the
//! first pass, which underrates heavy-tailed pixels (a caustic's rare
//! bright paths) and overrates a pixel beside one firefly. So the counts
//! follow σᵢ^½ instead, nᵢ = clamp(c·σᵢ^½, first, cap) with c chosen so
//! that they add up to `spp` × pixels, rounded to a multiple of 8 so a
//! Sobol pixel stops on whole strata of its points. Measured at 128 spp on
//! the five Mitsuba reference scenes (error off the light, two seeds):
//! Neyman's σᵢ with a quarter first pass and 3 × 3 neighbours made the
//! mirror-and-glass box 47% worse than even spreading; with a half first
//! pass and 5 × 5 neighbours it was better everywhere, and σᵢ^½ better
//! still on the mirror-and-glass box (3%) and the emissive shapes (5%).
//! σᵢ^½ with a half first pass, a 5 × 5 neighbourhood and a cap of
//! 8 × `spp`, against even spreading: 5.7% lower error on the diffuse box,
//! 5.8% on the mirror-and-glass box, 6.3% through the thin lens, 7.6% on
//! the emissive shapes and 43% on the spheres under the sky (where the
//! samples go to the glass sphere's longer paths: the render takes ~25%
//! longer).
//!
//! A pixel's own samples never decide its count: σᵢ is the root mean
//! variance of its (up to) 24 neighbours in a 5 × 5 window, which share its
//! noise (caustics, penumbrae and glossy highlights span several pixels)
//! but not its random numbers. The count is therefore independent of the
//! samples it averages, and every pixel stays an unbiased estimate — unlike
//! a stopping rule on its own samples (`noise_threshold`). The counts depend only on
//! the first pass's per-pixel sums, taken in a fixed order, so the image is
//! the same on any number of threads.

use rayon::prelude::*;

/// Renders below this many samples per pixel spread them evenly: a first
/// pass of fewer than 16 samples says too little about the noise.
pub const MIN_SPP: u32 = 32;
/// No pixel takes more than this many times `spp`: bounds the time a tile
/// of noisy pixels takes, and what one unlucky first pass can attract.
pub const MAX_FACTOR: u32 = 8;
/// Half-width of the window whose pixels (the centre left out) estimate a
/// pixel's noise.
const RADIUS: usize = 2;
/// Counts are multiples of this (a Sobol pixel's strata; see `sampler`).
const STEP: u32 = 8;

/// The two passes of a render spread by noise.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spread {
    /// Samples every pixel takes in the first pass: half of `spp`,
    /// rounded down to a multiple of 8.
    pub first: u32,
    /// The average number of samples per pixel (the scene's `spp`).
    pub spp: u32,
    /// The most samples any pixel takes.
    pub cap: u32,
}

impl Spread {
    /// The plan for `spp` samples per pixel, or `None` when they are too few
    /// to spread (below [`MIN_SPP`]).
    pub fn new(spp: u32) -> Option<Spread> {
        (spp >= MIN_SPP).then(|| Spread {
            first: (spp / 2) / STEP * STEP,
            spp,
            cap: spp.saturating_mul(MAX_FACTOR),
        })
    }

    /// Each pixel's sample count (row-major, `width × height`), from the
    /// variance of one sample of each pixel in the first pass (`variance`,
    /// summed over the colour channels). Counts are multiples of 8 in
    /// `first..=cap` and add up to about `spp` per pixel; a noiseless first
    /// pass gives every pixel `spp`.
    pub fn counts(&self, width: usize, height: usize, variance: &[f32]) -> Vec<u32> {
        debug_assert_eq!(variance.len(), width * height);
        // The weight of each pixel: σ^½ of its neighbourhood.
        let weight: Vec<f32> = neighbour_variance(width, height, variance)
            .into_iter()
            .map(|v| v.sqrt().sqrt())
            .collect();
        let n = weight.len();
        let budget = self.spp as f64 * n as f64;
        let (first, cap) = (self.first as f64, self.cap as f64);
        let round = |t: f64| {
            let k = ((t.clamp(first, cap) - first) / STEP as f64).round() as u32;
            self.first.saturating_add(k.saturating_mul(STEP)).min(self.cap)
        };
        let noisy = weight.iter().filter(|&&s| s > 0.0).count();
        if noisy == 0 {
            // Nothing to go by (a black or noiseless image): spread evenly.
            return vec![self.spp; n];
        }
        if noisy as f64 * cap + (n - noisy) as f64 * first <= budget {
            // The noisy pixels cannot take it all: they get `cap`, the
            // quiet ones share what is left evenly.
            let rest = round((budget - noisy as f64 * cap) / (n - noisy).max(1) as f64);
            return weight
                .iter()
                .map(|&s| if s > 0.0 { self.cap } else { rest })
                .collect();
        }
        // Σ clamp(c·w, first, cap) rises with c from n·first (c·w_max ≤ first)
        // to above the budget (c·w_min ≥ cap): bisect log c between the two.
        // The sum runs over fixed chunks in a fixed order, so c — and every
        // count — is the same on any number of threads.
        let total = |c: f64| -> f64 {
            let parts: Vec<f64> = weight
                .par_chunks(1 << 16)
                .map(|ch| ch.iter().map(|&s| (c * s as f64).clamp(first, cap)).sum::<f64>())
                .collect();
            parts.iter().sum()
        };
        let positive = weight.iter().copied().filter(|&s| s > 0.0);
        let w_max = positive.clone().fold(0.0f32, f32::max) as f64;
        let w_min = positive.fold(f32::INFINITY, f32::min) as f64;
        let (mut lo, mut hi) = ((first / w_max).ln(), (cap / w_min).ln());
        for _ in 0..48 {
            let mid = 0.5 * (lo + hi);
            if total(mid.exp()) > budget {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let c = (0.5 * (lo + hi)).exp();
        weight.iter().map(|&s| round(c * s as f64)).collect()
    }
}

/// Per pixel, the mean of its neighbours' variances (the 5 × 5 window
/// without the centre; fewer at the border), finite: non-finite or negative
/// variances count as 0, and the mean (summed in f64) stops at `f32::MAX`,
/// so the bisection's bounds stay finite whatever radiance a scene holds.
fn neighbour_variance(width: usize, height: usize, variance: &[f32]) -> Vec<f32> {
    let v = |x: usize, y: usize| {
        let a = variance[y * width + x];
        if a.is_finite() && a > 0.0 { a as f64 } else { 0.0 }
    };
    let mut out = vec![0.0f32; width * height];
    // Rows in parallel: each value reads only the input, so the result does
    // not depend on the split.
    out.par_chunks_mut(width.max(1)).enumerate().for_each(|(y, row)| {
        for (x, o) in row.iter_mut().enumerate() {
            let (mut sum, mut k) = (0.0f64, 0u32);
            for yy in y.saturating_sub(RADIUS)..(y + RADIUS + 1).min(height) {
                for xx in x.saturating_sub(RADIUS)..(x + RADIUS + 1).min(width) {
                    if (xx, yy) != (x, y) {
                        sum += v(xx, yy);
                        k += 1;
                    }
                }
            }
            let mean = if k > 0 { sum / k as f64 } else { v(x, y) };
            *o = mean.min(f32::MAX as f64) as f32;
        }
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn too_few_samples_are_not_spread() {
        assert_eq!(Spread::new(16), None);
        let p = Spread::new(128).unwrap();
        assert_eq!((p.first, p.spp, p.cap), (64, 128, 1024));
        assert_eq!(Spread::new(47).unwrap().first, 16);
    }

    #[test]
    fn a_noiseless_first_pass_spreads_evenly() {
        let p = Spread::new(64).unwrap();
        assert_eq!(p.counts(4, 3, &[0.0; 12]), vec![64; 12]);
        assert_eq!(p.counts(2, 2, &[f32::NAN; 4]), vec![64; 4]);
    }

    #[test]
    fn noisy_regions_get_more_and_the_budget_holds() {
        let (w, h) = (32, 32);
        // Left half quiet, right half 256× the variance (4× the σ^½).
        let var: Vec<f32> = (0..w * h)
            .map(|i| if i % w < w / 2 { 1.0 } else { 256.0 })
            .collect();
        let p = Spread::new(256).unwrap();
        let n = p.counts(w, h, &var);
        let mean = n.iter().map(|&k| k as f64).sum::<f64>() / n.len() as f64;
        assert!((mean - 256.0).abs() < 4.0, "mean {mean}");
        // Away from the border, weights 1 and 4 with a floor of 128: the
        // quiet half stays at the floor, the noisy half takes the rest
        // (384 if the halves were pure; the columns on either side of the
        // border see both, and take some).
        let (quiet, noisy) = (n[h / 2 * w + 2], n[h / 2 * w + w - 4]);
        assert!(quiet % 8 == 0 && noisy % 8 == 0);
        assert_eq!(quiet, 128);
        assert!((352..=392).contains(&noisy), "{noisy}");
        assert!(n.iter().all(|&k| (p.first..=p.cap).contains(&k)));
    }

    #[test]
    fn a_pixel_count_ignores_its_own_variance() {
        let (w, h) = (12, 12);
        let mut var = vec![1.0f32; w * h];
        let p = Spread::new(64).unwrap();
        let before = p.counts(w, h, &var);
        var[5 * w + 5] = 1000.0;
        let after = p.counts(w, h, &var);
        // Its neighbours now get more (and the rest less), it does not.
        assert!(after[5 * w + 5] <= before[5 * w + 5]);
        assert!(after[5 * w + 6] > before[5 * w + 6]);
        assert!(after[5 * w + 7] > before[5 * w + 7]);
    }

    #[test]
    fn huge_and_broken_variances_keep_the_counts_in_range() {
        let (w, h) = (16, 16);
        let var: Vec<f32> = (0..w * h)
            .map(|i| match i % 5 {
                0 => f32::MAX,
                1 => f32::INFINITY,
                2 => f32::NAN,
                3 => -1.0,
                _ => 1e-30,
            })
            .collect();
        let p = Spread::new(64).unwrap();
        let n = p.counts(w, h, &var);
        assert!(n.iter().all(|&k| (p.first..=p.cap).contains(&k)));
        let mean = n.iter().map(|&k| k as f64).sum::<f64>() / n.len() as f64;
        assert!((mean - 64.0).abs() < 4.0, "mean {mean}");
    }

    #[test]
    fn the_cap_bounds_a_lone_noisy_spot() {
        let (w, h) = (64, 64);
        let mut var = vec![0.0f32; w * h];
        var[10 * w + 10] = 1.0;
        let p = Spread::new(32).unwrap();
        let n = p.counts(w, h, &var);
        assert!(n.iter().all(|&k| k <= p.cap));
        assert_eq!(n[10 * w + 11], p.cap);
        assert_eq!(n[12 * w + 12], p.cap);
        // The rest share what the spot's 24 neighbours cannot take: about `spp`.
        assert_eq!(n[40 * w + 40], 32);
    }
}
