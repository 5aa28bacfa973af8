//! Perspective camera (pinhole or thin lens).
//!
//! Conventions follow the Mitsuba references: `forward = normalize(target −
//! eye)`, `right = normalize(forward × up)`, `true_up = right × forward`;
//! image x grows toward `right`, row 0 is the top; the field of view is the
//! full vertical angle.

use crate::math::{Ray, sampling};
use glam::{Vec2, Vec3A};

#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: Vec3A,
    pub forward: Vec3A,
    pub right: Vec3A,
    pub up: Vec3A,
    /// tan(fov_y / 2).
    pub tan_half_fov: f32,
    pub aperture_radius: f32,
    pub focus_distance: f32,
}

impl Camera {
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
