//! Normalised Blinn–Phong (Blinn 1977, "Models of Light Reflection for
//! Computer Synthesized Pictures", <https://doi.org/10.1145/965141.563893>):
//!
//! `f = kd/π + ks·(n+2)/(8π)·cos^n θh`, θh the angle of the half vector.
//!
//! **Normalisation, derived.** `D(h) = (n+2)/(2π) cos^n θh` is a normalised
//! normal distribution (∫ D cos θh dωh = 1). Put it in the microfacet BRDF
//! `D·G·F/(4 cos θo cos θi)` with F = ks and the implicit visibility
//! `G = cos θo cos θi` (Hoffman, "Background: Physics and Math of Shading",
//! SIGGRAPH 2013, <https://blog.selfshadow.com/publications/s2013-shading-course/>)
//! and the cosines cancel: `ks·D/4 = ks·(n+2)/(8π) cos^n θh`. The albedo
//! is `ks ∫ D(h) cos θi (wo·h) dωh`; at normal incidence that is
//! `ks ∫ D cos θh cos 2θh dωh < ks`, and it falls toward grazing (the
//! energy sweep test checks θo = 0…89° for n = 0…1000),
//! so, as for [`super::Phong`], `kd + ks ≤ 1` suffices. Giesen's exact factor
//! (n+2)(n+4)/(8π(2^(−n/2)+n)) (<http://www.farbrausch.de/~fg/stuff/phong.pdf>)
//! makes normal incidence exactly lossless; we keep the microfacet-derived
//! one, whose meaning (a normalised D) carries over to other angles.
//!
//! Reciprocal (h is symmetric in wo, wi). Sampled as a mixture of cosine
//! sampling and half vectors drawn ∝ cos^n θh, reflected: pdf(wi) =
//! (n+1)/(2π) cos^n θh / (4 wo·h).

use super::phong::{conserve, lobe_pdf, sample_lobe};
use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, ScalarTex, Texture, reflect};
use super::{TexPoint, TexProbe};
use crate::math::{Rgb, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

/// Energy-normalised Blinn–Phong BSDF with its parameters fixed at one hit (see the
/// module docs for the formula and sampling).
#[derive(Clone, Copy, Debug)]
pub struct BlinnPhong {
    kd: Rgb,
    ks: Rgb,
    exponent: f32,
    spec_prob: f32,
}

impl BlinnPhong {
    /// Scales `kd + ks` to ≤ 1 per channel, as [`super::Phong::new`].
    pub fn new(kd: Rgb, ks: Rgb, exponent: f32) -> Self {
        let (kd, ks, spec_prob) = conserve(kd, ks);
        Self {
            kd,
            ks,
            exponent: exponent.max(0.0),
            spec_prob,
        }
    }

    /// Half vector on the side of the normal, or None when undefined.
    fn half(wo: Vec3A, wi: Vec3A) -> Option<Vec3A> {
        let h = (wo + wi).try_normalize()?;
        Some(if h.z < 0.0 { -h } else { h })
    }
}

impl Bxdf for BlinnPhong {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let cos_h = Self::half(wo, wi).map_or(0.0, |h| h.z);
        let n = self.exponent;
        self.kd * FRAC_1_PI + self.ks * ((n + 2.0) * 0.125 * FRAC_1_PI * cos_h.powf(n))
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let p = self.spec_prob;
        let spec = match Self::half(wo, wi) {
            Some(h) => lobe_pdf(self.exponent, h.z) / (4.0 * wo.dot(h).abs()),
            None => 0.0,
        };
        (1.0 - p) * sampling::cosine_hemisphere_pdf(wi.z.abs()) + p * spec
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 || self.spec_prob == 0.0 && self.kd == Rgb::ZERO {
            return None;
        }
        let wi = if u_lobe < self.spec_prob {
            let h = sample_lobe(Vec3A::Z, self.exponent, u);
            let h = if wo.z < 0.0 { -h } else { h };
            // A facet facing away from wo cannot reflect it.
            if wo.dot(h) <= 0.0 {
                return None;
            }
            reflect(wo, h)
        } else {
            let w = sampling::cosine_hemisphere(u);
            Vec3A::new(w.x, w.y, w.z.copysign(wo.z))
        };
        BsdfSample::from_f(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

/// A Blinn–Phong material as the scene gives it: what
/// [`super::Material::BlinnPhong`] holds; `kd + ks` is capped per channel
/// as for Phong.
#[derive(Clone, Debug)]
pub struct BlinnPhongMaterial {
    /// Diffuse reflectance per channel.
    pub kd: ColorTex,
    /// Specular reflectance per channel.
    pub ks: ColorTex,
    /// Sharpness n of the `cosⁿθh` lobe, ≥ 0.
    pub exponent: ScalarTex,
}

impl MaterialModel for BlinnPhongMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::BlinnPhong(BlinnPhong::new(
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
    fn blinn_phong_chi2_agreement_energy() {
        for (i, n) in [1.0, 10.0, 100.0].into_iter().enumerate() {
            for wo in incidences() {
                let mixed = BlinnPhong::new(Rgb::splat(0.4), Rgb::splat(0.6), n);
                check_all(&mixed, wo, &format!("blinn n={n}"), 60 + i as u64);
                let spec = BlinnPhong::new(Rgb::ZERO, Rgb::ONE, n);
                check_all(&spec, wo, &format!("blinn spec n={n}"), 70 + i as u64);
            }
        }
    }

    #[test]
    fn blinn_phong_energy_sweep() {
        for n in [0.0, 1.0, 10.0, 100.0, 1000.0] {
            assert_energy_sweep(&BlinnPhong::new(Rgb::ZERO, Rgb::ONE, n), &format!("blinn n={n}"));
            let mixed = BlinnPhong::new(Rgb::splat(0.5), Rgb::splat(0.5), n);
            assert_energy_sweep(&mixed, &format!("blinn mixed n={n}"));
        }
    }
}
