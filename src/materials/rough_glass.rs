//! Rough dielectric boundary (frosted glass): microfacet reflection and
//! transmission after Walter et al. 2007, "Microfacet Models for Refraction
//! through Rough Surfaces" (<https://doi.org/10.2312/EGWR/EGSR07/195-206>),
//! in the form of pbrt-v4's rough `DielectricBxDF`
//! (<https://pbr-book.org/4ed/Reflection_Models/Roughness_Using_Microfacet_Theory>).
//!
//! * **Sides** as for [`super::Glass`]: the normal points outside, `wo.z < 0`
//!   arrives from inside, `ior` = η(inside)/η(outside). Internally a `wo`
//!   from inside is flipped up with `1/ior`, so the maths sees light
//!   arriving from above a boundary of relative index `η = η(below)/η(above)`.
//! * **Half vector** `wm ∝ wo + η'·wi` (η' = η for transmission, 1 for
//!   reflection), turned to +z; a pair whose `wo` or `wi` sees `wm` from
//!   behind scatters nothing.
//! * **Reflection** `f = D(wm)·G2·F / (4 |cos θo cos θi|)`; **transmission**
//!   `f = tint · D(wm)·G2·(1 − F)·|wi·wm|·|wo·wm| / ((wi·wm + wo·wm/η')²·|cos θi cos θo|) / η'²`,
//!   exact dielectric `F(wo·wm; η)`, GGX or Beckmann `D` and the
//!   height-correlated Smith `G2` of [`super::microfacet`] (pbrt-v4's
//!   choice; Walter's separable G1·G1 shadows a little more).
//! * **Radiance scaling** as for smooth glass: the final `1/η'²` is the
//!   camera path's `(η_from/η_to)²` (Mitsuba 3 `roughdielectric`, radiance
//!   mode). So `f(wo, wi)/η(wo side)² = f(wi, wo)/η(wi side)²` (Veach 1997,
//!   §5.2), and [`BsdfSample::eta`] is η' for a refracted sample.
//! * **Tint** colours transmitted light, once per crossing.
//! * **Sampling**: a microfacet normal (GGX by visible normals, Beckmann by
//!   `D cos`), then reflection with probability F, else refraction through
//!   it; `pdf = pdf(wm)·F/(4|wo·wm|)` or `pdf(wm)·(1 − F)·|wi·wm|/(wi·wm + wo·wm/η')²`.
//!   Under total internal reflection F = 1.
//!
//! Checked against Mitsuba 3's `roughdielectric` at 120 direction pairs on
//! both sides: equal to f32 rounding once its G1·G1 replaces our G2, and the
//! GGX pdf equal too (`rough_glass_matches_mitsuba_up_to_its_shadowing_term`).

use super::{
    Bsdf, BsdfSample, Bxdf, ColorTex, Distribution, MaterialModel, Microfacet, Roughness, ScalarTex, Texture,
    fresnel, reflect,
};
use super::{TexPoint, TexProbe};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// A rough dielectric boundary at one hit point (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct RoughGlass {
    /// Microfacet distribution and α of the boundary.
    pub microfacet: Microfacet,
    /// η(inside)/η(outside).
    pub ior: f32,
    /// Colour of transmitted light, once per crossing.
    pub tint: Rgb,
}

/// Mirrors `w` through the surface plane.
#[inline]
fn flip(w: Vec3A) -> Vec3A {
    Vec3A::new(w.x, w.y, -w.z)
}

impl RoughGlass {
    /// `wo` and `wi` in the frame where `wo` is above, with η(below)/η(above).
    #[inline]
    fn oriented(&self, wo: Vec3A, wi: Vec3A) -> (Vec3A, Vec3A, f32) {
        if wo.z < 0.0 {
            (flip(wo), flip(wi), 1.0 / self.ior)
        } else {
            (wo, wi, self.ior)
        }
    }

    /// `(f, pdf)` for `wo` above (z > 0) and any `wi`, boundary index `eta`.
    fn f_pdf(&self, wo: Vec3A, wi: Vec3A, eta: f32) -> Option<(Rgb, f32)> {
        let (cos_o, cos_i) = (wo.z, wi.z);
        if cos_o <= 0.0 || cos_i == 0.0 {
            return None;
        }
        let reflect = cos_i > 0.0;
        let etap = if reflect { 1.0 } else { eta };
        // Generalised half vector, on the outside (+z).
        let wm = (wi * etap + wo).try_normalize()?;
        let wm = if wm.z < 0.0 { -wm } else { wm };
        let (dot_o, dot_i) = (wo.dot(wm), wi.dot(wm));
        // Neither direction may see the microfacet from behind.
        if wm.z == 0.0 || dot_o <= 0.0 || dot_i * cos_i <= 0.0 {
            return None;
        }
        let m = &self.microfacet;
        // Through a refraction F is the same from either side; from the
        // thinner side it has no cancellation near the critical angle, and
        // f(wo, wi) and f(wi, wo) then round alike.
        let fr = if reflect {
            // wo·wm and wi·wm differ only by rounding; their mean makes
            // f(wo, wi) and f(wi, wo) bit for bit equal.
            fresnel::dielectric(0.5 * (dot_o + dot_i), eta)
        } else if eta >= 1.0 {
            fresnel::dielectric(dot_o, eta)
        } else {
            fresnel::dielectric(-dot_i, 1.0 / eta)
        };
        let d_g = m.d(wm) * m.g2(wo, wi);
        let pdf_wm = m.pdf_wm(wo, wm);
        if reflect {
            let f = d_g * fr / (4.0 * cos_o * cos_i);
            return Some((Rgb::splat(f), pdf_wm / (4.0 * dot_o) * fr));
        }
        let denom = dot_i + dot_o / etap;
        let denom2 = denom * denom;
        let f = d_g * (1.0 - fr) * (dot_i * dot_o).abs() / (denom2 * (cos_i * cos_o).abs()) / (etap * etap);
        let dwm_dwi = dot_i.abs() / denom2;
        Some((self.tint * f, pdf_wm * dwm_dwi * (1.0 - fr)))
    }
}

impl Bxdf for RoughGlass {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let (wo, wi, eta) = self.oriented(wo, wi);
        self.f_pdf(wo, wi, eta).map_or(Rgb::ZERO, |(f, _)| f)
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let (wo, wi, eta) = self.oriented(wo, wi);
        self.f_pdf(wo, wi, eta).map_or(0.0, |(_, pdf)| pdf)
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let (wo_up, _, eta) = self.oriented(wo, wo);
        let wm = self.microfacet.sample_wm(wo_up, u);
        let cos_om = wo_up.dot(wm);
        if cos_om <= 0.0 {
            return None;
        }
        let fr = fresnel::dielectric(cos_om, eta);
        let refract = u_lobe >= fr;
        let (wi, etap) = if refract {
            // Snell about wm (F < 1 here, so no total internal reflection).
            let sin2_t = (1.0 - cos_om * cos_om) / (eta * eta);
            if sin2_t >= 1.0 {
                return None;
            }
            let cos_t = (1.0 - sin2_t).sqrt();
            ((-wo_up / eta + (cos_om / eta - cos_t) * wm).normalize(), eta)
        } else {
            (reflect(wo_up, wm), 1.0)
        };
        // A reflection must stay above, a refraction go below.
        if (refract && wi.z >= 0.0) || (!refract && wi.z <= 0.0) {
            return None;
        }
        let (f, pdf) = self.f_pdf(wo_up, wi, eta)?;
        // Refuse a density that overflowed rather than return a NaN weight.
        if !pdf.is_finite() {
            return None;
        }
        let wi = if wo.z < 0.0 { flip(wi) } else { wi };
        BsdfSample::from_f(wi, f, pdf).map(|s| BsdfSample { eta: etap, ..s })
    }

    fn transmits(&self) -> bool {
        true
    }
}

/// A rough dielectric boundary (Walter et al. 2007) as the scene gives it,
/// sides as for smooth glass: what [`super::Material::RoughGlass`] holds.
#[derive(Clone, Debug)]
pub struct RoughGlassMaterial {
    /// Microfacet normal distribution.
    pub distribution: Distribution,
    /// Perceptual roughness in [0, 1] (`alpha = roughness²`) or α.
    pub roughness: Roughness,
    /// Index of refraction η(inside)/η(outside), > 0 and ≠ 1.
    pub ior: ScalarTex,
    /// Colour of transmitted light, applied once per refraction.
    pub tint: ColorTex,
    /// Absorption coefficient inside the solid, per channel, in 1/scene
    /// units (zero: clear glass); see [`super::Material::interior`].
    pub absorption: Rgb,
}

impl MaterialModel for RoughGlassMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::RoughGlass(RoughGlass {
            microfacet: self.roughness.microfacet(self.distribution, at, textures),
            ior: self.ior.eval(at, textures),
            tint: self.tint.eval(at, textures),
        })
    }
    /// 1 times the absorption tint, as OIDN asks of dielectrics.
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.tint.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.tint) || f(&self.roughness.tex) || f(&self.ior)
    }
}

#[cfg(test)]
#[path = "tests/rough_glass.rs"]
mod tests;
