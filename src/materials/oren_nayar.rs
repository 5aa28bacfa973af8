//! Rough diffuse reflection: Fujii's improved Oren–Nayar ("FON", Y. Fujii
//! 2012, "A tiny improvement of Oren-Nayar reflectance model",
//! <https://mimosa-pudica.net/improved-oren-nayar.html>), a reformulation of
//! the qualitative model of Oren & Nayar 1994
//! (<https://doi.org/10.1145/192161.192213>, eq. 30):
//!
//! `f = R·(A + B·s/t)`, `s = wi·wo − cos θi cos θo`,
//! `t = 1` if s ≤ 0 else `max(cos θi, cos θo)`,
//! `A = 1/(π + (π/2 − 2/3)σ)`, `B = σ·A`.
//!
//! **Why this variant.** The qualitative model of pbrt-v3 (A = 1 −
//! σ²/(2(σ²+0.33)), B = 0.45σ²/(σ²+0.09), σ an angle) creates energy at
//! grazing incidence: at θo → 90° its albedo is A + B/2, which is 1.015 for
//! σ = 10° (our energy sweep caught it at θo = 85°). FON keeps the same
//! shape (retro-reflection, flattening), has no dark-rim artefact, is
//! reciprocal, cheaper (no trigonometry) and never reflects more than R.
//! It loses some energy at large σ (no interreflection term; EON, Portsmouth
//! et al. 2025, <https://arxiv.org/abs/2410.18026>, adds it back with fits).
//!
//! **Units.** `sigma` is FON's **unitless** roughness, ≥ 0, useful range
//! [0, 1] (0 = Lambert); it is *not* an angle in radians or degrees.
//!
//! Cosine-sampled: the lobe is close to cosine, so the weight stays near R.

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, ScalarTex, Texture, flip_up};
use super::{TexPoint, TexProbe};
use crate::math::{Rgb, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Fujii's energy-conserving Oren–Nayar BSDF at one hit, its `A` and `B` terms
/// precomputed from `sigma`.
#[derive(Clone, Copy, Debug)]
pub struct OrenNayar {
    albedo: Rgb,
    a: f32,
    b: f32,
}

impl OrenNayar {
    /// `sigma`: unitless roughness ≥ 0 (clamped), see the module doc.
    pub fn new(albedo: Rgb, sigma: f32) -> Self {
        let sigma = sigma.max(0.0);
        let a = 1.0 / (PI + (0.5 * PI - 2.0 / 3.0) * sigma);
        Self {
            albedo,
            a,
            b: sigma * a,
        }
    }
}

impl Bxdf for OrenNayar {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (wo, wi) = flip_up(wo, wi);
        // s = cos(φi − φo) sin θi sin θo: the projected alignment.
        let s = wi.dot(wo) - wi.z * wo.z;
        let t = if s <= 0.0 { 1.0 } else { wi.z.max(wo.z) };
        self.albedo * (self.a + self.b * s / t)
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
        BsdfSample::from_f(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

/// An Oren–Nayar material as the scene gives it: what
/// [`super::Material::OrenNayar`] holds. `sigma` is Fujii's **unitless**
/// roughness ≥ 0 (0 = Lambert, useful up to 1); not an angle (see the
/// module doc for why).
#[derive(Clone, Debug)]
pub struct OrenNayarMaterial {
    /// Diffuse reflectance per channel, in [0, 1].
    pub albedo: ColorTex,
    /// Roughness, unitless, ≥ 0.
    pub sigma: ScalarTex,
}

impl MaterialModel for OrenNayarMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::OrenNayar(OrenNayar::new(
            self.albedo.eval(at, textures),
            self.sigma.eval(at, textures),
        ))
    }
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.albedo.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.albedo) || f(&self.sigma)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{assert_energy_sweep, check_all, incidences};
    use std::f32::consts::FRAC_1_PI;

    #[test]
    fn oren_nayar_chi2_agreement_energy() {
        for (i, sigma) in [0.3f32, 1.0].into_iter().enumerate() {
            let on = OrenNayar::new(Rgb::ONE, sigma);
            for wo in incidences() {
                check_all(&on, wo, &format!("oren-nayar σ={sigma}"), 80 + i as u64);
            }
        }
    }

    #[test]
    fn oren_nayar_energy_sweep() {
        for sigma in [0.0f32, 0.05, 0.1, 0.3, 0.6, 1.0, 2.0] {
            let on = OrenNayar::new(Rgb::ONE, sigma);
            let e = assert_energy_sweep(&on, &format!("oren-nayar σ={sigma}"));
            if sigma == 0.0 {
                assert!(e > 0.99, "σ = 0 is Lambert and must be lossless: {e}");
            }
        }
    }

    #[test]
    fn oren_nayar_sigma_zero_is_lambert() {
        let on = OrenNayar::new(Rgb::splat(0.5), 0.0);
        let (wo, wi) = (Vec3A::new(0.6, 0.0, 0.8), Vec3A::new(-0.28, 0.96, 0.0));
        let f = on.eval(wo, (wi * 0.5 + Vec3A::Z * 0.866).normalize());
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
        assert!(back > forward, "backscatter {back} must exceed forward {forward}");
        assert!(back > FRAC_1_PI, "retro-reflection exceeds Lambert: {back}");
    }
}
