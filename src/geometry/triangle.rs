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
use crate::math::float_error::gamma;
use glam::{Vec2, Vec3A, Vec4, Vec4Swizzles};

/// A bound on the rounding error of the computed hit distance `t`:
/// pbrt-v4's (`Triangle::Intersect`, "ensure that computed triangle t is
/// conservatively greater than zero"), `3·(2γ₃·E·Z + δ_E·Z)/|det|`, with
/// the largest edge value E replaced by |det| — inside a triangle the three
/// edge values share a sign, so E ≤ |det| and the bound is no smaller —
/// and δ_E expanded: a third fewer operations per hit lane. `max_x`,
/// `max_y`, `max_z` are the largest sheared corner coordinates in magnitude
/// (`max_z` scaled by the shear's `sz`), `inv_abs` = 1/|det|. A hit nearer
/// than this may be the surface the ray starts on: without it, a ray
/// leaving a mesh's triangle at a grazing angle, from an origin its error
/// bound does not move (a floor at y = 0 has none along its normal), met
/// the same triangle at t ≈ 10⁻⁸ about half the time, and a floor under a
/// uniform sky reflected 0.42 of a 0.5 albedo (`tests/self_hits.rs`).
#[inline(always)]
fn t_bound<T>(max_x: T, max_y: T, max_z: T, inv_abs: T) -> T
where
    T: Copy
        + std::ops::Add<Output = T>
        + std::ops::Add<f32, Output = T>
        + std::ops::Mul<Output = T>
        + std::ops::Mul<f32, Output = T>,
{
    // δ_E/2 = (γ₂ + 2γ₅)·X·Y + γ₅·Z·(X + Y).
    let half_delta_e = max_x * max_y * (gamma(2) + 2.0 * gamma(5)) + max_z * (max_x + max_y) * gamma(5);
    max_z * (half_delta_e * inv_abs * 6.0 + 6.0 * gamma(3))
}

/// The per-ray part of the watertight test: the axis permutation and shear.
#[derive(Clone, Copy, Debug)]
pub struct WatertightRay {
    /// The ray origin: vertices are moved by `−o` before the shear, so the ray runs
    /// through the origin.
    pub o: Vec3A,
    k: [usize; 3],
    /// Shear `(Sx, Sy, Sz)` of the paper.
    s: [f32; 3],
}

impl WatertightRay {
    /// Precomputes the axis permutation and shear for `ray`, once per traversal.
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
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let m = |p: f32, q: f32, r: f32| p.abs().max(q.abs()).max(r.abs());
        let bound = t_bound(
            m(ax, bx, cx),
            m(ay, by, cy),
            m(a[kz], b[kz], c[kz]) * sz.abs(),
            inv.abs(),
        );
        (t > bound).then(|| (t, Vec2::new(v * inv, w * inv)))
    }
}

/// Floats per triangle in a [`Tri4`] leaf block.
pub const FLOATS: usize = 9;

/// Up to four of a leaf's triangles, tested at once. The block holds its
/// `count` triangles in SoA order: component `k` (vertex `k / 3`, axis
/// `k % 3`) of lane `i` is `soa[k * count + i]`. A 4-lane load of a
/// component of a short leaf reads the next component's values into the
/// spare lanes, which the lane mask discards, so leaves need no padding; the
/// caller keeps 3 spare floats after the last block.
pub struct Tri4<'a> {
    /// The block's corner coordinates, `count` triangles in the SoA layout above.
    pub soa: &'a [f32],
    /// Number of triangles in the block, 1 to 4.
    pub count: u32,
}

impl Tri4<'_> {
    /// Writes `tris` (at most four) into `block` in the layout above.
    pub fn pack(block: &mut [f32], tris: &[[Vec3A; 3]]) {
        let c = tris.len();
        for (i, t) in tris.iter().enumerate() {
            for (k, x) in t.iter().flat_map(|p| p.to_array()).enumerate() {
                block[k * c + i] = x;
            }
        }
    }

    /// Triangle `i` of the block.
    #[inline]
    fn corners(&self, i: usize) -> [Vec3A; 3] {
        let c = self.count as usize;
        [0, 1, 2].map(|v| Vec3A::from_array([0, 1, 2].map(|a| self.soa[(3 * v + a) * c + i])))
    }
}

/// Row `k` of a block's corner rows, `k` one of a setup's axis indices
/// (`WatertightRay`'s private `k`, made only by [`WatertightRay::new`] as
/// a permutation of 0, 1, 2). The compiler cannot see that bound: indexed
/// plainly, every pair test paid three compares and branches for it.
#[inline(always)]
fn row(rows: &[Vec4; 3], k: usize) -> Vec4 {
    debug_assert!(k < 3);
    // SAFETY: `k` < 3 (above): within the array.
    unsafe { *rows.get_unchecked(k) }
}

/// [`WatertightRay`] splatted over four lanes for [`Tri4`] blocks.
pub struct WatertightRay4 {
    one: WatertightRay,
    /// Ray origin per sheared axis `(kx, ky, kz)`.
    o: [Vec4; 3],
    s: [Vec4; 3],
}

impl WatertightRay4 {
    /// Precomputes the watertight setup for `ray` and splats it over four lanes.
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let one = WatertightRay::new(ray);
        let ([kx, ky, kz], [sx, sy, sz]) = (one.k, one.s);
        // Through an array: indexing a `Vec3A` by a variable is a chain of
        // compares and branches.
        let o = one.o.to_array();
        Self {
            o: [Vec4::splat(o[kx]), Vec4::splat(o[ky]), Vec4::splat(o[kz])],
            s: [Vec4::splat(sx), Vec4::splat(sy), Vec4::splat(sz)],
            one,
        }
    }

    /// [`WatertightRay4::new`] out of line, for the scene's lazily made
    /// setup: inlined, the compiler hoisted half of it ahead of the
    /// traversal of every shadow ray, most of which meet no triangle.
    #[inline(never)]
    pub fn new_out_of_line(ray: &Ray) -> Self {
        Self::new(ray)
    }

    /// The setup for `ray` in `slot`, made there on first use (out of line,
    /// as [`WatertightRay4::new_out_of_line`]). It is written in place:
    /// returned by value, its 160 bytes were copied out of the callee's
    /// stores with wider loads than the stores, which store forwarding
    /// cannot serve (8% of the traversal's samples on the Cornell box as
    /// one OBJ, perf).
    #[inline(always)]
    pub fn lazily<'a>(slot: &'a mut Option<Self>, ray: &Ray) -> &'a Self {
        if slot.is_none() {
            Self::fill(slot, ray);
        }
        // Filled just above: the closure never runs.
        slot.get_or_insert_with(|| Self::new_out_of_line(ray))
    }

    #[inline(never)]
    fn fill(slot: &mut Option<Self>, ray: &Ray) {
        *slot = Some(Self::new(ray));
    }

    /// The lanes of `block` hit in `(0, t_max)`, their distances and the
    /// barycentrics `(b1, b2)` as two 4-lane vectors. Every lane computes
    /// exactly what [`WatertightRay::intersect`] does for its triangle, in
    /// the same order of operations, so results are bit-identical; a block
    /// where a live lane's edge value is exactly zero runs the scalar test
    /// (with its f64 fallback) instead.
    #[inline(always)]
    fn lanes(&self, block: &Tri4, t_max: f32) -> Lanes {
        let c = block.count as usize;
        // One bounds check for the block's nine rows (the last starts at
        // 8c), not two for each: indexed row by row, the checks were 14%
        // of a mesh instance's closest-hit instructions (callgrind, the
        // bunny on a grid floor).
        let soa = &block.soa[..8 * c + 4];
        let [kx, ky, kz] = self.one.k;
        let load = |k: usize| {
            debug_assert!(k <= 8);
            // SAFETY: `k` = 3 · vertex (0 to 2) + an axis of the setup (< 3,
            // see `row`) ≤ 8, so `k·c + 4 ≤ 8c + 4`, the slice's length.
            Vec4::from_slice(unsafe { soa.get_unchecked(k * c..k * c + 4) })
        };
        // Vertex `v` relative to the origin and sheared: (x, y, z).
        let vert = |v: usize| {
            let z = load(3 * v + kz) - self.o[2];
            (
                (load(3 * v + kx) - self.o[0]) - self.s[0] * z,
                (load(3 * v + ky) - self.o[1]) - self.s[1] * z,
                z,
            )
        };
        let live = (1u32 << c) - 1;
        self.edges(vert(0), vert(1), vert(2), live, t_max)
            .unwrap_or_else(|| self.scalar(block, t_max))
    }

    /// The watertight test on four lanes of sheared corners `a`, `b`, `c`
    /// (each `(x, y, z)`), the operations of [`WatertightRay::intersect`] in
    /// its order on every lane; `live` masks the lanes that hold triangles.
    /// `None` when a live lane's edge value is exactly zero: the caller
    /// runs the scalar test, whose f64 fallback handles it.
    #[inline(always)]
    fn edges(
        &self,
        a: (Vec4, Vec4, Vec4),
        b: (Vec4, Vec4, Vec4),
        c: (Vec4, Vec4, Vec4),
        live: u32,
        t_max: f32,
    ) -> Option<Lanes> {
        let ((ax, ay, az), (bx, by, bz), (cx, cy, cz)) = (a, b, c);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        if (u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero)).bitmask() & live != 0 {
            return None;
        }
        let inside =
            (u.cmpge(zero) & v.cmpge(zero) & w.cmpge(zero)) | (u.cmple(zero) & v.cmple(zero) & w.cmple(zero));
        let det = u + v + w;
        let ok = det.cmpne(zero) & det.abs().cmplt(Vec4::INFINITY);
        let tz = self.s[2] * (u * az + v * bz + w * cz);
        let inv = Vec4::ONE / det;
        let t = tz * inv;
        let hit = t.cmpgt(zero) & t.cmplt(Vec4::splat(t_max));
        let mut mask = (inside & ok & hit).bitmask() & live;
        if mask != 0 {
            // The scalar test's bound, lane by lane (only for the lanes
            // hit: most blocks are missed).
            let m = |p: Vec4, q: Vec4, r: Vec4| p.abs().max(q.abs()).max(r.abs());
            let bound = t_bound(
                m(ax, bx, cx),
                m(ay, by, cy),
                m(az, bz, cz) * self.s[2].abs(),
                inv.abs(),
            );
            mask &= t.cmpgt(bound).bitmask();
        }
        Some(Lanes {
            mask,
            t,
            b1: v * inv,
            b2: w * inv,
        })
    }

    /// The same result lane by lane through the scalar test.
    #[cold]
    fn scalar(&self, block: &Tri4, t_max: f32) -> Lanes {
        let mut out = Lanes {
            mask: 0,
            t: Vec4::ZERO,
            b1: Vec4::ZERO,
            b2: Vec4::ZERO,
        };
        for i in 0..block.count as usize {
            let [a, b, c] = block.corners(i);
            if let Some((t, bc)) = self.one.intersect(a, b, c, t_max) {
                out.mask |= 1 << i;
                out.t[i] = t;
                out.b1[i] = bc.x;
                out.b2[i] = bc.y;
            }
        }
        out
    }

    /// One triangle whose corners are the lanes of `rows` (`rows[axis]` =
    /// that coordinate of corners a, b, c, then a spare lane): what
    /// [`WatertightRay::intersect`] returns for it, bit for bit (the same
    /// operations in the same order). The axis permutation picks rows
    /// instead of moving scalars through memory, and the three edge
    /// functions are one vector product. The Cornell box's flattened blocks
    /// run this 0.8 times per camera-path ray; the closest-hit traversal took
    /// 3% fewer instructions with it than with the scalar test (callgrind).
    #[inline(always)]
    pub fn single(&self, rows: &[Vec4; 3], t_max: f32) -> Option<(f32, Vec2)> {
        let [kx, ky, kz] = self.one.k;
        // Corner coordinates relative to the origin, then sheared: lanes (a, b, c).
        let z = row(rows, kz) - self.o[2];
        let x = (row(rows, kx) - self.o[0]) - self.s[0] * z;
        let y = (row(rows, ky) - self.o[1]) - self.s[1] * z;
        // (u, v, w) = (cx·by − cy·bx, ax·cy − ay·cx, bx·ay − by·ax).
        let uvw = x.zxyw() * y.yzxw() - y.zxyw() * x.yzxw();
        let zero = Vec4::ZERO;
        if uvw.cmpeq(zero).bitmask() & 7 != 0 {
            return self.single_exact(rows, t_max);
        }
        if uvw.cmplt(zero).bitmask() & 7 != 0 && uvw.cmpgt(zero).bitmask() & 7 != 0 {
            return None;
        }
        let det = uvw.x + uvw.y + uvw.z;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let uz = uvw * z;
        let sz = self.s[2].x;
        let tz = sz * (uz.x + uz.y + uz.z);
        let inv = 1.0 / det;
        let t = tz * inv;
        if !(t > 0.0 && t < t_max) {
            return None;
        }
        let m = |v: Vec4| v.abs().xyz().max_element();
        let bound = t_bound(m(x), m(y), m(z) * sz.abs(), inv.abs());
        (t > bound).then(|| (t, Vec2::new(uvw.y * inv, uvw.z * inv)))
    }

    /// Two triangles sharing an edge, `(v0, v1, v2)` and `(v0, v2, v3)`,
    /// whose corners are the lanes of `rows` (`rows[axis]` = that
    /// coordinate of v0…v3): the nearest hit in `(0, t_max)`, which
    /// triangle (0 or 1) and its barycentrics of its second and third
    /// corners. Each lane computes exactly what [`WatertightRay::intersect`]
    /// does for its triangle, so the result is the two scalar tests' bit
    /// for bit (ties go to the first), and the shared edge `v0–v2` gets the
    /// same edge value with opposite signs in both: watertight. The four
    /// corners are moved and sheared once for both triangles — an OBJ quad
    /// costs about one triangle's test (`mesh_quad.rs`).
    #[inline(always)]
    pub fn pair(&self, rows: &[Vec4; 3], t_max: f32) -> Option<(f32, u32, Vec2)> {
        let [kx, ky, kz] = self.one.k;
        // Corners relative to the origin, then sheared: lanes (v0, v1, v2, v3).
        let z = row(rows, kz) - self.o[2];
        let x = (row(rows, kx) - self.o[0]) - self.s[0] * z;
        let y = (row(rows, ky) - self.o[1]) - self.s[1] * z;
        // Lane 0 is (a, b, c) = (v0, v1, v2), lane 1 (v0, v2, v3).
        let a = (x.xxxx(), y.xxxx(), z.xxxx());
        let b = (x.yzyz(), y.yzyz(), z.yzyz());
        let c = (x.zwzw(), y.zwzw(), z.zwzw());
        let Some(l) = self.edges(a, b, c, 3, t_max) else {
            return self.pair_exact(rows, t_max);
        };
        if l.mask == 0 {
            return None;
        }
        // The triangle hit: the second when only it is (mask 2), the
        // nearer when both are (mask 3; ties to the first). In bit
        // arithmetic, not a `match`: which half of a quad a ray meets is a
        // coin flip, and the branch was mispredicted 94 k times in the OBJ
        // room's 65 k samples (callgrind's branch model, 64², 16 spp).
        let lane = ((l.mask >> 1) & (!l.mask & 1 | u32::from(l.t.y < l.t.x))) as usize;
        // The barycentrics as one 8-byte value from a register: extracted
        // lane by lane they were stored as two floats, and the caller's
        // packing (`scene.rs`, `pack`) read them back as one 8-byte word
        // across both stores, which store forwarding cannot serve.
        let both = [l.b1.x, l.b2.x, l.b1.y, l.b2.y];
        let bc = Vec2::new(both[2 * lane], both[2 * lane + 1]);
        Some((l.t.to_array()[lane], lane as u32, bc))
    }

    /// [`WatertightRay4::pair`] through the scalar test (an edge value of
    /// exactly zero: its f64 fallback).
    #[cold]
    fn pair_exact(&self, rows: &[Vec4; 3], t_max: f32) -> Option<(f32, u32, Vec2)> {
        let p = [0, 1, 2, 3].map(|v| Vec3A::new(rows[0][v], rows[1][v], rows[2][v]));
        let first = self.one.intersect(p[0], p[1], p[2], t_max);
        let second = self.one.intersect(p[0], p[2], p[3], first.map_or(t_max, |h| h.0));
        match (first, second) {
            (_, Some((t, bc))) => Some((t, 1, bc)),
            (Some((t, bc)), None) => Some((t, 0, bc)),
            (None, None) => None,
        }
    }

    /// [`WatertightRay4::single`] through the scalar test, whose f64
    /// fallback handles an edge value of exactly zero.
    #[cold]
    fn single_exact(&self, rows: &[Vec4; 3], t_max: f32) -> Option<(f32, Vec2)> {
        let [a, b, c] = corners_of_rows(rows);
        self.one.intersect(a, b, c, t_max)
    }

    /// Nearest hit of the block in `(0, t_max)`: distance, lane and
    /// barycentrics. Ties go to the lowest lane, like a scalar loop.
    #[inline(always)]
    pub fn closest(&self, block: &Tri4, t_max: f32) -> Option<(f32, u32, Vec2)> {
        let l = self.lanes(block, t_max);
        let mut mask = l.mask;
        let mut best: Option<(f32, u32, Vec2)> = None;
        while mask != 0 {
            let i = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            if best.is_none_or(|(t, _, _)| l.t[i] < t) {
                best = Some((l.t[i], i as u32, Vec2::new(l.b1[i], l.b2[i])));
            }
        }
        best
    }

    /// Whether any triangle of the block is hit in `(0, t_max)`.
    #[inline(always)]
    pub fn any(&self, block: &Tri4, t_max: f32) -> bool {
        self.lanes(block, t_max).mask != 0
    }
}

/// The rows of [`WatertightRay4::single`] for corners `p`: x, y and z of
/// the three corners, a zero in the spare lane.
pub fn rows_of_corners(p: [Vec3A; 3]) -> [Vec4; 3] {
    [0, 1, 2].map(|a| Vec4::new(p[0][a], p[1][a], p[2][a], 0.0))
}

/// The corners back from [`rows_of_corners`].
pub fn corners_of_rows(rows: &[Vec4; 3]) -> [Vec3A; 3] {
    [0, 1, 2].map(|v| Vec3A::new(rows[0][v], rows[1][v], rows[2][v]))
}

/// Per-lane results of a [`Tri4`] test.
struct Lanes {
    mask: u32,
    t: Vec4,
    b1: Vec4,
    b2: Vec4,
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

    /// Packs `tris` as one `Tri4` block (plus the 3 spare floats).
    fn pack(tris: &[[Vec3A; 3]]) -> Vec<f32> {
        let mut soa = vec![f32::NAN; FLOATS * tris.len() + 3];
        Tri4::pack(&mut soa, tris);
        soa
    }

    #[test]
    fn four_lanes_match_the_scalar_test_bit_for_bit() {
        let mut rng = crate::math::Pcg32::new(7, 3);
        let mut p = || Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let (mut hits, mut checked) = (0, 0);
        for round in 0..4000 {
            let count = 1 + round % 4;
            let mut tris: Vec<[Vec3A; 3]> = (0..count).map(|_| [p(), p(), p()]).collect();
            if round % 7 == 0 {
                // Exact edge and vertex cases: a shared edge, a ray through a vertex.
                tris[0] = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
            }
            let o = p() * 3.0;
            let target = if round % 7 == 0 { Vec3A::ZERO } else { p() * 0.5 };
            let ray = Ray::new(o, (target - o).normalize());
            let soa = pack(&tris);
            let block = Tri4 {
                soa: &soa,
                count: count as u32,
            };
            let wt = WatertightRay4::new(&ray);
            let t_max = if round % 3 == 0 { 2.0 } else { f32::INFINITY };
            let want =
                tris.iter()
                    .enumerate()
                    .fold(None, |best: Option<(f32, u32, Vec2)>, (i, [a, b, c])| {
                        match wt.one.intersect(*a, *b, *c, best.map_or(t_max, |h| h.0)) {
                            Some((t, bc)) => Some((t, i as u32, bc)),
                            None => best,
                        }
                    });
            let got = wt.closest(&block, t_max);
            assert_eq!(
                got.map(|(t, i, bc)| (t.to_bits(), i, bc.x.to_bits(), bc.y.to_bits())),
                want.map(|(t, i, bc)| (t.to_bits(), i, bc.x.to_bits(), bc.y.to_bits())),
                "round {round}"
            );
            assert_eq!(wt.any(&block, t_max), want.is_some());
            hits += want.is_some() as u32;
            checked += 1;
        }
        assert!(hits > checked / 10, "the rays exercise hits: {hits}/{checked}");
    }

    /// The one-triangle row test against the scalar test, bit for bit,
    /// edge and vertex rays (the f64 fallback) included.
    #[test]
    fn row_test_matches_the_scalar_test_bit_for_bit() {
        let mut rng = crate::math::Pcg32::new(11, 5);
        let mut p = || Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let mut hits = 0;
        let rounds = 20_000;
        for round in 0..rounds {
            let mut tri = [p(), p(), p()];
            if round % 7 == 0 {
                tri = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
            }
            let o = p() * 3.0;
            let target = match round % 7 {
                0 => Vec3A::ZERO,
                3 => (tri[0] + tri[1]) * 0.5,
                _ => p() * 0.5,
            };
            let ray = Ray::new(o, (target - o).normalize());
            let wt = WatertightRay4::new(&ray);
            let t_max = if round % 3 == 0 { 2.0 } else { f32::INFINITY };
            let want = wt.one.intersect(tri[0], tri[1], tri[2], t_max);
            let rows = rows_of_corners(tri);
            assert_eq!(corners_of_rows(&rows), tri);
            let got = wt.single(&rows, t_max);
            assert_eq!(
                got.map(|(t, bc)| (t.to_bits(), bc.x.to_bits(), bc.y.to_bits())),
                want.map(|(t, bc)| (t.to_bits(), bc.x.to_bits(), bc.y.to_bits())),
                "round {round}"
            );
            hits += want.is_some() as u32;
        }
        assert!(hits > rounds / 10, "the rays exercise hits: {hits}/{rounds}");
    }

    /// The two-triangle test against two scalar tests, bit for bit, with
    /// rays through the shared edge, the corners and the f64 fallback.
    #[test]
    fn pair_test_matches_two_scalar_tests_bit_for_bit() {
        let mut rng = crate::math::Pcg32::new(13, 2);
        let mut p = || Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let (mut hits, mut second) = (0, 0);
        let rounds = 20_000;
        for round in 0..rounds {
            let mut q = [p(), p(), p(), p()];
            if round % 7 == 0 {
                q = [Vec3A::ZERO, Vec3A::X, Vec3A::new(1.0, 1.0, 0.0), Vec3A::Y];
            }
            let o = p() * 3.0;
            let target = match round % 7 {
                0 => Vec3A::ZERO,
                3 => (q[0] + q[2]) * 0.5,
                5 => (q[0] + q[1] + q[2] + q[3]) * 0.25,
                _ => p() * 0.5,
            };
            let ray = Ray::new(o, (target - o).normalize());
            let wt = WatertightRay4::new(&ray);
            let t_max = if round % 3 == 0 { 2.0 } else { f32::INFINITY };
            let a = wt.one.intersect(q[0], q[1], q[2], t_max);
            let b = wt.one.intersect(q[0], q[2], q[3], a.map_or(t_max, |h| h.0));
            let want = match (a, b) {
                (_, Some((t, bc))) => Some((t, 1, bc)),
                (Some((t, bc)), None) => Some((t, 0, bc)),
                (None, None) => None,
            };
            let rows = [0, 1, 2].map(|k| Vec4::new(q[0][k], q[1][k], q[2][k], q[3][k]));
            let got = wt.pair(&rows, t_max);
            assert_eq!(
                got.map(|(t, i, bc)| (t.to_bits(), i, bc.x.to_bits(), bc.y.to_bits())),
                want.map(|(t, i, bc)| (t.to_bits(), i, bc.x.to_bits(), bc.y.to_bits())),
                "round {round}"
            );
            hits += want.is_some() as u32;
            second += want.is_some_and(|h| h.1 == 1) as u32;
        }
        assert!(
            hits > rounds / 10 && second > rounds / 40,
            "hits {hits}, second {second}"
        );
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
