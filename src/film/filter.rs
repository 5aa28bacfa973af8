//! Pixel filters by filter importance sampling (pbrt-v4's `FilterSampler`,
//! Ernst et al. 2006, "Filter importance sampling").
//!
//! Instead of splatting every sample into the pixels its filter reaches
//! with weight f(p), each sample of pixel (x, y) is placed at an offset
//! drawn from the filter itself, and counts with a weight of constant
//! magnitude: 1 for the positive filters, ± ∫|f| / ∫f for Mitchell's
//! negative lobes. A pixel is then the plain mean of its own samples, so
//! tiles, sample splits and the exact fixed-point sums
//! (`math/exact_sum.rs`) stay as they are with any filter.
//!
//! The filters here are separable, f(x, y) = f₁(x)·f₁(y), so each axis draws
//! its offset from a 1-D table of |f₁| at [`BINS_PER_PIXEL`] bins per pixel
//! of radius (pbrt-v4 tabulates 32 per pixel, in 2-D), uniformly inside the
//! chosen bin: the filter used is the piecewise-constant table, which
//! integrates exactly to what the weights assume. `Box` draws the sample
//! uniformly in the pixel, exactly as ronray did before filters existed, so
//! its images are unchanged bit for bit.

use glam::Vec2;
use std::sync::Arc;

/// Table bins per pixel of filter radius, per axis.
pub const BINS_PER_PIXEL: usize = 64;

/// The filter shapes; radii in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FilterKind {
    /// Uniform over the pixel (radius ½).
    Box,
    /// `max(0, g(x) − g(radius))`, g the Gaussian of deviation `sigma`
    /// (pbrt-v4's `GaussianFilter`).
    Gaussian {
        /// Half-width in pixels.
        radius: f32,
        /// Standard deviation in pixels.
        sigma: f32,
    },
    /// Mitchell–Netravali (1988) cubic stretched to `radius` (pbrt-v4's
    /// `MitchellFilter`).
    Mitchell {
        /// Half-width in pixels.
        radius: f32,
        /// Blur parameter B.
        b: f32,
        /// Ringing parameter C.
        c: f32,
    },
}

impl FilterKind {
    /// Half-width in pixels.
    pub fn radius(&self) -> f32 {
        match *self {
            FilterKind::Box => 0.5,
            FilterKind::Gaussian { radius, .. } | FilterKind::Mitchell { radius, .. } => radius,
        }
    }

    /// The 1-D profile f₁(x), x in pixels from the pixel centre.
    pub fn eval_1d(&self, x: f32) -> f32 {
        match *self {
            FilterKind::Box => {
                if x.abs() <= 0.5 {
                    1.0
                } else {
                    0.0
                }
            }
            FilterKind::Gaussian { radius, sigma } => {
                let g = |x: f32| (-x * x / (2.0 * sigma * sigma)).exp();
                (g(x) - g(radius)).max(0.0)
            }
            FilterKind::Mitchell { radius, b, c } => mitchell_1d(2.0 * x / radius, b, c),
        }
    }
}

/// Mitchell–Netravali's cubic on [−2, 2] (Mitchell & Netravali 1988, eq. 8).
fn mitchell_1d(x: f32, b: f32, c: f32) -> f32 {
    let x = x.abs();
    if x <= 1.0 {
        // Inner piece: (12 − 9B − 6C)x³ + (−18 + 12B + 6C)x² + (6 − 2B), over 6.
        ((12.0 - 9.0 * b - 6.0 * c) * x * x * x + (-18.0 + 12.0 * b + 6.0 * c) * x * x + (6.0 - 2.0 * b))
            / 6.0
    } else if x <= 2.0 {
        // Outer piece, where the negative lobes are.
        ((-b - 6.0 * c) * x * x * x
            + (6.0 * b + 30.0 * c) * x * x
            + (-12.0 * b - 48.0 * c) * x
            + (8.0 * b + 24.0 * c))
            / 6.0
    } else {
        0.0
    }
}

/// The 1-D sampling table of a filter's |f₁| over [−radius, radius].
#[derive(Debug, PartialEq)]
struct Table {
    radius: f32,
    /// f₁ at each bin's centre (its sign is the sample's).
    values: Vec<f32>,
    /// Normalised CDF of |values|: `cdf[0] = 0`, `cdf[n] = 1`.
    cdf: Vec<f32>,
    /// ∫|f̃₁| / ∫f̃₁ of the tabulated profile: the weight's magnitude per axis
    /// (exactly 1 when f₁ ≥ 0).
    magnitude: f32,
}

impl Table {
    fn new(kind: &FilterKind) -> Self {
        let radius = kind.radius();
        let n = ((radius * BINS_PER_PIXEL as f32).ceil() as usize).max(1);
        let dx = 2.0 * radius / n as f32;
        let values: Vec<f32> = (0..n)
            .map(|i| kind.eval_1d(-radius + (i as f32 + 0.5) * dx))
            .collect();
        let mut cdf = Vec::with_capacity(n + 1);
        let (mut abs_sum, mut sum) = (0.0f64, 0.0f64);
        cdf.push(0.0);
        for v in &values {
            abs_sum += f64::from(v.abs());
            sum += f64::from(*v);
            cdf.push(abs_sum as f32);
        }
        for c in &mut cdf {
            *c = (f64::from(*c) / abs_sum) as f32;
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let magnitude = if abs_sum == sum {
            1.0
        } else {
            (abs_sum / sum) as f32
        };
        Self {
            radius,
            values,
            cdf,
            magnitude,
        }
    }

    /// An offset from the pixel centre drawn with density ∝ |f̃₁| for `u` ∈
    /// [0, 1), and the sign of f̃₁ there.
    fn sample(&self, u: f32) -> (f32, f32) {
        let n = self.values.len();
        // The bin whose CDF interval holds u (empty bins are never chosen).
        let i = (self.cdf.partition_point(|&c| c <= u).max(1) - 1).min(n - 1);
        let width = self.cdf[i + 1] - self.cdf[i];
        let t = if width > 0.0 {
            ((u - self.cdf[i]) / width).clamp(0.0, 1.0)
        } else {
            0.5
        };
        let dx = 2.0 * self.radius / n as f32;
        let x = -self.radius + (i as f32 + t) * dx;
        (x, if self.values[i] < 0.0 { -1.0 } else { 1.0 })
    }
}

/// A pixel filter ready to sample: cheap to clone (the table is shared).
#[derive(Clone, Debug, PartialEq)]
pub struct Filter {
    /// The filter's shape.
    pub kind: FilterKind,
    table: Option<Arc<Table>>,
}

impl Default for Filter {
    fn default() -> Self {
        Self::new(FilterKind::Box)
    }
}

impl Filter {
    /// Tabulates `kind` (nothing to tabulate for `Box`). Radii must be > 0 and
    /// finite (the loader checks them).
    pub fn new(kind: FilterKind) -> Self {
        let table = match kind {
            FilterKind::Box => None,
            _ => Some(Arc::new(Table::new(&kind))),
        };
        Self { kind, table }
    }

    /// The sample's film position relative to the pixel's top-left corner,
    /// in pixels, and its weight, for `u` ∈ [0, 1)². `Box` returns `u` itself
    /// and weight 1, as ronray drew samples before filters existed.
    #[inline]
    pub fn sample(&self, u: Vec2) -> (Vec2, f32) {
        match &self.table {
            None => (u, 1.0),
            Some(t) => {
                let (x, sx) = t.sample(u.x);
                let (y, sy) = t.sample(u.y);
                let w = if sx * sy < 0.0 { -1.0 } else { 1.0 };
                (Vec2::new(0.5 + x, 0.5 + y), w * t.magnitude * t.magnitude)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds() -> [FilterKind; 4] {
        [
            FilterKind::Box,
            FilterKind::Gaussian {
                radius: 1.5,
                sigma: 0.5,
            },
            FilterKind::Mitchell {
                radius: 2.0,
                b: 1.0 / 3.0,
                c: 1.0 / 3.0,
            },
            FilterKind::Mitchell {
                radius: 1.0,
                b: 0.0,
                c: 1.0,
            },
        ]
    }

    /// E[weight] = 1 (the filter is normalised) and E[weight·offset] = 0 (it
    /// is centred), over a fine stratified grid of `u` (4096² points: a
    /// coarser grid misplaces Mitchell's sign changes by up to 1/n).
    #[test]
    fn filter_weights_average_to_one_and_are_centred() {
        for kind in kinds() {
            let f = Filter::new(kind);
            let n = 4096;
            let (mut w_sum, mut centre) = (0.0f64, Vec2::ZERO.as_dvec2());
            for i in 0..n {
                for j in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let (p, w) = f.sample(u);
                    w_sum += f64::from(w);
                    centre += (p - Vec2::splat(0.5)).as_dvec2() * f64::from(w);
                }
            }
            let mean = w_sum / (n * n) as f64;
            let centre = centre / (n * n) as f64;
            assert!(
                (mean - 1.0).abs() < 2e-3,
                "{kind:?}: mean weight {mean}, expected 1"
            );
            assert!(
                centre.length() < 2e-3,
                "{kind:?}: weighted mean offset {centre:?}"
            );
        }
    }

    #[test]
    fn filter_offsets_stay_within_the_radius() {
        for kind in kinds() {
            let f = Filter::new(kind);
            let r = kind.radius();
            for i in 0..1000 {
                let u = Vec2::new(i as f32 / 1000.0, (i * 7 % 1000) as f32 / 1000.0);
                let (p, _) = f.sample(u);
                let d = p - Vec2::splat(0.5);
                assert!(d.x.abs() <= r + 1e-5 && d.y.abs() <= r + 1e-5, "{kind:?}: {d:?}");
            }
        }
    }

    #[test]
    fn positive_filters_have_weight_exactly_one_and_mitchell_has_negative_lobes() {
        let g = Filter::new(FilterKind::Gaussian {
            radius: 1.5,
            sigma: 0.5,
        });
        assert!((0..100).all(|i| g.sample(Vec2::splat(i as f32 / 100.0)).1 == 1.0));
        let m = Filter::new(FilterKind::Mitchell {
            radius: 2.0,
            b: 1.0 / 3.0,
            c: 1.0 / 3.0,
        });
        let ws: Vec<f32> = (0..1000)
            .map(|i| m.sample(Vec2::new(i as f32 / 1000.0, 0.5)).1)
            .collect();
        assert!(ws.iter().any(|&w| w < 0.0), "no negative-lobe sample");
        assert!(
            ws.iter().all(|&w| (w.abs() - ws[0].abs()).abs() < 1e-6),
            "magnitudes differ"
        );
    }

    #[test]
    fn box_filter_returns_u_unchanged() {
        let u = Vec2::new(0.123, 0.987);
        assert_eq!(Filter::default().sample(u), (u, 1.0));
    }
}
