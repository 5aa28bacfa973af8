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
    // The direction is taken relative to the eye: the focus is never formed
    // in world space, and the lens point's offset is read back from the
    // stored origin (exact: the two are within a factor of 2, Sterbenz).
    // Far from the origin, world-space focus and lens points are rounded to
    // the ulp of the eye's coordinates (5e-4 at 10,000), and the rays of
    // one pixel missed their common focus by that.
    let to_focus = c.focus_distance * d / d.dot(c.forward);
    let lens = sampling::concentric_disk(u_lens) * c.aperture_radius;
    let o = c.eye + (lens.x * c.right + lens.y * c.up);
    Ray::new(o, (to_focus - (o - c.eye)).normalize())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;
    use glam::Vec3A;

    /// Every lens sample's ray must pass through the point of the focal
    /// plane its pinhole ray reaches. 10,000 units from the origin the
    /// focus and lens points, taken in world space, were rounded to the eye
    /// coordinates' ulp (1e-3) and the rays missed it by that.
    #[test]
    fn thin_lens_rays_meet_at_the_focus_far_from_the_origin() {
        let eye = Vec3A::new(1e4, 5e3, 1e4);
        let mut c = Camera::look_at(eye, eye + Vec3A::new(0.3, -0.2, -1.0), Vec3A::Y, 40.0);
        c.aperture_radius = 0.05;
        c.focus_distance = 3.0;
        let mut rng = Pcg32::new(44, 1);
        let mut worst = 0.0f32;
        for _ in 0..1000 {
            let film = rng.next_vec2();
            let pinhole = ray(
                &Camera {
                    aperture_radius: 0.0,
                    ..c
                },
                film,
                1.5,
                Vec2::ZERO,
            );
            let r = ray(&c, film, 1.5, rng.next_vec2());
            // In f64: the focus the pinhole ray reaches, and how far the lens
            // ray's line (from its stored origin) passes from it.
            let d64 = |v: Vec3A| glam::DVec3::new(v.x.into(), v.y.into(), v.z.into());
            let (pd, fwd) = (d64(pinhole.d), d64(c.forward));
            let focus = d64(eye) + pd * (f64::from(c.focus_distance) / pd.dot(fwd));
            let (o, dir) = (d64(r.o), d64(r.d).normalize());
            let to = focus - o;
            let miss = (to - dir * to.dot(dir)).length() as f32;
            worst = worst.max(miss);
        }
        assert!(worst < 1e-5, "a lens ray passes {worst:e} from its focus point");
    }
}
