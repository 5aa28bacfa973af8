//! Orthographic projection: parallel rays along `forward`, starting on the
//! rectangle through `eye` perpendicular to the view, `view_height` scene
//! units tall and `view_height × aspect` wide (pbrt-v4's
//! `OrthographicCamera` with its screen window set from the view height).
//! Objects keep their size whatever their distance: a sphere of radius r
//! covers 2r / view_height of the image's height.

use super::Camera;
use crate::math::Ray;
use glam::Vec2;

/// Ray through film position `film` for an image of aspect `width / height`.
#[inline]
pub fn ray(c: &Camera, film: Vec2, aspect: f32, view_height: f32) -> Ray {
    let half = 0.5 * view_height;
    // Film [0, 1]² onto the rectangle: x to the right, y (down on film) up.
    let o = c.eye + (2.0 * film.x - 1.0) * half * aspect * c.right + (1.0 - 2.0 * film.y) * half * c.up;
    Ray::new(o, c.forward)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Projection;
    use glam::Vec3A;

    #[test]
    fn orthographic_rays_are_parallel_and_span_the_view_height() {
        let cam = Camera::look_at(Vec3A::new(0.0, 0.0, 5.0), Vec3A::ZERO, Vec3A::Y, 40.0)
            .with_projection(Projection::Orthographic { view_height: 4.0 });
        let top = cam.ray(Vec2::new(0.5, 0.0), 2.0, Vec2::ZERO);
        let bottom_right = cam.ray(Vec2::new(1.0, 1.0), 2.0, Vec2::ZERO);
        assert_eq!(top.d, Vec3A::new(0.0, 0.0, -1.0));
        assert_eq!(bottom_right.d, top.d, "every ray is along forward");
        assert!(
            (top.o - Vec3A::new(0.0, 2.0, 5.0)).length() < 1e-6,
            "top edge at +h/2: {:?}",
            top.o
        );
        assert!(
            (bottom_right.o - Vec3A::new(4.0, -2.0, 5.0)).length() < 1e-6,
            "corner at (aspect·h/2, −h/2): {:?}",
            bottom_right.o
        );
    }
}
