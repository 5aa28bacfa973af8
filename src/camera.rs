//! Perspective camera (pinhole or thin lens).
//!
//! Conventions follow the Mitsuba references: `forward = normalize(target −
//! eye)`, `right = normalize(forward × up)`, `true_up = right × forward`;
//! image x grows toward `right`, row 0 is the top; the field of view is the
//! full vertical angle.

use crate::math::{Ray, sampling};
use glam::{Vec2, Vec3A};

/// A perspective camera in world space, with its orthonormal frame precomputed so
/// generating a ray is a few multiply-adds.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Centre of projection (pinhole or lens centre), in world space.
    pub eye: Vec3A,
    /// Unit view direction, `normalize(target − eye)`.
    pub forward: Vec3A,
    /// Unit image-right direction, `normalize(forward × up)`.
    pub right: Vec3A,
    /// Unit image-up direction, perpendicular to `forward` and `right` (not
    /// necessarily the `up` the scene gave).
    pub up: Vec3A,
    /// tan(fov_y / 2).
    pub tan_half_fov: f32,
    /// Thin-lens aperture radius in scene units; 0 (or less) is a pinhole, with
    /// everything in focus.
    pub aperture_radius: f32,
    /// Distance from `eye` along `forward` to the plane in focus, in scene units.
    pub focus_distance: f32,
}

impl Camera {
    /// A pinhole camera at `eye` looking at `target`, with `up` the image's rough up
    /// direction and `fov_y_degrees` the full vertical field of view in degrees;
    /// focus distance `|target − eye|`. `up` must not be parallel to the view (the
    /// loader checks it).
    pub fn look_at(eye: Vec3A, target: Vec3A, up: Vec3A, fov_y_degrees: f32) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let true_up = right.cross(forward);
        Self {
            eye,
            forward,
            right,
            up: true_up,
            tan_half_fov: (fov_y_degrees.to_radians() * 0.5).tan(),
            aperture_radius: 0.0,
            focus_distance: (target - eye).length(),
        }
    }

    /// Ray through film position `film` ∈ `[0, 1]²` (x right, y down) for an
    /// image of aspect `width / height`; `u_lens` samples the aperture.
    #[inline]
    pub fn ray(&self, film: Vec2, aspect: f32, u_lens: Vec2) -> Ray {
        let th = self.tan_half_fov;
        let d = self.forward
            + (2.0 * film.x - 1.0) * th * aspect * self.right
            + (1.0 - 2.0 * film.y) * th * self.up;
        if self.aperture_radius <= 0.0 {
            return Ray::new(self.eye, d.normalize());
        }
        // Thin lens: aim at the point of the focal plane the pinhole ray reaches.
        let focus = self.eye + self.focus_distance * d / d.dot(self.forward);
        let lens = sampling::concentric_disk(u_lens) * self.aperture_radius;
        let o = self.eye + lens.x * self.right + lens.y * self.up;
        Ray::new(o, (focus - o).normalize())
    }
}
