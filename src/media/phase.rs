//! The Henyey–Greenstein phase function: how a medium scatters light by
//! angle. `g` is the mean cosine of the deflection: 0 scatters equally
//! everywhere (isotropic, 1/4π), g > 0 forward, g < 0 backward.
//!
//! Directions follow the light's flight: the cosine is between the ray's
//! direction of travel `d` and the scattered direction `wi`, so g > 0 keeps
//! light going the way it went (Mitsuba's `hg`; pbrt-v4's
//! `HenyeyGreenstein` writes the same function with `wo = −d`).

use crate::math::Frame;
use crate::math::sampling::UNIFORM_SPHERE_PDF;
use crate::math::trig::sin_cos_turns;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Below this |g| the function is sampled as isotropic: the closed-form
/// inversion divides by g.
const ISOTROPIC_G: f32 = 1e-3;

/// Henyey–Greenstein with mean cosine `g` ∈ (−1, 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// Mean cosine of the deflection.
    pub g: f32,
}

impl HenyeyGreenstein {
    /// Density (1/sr) of scattering from travel direction `d` into `wi`,
    /// both unit: (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}). Also the value
    /// of the phase function, which is normalised.
    #[inline]
    pub fn eval(&self, d: Vec3A, wi: Vec3A) -> f32 {
        hg(d.dot(wi), self.g)
    }

    /// A direction scattered from travel direction `d` for `u` ∈ [0, 1)²,
    /// with its density; the weight (value / density) is exactly 1.
    /// Inversion of the cumulative distribution in cos θ (pbrt-v4,
    /// `SampleHenyeyGreenstein`, written for the travel direction).
    #[inline]
    pub fn sample(&self, d: Vec3A, u: Vec2) -> (Vec3A, f32) {
        let g = self.g;
        let cos = if g.abs() < ISOTROPIC_G {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u.x);
            ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
        };
        let sin = (1.0 - cos * cos).max(0.0).sqrt();
        // φ = 2π·u.y, by the polynomial the path loop uses (libm's
        // `sincosf` was 2.5% of a fog render).
        let (sin_p, cos_p) = sin_cos_turns(u.y);
        let local = Vec3A::new(sin * cos_p, sin * sin_p, cos);
        if g.abs() < ISOTROPIC_G {
            // Uniform over the sphere whatever `d` is: no frame about it
            // (its construction and the normalisation were 2% of
            // `fog_box`'s time, alternated runs).
            return (local, UNIFORM_SPHERE_PDF);
        }
        let wi = Frame::from_normal(d).to_world(local).normalize();
        (wi, hg(cos, g))
    }
}

/// The Henyey–Greenstein density at cosine `cos` between travel and
/// scattered directions. Below [`ISOTROPIC_G`] it is the uniform density
/// [`HenyeyGreenstein::sample`] draws from there: no division or square root (with
/// them the density was 9% of a fog render's path loop, perf), the same
/// float at g = 0, and for 0 < |g| < 10⁻³ the density of what is sampled
/// rather than one up to 0.3% off it.
#[inline]
fn hg(cos: f32, g: f32) -> f32 {
    if g.abs() < ISOTROPIC_G {
        return UNIFORM_SPHERE_PDF;
    }
    let denom = 1.0 + g * g - 2.0 * g * cos;
    (1.0 - g * g) / (4.0 * PI * denom * denom.max(0.0).sqrt().max(1e-20))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::Pcg32;

    /// The density integrates to 1 over the sphere and its mean cosine is
    /// g, for isotropic, forward and backward media (midpoint rule in cos θ).
    #[test]
    fn henyey_greenstein_is_normalised_with_mean_cosine_g() {
        for g in [0.0, 0.3, 0.8, -0.6] {
            let n = 200_000;
            let (mut total, mut mean) = (0.0f64, 0.0f64);
            for i in 0..n {
                let c = -1.0 + 2.0 * (i as f64 + 0.5) / n as f64;
                let p = hg(c as f32, g) as f64 * 2.0 * std::f64::consts::PI * (2.0 / n as f64);
                total += p;
                mean += p * c;
            }
            assert!((total - 1.0).abs() < 2e-3, "g {g}: integral {total}");
            assert!((mean - g as f64).abs() < 2e-3, "g {g}: mean cosine {mean}");
        }
    }

    /// Sampled directions have the density `sample` reports and `eval`
    /// gives, and their mean cosine is g.
    #[test]
    fn henyey_greenstein_sampling_matches_its_density() {
        let d = Vec3A::new(0.3, -0.5, 0.8).normalize();
        let mut rng = Pcg32::new(7, 1);
        for g in [0.0, 0.5, -0.7] {
            let hgf = HenyeyGreenstein { g };
            let n = 100_000;
            let mut mean = 0.0f64;
            for _ in 0..n {
                let (wi, pdf) = hgf.sample(d, rng.next_vec2());
                assert!((wi.length() - 1.0).abs() < 1e-4);
                assert!(
                    (pdf - hgf.eval(d, wi)).abs() <= 1e-3 * pdf.max(1.0),
                    "g {g}: {pdf} vs {}",
                    hgf.eval(d, wi)
                );
                mean += d.dot(wi) as f64;
            }
            mean /= n as f64;
            assert!(
                (mean - g as f64).abs() < 0.01,
                "g {g}: sampled mean cosine {mean}"
            );
        }
    }
}
