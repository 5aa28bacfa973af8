//! A camera that moves: its keys, and the camera at any time.

use super::Camera;
use crate::anim::Track;
use glam::{Vec3, Vec3A};

/// The camera's keyed `eye`, `target` and `up`, and what does not move.
#[derive(Clone, Debug)]
pub struct CameraMotion {
    /// Position over time.
    pub eye: Track<Vec3>,
    /// Point looked at over time.
    pub target: Track<Vec3>,
    /// Up direction over time.
    pub up: Track<Vec3>,
    /// The camera at the shutter's opening: projection, field of view and
    /// lens are taken from it.
    pub base: Camera,
    /// The scene's `focus_distance`; without one the focus follows
    /// `|target − eye|`.
    pub focus_distance: Option<f32>,
}

impl CameraMotion {
    /// The camera at `time` (frames). Where interpolated keys make `up`
    /// parallel to the view (the loader checks only the keys), the frame
    /// at the opening is kept, moved to the new eye.
    pub fn at(&self, time: f32) -> Camera {
        let (eye, target) = (Vec3A::from(self.eye.at(time)), Vec3A::from(self.target.at(time)));
        let c = Camera::look_at(eye, target, Vec3A::from(self.up.at(time)), 40.0);
        if !(c.right.is_finite() && c.forward.is_finite()) {
            return Camera { eye, ..self.base };
        }
        Camera {
            tan_half_fov: self.base.tan_half_fov,
            aperture_radius: self.base.aperture_radius,
            projection: self.base.projection,
            focus_distance: self.focus_distance.unwrap_or(c.focus_distance),
            ..c
        }
    }
}
