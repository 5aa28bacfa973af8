//! What a scene file may say: plain serde data, nothing resolved.
//!
//! Every struct denies unknown fields so a misspelling is an error, not a
//! silently ignored line. Defaults live here (`#[serde(default)]`); name
//! references (materials) are resolved later, in `build`.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     film: (width: 64, height: 48, spp: 4),
//!     materials: { "white": Lambert(albedo: (0.8, 0.8, 0.8)) },
//!     lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))],
//!     objects: [Sphere(center: (0, 0, 0), radius: 1, material: "white")],
//! )"#;
//! // As the loader reads it: optional fields are written bare (`40`, not `Some(40)`).
//! let scene: ronray::desc::SceneDesc = ron::Options::default()
//!     .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
//!     .from_str(text)
//!     .unwrap();
//! assert_eq!(scene.objects.len(), 1);
//! ```

mod animation;
mod aov;
mod camera;
mod color;
mod display;
mod emission;
mod film;
mod integrator;
mod light;
mod material;
mod medium;
mod object;
mod sdf;
mod texture;
mod transform;

pub use animation::{AnimationDesc, CameraKeyDesc, InterpolationDesc, TransformKeyDesc};
pub use aov::AovDesc;
pub use camera::{CameraDesc, GltfCameraDesc, ProjectionDesc};
pub use color::ColorDesc;
pub use display::{FilterDesc, TonemapDesc};
pub use emission::EmissionDesc;
pub use film::{AllocationDesc, FilmDesc, SamplerDesc};
pub use integrator::{CausticsDesc, IntegratorDesc, LightSelectionDesc};
pub use light::LightDesc;
pub use material::{
    AttenuationDesc, CutoutModeDesc, DielectricFresnelDesc, DistributionDesc, FresnelDesc, MaterialDesc,
    MaterialInner, MetalDesc, RoughnessUnitDesc, TangentFrameDesc,
};
pub use medium::MediumDesc;
pub use object::{MeshDesc, ObjectDesc, SphereUvDesc};
pub use sdf::{MarchDesc, RotationDesc, SdfDesc};
pub use texture::{
    ChannelDesc, ColorspaceDesc, ImageDesc, OriginDesc, PatternDesc, ScalarDesc, TexDesc, UvDesc, WrapDesc,
};
pub use transform::TransformDesc;

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A point or vector, written `(x, y, z)`.
pub type V3 = [f32; 3];
/// A linear RGB colour, written `(r, g, b)`.
pub type Color = [f32; 3];

/// A whole scene file.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(rename = "Scene", deny_unknown_fields)]
pub struct SceneDesc {
    /// The scene-format version the file is written in (`ronray migrate`
    /// brings a file to the current one, [`crate::migrate::CURRENT`]). A file
    /// without one is version 1, the format before textures on every number;
    /// version 2 only added forms, so version 1 files mean what they meant.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub version: Option<u32>,
    /// Files whose materials, lights and objects are added to this scene
    /// (relative to this file); this file's own materials override theirs.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub include: Vec<String>,
    /// Where the image is seen from: position, aim, field of view and depth of
    /// field. The only section every scene must have.
    pub camera: CameraDesc,
    /// Image size, samples per pixel, seed, sampler and output file; every field
    /// has a default (512×512, 16 spp).
    #[serde(default)]
    pub film: FilmDesc,
    /// How light transport is estimated; default `Direct(light_samples: 1)`.
    #[serde(default)]
    pub integrator: IntegratorDesc,
    /// Named materials; objects refer to them by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDesc>,
    /// Light sources. Area lights (`Quad`, `Rect`) are also surfaces that camera
    /// rays see; point and spot lights are not; an `Environment` (at most one)
    /// surrounds the scene.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// The geometry; each entry names a material from `materials`.
    #[serde(default)]
    pub objects: Vec<ObjectDesc>,
    /// Named participating media (fog, smoke, the inside of wax); the
    /// global `medium` and the `interior`/`exterior` of shapes name them.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub media: BTreeMap<String, MediumDesc>,
    /// The medium the camera is in, filling all space outside media shapes
    /// (default none: vacuum). Needs the `Path` integrator.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub medium: Option<String>,
    /// Named meshes that `Instance` objects place; loaded once each.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub meshes: BTreeMap<String, MeshDesc>,
    /// Settings for `ronray check`: the scene's regression test.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub test: Option<TestDesc>,
    /// The frames of an animation, for scenes with `keys` (default: one
    /// still frame, time 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub animation: Option<AnimationDesc>,
}

impl SceneDesc {
    /// The time drawn, in frames: the animation's current frame, or 0.
    pub fn frame(&self) -> i32 {
        self.animation.as_ref().map_or(0, AnimationDesc::current)
    }
}

/// An included file: shared materials, lights and objects (a studio rig, a
/// material library). Camera, film and integrator belong to the scene that
/// includes it.
#[derive(Clone, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(rename = "Include", deny_unknown_fields)]
pub struct IncludeDesc {
    /// Further files to include, relative to this file; they may include others
    /// in turn (a cycle is an error).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub include: Vec<String>,
    /// Materials offered to the including scene. A scene's own material of the
    /// same name overrides this one; two included files defining the same name is
    /// an error.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDesc>,
    /// Lights added to the including scene.
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    /// Objects added to the including scene; their material names are looked up
    /// among all the scene's materials, included or its own.
    #[serde(default)]
    pub objects: Vec<ObjectDesc>,
}

/// How `ronray check` renders this scene and compares it with its golden
/// image `golden/<scene name>.png` beside the scene file.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TestDesc {
    /// Test image width; the height keeps the film's aspect unless given.
    #[serde(default = "test_width")]
    pub width: u32,
    /// Test image height in pixels; by default `width` × the film's height/width,
    /// so the test keeps the film's aspect ratio.
    #[serde(default)]
    pub height: Option<u32>,
    /// Samples per pixel of the test render (default 16). Kept low: the
    /// comparison box-downsamples 4×4 before measuring, which averages noise out.
    #[serde(default = "test_spp")]
    pub spp: u32,
    /// Seed of the test render (default 0), fixed so a rerun of an unchanged
    /// renderer gives the same image.
    #[serde(default)]
    pub seed: u64,
    /// Largest accepted score against the golden image: the worst
    /// 8×8-pixel window's mean squared z-score of the difference against
    /// the noise measured in it (about 1 per window for noise alone, up to about
    /// 4.5 at the worst window; `crate::check`).
    #[serde(default = "test_tolerance")]
    pub tolerance: f32,
}

fn test_width() -> u32 {
    64
}
fn test_spp() -> u32 {
    16
}
/// Default largest score of a regression render against its golden image
/// (`test.tolerance`; the metric is `crate::check::metric`'s). Re-seeded
/// renders of the shipped scenes score at most about 4.5 at their worst
/// 8×8-pixel window, a small sphere 3 pixels across recoloured or halved 13
/// and more (`tests/check.rs`).
pub const DEFAULT_TOLERANCE: f32 = 8.0;

fn test_tolerance() -> f32 {
    DEFAULT_TOLERANCE
}

impl Default for TestDesc {
    fn default() -> Self {
        Self {
            width: test_width(),
            height: None,
            spp: test_spp(),
            seed: 0,
            tolerance: test_tolerance(),
        }
    }
}
