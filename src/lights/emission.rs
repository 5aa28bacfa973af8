//! Radiance that varies over an emitter's surface: an emission texture.
//!
//! An emitting quad, rectangle, sphere or mesh may give its `radiance` as a
//! texture (an image, a checker, a pattern) looked up at the surface's UVs.
//! The light keeps its own copy of the one image it reads, so sampling and
//! evaluating it need nothing from the scene.
//!
//! **Sampling stays unbiased, not importance-sampled within the light.** A
//! textured light is sampled exactly as a constant one (uniformly by area or
//! solid angle), and the sample carries the texture's value at the sampled
//! point; every point where the texture is non-zero has a non-zero density,
//! so the estimate is unbiased (pbrt-v4's `DiffuseAreaLight` with an image
//! does the same). Light *selection* (power, the light tree) weighs the light
//! by its texture's **average** over the unit uv square, measured on a
//! 128 × 128 grid ([`GRID`]) when the scene loads. A mostly black image with a
//! small bright logo is therefore sampled over its whole area: correct, but
//! noisier than sampling the texels by their power would be.

use crate::materials::texture::{ColorTex, Tex, Texture};
use crate::math::{Rgb, luminance};
use glam::Vec2;
use std::sync::Arc;

/// Samples per uv axis over which an emission texture's average is measured.
pub const GRID: u32 = 128;

/// An emission texture with the one image it reads (if any).
#[derive(Debug)]
pub struct EmissionTexture {
    /// The texture; an image lookup's index is 0, into `image`.
    tex: ColorTex,
    /// The image the texture reads, empty for checkers and patterns.
    image: Vec<Texture>,
    /// Factor on every value (an MTL `Ke` on its `map_Ke`).
    factor: Rgb,
}

impl EmissionTexture {
    /// `tex` reading the scene's `textures`, with a copy of the image it
    /// reads. `None` for a constant (which needs no texture).
    pub fn new(tex: &ColorTex, textures: &[Texture]) -> Option<Arc<Self>> {
        let (tex, image) = match tex {
            Tex::Const(_) => return None,
            Tex::Image(l) => {
                let image = textures.get(l.index as usize)?.clone();
                let mut l = *l;
                l.index = 0;
                (Tex::Image(l), vec![image])
            }
            t => (t.clone(), Vec::new()),
        };
        Some(Arc::new(Self {
            tex,
            image,
            factor: Rgb::ONE,
        }))
    }

    /// Radiance at texture coordinates `uv`.
    #[inline]
    pub fn eval(&self, uv: Vec2) -> Rgb {
        self.factor
            * self
                .tex
                .eval(&crate::materials::TexPoint::uv(uv), &self.image)
                .max(Rgb::ZERO)
    }

    /// The average over the unit uv square on a [`GRID`]² grid of cell
    /// centres, raised to a thousandth of the largest value seen where the
    /// average is zero: what light selection weighs. Never zero where the
    /// texture is non-zero anywhere on the grid, so a light that glows is
    /// always picked now and then.
    pub fn average(&self) -> Rgb {
        let mut sum = glam::DVec3::ZERO;
        let mut max = Rgb::ZERO;
        for j in 0..GRID {
            for i in 0..GRID {
                let uv = Vec2::new((i as f32 + 0.5) / GRID as f32, (j as f32 + 0.5) / GRID as f32);
                let c = self.eval(uv);
                sum += glam::DVec3::new(c.x as f64, c.y as f64, c.z as f64);
                max = max.max(c);
            }
        }
        let mean = sum / (GRID * GRID) as f64;
        let mean = Rgb::new(mean.x as f32, mean.y as f32, mean.z as f32);
        if luminance(mean) > 0.0 { mean } else { 1e-3 * max }
    }
}

/// An emitter's radiance: a constant, or a texture with its average (what
/// [`super::Light::power`] reports).
#[derive(Clone, Debug)]
pub struct Emission {
    /// The constant radiance, or the texture's average.
    pub radiance: Rgb,
    /// The texture, when the radiance varies.
    pub texture: Option<Arc<EmissionTexture>>,
}

impl Emission {
    /// The same radiance everywhere.
    pub fn constant(radiance: Rgb) -> Self {
        Self {
            radiance,
            texture: None,
        }
    }

    /// `tex` over the scene's `textures`: a constant stays one.
    pub fn new(tex: &ColorTex, textures: &[Texture]) -> Self {
        match EmissionTexture::new(tex, textures) {
            None => Self::constant(tex.eval(&crate::materials::TexPoint::uv(Vec2::ZERO), textures)),
            Some(t) => Self {
                radiance: t.average(),
                texture: Some(t),
            },
        }
    }

    /// This emission times `f` per channel.
    pub fn scaled(self, f: Rgb) -> Self {
        Self {
            radiance: self.radiance * f,
            texture: self.texture.map(|t| {
                Arc::new(EmissionTexture {
                    tex: t.tex.clone(),
                    image: t.image.clone(),
                    factor: t.factor * f,
                })
            }),
        }
    }

    /// Radiance at texture coordinates `uv`.
    #[inline]
    pub fn at(&self, uv: Vec2) -> Rgb {
        match &self.texture {
            None => self.radiance,
            Some(t) => t.eval(uv),
        }
    }

    /// Whether the radiance varies over the surface.
    pub fn is_textured(&self) -> bool {
        self.texture.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::texture::UvTransform;

    #[test]
    fn checker_emission_averages_its_two_squares() {
        let tex = Tex::Checker {
            a: Rgb::splat(4.0),
            b: Rgb::ZERO,
            scale: 4.0,
            uv: UvTransform::default(),
        };
        let e = Emission::new(&tex, &[]);
        assert!((e.radiance.x - 2.0).abs() < 1e-4, "{:?}", e.radiance);
        assert_eq!(e.at(Vec2::new(0.1, 0.1)), Rgb::splat(4.0));
        assert_eq!(e.at(Vec2::new(0.3, 0.1)), Rgb::ZERO);
    }

    #[test]
    fn constant_emission_is_not_textured() {
        let e = Emission::new(&Tex::Const(Rgb::splat(3.0)), &[]);
        assert!(!e.is_textured());
        assert_eq!(e.at(Vec2::new(0.7, 0.2)), Rgb::splat(3.0));
    }

    #[test]
    fn an_image_emission_reads_its_own_copy() {
        let img = Texture::from_srgb8(2, 1, &[255, 255, 255, 0, 0, 0]);
        let e = Emission::new(&ColorTex::image(1), &[Texture::from_srgb8(1, 1, &[0, 0, 0]), img]);
        assert!(e.is_textured());
        assert!((e.radiance.x - 0.5).abs() < 0.02, "{:?}", e.radiance);
    }
}
