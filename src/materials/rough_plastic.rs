//! Rough plastic: a diffuse base under a rough dielectric coat, Mitsuba 3's
//! `roughplastic` with `nonlinear = false`
//! (<https://github.com/mitsuba-renderer/mitsuba3/blob/master/src/bsdfs/roughplastic.cpp>),
//! after Weidlich & Wilkie 2007 (<https://doi.org/10.1145/1321261.1321292>).
//!
//! `f = s·F(wo·h; η)·D(h)·G1(wo)·G1(wi) / (4 cos θo cos θi)
//!    + ρ/(1 − R_int) · t(cos θo)·t(cos θi) / (π η²)`
//!
//! with `s` the specular factor, `ρ` the diffuse reflectance, `h` the half
//! vector, exact dielectric `F`, Mitsuba's *separable* Smith shadowing (not
//! the height-correlated G2 of [`super::CookTorrance`]) and the coat's
//! tabulated transmittance `t` and internal reflectance `R_int` (see
//! [`RoughCoat`]). `η` = η(coat)/η(outside). The first term is the coat's
//! reflection; the second is light that crosses the coat, is scattered by
//! the base and crosses back, its inter-reflections under the coat summed as
//! if the base were white (`nonlinear = false`: the colour stays linear in ρ).
//! Single scattering in the coat, and the light the coat's masking loses is
//! lost for good, so rough coats darken: white (ρ = s = 1) GGX plastic
//! returns 98 % of the light at roughness 0.1, 92 % at 0.3 and 55 % at 0.7
//! (Beckmann, with lighter tails, 98 %, 97 %, 75 %), as Mitsuba's does.
//!
//! Two-sided like every opaque model (Mitsuba's is one-sided).
//!
//! Sampling, as Mitsuba: the coat's visible normals (see
//! [`super::microfacet`]) with probability `(1 − t(cos θo))·w / ((1 −
//! t(cos θo))·w + t(cos θo)·(1 − w))`, `w = mean(s)/(mean(ρ) + mean(s))`,
//! else the cosine-weighted hemisphere; the pdf is the mixture's. The means
//! are this hit's colours (Mitsuba averages a texture over its whole image).

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, RoughCoat, Texture, flip_up, fresnel, reflect};
use super::{TexPoint, TexProbe};
use crate::math::{Rgb, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

/// Rough plastic at one hit point: resolved colours and the material's coat.
#[derive(Clone, Copy, Debug)]
pub struct RoughPlastic<'a> {
    /// ρ, the base's reflectance.
    pub diffuse: Rgb,
    /// s, a factor on the coat's reflection (1 for a physical coat).
    pub specular: Rgb,
    /// The coat and its tables, built once per material at load.
    pub coat: &'a RoughCoat,
}

impl RoughPlastic<'_> {
    /// Probability of sampling the coat's reflection at `cos θo`.
    fn specular_prob(&self, cos_o: f32) -> f32 {
        let (s, d) = (self.specular.element_sum(), self.diffuse.element_sum());
        if s + d <= 0.0 {
            return 1.0;
        }
        let w = s / (s + d);
        let t = self.coat.t(cos_o);
        let (ps, pd) = ((1.0 - t) * w, t * (1.0 - w));
        if ps + pd > 0.0 { ps / (ps + pd) } else { 1.0 }
    }

    /// `f` for `wo`, `wi` in the upper hemisphere.
    fn f(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        let coat = self.coat;
        let m = &coat.microfacet;
        let diffuse = self.diffuse
            * (coat.t(wo.z) * coat.t(wi.z) * FRAC_1_PI
                / ((1.0 - coat.internal_reflectance) * coat.eta * coat.eta));
        let Some(h) = (wo + wi).try_normalize() else {
            return diffuse;
        };
        let fr = fresnel::dielectric(wo.dot(h), coat.eta);
        let specular = fr * m.d(h) * m.g1(wo) * m.g1(wi) / (4.0 * wo.z * wi.z);
        self.specular * specular + diffuse
    }

    /// The mixture's density for `wo`, `wi` in the upper hemisphere.
    fn pdf_up(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        let p = self.specular_prob(wo.z);
        let specular = match (wo + wi).try_normalize() {
            Some(h) => self.coat.microfacet.pdf_wm(wo, h) / (4.0 * wo.dot(h)),
            None => 0.0,
        };
        p * specular + (1.0 - p) * sampling::cosine_hemisphere_pdf(wi.z)
    }
}

impl Bxdf for RoughPlastic<'_> {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (wo, wi) = flip_up(wo, wi);
        self.f(wo, wi)
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let (wo, wi) = flip_up(wo, wi);
        self.pdf_up(wo, wi)
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let (wo_up, _) = flip_up(wo, wo);
        let wi = if u_lobe < self.specular_prob(wo_up.z) {
            let wm = self.coat.microfacet.sample_wm(wo_up, u);
            reflect(wo_up, wm)
        } else {
            sampling::cosine_hemisphere(u)
        };
        if wi.z <= 0.0 {
            return None;
        }
        let pdf = self.pdf_up(wo_up, wi);
        // A density that overflowed (a sliver of a narrow lobe) is refused
        // rather than turned into a zero or NaN weight.
        if !pdf.is_finite() {
            return None;
        }
        let f = self.f(wo_up, wi);
        // Back to wo's side; |wi.z| is unchanged, so the weight is too.
        let wi = if wo.z < 0.0 {
            Vec3A::new(wi.x, wi.y, -wi.z)
        } else {
            wi
        };
        BsdfSample::from_f(wi, f, pdf)
    }
}

/// Mitsuba's `roughplastic` (`nonlinear = false`) as the scene gives it:
/// what [`super::Material::RoughPlastic`] holds. `coat` holds the tables
/// integrated at load (shared by materials with the same distribution, α
/// and η).
#[derive(Clone, Debug)]
pub struct RoughPlasticMaterial {
    /// Reflectance of the diffuse base per channel, in [0, 1].
    pub diffuse: ColorTex,
    /// Factor on the coat's reflection per channel (1 for a physical coat).
    pub specular: ColorTex,
    /// The coat: distribution, α, η and its t(μ) and R_int tables.
    pub coat: std::sync::Arc<RoughCoat>,
}

impl MaterialModel for RoughPlasticMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::RoughPlastic(RoughPlastic {
            diffuse: self.diffuse.eval(at, textures),
            specular: self.specular.eval(at, textures),
            coat: &self.coat,
        })
    }
    /// The base of the layered surface (OIDN ignores a clear coat).
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.diffuse.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.diffuse) || f(&self.specular)
    }
}

#[cfg(test)]
#[path = "tests/rough_plastic.rs"]
mod tests;
