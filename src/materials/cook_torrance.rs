//! Microfacet reflection from a rough conductor (Cook & Torrance 1982,
//! <https://doi.org/10.1145/357290.357293>, in the form of Walter et al.
//! 2007): `f = D(wm)·G2(wo, wi)·F(wo·wm) / (4 cos θo cos θi)` with `wm` the
//! half vector. Only single scattering: rough surfaces lose some energy to
//! light that bounces between facets (Heitz et al. 2016 would restore it).
//!
//! Sampling draws `wm` from the distribution (see [`super::microfacet`]) and
//! reflects `wo` about it; `pdf(wi) = pdf(wm) / (4 |wo·wm|)`.

use super::{
    Bsdf, BsdfSample, Bxdf, Distribution, Fresnel, MaterialModel, Microfacet, Roughness, Texture, flip_up,
    reflect,
};
use super::{TexPoint, TexProbe};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// Rough-conductor BSDF at one hit: a microfacet distribution and the conductor's
/// Fresnel reflectance.
#[derive(Clone, Copy, Debug)]
pub struct CookTorrance {
    /// Normal distribution and width (α) of the microfacets.
    pub distribution: Microfacet,
    /// Reflectance of each microfacet.
    pub fresnel: Fresnel,
}

impl CookTorrance {
    /// `f` for `wo`, `wi` in the upper hemisphere and their half vector `wm`.
    fn f(&self, wo: Vec3A, wi: Vec3A, wm: Vec3A) -> Rgb {
        let m = &self.distribution;
        let fr = self.fresnel.eval(wo.dot(wm));
        fr * (m.d(wm) * m.g2(wo, wi) / (4.0 * wo.z * wi.z))
    }
}

impl Bxdf for CookTorrance {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        let (wo, wi) = flip_up(wo, wi);
        let Some(wm) = (wo + wi).try_normalize() else {
            return Rgb::ZERO;
        };
        self.f(wo, wi, wm)
    }

    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        let (wo, wi) = flip_up(wo, wi);
        let Some(wm) = (wo + wi).try_normalize() else {
            return 0.0;
        };
        self.distribution.pdf_wm(wo, wm) / (4.0 * wo.dot(wm))
    }

    fn sample(&self, wo: Vec3A, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let (wo_up, _) = flip_up(wo, wo);
        let wm = self.distribution.sample_wm(wo_up, u);
        let cos_om = wo_up.dot(wm);
        let wi = reflect(wo_up, wm);
        if cos_om <= 0.0 || wi.z <= 0.0 {
            return None;
        }
        let pdf = self.distribution.pdf_wm(wo_up, wm) / (4.0 * cos_om);
        // Model-specific guard, on top of from_f's pdf ≤ 0: refuse a density
        // that overflowed rather than return a zero or NaN weight.
        if !pdf.is_finite() {
            return None;
        }
        let f = self.f(wo_up, wi, wm);
        // Back to wo's side; |wi.z| is unchanged, so the weight is too.
        let wi = if wo.z < 0.0 {
            Vec3A::new(wi.x, wi.y, -wi.z)
        } else {
            wi
        };
        BsdfSample::from_f(wi, f, pdf)
    }
}

/// A microfacet conductor as the scene gives it (Smith height-correlated
/// masking-shadowing): what [`super::Material::CookTorrance`] holds.
#[derive(Clone, Debug)]
pub struct CookTorranceMaterial {
    /// Microfacet normal distribution.
    pub distribution: Distribution,
    /// Perceptual roughness in [0, 1] (`alpha = roughness²`) or α.
    pub roughness: Roughness,
    /// Reflectance of the conductor.
    pub fresnel: Fresnel,
}

impl MaterialModel for CookTorranceMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::CookTorrance(CookTorrance {
            distribution: self.roughness.microfacet(self.distribution, at, textures),
            fresnel: self.fresnel,
        })
    }
    /// The conductor's colour lives in its Fresnel term; OIDN allows 1.
    fn albedo(&self, _at: &TexPoint, _textures: &[Texture]) -> Rgb {
        Rgb::ONE
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.roughness.tex)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{assert_energy_sweep, check_all, incidences};
    use crate::materials::{Distribution, Metal};

    fn white(distribution: Distribution, roughness: f32) -> CookTorrance {
        CookTorrance {
            distribution: Microfacet::from_roughness(distribution, roughness),
            fresnel: Fresnel::Schlick { f0: Rgb::ONE },
        }
    }

    #[test]
    fn cook_torrance_ggx_chi2_agreement_energy() {
        for (i, roughness) in [0.1, 0.3, 0.7].into_iter().enumerate() {
            for wo in incidences() {
                let e = check_all(&white(Distribution::Ggx, roughness), wo, "ggx", 10 + i as u64);
                // Single scattering: lossless only when smooth and not grazing.
                if roughness <= 0.1 && wo.z > 0.5 {
                    assert!(e > 0.97, "smooth GGX with F = 1 should reflect ~all: {e}");
                }
            }
        }
    }

    #[test]
    fn cook_torrance_beckmann_chi2_agreement_energy() {
        for (i, roughness) in [0.1, 0.3, 0.7].into_iter().enumerate() {
            for wo in incidences() {
                check_all(
                    &white(Distribution::Beckmann, roughness),
                    wo,
                    "beckmann",
                    20 + i as u64,
                );
            }
        }
    }

    #[test]
    fn cook_torrance_gold_is_yellow() {
        let gold = CookTorrance {
            distribution: Microfacet::from_roughness(Distribution::Ggx, 0.3),
            fresnel: Metal::Gold.fresnel(),
        };
        let e = check_all(&gold, incidences()[0], "gold", 30);
        assert!(e < 1.0);
    }

    #[test]
    fn cook_torrance_energy_sweep() {
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            for roughness in [0.0, 0.1, 0.3, 0.5, 0.7, 1.0] {
                let b = white(distribution, roughness);
                assert_energy_sweep(&b, &format!("{distribution:?} r={roughness}"));
            }
        }
    }
}
