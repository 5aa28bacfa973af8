//! The camera a scene file describes: where it looks from and its
//! projection.

use super::{CameraKeyDesc, InterpolationDesc, V3};
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
