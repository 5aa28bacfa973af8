//! Spherical (equirectangular) projection: every direction around `eye`,
//! with exactly the latitude–longitude mapping of the environment map
//! (`lights/environment.rs`, Mitsuba 3's `envmap`), so an environment map
//! rendered through this camera at the map's resolution comes back as
//! itself (`tests/cameras.rs` states the RMSE).
//!
//! In the camera's frame `(x, y, z) = (−right, up, forward)` — the
//! environment's own frame when the camera looks along +z with +y up — the
//! film position `(s, t)` ∈ [0, 1]² is the image point `u = s`, `v = (t·H −
//! ½)/(H − 1)`: columns are centred at `u = (i + ½)/W` and rows at `v = j/(H
//! − 1)`, as the map's are, so pixel centres land on the map's texels. The
//! direction of `(u, v)` is `(sin θ sin φ, cos θ, −sin θ cos φ)` with `φ =
//! 2πu`, `θ = πv`: the image centre looks along `forward`, the seam is
//! behind, row 0 is straight up and the last row straight down. pbrt-v4's
//! `SphericalCamera` also offers an equal-area octahedral mapping; only the
//! equirectangular one is here.

use super::Camera;
use crate::math::Ray;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Image point `(u, v)` of film position `film` for an image `rows` pixels
/// tall (see the module docs). Neither is clamped: `u` wraps, and the half
/// rows beyond the poles (`v < 0`, `v > 1`) continue over them to the other
/// side, as the sphere does.
#[inline]
pub fn film_to_uv(film: Vec2, rows: u32) -> Vec2 {
    let v = if rows > 1 {
        (film.y * rows as f32 - 0.5) / (rows - 1) as f32
    } else {
        film.y
    };
    Vec2::new(film.x, v)
}

/// Unit direction of image point `(u, v)` in the environment's frame: the
/// inverse of `EnvironmentLight::uv`.
#[inline]
pub fn uv_to_direction(uv: Vec2) -> Vec3A {
    let (sin_t, cos_t) = (PI * uv.y).sin_cos();
    let (sin_p, cos_p) = (2.0 * PI * uv.x).sin_cos();
    Vec3A::new(sin_t * sin_p, cos_t, -sin_t * cos_p)
}

/// Ray through film position `film` for an image `rows` pixels tall.
#[inline]
pub fn ray(c: &Camera, film: Vec2, rows: u32) -> Ray {
    let d = uv_to_direction(film_to_uv(film, rows));
    // Camera frame (−right, up, forward) to world.
    let w = -d.x * c.right + d.y * c.up + d.z * c.forward;
    Ray::new(c.eye, w.normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Projection;
    use crate::lights::environment::EnvironmentLight;

    /// Pixel centres land on the map's texel centres: the environment's own
    /// `uv` of the camera's direction is `((i + ½)/W, j/(H − 1))`.
    #[test]
    fn spherical_pixel_centres_hit_environment_texel_centres() {
        let (w, h) = (16u32, 8u32);
        let cam = Camera::look_at(Vec3A::ZERO, Vec3A::Z, Vec3A::Y, 40.0)
            .with_projection(Projection::Spherical { rows: h });
        for j in 0..h {
            for i in 0..w {
                let film = Vec2::new((i as f32 + 0.5) / w as f32, (j as f32 + 0.5) / h as f32);
                let r = cam.ray(film, 2.0, Vec2::ZERO);
                let uv = EnvironmentLight::uv(r.d);
                let want = Vec2::new((i as f32 + 0.5) / w as f32, j as f32 / (h - 1) as f32);
                // At the poles every u is the same direction.
                let du = if j == 0 || j == h - 1 {
                    0.0
                } else {
                    (uv.x - want.x).abs()
                };
                assert!(
                    du < 1e-5 && (uv.y - want.y).abs() < 1e-5,
                    "pixel ({i}, {j}): uv {uv:?}, expected {want:?}"
                );
            }
        }
    }

    #[test]
    fn spherical_image_centre_looks_forward() {
        let cam = Camera::look_at(Vec3A::ZERO, Vec3A::new(1.0, 0.0, 0.0), Vec3A::Y, 40.0)
            .with_projection(Projection::Spherical { rows: 9 });
        let r = cam.ray(Vec2::new(0.5, 0.5), 2.0, Vec2::ZERO);
        assert!((r.d - Vec3A::X).length() < 1e-6, "centre ray {:?}", r.d);
        // A quarter turn to the right of the centre is the camera's right.
        let r = cam.ray(Vec2::new(0.75, 0.5), 2.0, Vec2::ZERO);
        assert!(
            (r.d - cam.right).length() < 1e-6,
            "{:?} vs right {:?}",
            r.d,
            cam.right
        );
    }
}
