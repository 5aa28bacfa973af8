//! The surface of an area light: black and non-reflecting, as the Mitsuba
//! references' area emitters are. The loader gives it to every emitting
//! object and light surface; what they emit is the light's business
//! (`lights/`), not the material's.

use super::{Bsdf, Lambert, MaterialModel, Texture};
use super::{TexPoint, TexProbe};
use crate::math::Rgb;

/// The material of an emitting surface: reflects nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct Emitter;

impl MaterialModel for Emitter {
    /// A black diffuse lobe: light sampling and BSDF sampling both give
    /// zero, the same arithmetic as any other Lambert surface.
    #[inline]
    fn bsdf(&self, _at: &TexPoint, _textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::Lambert(Lambert { albedo: Rgb::ZERO })
    }
    /// Light sources reflect nothing.
    fn albedo(&self, _at: &TexPoint, _textures: &[Texture]) -> Rgb {
        Rgb::ZERO
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        let _ = f;
        false
    }
}
