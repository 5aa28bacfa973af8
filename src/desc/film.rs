//! The film a scene file describes: image size, sampling, filter, output
//! and layers.

use super::AovDesc;
use super::display::{FilterDesc, TonemapDesc};
use serde::{Deserialize, Serialize};

/// Image size, sampling and output.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FilmDesc {
    /// Image width in pixels, 1 to 16384 (default 512).
    #[serde(default = "default_width")]
    #[schemars(range(min = 1, max = 16384))]
    pub width: u32,
    /// Image height in pixels, 1 to 16384 (default 512).
    #[serde(default = "default_height")]
    #[schemars(range(min = 1, max = 16384))]
    pub height: u32,
    /// Samples per pixel.
    #[serde(default = "default_spp")]
    #[schemars(range(min = 1, max = 1048576))]
    pub spp: u32,
    /// Seed of every random stream: same seed, same image.
    #[serde(default)]
    pub seed: u64,
    /// Default output path (relative to the scene file): `.png` (display-referred:
    /// exposure and tone map applied, 8- or 16-bit sRGB), `.exr`, `.pfm` or `.hdr`
    /// (scene-linear radiance, as rendered).
    /// Defaults to the scene's file name with `.png`, in the current folder.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<String>,
    /// How sample positions are drawn.
    #[serde(default)]
    pub sampler: SamplerDesc,
    /// Pixel filter: `Box` (default), `Gaussian(..)` or `Mitchell(..)`.
    #[serde(default)]
    pub filter: FilterDesc,
    /// Exposure of PNG outputs in stops (default 0): +1 doubles the linear
    /// values before tone mapping. EXR, PFM and HDR outputs stay as rendered.
    #[serde(default)]
    #[schemars(range(min = -64, max = 64))]
    pub exposure: f32,
    /// Tone map of PNG outputs: `Clamp` (default), `Reinhard`, `Aces` or `AgX`.
    #[serde(default)]
    pub tonemap: TonemapDesc,
    /// Bits per channel of PNG outputs: 8 (default) or 16.
    #[serde(default = "default_png_bits")]
    #[schemars(range(min = 8, max = 16))]
    pub png_bits: u8,
    /// Extra layers written beside the beauty pass, EXR outputs only:
    /// `[Albedo, Normal, Depth, Position, MaterialIndex, ObjectIndex]` in any order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub aovs: Vec<AovDesc>,
    /// Denoise the image with Intel Open Image Denoise (needs ronray built
    /// with `--features denoise`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub denoise: bool,
    /// Adaptive sampling: a pixel stops before `spp` samples once the
    /// standard error of its mean is at most this fraction of its value (of
    /// display white, for darker pixels). 0 (the default) takes `spp`
    /// samples everywhere; 0.01 is typical.
    #[serde(default)]
    #[schemars(range(min = 0.0, max = 1.0))]
    pub noise_threshold: f32,
    /// With `noise_threshold`: samples every pixel takes before it may stop
    /// (default 16). Raise it for caustics a few samples can miss.
    #[serde(default = "default_min_spp")]
    #[schemars(range(min = 2, max = 1048576))]
    pub min_spp: u32,
    /// How the `spp × pixels` samples are spread: `ByNoise` (default) takes
    /// half of them in every pixel, then the rest where that first pass
    /// saw noise (same time, lower error); `Even` takes `spp` in every pixel.
    /// Renders below 32 spp, adaptive or `Stratified` ones and farm pieces
    /// spread evenly.
    #[serde(default)]
    pub allocation: AllocationDesc,
}

/// `film.allocation`: how samples are spread over the pixels.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum AllocationDesc {
    /// `spp` samples in every pixel.
    Even,
    /// Half everywhere, the rest by the noise around each pixel.
    #[default]
    ByNoise,
}

/// `film.min_spp` when the scene leaves it out.
pub const DEFAULT_MIN_SPP: u32 = 16;

fn default_min_spp() -> u32 {
    DEFAULT_MIN_SPP
}

fn default_png_bits() -> u8 {
    8
}

/// Sample generator; all are deterministic per (pixel, sample, seed).
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum SamplerDesc {
    /// Uniform random numbers.
    Independent,
    /// Jittered strata (per pair of dimensions).
    Stratified,
    /// Owen-scrambled Sobol points: lowest error, stratified at any multiple of 8 spp.
    #[default]
    Sobol,
}

fn default_width() -> u32 {
    512
}
fn default_height() -> u32 {
    512
}
fn default_spp() -> u32 {
    16
}

impl Default for FilmDesc {
    fn default() -> Self {
        Self {
            width: default_width(),
            height: default_height(),
            spp: default_spp(),
            seed: 0,
            output: None,
            sampler: SamplerDesc::default(),
            filter: FilterDesc::default(),
            exposure: 0.0,
            tonemap: TonemapDesc::default(),
            png_bits: default_png_bits(),
            aovs: Vec::new(),
            denoise: false,
            noise_threshold: 0.0,
            min_spp: DEFAULT_MIN_SPP,
            allocation: AllocationDesc::default(),
        }
    }
}
