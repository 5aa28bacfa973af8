//! The albedo a first hit shows, as Open Image Denoise's documentation asks
//! for its `albedo` input ("Albedos" in the RT filter section of
//! <https://github.com/RenderKit/oidn/blob/master/doc/api.md>): the diffuse
//! colour of matte surfaces, the reflectance at normal incidence of metals
//! (or 1 when that is not a colour we hold), the tint of mirrors, 1 times the
//! absorption tint for dielectrics, the base of layered surfaces (a clear
//! coat is ignored). Values are clamped to [0, 1].

use crate::materials::TexPoint;
use crate::materials::{Material, Texture};
use crate::math::Rgb;

/// The albedo of `material` at surface coordinates `uv`, in [0, 1].
pub fn first_hit_albedo(material: &Material, at: &TexPoint, textures: &[Texture]) -> Rgb {
    // Each model says what its albedo is (`MaterialModel::albedo`).
    material.albedo(at, textures).clamp(Rgb::ZERO, Rgb::ONE)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::{ColorTex, Emitter, LambertMaterial, PhongMaterial};

    #[test]
    fn matte_albedo_is_its_colour_and_phong_sums_are_clamped() {
        let c = Rgb::new(0.2, 0.5, 0.7);
        let m = Material::Lambert(LambertMaterial {
            albedo: ColorTex::Const(c),
        });
        assert_eq!(first_hit_albedo(&m, &TexPoint::uv(glam::Vec2::ZERO), &[]), c);
        let p = Material::Phong(PhongMaterial {
            kd: ColorTex::Const(Rgb::splat(0.7)),
            ks: ColorTex::Const(Rgb::splat(0.6)),
            exponent: crate::materials::Tex::Const(10.0),
        });
        assert_eq!(
            first_hit_albedo(&p, &TexPoint::uv(glam::Vec2::ZERO), &[]),
            Rgb::ONE
        );
        assert_eq!(
            first_hit_albedo(&Material::Emitter(Emitter), &TexPoint::uv(glam::Vec2::ZERO), &[]),
            Rgb::ZERO
        );
    }
}
