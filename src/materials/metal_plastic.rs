//! The glTF 2.0 metallic–roughness material
//! (<https://registry.khronos.org/glTF/specs/2.0/glTF-2.0.html#appendix-b-brdf-implementation>):
//! one parameter set spans dielectrics ("plastic", metalness 0) and metals
//! (metalness 1).
//!
//! `f = F(wo·h)·D·G2/(4 cos θo cos θi) + (1 − m)·(1 − F(cos θo))·(1 − F(cos θi))·base/π`
//! with Schlick `F`, `F0 = mix(0.04, base, m)`, GGX `alpha = roughness²` and
//! height-correlated Smith G2 (see [`super::microfacet`]).
//!
//! **Deviation from glTF.** glTF weights the diffuse term by `1 − F(wo·h)`.
//! That is not energy conserving: at θo = 80°, roughness 0.1, white base,
//! it reflects 1.35 (the specular lobe takes F(80°) ≈ 0.4 of the light,
//! but the diffuse lobe, integrated over `wi`, mostly sees half vectors
//! near `wo` where F is small). We use the reciprocal coupling
//! `(1 − F(cos θo))(1 − F(cos θi))` of Shirley et al. 1997 / Ashikhmin &
//! Shirley 2000 (<https://doi.org/10.1080/10867651.2000.10487522>): light
//! enters the diffuse base through the interface once each way. The
//! specular albedo stays near or below F(cos θo), so the sum stays ≤ 1;
//! the energy sweep test checks it over roughness × metalness × θo.
//! The diffuse base is Lambert, as in glTF; Oren–Nayar's extra backscatter
//! is not worth its cost under a coat.
//!
//! Sampling: GGX visible normals with probability ∝ luminance of
//! F(cos θo), else cosine; the pdf is the mixture's.

use super::{
    Bsdf, BsdfSample, Bxdf, ColorTex, Distribution, MaterialModel, Microfacet, Roughness, ScalarTex, Texture,
    fresnel, reflect,
};
use super::{TexPoint, TexProbe};
use crate::math::{Rgb, luminance, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

/// glTF metallic–roughness BSDF at one hit, with the parameters already mixed into a
/// specular `F0` and a diffuse colour.
#[derive(Clone, Copy, Debug)]
pub struct MetalPlastic {
    f0: Rgb,
    /// `(1 − metalness)·base_color`.
    diffuse: Rgb,
    ggx: Microfacet,
}

impl MetalPlastic {
    /// `roughness`, `metalness` are clamped to [0, 1].
    pub fn new(base_color: Rgb, roughness: f32, metalness: f32) -> Self {
        let m = metalness.clamp(0.0, 1.0);
        let base = base_color.clamp(Rgb::ZERO, Rgb::ONE);
        Self {
            f0: Rgb::splat(0.04).lerp(base, m),
            diffuse: base * (1.0 - m),
            ggx: Microfacet::from_roughness(Distribution::Ggx, roughness),
        }
    }

    /// Probability of sampling the specular lobe from `wo` (z > 0).
    fn spec_prob(&self, cos_o: f32) -> f32 {
        let ls = luminance(fresnel::schlick(self.f0, cos_o));
        let ld = luminance(self.diffuse) * (1.0 - ls);
        if ld <= 0.0 {
            1.0
        } else {
            (ls / (ls + ld)).clamp(0.1, 0.9)
        }
    }
}

impl Bxdf for MetalPlastic {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (wo, wi) = super::flip_up(wo, wi);
        let Some(wm) = (wo + wi).try_normalize() else {
            return Rgb::ZERO;
        };
        let f = fresnel::schlick(self.f0, wo.dot(wm));
        let spec = self.ggx.d(wm) * self.ggx.g2(wo, wi) / (4.0 * wo.z * wi.z);
        let (f_o, f_i) = (fresnel::schlick(self.f0, wo.z), fresnel::schlick(self.f0, wi.z));
        let diffuse = (Rgb::ONE - f_o) * (Rgb::ONE - f_i) * self.diffuse * FRAC_1_PI;
        f * spec + diffuse
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let (wo, wi) = super::flip_up(wo, wi);
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        let p = self.spec_prob(wo.z);
        let spec = self.ggx.pdf_wm(wo, wm) / (4.0 * wo.dot(wm));
        p * spec + (1.0 - p) * sampling::cosine_hemisphere_pdf(wi.z)
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let (wo_up, _) = super::flip_up(wo, wo);
        let wi = if u_lobe < self.spec_prob(wo_up.z) {
            let wm = self.ggx.sample_wm(wo_up, u);
            reflect(wo_up, wm)
        } else {
            sampling::cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        let wi = if wo.z < 0.0 {
            Vec3A::new(wi.x, wi.y, -wi.z)
        } else {
            wi
        };
        BsdfSample::from_f(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

/// glTF's metallic–roughness material as the scene gives it (a diffuse base
/// under a GGX coat): what [`super::Material::MetalPlastic`] holds.
#[derive(Clone, Debug)]
pub struct MetalPlasticMaterial {
    /// Diffuse colour (plastic) or reflectance at normal incidence (metal),
    /// per channel in [0, 1].
    pub base_color: ColorTex,
    /// Perceptual roughness in [0, 1] (GGX `alpha = roughness²`) or α.
    pub roughness: Roughness,
    /// 0 is plastic, 1 is metal, in [0, 1].
    pub metalness: ScalarTex,
}

impl MaterialModel for MetalPlasticMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::MetalPlastic(MetalPlastic::new(
            self.base_color.eval(at, textures),
            self.roughness.perceptual_at(at, textures),
            self.metalness.eval(at, textures),
        ))
    }
    /// Diffuse colour for plastic, reflectance at normal incidence for metal.
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.base_color.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.base_color) || f(&self.roughness.tex) || f(&self.metalness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{assert_energy_sweep, check_all, incidences};

    fn check(metalness: f32, seed: u64) {
        for roughness in [0.1, 0.3, 0.7] {
            let b = MetalPlastic::new(Rgb::ONE, roughness, metalness);
            for wo in incidences() {
                check_all(
                    &b,
                    wo,
                    &format!("metal-plastic r={roughness} m={metalness}"),
                    seed,
                );
            }
        }
    }

    #[test]
    fn metal_plastic_half_metal_chi2_agreement_energy() {
        check(0.5, 90);
    }

    // White plastic and white metal: the extremes for energy.
    #[test]
    fn metal_plastic_white_plastic_chi2_agreement_energy() {
        check(0.0, 91);
    }

    #[test]
    fn metal_plastic_white_metal_chi2_agreement_energy() {
        check(1.0, 92);
    }

    #[test]
    fn metal_plastic_energy_sweep() {
        for roughness in [0.0, 0.1, 0.3, 0.5, 0.7, 1.0] {
            for m in [0.0, 0.5, 1.0] {
                let b = MetalPlastic::new(Rgb::ONE, roughness, m);
                assert_energy_sweep(&b, &format!("metal-plastic r={roughness} m={m}"));
            }
        }
    }
}
