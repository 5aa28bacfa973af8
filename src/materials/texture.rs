//! Colour parameters that vary over a surface.

use crate::math::Rgb;
use glam::Vec2;

/// A colour parameter: a constant or a lookup into the scene's textures.
#[derive(Clone, Debug)]
pub enum ColorTex {
    Const(Rgb),
}

impl ColorTex {
    #[inline]
    pub fn eval(&self, _uv: Vec2, _textures: &[Texture]) -> Rgb {
        match self {
            ColorTex::Const(c) => *c,
        }
    }
}

/// A decoded image texture (linear RGB texels).
#[derive(Clone, Debug)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub texels: Vec<Rgb>,
}
