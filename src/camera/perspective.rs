//! Perspective projection: rays through the pinhole `eye`, or, with an
//! aperture, from a thin lens around it toward the point of the focal plane
//! the pinhole ray reaches (pbrt-v4's `PerspectiveCamera`).

use super::Camera;
use crate::math::{Ray, sampling};
use glam::Vec2;

/// Ray through film position `film` for an image of aspect `width / height`;
/// `u_lens` samples the aperture.
#[inline]
pub fn ray(c: &Camera, film: Vec2, aspect: f32, u_lens: Vec2) -> Ray {
    let th = c.tan_half_fov;
    let d = c.forward + (2.0 * film.x - 1.0) * th * aspect * c.right + (1.0 - 2.0 * film.y) * th * c.up;
    if c.aperture_radius <= 0.0 {
        return Ray::new(c.eye, d.normalize());
    }
    // Thin lens: aim at the point of the focal plane the pinhole ray reaches.
    // The direction is taken from the lens point to the focus relative to
    // the eye, not from their world positions, which far from the origin
    // are rounded to the ulp of the eye's coordinates (1e-3 at 10,000) and
    // would tilt the ray by that over the focus distance.
    let to_focus = c.focus_distance * d / d.dot(c.forward);
    let lens = sampling::concentric_disk(u_lens) * c.aperture_radius;
    let on_lens = lens.x * c.right + lens.y * c.up;
    Ray::new(c.eye + on_lens, (to_focus - on_lens).normalize())
}
