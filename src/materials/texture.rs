//! Colour parameters that vary over a surface.
//!
//! Images are stored decoded, in **linear** RGB: the scene loader reads the
//! file and calls [`Texture::from_srgb8`], so this module does no file IO and
//! the render path never converts colour spaces.
//!
//! Texture coordinates: `uv = (0, 0)` is the **bottom-left** corner of the
//! image and `(1, 1)` the top-right (OpenGL/OBJ convention); texels are
//! stored in file order, top row first. Lookups wrap (repeat) in both axes.

use crate::math::Rgb;
use glam::Vec2;

/// A colour parameter: a constant or a lookup into the scene's textures.
#[derive(Clone, Debug)]
pub enum ColorTex {
    /// The same linear RGB value everywhere.
    Const(Rgb),
    /// Index into the scene's texture list (checked by the loader).
    Image(u32),
    /// Squares of side `1/scale` in uv space alternating `a` and `b`; the
    /// square containing uv (0, 0)+ is `a`.
    Checker {
        /// Colour of the square at uv (0, 0) and every other square, linear RGB.
        a: Rgb,
        /// Colour of the remaining squares, linear RGB.
        b: Rgb,
        /// Squares per uv unit, > 0.
        scale: f32,
    },
}

impl ColorTex {
    /// The colour at texture coordinates `uv`; images are filtered bilinearly and
    /// repeat outside [0, 1]².
    #[inline]
    pub fn eval(&self, uv: Vec2, textures: &[Texture]) -> Rgb {
        match self {
            ColorTex::Const(c) => *c,
            ColorTex::Image(i) => match textures.get(*i as usize) {
                Some(t) => t.bilinear(uv),
                None => {
                    debug_assert!(false, "texture index {i} out of range");
                    Rgb::ZERO
                }
            },
            ColorTex::Checker { a, b, scale } => {
                let p = (uv * *scale).floor();
                if (p.x + p.y).rem_euclid(2.0) < 0.5 { *a } else { *b }
            }
        }
    }
}

/// A decoded image texture (linear RGB texels, row-major, top row first).
#[derive(Clone, Debug)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Linear RGB texels, row-major, top row first: texel `(x, y)` is
    /// `texels[y·width + x]`.
    pub texels: Vec<Rgb>,
}

/// The sRGB transfer function lives with the other image conversions.
pub use crate::imageio::srgb_decode as srgb_to_linear;

impl Texture {
    /// As [`Texture::from_srgb8`], but running out of memory for the texels
    /// (a 8192² texture is 1 GiB of them) is an error, not an abort.
    pub fn try_from_srgb8(width: u32, height: u32, rgb: &[u8]) -> Result<Self, String> {
        let mut texels = Vec::new();
        let n = rgb.len() / 3;
        texels.try_reserve_exact(n).map_err(|_| {
            format!(
                "not enough memory for a {width}×{height} texture ({} MiB)",
                (n * std::mem::size_of::<Rgb>()) >> 20
            )
        })?;
        let lut: Vec<f32> = (0..=255u8).map(|b| srgb_to_linear(b as f32 / 255.0)).collect();
        texels.extend(
            rgb.chunks_exact(3)
                .map(|p| Rgb::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize])),
        );
        Ok(Self {
            width,
            height,
            texels,
        })
    }

    /// Decodes 8-bit sRGB texels (`rgb.len() == 3·width·height`, file order)
    /// to linear RGB.
    pub fn from_srgb8(width: u32, height: u32, rgb: &[u8]) -> Self {
        debug_assert_eq!(rgb.len(), 3 * width as usize * height as usize);
        // 256 entries: decoding stays exact and costs one lookup per byte.
        let lut: Vec<f32> = (0..=255u8).map(|b| srgb_to_linear(b as f32 / 255.0)).collect();
        let texels = rgb
            .chunks_exact(3)
            .map(|p| Rgb::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
            .collect();
        Self {
            width,
            height,
            texels,
        }
    }

    #[inline]
    fn texel(&self, x: i64, y: i64) -> Rgb {
        let x = x.rem_euclid(self.width as i64) as usize;
        let y = y.rem_euclid(self.height as i64) as usize;
        self.texels[y * self.width as usize + x]
    }

    /// Bilinear lookup with repeat wrapping; texel centres sit at half-integer
    /// positions, so a 1×1 image is constant.
    pub fn bilinear(&self, uv: Vec2) -> Rgb {
        if self.texels.is_empty() {
            return Rgb::ZERO;
        }
        // Continuous texel coordinates, v flipped so v = 0 is the bottom row.
        let x = uv.x * self.width as f32 - 0.5;
        let y = (1.0 - uv.y) * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let (x0, y0) = (x0 as i64, y0 as i64);
        let top = self.texel(x0, y0).lerp(self.texel(x0 + 1, y0), fx);
        let bottom = self.texel(x0, y0 + 1).lerp(self.texel(x0 + 1, y0 + 1), fx);
        top.lerp(bottom, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texture_srgb_decode_endpoints_and_mid_grey() {
        let t = Texture::from_srgb8(3, 1, &[255, 255, 255, 0, 0, 0, 128, 128, 128]);
        assert_eq!(t.texels[0], Rgb::ONE, "sRGB 255 must decode to 1");
        assert_eq!(t.texels[1], Rgb::ZERO, "sRGB 0 must decode to 0");
        let mid = srgb_to_linear(0.5);
        assert!((mid - 0.214).abs() < 1e-3, "sRGB 0.5 → {mid}, expected ≈ 0.214");
        assert!(
            (t.texels[2].x - 0.2158).abs() < 1e-3,
            "sRGB 128 → {}",
            t.texels[2].x
        );
    }

    #[test]
    fn texture_checker_alternates() {
        let c = ColorTex::Checker {
            a: Rgb::ONE,
            b: Rgb::ZERO,
            scale: 4.0,
        };
        let at = |u: f32, v: f32| c.eval(Vec2::new(u, v), &[]).x;
        assert_eq!(at(0.1, 0.1), 1.0);
        assert_eq!(at(0.3, 0.1), 0.0);
        assert_eq!(at(0.1, 0.3), 0.0);
        assert_eq!(at(0.3, 0.3), 1.0);
        assert_eq!(at(-0.1, 0.1), 0.0, "negative uv continues the pattern");
    }

    #[test]
    fn texture_bilinear_interpolates_and_wraps() {
        // 2×1 image: black on the left, white on the right.
        let t = Texture {
            width: 2,
            height: 1,
            texels: vec![Rgb::ZERO, Rgb::ONE],
        };
        let at = |u: f32| t.bilinear(Vec2::new(u, 0.5)).x;
        assert!((at(0.25) - 0.0).abs() < 1e-6, "left texel centre: {}", at(0.25));
        assert!((at(0.75) - 1.0).abs() < 1e-6, "right texel centre: {}", at(0.75));
        assert!((at(0.5) - 0.5).abs() < 1e-6, "halfway: {}", at(0.5));
        assert!((at(0.375) - 0.25).abs() < 1e-6, "quarter: {}", at(0.375));
        // u = 0 lies halfway between the right texel (wrapped) and the left one.
        assert!((at(0.0) - 0.5).abs() < 1e-6, "wrap: {}", at(0.0));
        assert!((at(1.25) - at(0.25)).abs() < 1e-6, "repeat");
        // uv (0,0) is the bottom-left: a 1×2 image with white on the top row.
        let t = Texture {
            width: 1,
            height: 2,
            texels: vec![Rgb::ONE, Rgb::ZERO],
        };
        assert!(
            t.bilinear(Vec2::new(0.5, 0.75)).x > 0.99,
            "v = 0.75 is the top row"
        );
        assert!(
            t.bilinear(Vec2::new(0.5, 0.25)).x < 0.01,
            "v = 0.25 is the bottom row"
        );
    }
}
