//! How samples become pixels and pixels become a picture: the pixel filter
//! and the tone map (fields of `film`).

use serde::{Deserialize, Serialize};

/// Pixel reconstruction filter. Each camera sample's film position is drawn
/// from the filter around the pixel centre (filter importance sampling), so a
/// pixel depends only on its own samples.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum FilterDesc {
    /// Uniform over the pixel's square (radius ½): sharp, slightly aliased.
    #[default]
    Box,
    /// Gaussian `exp(−x²/2σ²)`, shifted to reach 0 at `radius` (pbrt-v4's).
    Gaussian {
        /// Half-width in pixels, in (0, 8] (default 1.5).
        #[serde(default = "gaussian_radius")]
        #[schemars(range(min = 0, max = 8))]
        radius: f32,
        /// Standard deviation in pixels, in [0.05, 8] (default 0.5).
        #[serde(default = "gaussian_sigma")]
        #[schemars(range(min = 0.05, max = 8))]
        sigma: f32,
    },
    /// Mitchell–Netravali cubic; sharper than the Gaussian, with small negative
    /// lobes (a sample there counts negatively).
    Mitchell {
        /// Half-width in pixels, in (0, 8] (default 2).
        #[serde(default = "mitchell_radius")]
        #[schemars(range(min = 0, max = 8))]
        radius: f32,
        /// Blur parameter B, in [0, 1] (default ⅓).
        #[serde(default = "third")]
        #[schemars(range(min = 0, max = 1))]
        b: f32,
        /// Ringing parameter C, in [0, 1] (default ⅓).
        #[serde(default = "third")]
        #[schemars(range(min = 0, max = 1))]
        c: f32,
    },
}

fn gaussian_radius() -> f32 {
    1.5
}
fn gaussian_sigma() -> f32 {
    0.5
}
fn mitchell_radius() -> f32 {
    2.0
}
fn third() -> f32 {
    1.0 / 3.0
}

/// How linear radiance (after exposure) becomes display values in [0, 1].
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum TonemapDesc {
    /// Values above 1 are cut to 1: highlights burn out.
    #[default]
    Clamp,
    /// `x / (1 + x)` per channel: never burns out, flattens highlights.
    Reinhard,
    /// Narkowicz's fit of the ACES filmic curve, per channel.
    Aces,
    /// Troy Sobotka's AgX (Blender's default view since 4.0): bright colours
    /// desaturate toward white instead of skewing hue.
    AgX,
}
