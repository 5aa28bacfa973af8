//! Exact signed distances to the primitives of [`SdfNode`], negative inside.
//! Formulas from <https://iquilezles.org/articles/distfunctions/>.
//!
//! [`SdfNode`]: super::SdfNode

use glam::{Vec2, Vec3A};

/// Ball of `radius` around the origin.
#[inline]
pub fn sphere(p: Vec3A, radius: f32) -> f32 {
    p.length() - radius
}

/// Axis-aligned box from `-half_extents` to `half_extents`.
#[inline]
pub fn cuboid(p: Vec3A, half_extents: Vec3A) -> f32 {
    // Per-axis distance outside the slabs (negative inside).
    let q = p.abs() - half_extents;
    // Outside: length of the positive part; inside: the nearest face.
    q.max(Vec3A::ZERO).length() + q.max_element().min(0.0)
}

/// Box of outer size `half_extents` with edges rounded by `radius` (`0 ≤ radius ≤`
/// the smallest half extent).
#[inline]
pub fn round_box(p: Vec3A, half_extents: Vec3A, radius: f32) -> f32 {
    // A box shrunk by the radius, inflated by it again.
    cuboid(p, half_extents - Vec3A::splat(radius)) - radius
}

/// Torus around the y axis: `major` from the origin to the tube's centre line,
/// `minor` the tube's radius.
#[inline]
pub fn torus(p: Vec3A, major: f32, minor: f32) -> f32 {
    // Distance to the centre circle in the (radial, y) half-plane, minus the tube.
    let q = Vec2::new(Vec2::new(p.x, p.z).length() - major, p.y);
    q.length() - minor
}

/// Segment from `a` to `b` swept by a ball of `radius`; `a = b` is a sphere.
#[inline]
pub fn capsule(p: Vec3A, a: Vec3A, b: Vec3A, radius: f32) -> f32 {
    let pa = p - a;
    let ba = b - a;
    // Parameter of the closest point on the segment (a point if a = b).
    let bb = ba.length_squared();
    let h = if bb > 0.0 {
        (pa.dot(ba) / bb).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (pa - ba * h).length() - radius
}

/// Capped cylinder along y, of `radius`, from `-half_height` to `half_height`.
#[inline]
pub fn cylinder(p: Vec3A, radius: f32, half_height: f32) -> f32 {
    // A 2D box in the (radial, y) half-plane.
    let d = Vec2::new(Vec2::new(p.x, p.z).length(), p.y).abs() - Vec2::new(radius, half_height);
    d.max_element().min(0.0) + d.max(Vec2::ZERO).length()
}

/// `normal` must be unit length.
#[inline]
pub fn plane(p: Vec3A, normal: Vec3A, offset: f32) -> f32 {
    p.dot(normal) - offset
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Pcg32, sampling::uniform_sphere};
    use std::f32::consts::TAU;

    fn vec_in(rng: &mut Pcg32, half: f32) -> Vec3A {
        let u = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
        (2.0 * u - Vec3A::ONE) * half
    }

    /// Closest point of the box `[-b, b]` to `y`, by clamping (exact, and
    /// independent of the formula under test).
    fn box_surface(y: Vec3A, b: Vec3A) -> Vec3A {
        let c = y.clamp(-b, b);
        // Inside: scale out along the ray from the centre to the nearest face.
        if c != y {
            c
        } else {
            y / (y / b).abs().max_element()
        }
    }

    /// Checks `d` against the distance to dense surface samples at random
    /// queries: `|d| ≤` the sampled distance always (a bound), and within
    /// `tol` of it (exact), since samples lie at most ~`tol` apart.
    fn check_exact(name: &str, d: impl Fn(Vec3A) -> f32, surface: &[Vec3A], half: f32, tol: f32) {
        let mut rng = Pcg32::new(11, name.len() as u64);
        for _ in 0..400 {
            let q = vec_in(&mut rng, half);
            let sampled = surface
                .iter()
                .map(|s| (q - *s).length())
                .fold(f32::INFINITY, f32::min);
            let got = d(q).abs();
            assert!(
                got <= sampled + 1e-4,
                "{name} at {q}: |d| = {got} exceeds sampled distance {sampled}"
            );
            assert!(
                got >= sampled - tol,
                "{name} at {q}: |d| = {got}, expected ≈ {sampled} (tol {tol})"
            );
        }
    }

    fn samples(n: usize, mut f: impl FnMut(&mut Pcg32) -> Vec3A) -> Vec<Vec3A> {
        let mut rng = Pcg32::new(5, n as u64);
        (0..n).map(|_| f(&mut rng)).collect()
    }

    #[test]
    fn sphere_is_exact() {
        let s = samples(40_000, |r| 1.3 * uniform_sphere(r.next_vec2()));
        check_exact("sphere", |p| sphere(p, 1.3), &s, 3.0, 0.03);
    }

    #[test]
    fn box_is_exact() {
        let b = Vec3A::new(1.0, 0.5, 0.8);
        let s = samples(80_000, |r| box_surface(vec_in(r, 2.0), b));
        check_exact("box", |p| cuboid(p, b), &s, 2.5, 0.03);
    }

    #[test]
    fn round_box_is_exact() {
        let (b, r) = (Vec3A::new(1.0, 0.5, 0.8), 0.2);
        let inner = b - Vec3A::splat(r);
        let s = samples(80_000, |rng| {
            loop {
                // Push the closest point of the inner box out by the radius.
                let y = vec_in(rng, 2.0);
                let c = y.clamp(-inner, inner);
                if c != y {
                    break c + r * (y - c).normalize();
                }
            }
        });
        check_exact("round_box", |p| round_box(p, b, r), &s, 2.5, 0.03);
    }

    #[test]
    fn torus_is_exact() {
        let (big, small) = (1.0, 0.3);
        let s = samples(60_000, |r| {
            let (u, v) = (TAU * r.next_f32(), TAU * r.next_f32());
            let rho = big + small * v.cos();
            Vec3A::new(rho * u.cos(), small * v.sin(), rho * u.sin())
        });
        check_exact("torus", |p| torus(p, big, small), &s, 2.0, 0.03);
    }

    #[test]
    fn capsule_is_exact() {
        let (a, b, radius) = (Vec3A::new(-0.5, 0.2, 0.0), Vec3A::new(0.6, -0.3, 0.4), 0.35);
        let s = samples(60_000, |r| {
            // Closest point on the segment, pushed out along the offset.
            let y = vec_in(r, 2.0);
            let h = ((y - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            let c = a + (b - a) * h;
            c + radius * (y - c).normalize()
        });
        check_exact("capsule", |p| capsule(p, a, b, radius), &s, 2.0, 0.03);
        // Degenerate segment: a ball.
        assert!((capsule(Vec3A::X * 2.0, a, a, 0.5) - ((Vec3A::X * 2.0 - a).length() - 0.5)).abs() < 1e-6);
    }

    #[test]
    fn cylinder_is_exact() {
        let (radius, h) = (0.7, 0.5);
        let s = samples(60_000, |r| {
            let phi = TAU * r.next_f32();
            let (c, sn) = (phi.cos(), phi.sin());
            if r.next_f32() < 0.5 {
                Vec3A::new(radius * c, h * (2.0 * r.next_f32() - 1.0), radius * sn)
            } else {
                // A cap: uniform in the disk, top or bottom.
                let rho = radius * r.next_f32().sqrt();
                let y = if r.next_f32() < 0.5 { h } else { -h };
                Vec3A::new(rho * c, y, rho * sn)
            }
        });
        check_exact("cylinder", |p| cylinder(p, radius, h), &s, 2.0, 0.03);
    }

    #[test]
    fn plane_is_exact() {
        let n = Vec3A::new(1.0, 2.0, -0.5).normalize();
        let mut rng = Pcg32::new(3, 3);
        for _ in 0..1000 {
            let q = vec_in(&mut rng, 5.0);
            // Foot of the perpendicular lies on the plane, at distance |d|.
            let d = plane(q, n, 0.4);
            assert!(
                plane(q - d * n, n, 0.4).abs() < 1e-5,
                "foot of {q} is off the plane"
            );
        }
    }
}
