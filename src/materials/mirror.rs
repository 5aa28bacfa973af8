//! Perfect specular reflection: a Dirac lobe in the mirror direction.
//! `eval` and `pdf` are zero (a delta cannot be evaluated at a direction);
//! `sample` returns the reflected direction with weight `tint`, pdf 1.
//! For a coloured metal with physical Fresnel use a smooth `CookTorrance`.

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, MaterialModel, Texture};
use super::{TexPoint, TexProbe};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// Perfect mirror BSDF at one hit.
#[derive(Clone, Copy, Debug)]
pub struct Mirror {
    /// Colour multiplying the reflection, per channel in [0, 1].
    pub tint: Rgb,
}

impl Bxdf for Mirror {
    fn eval(&self, _wo: Vec3A, _wi: Vec3A) -> Rgb {
        Rgb::ZERO
    }

    fn pdf(&self, _wo: Vec3A, _wi: Vec3A) -> f32 {
        0.0
    }

    fn sample(&self, wo: Vec3A, _u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let wi = Vec3A::new(-wo.x, -wo.y, wo.z);
        Some(BsdfSample::delta(wi, self.tint, 1.0, 1.0))
    }

    fn is_delta(&self) -> bool {
        true
    }
}

/// A perfect mirror as the scene gives it: what [`super::Material::Mirror`]
/// holds.
#[derive(Clone, Debug)]
pub struct MirrorMaterial {
    /// Colour multiplying the reflection, per channel in [0, 1].
    pub tint: ColorTex,
}

impl MaterialModel for MirrorMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::Mirror(Mirror {
            tint: self.tint.eval(at, textures),
        })
    }
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.tint.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.tint)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Pcg32, sampling};

    #[test]
    fn mirror_reflects_exactly_and_losslessly() {
        let m = Mirror { tint: Rgb::ONE };
        assert!(m.is_delta());
        let mut rng = Pcg32::new(5, 6);
        for _ in 0..1000 {
            let wo = sampling::uniform_sphere(rng.next_vec2());
            let s = m
                .sample(wo, rng.next_f32(), rng.next_vec2())
                .expect("mirror always reflects");
            // Law of reflection: same angle to the normal, opposite tangent.
            assert_eq!(s.wi.z, wo.z);
            assert_eq!((s.wi.x, s.wi.y), (-wo.x, -wo.y));
            assert!(s.delta && s.pdf == 1.0 && s.eta == 1.0);
            assert_eq!(s.weight, Rgb::ONE, "tint 1 is lossless");
            assert_eq!(m.eval(wo, s.wi), Rgb::ZERO);
            assert_eq!(m.pdf(wo, s.wi), 0.0);
        }
    }
}
