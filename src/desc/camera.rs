//! The camera a scene file describes: where it looks from and its
//! projection.

use super::{CameraKeyDesc, InterpolationDesc, V3};
use serde::{Deserialize, Serialize};

/// A camera looking from `eye` toward `target`: perspective (the default,
/// with `fov_y_degrees`), orthographic or spherical by `projection`.
/// Image x runs along `normalize(forward × up)` (to the right), image row 0 is
/// at the top. Or a glTF asset's own camera, by `gltf`: its node gives the
/// place and direction, its projection the field of view.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Position of the camera (the pinhole, or the centre of the lens), in world
    /// space. Required, unless `gltf` takes an asset's camera.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub eye: Option<V3>,
    /// A point the camera looks at; it is centred in the image. By default also
    /// the distance in focus. Required, unless `gltf` takes an asset's camera.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<V3>,
    /// An asset's own camera instead of `eye`, `target`, `up` and the
    /// projection: `gltf: (file: "scene.gltf")` takes the first camera of
    /// the `Gltf` object that reads that file, placed as its meshes are (the
    /// object's `transform`, `scene` and `animation`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gltf: Option<GltfCameraDesc>,
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
    #[schemars(range(min = 0))]
    pub aperture_radius: f32,
    /// Distance from `eye` to the plane in focus; defaults to |target − eye|.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[schemars(range(min = 0))]
    pub focus_distance: Option<f32>,
    /// When the shutter opens and closes, in frames from the frame's start
    /// (default closed at 0: no motion blur): `(0, 0.5)` is a 180° shutter.
    /// Within [−1, 1], open ≤ close.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shutter: Option<(f32, f32)>,
    /// Where the camera is at given frames (`eye`, `target`, `up` keyed
    /// together); between keys by `interpolation`. The camera's own `eye`
    /// and `target` are used when there are none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keys: Vec<CameraKeyDesc>,
    /// How the camera moves between `keys` (default `Linear`).
    #[serde(default, skip_serializing_if = "InterpolationDesc::is_default")]
    pub interpolation: InterpolationDesc,
}

impl CameraDesc {
    /// `eye` and `target`, once checked (or filled in from a glTF camera):
    /// a stand-in looking down −z from the origin where one is missing,
    /// which validation has refused already.
    pub fn look(&self) -> ([f32; 3], [f32; 3]) {
        (
            self.eye.unwrap_or([0.0; 3]),
            self.target.unwrap_or([0.0, 0.0, -1.0]),
        )
    }
}

/// Which glTF camera the scene looks through.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct GltfCameraDesc {
    /// The `file` of the scene's `Gltf` object that holds the camera,
    /// written as that object writes it.
    pub file: String,
    /// The camera by the name of its node or of the camera itself, or by
    /// index (`"#0"`); default the first camera the asset's scene places.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub camera: Option<String>,
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
        #[schemars(range(min = 0, max = 1e15))]
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
