//! Ideal diffuse reflection, `f = albedo / π`, sampled by cosine weighting
//! (so the sample weight is exactly the albedo).

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, Texture};
use super::{TexPoint, TexProbe};
use crate::math::{Rgb, sampling};
use glam::{Vec2, Vec3A};
use std::f32::consts::FRAC_1_PI;

/// Ideal diffuse BSDF at one hit.
#[derive(Clone, Copy, Debug)]
pub struct Lambert {
    /// Diffuse reflectance per channel, in [0, 1]: the fraction of light reflected.
    pub albedo: Rgb,
}

impl Bxdf for Lambert {
    #[inline]
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        if wo.z * wi.z <= 0.0 {
            return Rgb::ZERO;
        }
        self.albedo * FRAC_1_PI
    }

    #[inline]
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        if wo.z * wi.z <= 0.0 {
            return 0.0;
        }
        sampling::cosine_hemisphere_pdf(wi.z.abs())
    }

    #[inline]
    fn sample(&self, wo: Vec3A, _u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let mut wi = sampling::cosine_hemisphere(u);
        if wo.z < 0.0 {
            wi.z = -wi.z;
        }
        let pdf = sampling::cosine_hemisphere_pdf(wi.z.abs());
        // (albedo/π)·cos / (cos/π) = albedo exactly: pass the weight, not f.
        BsdfSample::from_weight(wi, self.albedo, pdf)
    }
}

/// A Lambert material as the scene gives it, its albedo possibly a
/// texture: what [`super::Material::Lambert`] holds. It resolves to a
/// [`Lambert`] lobe at each hit.
#[derive(Clone, Debug)]
pub struct LambertMaterial {
    /// Diffuse reflectance per channel, in [0, 1].
    pub albedo: ColorTex,
}

impl MaterialModel for LambertMaterial {
    // Inline: the material dispatch inlines this one (see `Material::bsdf`).
    #[inline(always)]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::Lambert(Lambert {
            albedo: self.albedo.eval(at, textures),
        })
    }
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.albedo.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.albedo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::tests::{check_all, incidences};

    #[test]
    fn lambert_chi2_agreement_energy() {
        let white = Lambert { albedo: Rgb::ONE };
        for wo in incidences() {
            let e = check_all(&white, wo, "lambert", 1);
            assert!((0.99..1.01).contains(&e), "albedo 1 must reflect all: got {e}");
        }
    }
}
