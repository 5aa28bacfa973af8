//! Energy-normalised modified Phong (Lafortune & Willems 1994, "Using the
//! Modified Phong Reflectance Model for Physically Based Rendering",
//! <https://graphics.cs.kuleuven.be/publications/Phong/>):
//!
//! `f = kd/π + ks·(n+2)/(2π)·cos^n α`, α the angle between `wi` and the
//! mirror direction of `wo`.
//!
//! * **Normalisation.** At normal incidence ∫ cos^n α cos θi dωi = 2π/(n+2),
//!   so the specular lobe reflects exactly `ks` there and less elsewhere
//!   (the lobe is clipped by the horizon and tilted away from the normal).
//!   With `kd + ks ≤ 1` per channel the model never creates energy;
//!   [`Phong::new`] scales both down by their sum where it exceeds 1.
//! * **Reciprocal:** the angle between `wi` and the mirror of `wo` equals the
//!   angle between `wo` and the mirror of `wi`.
//! * **Sampling:** a one-sample mixture of cosine sampling and the lobe
//!   `(n+1)/(2π) cos^n α` around the mirror direction, chosen by the
//!   luminance of `kd` and `ks`; the pdf is the mixture's pdf. Lobe samples
//!   below the horizon are rejected (`None`), so the pdf integrates to < 1.

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, ScalarTex, Texture};
use super::{TexPoint, TexProbe};
use crate::math::{Frame, Rgb, luminance, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::{FRAC_1_PI, PI};

/// Energy-normalised Phong BSDF at one hit (see the module docs for the formula and
/// sampling).
#[derive(Clone, Copy, Debug)]
pub struct Phong {
    kd: Rgb,
    ks: Rgb,
    exponent: f32,
    /// Probability of sampling the specular lobe.
    spec_prob: f32,
}

/// Clamps to ≥ 0 and scales `kd`, `ks` so that `kd + ks ≤ 1` per channel;
/// returns them with the specular selection probability.
pub(crate) fn conserve(kd: Rgb, ks: Rgb) -> (Rgb, Rgb, f32) {
    let (kd, ks) = (kd.max(Rgb::ZERO), ks.max(Rgb::ZERO));
    let scale = Rgb::ONE / (kd + ks).max(Rgb::ONE);
    let (kd, ks) = (kd * scale, ks * scale);
    let (ld, ls) = (luminance(kd), luminance(ks));
    let spec_prob = if ld + ls > 0.0 { ls / (ld + ls) } else { 0.0 };
    (kd, ks, spec_prob)
}

/// Draws a direction around `axis` with density (n+1)/(2π) cos^n.
pub(crate) fn sample_lobe(axis: Vec3A, exponent: f32, u: Vec2) -> Vec3A {
    let cos = u.x.powf(1.0 / (exponent + 1.0));
    let sin = (1.0 - cos * cos).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Frame::from_normal(axis).to_world(Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos))
}

/// Density of [`sample_lobe`] at angle cosine `cos` from its axis.
pub(crate) fn lobe_pdf(exponent: f32, cos: f32) -> f32 {
    if cos <= 0.0 {
        0.0
    } else {
        (exponent + 1.0) * 0.5 * FRAC_1_PI * cos.powf(exponent)
    }
}

impl Phong {
    /// Diffuse `kd` and specular `ks` reflectance (scaled down per channel so
    /// `kd + ks ≤ 1`, so the surface creates no energy) and lobe sharpness
    /// `exponent` ≥ 0 (clamped).
    pub fn new(kd: Rgb, ks: Rgb, exponent: f32) -> Self {
        let (kd, ks, spec_prob) = conserve(kd, ks);
        Self {
            kd,
            ks,
            exponent: exponent.max(0.0),
            spec_prob,
        }
    }

    /// Cosine between `wi` and the mirror direction of `wo`.
    fn cos_alpha(wo: Vec3A, wi: Vec3A) -> f32 {
        Vec3A::new(-wo.x, -wo.y, wo.z).dot(wi)
    }
}

impl Bxdf for Phong {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let cos_a = Self::cos_alpha(wo, wi).max(0.0);
        let n = self.exponent;
        self.kd * FRAC_1_PI + self.ks * ((n + 2.0) * 0.5 * FRAC_1_PI * cos_a.powf(n))
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let p = self.spec_prob;
        (1.0 - p) * sampling::cosine_hemisphere_pdf(wi.z.abs())
            + p * lobe_pdf(self.exponent, Self::cos_alpha(wo, wi))
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 || self.spec_prob == 0.0 && self.kd == Rgb::ZERO {
            return None;
        }
        let wi = if u_lobe < self.spec_prob {
            sample_lobe(Vec3A::new(-wo.x, -wo.y, wo.z), self.exponent, u)
        } else {
            let w = sampling::cosine_hemisphere(u);
            Vec3A::new(w.x, w.y, w.z.copysign(wo.z))
        };
        BsdfSample::from_f(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

/// A Phong material as the scene gives it: what [`super::Material::Phong`]
/// holds. `kd + ks` is scaled down per channel to at most 1 when the lobe
/// is built (see [`Phong::new`]).
#[derive(Clone, Debug)]
pub struct PhongMaterial {
    /// Diffuse reflectance per channel.
    pub kd: ColorTex,
    /// Specular reflectance per channel.
    pub ks: ColorTex,
    /// Sharpness n of the `cosⁿα` lobe, ≥ 0.
    pub exponent: ScalarTex,
}

impl MaterialModel for PhongMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::Phong(Phong::new(
            self.kd.eval(at, textures),
            self.ks.eval(at, textures),
            self.exponent.eval(at, textures),
        ))
    }
    /// Both lobes reflect: their sum (the AOV clamps it as the model caps it).
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.kd.eval(at, textures) + self.ks.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.kd) || f(&self.ks) || f(&self.exponent)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{assert_energy_sweep, check_all, incidences};

    #[test]
    fn phong_chi2_agreement_energy() {
        for (i, n) in [1.0, 10.0, 100.0].into_iter().enumerate() {
            for wo in incidences() {
                let mixed = Phong::new(Rgb::splat(0.4), Rgb::splat(0.6), n);
                check_all(&mixed, wo, &format!("phong n={n}"), 40 + i as u64);
            }
            // All specular at normal incidence reflects exactly ks = 1.
            let spec = Phong::new(Rgb::ZERO, Rgb::ONE, n);
            let e = check_all(&spec, Vec3A::Z, &format!("phong spec n={n}"), 50 + i as u64);
            assert!(
                e > 0.99,
                "n={n}: ks = 1 at normal incidence must reflect all, got {e}"
            );
        }
    }

    #[test]
    fn phong_scales_kd_plus_ks_to_one() {
        let p = Phong::new(Rgb::new(0.8, 0.2, 0.0), Rgb::new(0.8, 0.2, 2.0), 5.0);
        assert_eq!(p.kd + p.ks, Rgb::new(1.0, 0.4, 1.0));
        assert_eq!(p.kd.x, 0.5);
    }

    #[test]
    fn phong_energy_sweep() {
        for n in [0.0, 1.0, 10.0, 100.0, 1000.0] {
            assert_energy_sweep(&Phong::new(Rgb::ZERO, Rgb::ONE, n), &format!("phong n={n}"));
            let mixed = Phong::new(Rgb::splat(0.5), Rgb::splat(0.5), n);
            assert_energy_sweep(&mixed, &format!("phong mixed n={n}"));
        }
    }
}
