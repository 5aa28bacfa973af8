//! Time as a scene file writes it: the frames of an animation, and keys on
//! the things that move.

use super::{TransformDesc, V3};
use serde::{Deserialize, Serialize};

/// The frames a scene is rendered at (`animation`): keys give values in
/// frames, and `render --frame N` / `--frames A..B` choose which to draw.
///
/// ```
/// # let text = "(frames: (1, 48), fps: 24)";
/// let a: ronray::desc::AnimationDesc = ron::from_str(text).unwrap();
/// assert_eq!(a.current(), 1);
/// ```
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AnimationDesc {
    /// First and last frame, both included: `(1, 48)` is 48 frames. Within
    /// ±1,000,000.
    pub frames: (i32, i32),
    /// Frames per second (default 24): what a frame is in seconds, for
    /// players; keys and shutters are written in frames.
    #[serde(default = "default_fps")]
    #[schemars(range(min = 0, max = 1000))]
    pub fps: f32,
    /// The frame drawn when the command line names none (`--frame N` sets
    /// it); default the first.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame: Option<i32>,
}

impl AnimationDesc {
    /// The frame to draw: `frame`, or the first of `frames`.
    pub fn current(&self) -> i32 {
        self.frame.unwrap_or(self.frames.0)
    }
}

fn default_fps() -> f32 {
    24.0
}

/// How values between keys are made.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum InterpolationDesc {
    /// Straight from key to key at constant speed (rotations at constant
    /// angular speed, along the shortest arc).
    #[default]
    Linear,
    /// A Catmull-Rom spline through the keys (positions, scales, the
    /// camera's points); rotations still turn at constant speed between
    /// two keys.
    Smooth,
}

impl InterpolationDesc {
    /// Whether this is the default, `Linear` (left out when written).
    pub fn is_default(&self) -> bool {
        *self == InterpolationDesc::Linear
    }
}

/// A key of an `Instance`'s `keys`: where the instance is at `frame`.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TransformKeyDesc {
    /// Time of the key, in frames (may be fractional); keys in increasing
    /// order.
    pub frame: f32,
    /// The placement at that time, steps in written order as `transform`.
    #[serde(default)]
    pub transform: Vec<TransformDesc>,
}

/// A key of the camera's `keys`: where it is and looks at `frame`.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CameraKeyDesc {
    /// Time of the key, in frames (may be fractional); keys in increasing
    /// order.
    pub frame: f32,
    /// Position of the camera at that time.
    pub eye: V3,
    /// The point it looks at.
    pub target: V3,
    /// Its up direction (default: the camera's `up`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<V3>,
}
