//! Ray–triangle intersection: watertight, two-sided.
//!
//! We use Woop, Benthin and Wald 2013, "Watertight Ray/Triangle
//! Intersection" (<https://jcgt.org/published/0002/01/05/>) rather than
//! Möller–Trumbore: the ray is sheared so it runs along +z through the
//! origin, and the three 2D edge functions are evaluated on the sheared
//! vertices. A shared edge gives bit-identical edge values (with opposite
//! signs) in both of its triangles, so a ray through an edge or a vertex of a
//! closed mesh always hits one of them — Möller–Trumbore's per-triangle
//! `e1`, `e2` rounding can let it slip through. Edge values of exactly zero
//! are recomputed in f64, as the paper recommends, so the test is also exact
//! on vertices. Per-ray setup ([`WatertightRay`]) is done once per traversal.

use crate::math::Ray;
use glam::{Vec2, Vec3A};

/// The per-ray part of the watertight test: the axis permutation and shear.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    pub o: Vec3A,
    k: [usize; 3],
    /// Shear `(Sx, Sy, Sz)` of the paper.
    s: [f32; 3],
}

impl WatertightRay {
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let d = ray.d;
        let a = d.abs();
        let d = d.to_array();
        // kz: the dominant axis; kx, ky the others, swapped if d[kz] < 0 so
        // the winding (and hence the edge-function signs) is preserved.
        let kz = if a.x >= a.y && a.x >= a.z {
            0
        } else if a.y >= a.z {
            1
        } else {
            2
        };
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Self {
            o: ray.o,
            k: [kx, ky, kz],
            s: [d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]],
        }
    }

    /// Hit distance and barycentrics `(b1, b2)` of `p1`, `p2`, for `t` in
    /// `(0, t_max)`; two-sided. Degenerate triangles never hit.
    #[inline(always)]
    pub fn intersect(&self, p0: Vec3A, p1: Vec3A, p2: Vec3A, t_max: f32) -> Option<(f32, Vec2)> {
        let [kx, ky, kz] = self.k;
        let [sx, sy, sz] = self.s;
        // Vertices relative to the ray origin, then sheared.
        let (a, b, c) = (
            (p0 - self.o).to_array(),
            (p1 - self.o).to_array(),
            (p2 - self.o).to_array(),
        );
        let (ax, ay) = (a[kx] - sx * a[kz], a[ky] - sy * a[kz]);
        let (bx, by) = (b[kx] - sx * b[kz], b[ky] - sy * b[kz]);
        let (cx, cy) = (c[kx] - sx * c[kz], c[ky] - sy * c[kz]);
        // Scaled barycentrics: 2D edge functions.
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        // Fall back to f64 on an exact zero (ray through an edge or vertex).
        if u == 0.0 || v == 0.0 || w == 0.0 {
            let f =
                |px: f32, py: f32, qx: f32, qy: f32| (px as f64 * qy as f64 - py as f64 * qx as f64) as f32;
            u = f(cx, cy, bx, by);
            v = f(ax, ay, cx, cy);
            w = f(bx, by, ax, ay);
        }
        // Inside iff the three have the same sign (either winding).
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        // Scaled hit distance.
        let tz = sz * (u * a[kz] + v * b[kz] + w * c[kz]);
        let inv = 1.0 / det;
        let t = tz * inv;
        (t > 0.0 && t < t_max).then(|| (t, Vec2::new(v * inv, w * inv)))
    }
}

/// One-shot test (sets up the ray each call); traversal uses
/// [`WatertightRay`] directly.
#[inline]
pub fn intersect(p0: Vec3A, p1: Vec3A, p2: Vec3A, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
    WatertightRay::new(ray).intersect(p0, p1, p2, t_max)
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
        let up = Ray::new(Vec3A::new(0.2, 0.1, -1.0), Vec3A::Z);
        let (t, bc) = intersect(a, b, c, &up, f32::INFINITY).expect("two-sided");
        assert!((t - 1.0).abs() < 1e-6 && (bc - Vec2::new(0.2, 0.1)).length() < 1e-6);
    }

    #[test]
    fn triangle_shared_edge_is_watertight() {
        // Two triangles sharing the diagonal of the unit square; rays aimed
        // at points of the open diagonal must hit at least one (its ends are
        // the square's corners, where a rounded ray may pass outside).
        let (a, b, c, d) = (Vec3A::ZERO, Vec3A::X, Vec3A::new(1.0, 1.0, 0.0), Vec3A::Y);
        for i in 1..1000 {
            let s = i as f32 / 1000.0;
            let target = Vec3A::new(s, s, 0.0);
            let o = Vec3A::new(0.3, -0.7, 2.1);
            let ray = Ray::new(o, (target - o).normalize());
            let h = intersect(a, b, c, &ray, f32::INFINITY).or(intersect(a, c, d, &ray, f32::INFINITY));
            assert!(h.is_some(), "ray at diagonal point {s} slipped through");
        }
    }
}
