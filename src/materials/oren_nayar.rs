//! Rough diffuse reflection: the qualitative Oren–Nayar model (Oren & Nayar
//! 1994, "Generalization of Lambert's Reflectance Model",
//! <https://doi.org/10.1145/192161.192213>, eq. 30; pbrt-v3 §8.4.2):
//!
//! `f = R/π · (A + B·max(0, cos(φi − φo))·sin α·tan β)`, α = max(θi, θo),
//! β = min(θi, θo), A = 1 − σ²/(2(σ² + 0.33)), B = 0.45σ²/(σ² + 0.09).
//!
//! **Why this variant.** σ is a physical quantity, the standard deviation
//! of the V-cavity facet angle in **radians** (scene files give
//! `sigma_degrees`), and the same formula is pbrt-v3's and Mitsuba's fast
//! `roughdiffuse`, so renders compare against those references. It is
//! reciprocal and never reflects more than R (it drops the
//! interreflection term, so it is slightly dark at large σ). Fujii's
//! "improved" ON (<https://mimosa-pudica.net/improved-oren-nayar.html>)
//! removes the dark rim but its σ is a unitless fit parameter, not an
//! angle; the energy-preserving EON (Portsmouth et al. 2025) needs albedo
//! fits. σ = 0 is exactly Lambert.
//!
//! Cosine-sampled: the lobe is close to cosine, so the weight stays near R.

use super::{BsdfSample, Bxdf};
use crate::math::{Rgb, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

#[derive(Clone, Copy, Debug)]
pub struct OrenNayar {
    albedo: Rgb,
    a: f32,
    b: f32,
}

impl OrenNayar {
    /// `sigma` in radians (clamped to ≥ 0).
    pub fn new(albedo: Rgb, sigma: f32) -> Self {
        let s2 = sigma.max(0.0).powi(2);
        Self {
            albedo,
            a: 1.0 - s2 / (2.0 * (s2 + 0.33)),
            b: 0.45 * s2 / (s2 + 0.09),
        }
    }
}

impl Bxdf for OrenNayar {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (cos_i, cos_o) = (wi.z.abs(), wo.z.abs());
        let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
        let sin_o = (1.0 - cos_o * cos_o).max(0.0).sqrt();
        // cos(φi − φo) = projected dot product / (sin θi sin θo).
        let cos_dphi = if sin_i > 1e-4 && sin_o > 1e-4 {
            ((wi.x * wo.x + wi.y * wo.y) / (sin_i * sin_o)).max(0.0)
        } else {
            0.0
        };
        // sin α tan β with α the larger angle (smaller cosine).
        let (sin_alpha, tan_beta) = if cos_i > cos_o {
            (sin_o, sin_i / cos_i)
        } else {
            (sin_i, sin_o / cos_o)
        };
        self.albedo * (FRAC_1_PI * (self.a + self.b * cos_dphi * sin_alpha * tan_beta))
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        sampling::cosine_hemisphere_pdf(wi.z.abs())
    }

    fn sample(&self, wo: Vec3A, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let w = sampling::cosine_hemisphere(u);
        let wi = Vec3A::new(w.x, w.y, w.z.copysign(wo.z));
        let pdf = self.pdf(wo, wi);
        if pdf <= 0.0 {
            return None;
        }
        let weight = self.eval(wo, wi) * wi.z.abs() / pdf;
        Some(BsdfSample {
            wi,
            weight,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{check_all, incidences};

    #[test]
    fn oren_nayar_chi2_agreement_energy() {
        for (i, deg) in [20.0f32, 60.0].into_iter().enumerate() {
            let on = OrenNayar::new(Rgb::ONE, deg.to_radians());
            for wo in incidences() {
                check_all(&on, wo, &format!("oren-nayar σ={deg}°"), 80 + i as u64);
            }
        }
    }

    #[test]
    fn oren_nayar_sigma_zero_is_lambert() {
        let on = OrenNayar::new(Rgb::splat(0.5), 0.0);
        let (wo, wi) = (
            Vec3A::new(0.6, 0.0, 0.8),
            Vec3A::new(-0.28, 0.96, 0.0).normalize() * 0.5 + Vec3A::Z * 0.866,
        );
        let f = on.eval(wo, wi.normalize());
        assert!(
            (f.x - 0.5 * FRAC_1_PI).abs() < 1e-6,
            "σ = 0 must be albedo/π, got {f}"
        );
    }

    #[test]
    fn oren_nayar_brightens_backscatter() {
        // Rough surfaces reflect more toward the light than Lambert does.
        let on = OrenNayar::new(Rgb::ONE, 0.5);
        let wo = Vec3A::new(0.866, 0.0, 0.5);
        let back = on.eval(wo, wo).x;
        let forward = on.eval(wo, Vec3A::new(-0.866, 0.0, 0.5)).x;
        assert!(
            back > forward,
            "backscatter {back} must exceed forward {forward}"
        );
    }
}
