//! Ray–triangle intersection.

use crate::math::Ray;
use glam::{Vec2, Vec3A};

/// Möller–Trumbore (<https://doi.org/10.1080/10867651.1997.10487468>),
/// two-sided. Returns t and the barycentrics (b1, b2) of p1 and p2.
///
/// Edges are inclusive (`>= 0`), so a ray through a shared edge hits at least
/// one of the two triangles.
#[inline]
pub fn intersect(p0: Vec3A, p1: Vec3A, p2: Vec3A, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
    let e1 = p1 - p0;
    let e2 = p2 - p0;
    let pvec = ray.d.cross(e2);
    let det = e1.dot(pvec);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let inv_det = 1.0 / det;
    let tvec = ray.o - p0;
    let b1 = tvec.dot(pvec) * inv_det;
    if !(0.0..=1.0).contains(&b1) {
        return None;
    }
    let qvec = tvec.cross(e1);
    let b2 = ray.d.dot(qvec) * inv_det;
    if b2 < 0.0 || b1 + b2 > 1.0 {
        return None;
    }
    let t = e2.dot(qvec) * inv_det;
    (t > 1e-6 * (1.0 + tvec.abs().max_element()) && t < t_max).then_some((t, Vec2::new(b1, b2)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn triangle_hits_inside_and_misses_outside() {
        let (a, b, c) = (Vec3A::ZERO, Vec3A::X, Vec3A::Y);
        let down = |x: f32, y: f32| Ray::new(Vec3A::new(x, y, 1.0), Vec3A::NEG_Z);
        let (t, bc) = intersect(a, b, c, &down(0.25, 0.25), f32::INFINITY).expect("inside");
        assert!((t - 1.0).abs() < 1e-6 && (bc - Vec2::splat(0.25)).length() < 1e-6);
        assert!(intersect(a, b, c, &down(0.6, 0.6), f32::INFINITY).is_none());
        assert!(
            intersect(a, b, c, &down(0.25, 0.25), 0.5).is_none(),
            "t_max respected"
        );
    }
}
