//! Camera, film and integrator settings.

use super::display::{FilterDesc, TonemapDesc};
use super::{AovDesc, V3};
use serde::{Deserialize, Serialize};

/// A camera looking from `eye` toward `target`: perspective (the default,
/// with `fov_y_degrees`), orthographic or spherical by `projection`.
/// Image x runs along `normalize(forward × up)` (to the right), image row 0 is
/// at the top.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Position of the camera (the pinhole, or the centre of the lens), in world
    /// space.
    pub eye: V3,
    /// A point the camera looks at; it is centred in the image. By default also
    /// the distance in focus.
    pub target: V3,
    /// Which way is up in the image, default `(0, 1, 0)`; need not be unit length
    /// or perpendicular to the view, but must not be parallel to `target − eye`.
    #[serde(default = "default_up")]
    pub up: V3,
    /// Full vertical field of view, in degrees, in (0, 180); required by the
    /// perspective projection, meaningless for the others.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0, max = 180))]
    pub fov_y_degrees: Option<f32>,
    /// How the image is formed: `Perspective` (default), `Orthographic(view_height:
    /// ..)` or `Spherical`.
    #[serde(default)]
    pub projection: ProjectionDesc,
    /// Thin-lens aperture radius in scene units; 0 is a pinhole (perspective only).
    #[serde(default)]
    pub aperture_radius: f32,
    /// Distance from `eye` to the plane in focus; defaults to |target − eye|.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<f32>,
}

/// The camera's projection.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum ProjectionDesc {
    /// Rays through the eye (a pinhole, or a thin lens with `aperture_radius`),
    /// with the camera's `fov_y_degrees`.
    #[default]
    Perspective,
    /// Parallel rays along the view: sizes do not shrink with distance. The
    /// image shows a rectangle `view_height` scene units tall (and `view_height ×
    /// width / height` wide) centred on `eye`, perpendicular to the view.
    Orthographic {
        /// Height of the rectangle seen, in scene units, > 0.
        view_height: f32,
    },
    /// Every direction around `eye`, latitude–longitude (equirectangular), with
    /// the environment map's mapping: the image centre looks at `target`, row 0
    /// straight up along `up`, the seam is behind. Use a 2:1 image.
    Spherical,
}

fn default_up() -> V3 {
    [0.0, 1.0, 0.0]
}

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

/// How light transport is estimated.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum IntegratorDesc {
    /// Emission plus one bounce of light: hard shadows from point lights,
    /// soft shadows from area lights with `light_samples` shadow rays per
    /// area light per camera sample.
    Direct {
        /// Shadow rays per area light per camera sample, 1 to 4096 (default 1): more
        /// gives smoother soft shadows at proportional cost.
        #[serde(default = "one")]
        light_samples: u32,
    },
    /// Direct lighting at diffuse and glossy surfaces, perfect reflection and
    /// refraction at mirrors and glass, up to `max_depth` specular bounces.
    Whitted {
        /// Most specular bounces (mirror reflections and glass refractions) followed
        /// from a camera ray, at most 64 (default 5).
        #[serde(default = "whitted_depth")]
        max_depth: u32,
        /// Shadow rays per area light at each diffuse or glossy hit, 1 to 4096
        /// (default 1).
        #[serde(default = "one")]
        light_samples: u32,
    },
    /// Path tracing with next-event estimation and MIS. `max_depth` counts
    /// path segments as Mitsuba does (2 = direct lighting only); −1 means
    /// unlimited. Russian roulette starts after `rr_depth` segments.
    Path {
        /// Longest path in segments (default 8): 1 sees only emitters, 2 is direct
        /// lighting, −1 is unlimited (Russian roulette still ends paths).
        #[serde(default = "path_depth")]
        max_depth: i32,
        /// Path segments before Russian roulette may end a path (default 5); lower is
        /// faster and noisier, never biased.
        #[serde(default = "rr_depth")]
        rr_depth: u32,
        /// How the light for next-event estimation is chosen.
        #[serde(default)]
        light_selection: LightSelectionDesc,
        /// How caustics seen directly (light focused onto a surface by perfect
        /// mirrors and smooth glass) are found (default `LightTracing`).
        #[serde(default)]
        caustics: CausticsDesc,
        /// Paths per camera sample, 1 to 16 (default 1, one path per camera
        /// sample, as Mitsuba traces): at its first diffuse or glossy surface a
        /// camera sample's path takes its one light sample, then goes on along
        /// this many BSDF samples, each weighted 1/splits (path splitting). The
        /// camera ray, first hit and light sample are shared, so the indirect
        /// light costs less per path; `spp` still counts camera samples.
        #[serde(default = "path_splits")]
        splits: u32,
    },
}

/// How the path tracer finds caustics seen directly: light reaching a
/// diffuse or glossy surface the camera sees through perfect mirrors and
/// smooth glass.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum CausticsDesc {
    /// Also from the light's side: a render of the whole frame traces paths
    /// from its rectangle and sphere lights toward its mirrors and glass and
    /// joins the surfaces they reach to the camera, for the caustics the
    /// camera sees directly. Far less noise there, the same image in
    /// expectation. Scenes without a perfect mirror or smooth glass surface,
    /// pinhole-less cameras, filters other than `Box`, farm pieces and watch
    /// passes render exactly as with `PathOnly`.
    #[default]
    LightTracing,
    /// Only by BSDF sampling from the camera's side (Mitsuba's `path`).
    PathOnly,
}

/// How next-event estimation picks the one light it samples at each path
/// vertex.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum LightSelectionDesc {
    /// In proportion to emitted power.
    Power,
    /// Every light equally likely.
    Uniform,
    /// By a light tree: in proportion to what each light can send to the
    /// shading point (power over squared distance, bounded by its extent
    /// and orientation), so scenes of many lights spend their shadow rays
    /// on the near ones that face the point. The sky is weighed by what it
    /// sends to the point (its irradiance there), not by its power through
    /// the scene, and a tenth of the picks stay uniform over all lights, so
    /// no light is starved where the estimate is wrong. With one light of
    /// finite extent and no sky it is `Power`: there is nothing to choose.
    #[default]
    Tree,
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
fn path_splits() -> u32 {
    1
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        IntegratorDesc::Direct { light_samples: 1 }
    }
}
