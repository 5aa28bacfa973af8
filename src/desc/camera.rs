//! Camera, film and integrator settings.

use super::V3;
use serde::{Deserialize, Serialize};

/// A perspective camera looking from `eye` toward `target`.
/// Image x runs along `normalize(forward × up)` (to the right), image row 0 is
/// at the top.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    pub eye: V3,
    pub target: V3,
    #[serde(default = "default_up")]
    pub up: V3,
    /// Full vertical field of view, in degrees, in (0, 180).
    #[schemars(range(min = 0, max = 180))]
    pub fov_y_degrees: f32,
    /// Thin-lens aperture radius in scene units; 0 is a pinhole.
    #[serde(default)]
    pub aperture_radius: f32,
    /// Distance from `eye` to the plane in focus; defaults to |target − eye|.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<f32>,
}

fn default_up() -> V3 {
    [0.0, 1.0, 0.0]
}

/// Image size, sampling and output.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FilmDesc {
    #[serde(default = "default_width")]
    #[schemars(range(min = 1, max = 16384))]
    pub width: u32,
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
    /// Default output path (relative to the scene file); `.png` or `.exr`.
    /// Defaults to the scene's file name with `.png`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output: Option<String>,
    /// How sample positions are drawn.
    #[serde(default)]
    pub sampler: SamplerDesc,
}

/// Sample generator; all are deterministic per (pixel, sample, seed).
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum SamplerDesc {
    /// Uniform random numbers.
    Independent,
    /// Jittered strata (per pair of dimensions).
    Stratified,
    /// Owen-scrambled Sobol points: lowest error, best at power-of-two spp.
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
        }
    }
}

/// How light transport is estimated.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum IntegratorDesc {
    /// Emission plus one bounce of light: hard shadows from point lights,
    /// soft shadows from area lights with `light_samples` shadow rays per
    /// area light per camera sample.
    Direct {
        #[serde(default = "one")]
        light_samples: u32,
    },
    /// Direct lighting at diffuse and glossy surfaces, perfect reflection and
    /// refraction at mirrors and glass, up to `max_depth` specular bounces.
    Whitted {
        #[serde(default = "whitted_depth")]
        max_depth: u32,
        #[serde(default = "one")]
        light_samples: u32,
    },
    /// Path tracing with next-event estimation and MIS. `max_depth` counts
    /// path segments as Mitsuba does (2 = direct lighting only); −1 means
    /// unlimited. Russian roulette starts after `rr_depth` segments.
    Path {
        #[serde(default = "path_depth")]
        max_depth: i32,
        #[serde(default = "rr_depth")]
        rr_depth: u32,
        /// How the light for next-event estimation is chosen.
        #[serde(default)]
        light_selection: LightSelectionDesc,
    },
}

#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum LightSelectionDesc {
    /// In proportion to emitted power.
    #[default]
    Power,
    /// Every light equally likely.
    Uniform,
}

fn one() -> u32 {
    1
}
fn whitted_depth() -> u32 {
    5
}
fn path_depth() -> i32 {
    8
}
fn rr_depth() -> u32 {
    5
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        IntegratorDesc::Direct { light_samples: 1 }
    }
}
