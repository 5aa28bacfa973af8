//! The bounded shapes of a small analytic scene — up to eight spheres and
//! eight quads — in SIMD lanes, tested all at once instead of through the
//! scene BVH.
//!
//! Why: with a handful of shapes the BVH buys nothing. A ray paid the slab
//! setup (three divisions), the root's eight-box test, a sorted push and a
//! pop per leaf its box let through, and one scalar shape test per leaf:
//! ~280 instructions per closest hit on `textured_spheres` (five shapes,
//! callgrind), the largest single share of its render. One ray against
//! eight spheres in the lanes of one AVX computation, and one against
//! eight quads, costs about what one scalar test did. Embree's leaves are
//! the same idea (four or eight primitives per leaf, tested in lanes).
//!
//! Each lane performs its scalar test's operations in the same order
//! ([`Sphere::intersect`], [`Quad::intersect`]), so every distance and
//! every `(s, t)` is the scalar one bit for bit (unit test below) and a
//! scene renders the same with or without lanes, up to which of two shapes
//! hit at exactly the same distance is reported (lanes: the lower index).

use super::{Quad, Shape, Sphere};
use crate::math::Ray;
use glam::{Vec2, Vec3A};
use wide::f32x8;

/// Lanes per kind of shape.
pub const LANES: usize = 8;

/// Up to eight spheres, structure of arrays. Unused lanes hold a sphere
/// of radius −1 at the origin, which the `valid` mask keeps from hitting.
#[derive(Clone, Debug)]
struct SphereLanes {
    c: [f32x8; 3],
    /// r · r, as the scalar test computes it.
    r2: f32x8,
    /// The scalar test's self-intersection bound, `1e-4 · max(r, 1e-3)`.
    eps: f32x8,
    valid: f32x8,
    /// Index in the scene's `shapes` of each lane.
    shape: [u32; LANES],
    len: usize,
}

/// Up to eight quads, structure of arrays (corner, unit normal and the
/// dual basis of [`Quad`]).
#[derive(Clone, Debug)]
struct QuadLanes {
    corner: [f32x8; 3],
    n: [f32x8; 3],
    du: [f32x8; 3],
    dv: [f32x8; 3],
    valid: f32x8,
    shape: [u32; LANES],
    len: usize,
}

/// The closest shape a ray meets in [`ShapeLanes::closest`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LaneHit {
    /// Index in `shapes` of a sphere.
    Sphere(u32),
    /// Index in `shapes` of a quad and the hit's `(s, t)`.
    Quad(u32, Vec2),
}

/// See the module docs.
#[derive(Clone, Debug)]
pub struct ShapeLanes {
    spheres: SphereLanes,
    quads: QuadLanes,
}

/// `x` with every lane set where `mask` is (all-ones lanes) and +∞ elsewhere.
#[inline(always)]
fn or_inf(mask: f32x8, x: f32x8) -> f32x8 {
    mask.select(x, f32x8::splat(f32::INFINITY))
}

/// `f` of each item in its lane, `fill` in the lanes past the last.
fn lanes_of<T>(items: &[(u32, T)], fill: f32, f: impl Fn(&T) -> f32) -> f32x8 {
    let mut a = [fill; LANES];
    for (x, (_, item)) in a.iter_mut().zip(items) {
        *x = f(item);
    }
    f32x8::from(a)
}

/// The shape index of each item's lane.
fn shapes_of<T>(items: &[(u32, T)]) -> [u32; LANES] {
    let mut a = [0; LANES];
    for (x, (i, _)) in a.iter_mut().zip(items) {
        *x = *i;
    }
    a
}

/// Lanes as an array.
#[inline(always)]
fn lanes(x: f32x8) -> [f32; LANES] {
    x.to_array()
}

impl ShapeLanes {
    /// The lanes of `shapes` (the scene's bounded shapes, in their order),
    /// or `None` when a shape is neither a sphere nor a quad, or there are
    /// more than eight of either.
    pub fn new(shapes: &[Shape]) -> Option<Self> {
        let mut s: Vec<(u32, Sphere)> = Vec::new();
        let mut q: Vec<(u32, Quad)> = Vec::new();
        for (i, shape) in shapes.iter().enumerate() {
            match shape {
                Shape::Sphere(sp) => s.push((i as u32, *sp)),
                Shape::Quad(qd) => q.push((i as u32, *qd)),
                _ => return None,
            }
        }
        if s.len() > LANES || q.len() > LANES || shapes.is_empty() {
            return None;
        }
        let spheres = SphereLanes {
            c: [
                lanes_of(&s, 0.0, |sp| sp.center.x),
                lanes_of(&s, 0.0, |sp| sp.center.y),
                lanes_of(&s, 0.0, |sp| sp.center.z),
            ],
            r2: lanes_of(&s, -1.0, |sp| sp.radius * sp.radius),
            eps: lanes_of(&s, 0.0, |sp| 1e-4 * sp.radius.max(1e-3)),
            valid: lanes_of(&s, 0.0, |_| f32::from_bits(u32::MAX)),
            shape: shapes_of(&s),
            len: s.len(),
        };
        let axes = |f: fn(&Quad) -> Vec3A| {
            [
                lanes_of(&q, 0.0, |qd| f(qd).x),
                lanes_of(&q, 0.0, |qd| f(qd).y),
                lanes_of(&q, 0.0, |qd| f(qd).z),
            ]
        };
        let quads = QuadLanes {
            corner: axes(|qd| qd.corner),
            n: axes(|qd| qd.n),
            du: axes(|qd| qd.dual().0),
            dv: axes(|qd| qd.dual().1),
            valid: lanes_of(&q, 0.0, |_| f32::from_bits(u32::MAX)),
            shape: shapes_of(&q),
            len: q.len(),
        };
        Some(Self { spheres, quads })
    }

    /// Each sphere lane's nearest root in `(eps, t_max)`, +∞ where none:
    /// [`Sphere::intersect`]'s operations lane by lane.
    #[inline(always)]
    fn sphere_t(&self, o: [f32x8; 3], d: [f32x8; 3], t_max: f32x8) -> f32x8 {
        let s = &self.spheres;
        let oc = [o[0] - s.c[0], o[1] - s.c[1], o[2] - s.c[2]];
        let dot = |a: [f32x8; 3], b: [f32x8; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let a = dot(d, d);
        let b = dot(oc, d);
        let oc2 = dot(oc, oc);
        let c = oc2 - s.r2;
        // Lanes the scalar test surely misses, found before its division:
        // a sphere behind an origin outside it (b > 0 and c > 0 make both
        // roots negative whatever the rounding: q < 0, q/a < 0, c/q < 0),
        // and a line farther from the centre than r by a margin (a·|oc|² −
        // b² is a·(its distance)²; in f32 it is off by a few ε·a·|oc|², and
        // the scalar distance by as little, far below the 10⁻⁵ allowed).
        let behind = b.simd_gt(f32x8::ZERO) & c.simd_gt(f32x8::ZERO);
        let far = (oc2 * a - b * b).simd_gt(s.r2 * a + f32x8::splat(1e-5) * oc2 * a);
        let maybe = s.valid & !(behind | far);
        // Most rays pass every sphere by: no square root, no division.
        if maybe.to_bitmask() == 0 {
            return f32x8::splat(f32::INFINITY);
        }
        let k = b / a;
        let l = [oc[0] - k * d[0], oc[1] - k * d[1], oc[2] - k * d[2]];
        let disc = s.r2 - dot(l, l);
        // The scalar test returns at `disc < 0`; a NaN goes on (and fails below).
        let go_on = !disc.simd_lt(f32x8::ZERO) & maybe;
        // b.signum(): ±1 with b's sign bit (NaN stays NaN below either way).
        let sign = f32x8::ONE.flip_signs(b);
        let q = -b - sign * (a * disc).sqrt();
        let x = q / a;
        let y = q.simd_ne(f32x8::ZERO).select(c / q, x);
        // `min`/`max` as f32's: a NaN lane takes the other operand.
        let (t0, t1) = (x.min(y), x.max(y));
        let in0 = t0.simd_gt(s.eps) & t0.simd_lt(t_max);
        let in1 = t1.simd_gt(s.eps) & t1.simd_lt(t_max);
        or_inf(go_on & (in0 | in1), in0.select(t0, t1))
    }

    /// Each quad lane's hit distance in `(1e-5, t_max)` and `(s, t)`, +∞
    /// where none: [`Quad::intersect`]'s operations lane by lane.
    #[inline(always)]
    fn quad_t(&self, o: [f32x8; 3], d: [f32x8; 3], t_max: f32x8) -> (f32x8, f32x8, f32x8) {
        let q = &self.quads;
        let dot = |a: [f32x8; 3], b: [f32x8; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let denom = dot(q.n, d);
        let facing = !denom.abs().simd_lt(f32x8::splat(1e-12)) & q.valid;
        let t = dot([q.corner[0] - o[0], q.corner[1] - o[1], q.corner[2] - o[2]], q.n) / denom;
        let in_range = t.simd_gt(f32x8::splat(1e-5)) & t.simd_lt(t_max);
        let p = [
            (o[0] + d[0] * t) - q.corner[0],
            (o[1] + d[1] * t) - q.corner[1],
            (o[2] + d[2] * t) - q.corner[2],
        ];
        let (s, r) = (dot(p, q.du), dot(p, q.dv));
        let inside =
            s.simd_ge(f32x8::ZERO) & s.simd_le(f32x8::ONE) & r.simd_ge(f32x8::ZERO) & r.simd_le(f32x8::ONE);
        (or_inf(facing & in_range & inside, t), s, r)
    }

    /// The ray's origin and direction, splatted.
    #[inline(always)]
    fn splat(ray: &Ray) -> ([f32x8; 3], [f32x8; 3]) {
        let (o, d) = (ray.o, ray.d);
        (
            [f32x8::splat(o.x), f32x8::splat(o.y), f32x8::splat(o.z)],
            [f32x8::splat(d.x), f32x8::splat(d.y), f32x8::splat(d.z)],
        )
    }

    /// The closest shape hit in `(0, t_max)` and its distance. Of two at
    /// the same distance, a sphere before a quad and the lower index first.
    #[inline]
    pub fn closest(&self, ray: &Ray, t_max: f32) -> Option<(f32, LaneHit)> {
        let (o, d) = Self::splat(ray);
        let tm = f32x8::splat(t_max);
        let mut best: Option<(f32, LaneHit)> = None;
        if self.spheres.len > 0 {
            let ts = self.sphere_t(o, d, tm);
            let m = ts.simd_lt(tm).to_bitmask();
            if m != 0 {
                let ts = lanes(ts);
                let k = nearest_lane(&ts, m);
                best = Some((ts[k], LaneHit::Sphere(self.spheres.shape[k])));
            }
        }
        if self.quads.len > 0 {
            let bound = f32x8::splat(best.map_or(t_max, |b| b.0));
            let (tq, s, r) = self.quad_t(o, d, tm);
            let m = tq.simd_lt(bound).to_bitmask();
            if m != 0 {
                let tq = lanes(tq);
                let k = nearest_lane(&tq, m);
                let uv = Vec2::new(lanes(s)[k], lanes(r)[k]);
                best = Some((tq[k], LaneHit::Quad(self.quads.shape[k], uv)));
            }
        }
        best
    }

    /// Whether any shape is hit in `(0, t_max)`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let (o, d) = Self::splat(ray);
        let tm = f32x8::splat(t_max);
        (self.spheres.len > 0 && self.sphere_t(o, d, tm).simd_lt(tm).to_bitmask() != 0)
            || (self.quads.len > 0 && self.quad_t(o, d, tm).0.simd_lt(tm).to_bitmask() != 0)
    }
}

/// The lane of `mask` (non-empty) with the smallest `t`, the first of equals.
#[inline(always)]
fn nearest_lane(t: &[f32; LANES], mut mask: u32) -> usize {
    let mut k = mask.trailing_zeros() as usize;
    mask &= mask - 1;
    while mask != 0 {
        let j = mask.trailing_zeros() as usize;
        mask &= mask - 1;
        if t[j] < t[k] {
            k = j;
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::NO_LIGHT;
    use crate::math::rng::Pcg32 as Rng;
    use glam::Vec3A;

    fn shapes(rng: &mut Rng, spheres: usize, quads: usize) -> Vec<Shape> {
        let mut v = Vec::new();
        let mut p = || Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 - 2.0;
        for _ in 0..spheres {
            let c = p();
            let r = 0.05 + 0.5 * (p().x + 2.0) / 4.0;
            v.push(Shape::Sphere(Sphere {
                center: c,
                radius: r,
                material: 0,
                light: NO_LIGHT,
                mitsuba_uv: false,
            }));
        }
        for _ in 0..quads {
            let (c, u, w) = (p(), p() * 0.5, p() * 0.5);
            if u.cross(w).length_squared() > 1e-4 {
                v.push(Shape::Quad(Quad::new(c, u, w, 0, NO_LIGHT)));
            }
        }
        v
    }

    /// Lanes and the scalar tests agree bit for bit on every distance and
    /// `(s, t)`, on rays from inside and outside, in random scenes of 1–8
    /// spheres and 0–8 quads, with bounded and unbounded `t_max`.
    #[test]
    fn lanes_are_the_scalar_tests() {
        let mut rng = Rng::new(7, 1);
        let mut hits = 0;
        for scene in 0..200 {
            let sh = shapes(&mut rng, 1 + scene % 8, scene % 9);
            let lanes = ShapeLanes::new(&sh).expect("spheres and quads only");
            for _ in 0..200 {
                let o = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 6.0 - 3.0;
                // Aimed into the shapes' region, so that most rays hit.
                let d = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 3.0 - 1.5 - o;
                let ray = Ray::new(o, d.normalize_or(Vec3A::X));
                let t_max = if rng.next_f32() < 0.3 {
                    f32::INFINITY
                } else {
                    4.0 * rng.next_f32()
                };
                // The scalar answer: the first of the closest in index order.
                let mut want: Option<(f32, LaneHit)> = None;
                for (i, s) in sh.iter().enumerate() {
                    let bound = want.map_or(t_max, |w| w.0);
                    match s {
                        Shape::Sphere(sp) => {
                            if let Some(t) = sp.intersect(&ray, bound) {
                                want = Some((t, LaneHit::Sphere(i as u32)));
                            }
                        }
                        Shape::Quad(q) => {
                            if let Some((t, uv)) = q.intersect(&ray, bound) {
                                want = Some((t, LaneHit::Quad(i as u32, uv)));
                            }
                        }
                        _ => unreachable!(),
                    }
                }
                let got = lanes.closest(&ray, t_max);
                let bits = |h: Option<(f32, LaneHit)>| {
                    h.map(|(t, k)| match k {
                        LaneHit::Sphere(i) => (t.to_bits(), i, 0, 0),
                        LaneHit::Quad(i, uv) => (t.to_bits(), i, uv.x.to_bits(), uv.y.to_bits()),
                    })
                };
                assert_eq!(bits(got), bits(want), "scene {scene}, ray {ray:?}, t_max {t_max}");
                assert_eq!(lanes.occluded(&ray, t_max), want.is_some());
                hits += usize::from(want.is_some());
            }
        }
        assert!(hits > 3000, "only {hits} hits: the test rays miss too often");
    }

    /// The early rejection before the division never drops a hit: rays
    /// grazing spheres far from their origin (up to 10⁵ radii away, where
    /// the squared distances cancel most) and rays from inside, near the
    /// surface, against spheres behind them; lanes and scalar agree bit
    /// for bit.
    #[test]
    fn grazing_and_distant_rays_match_the_scalar_test() {
        let mut rng = Rng::new(3, 5);
        let mut hits = 0;
        for case in 0..20000 {
            let far = 10f32.powf(rng.next_f32() * 5.0);
            let r = 0.01 + rng.next_f32();
            let c = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5) * far;
            let sp = Sphere {
                center: c,
                radius: r,
                material: 0,
                light: NO_LIGHT,
                mitsuba_uv: false,
            };
            let lanes = ShapeLanes::new(&[Shape::Sphere(sp)]).expect("one sphere");
            let o = if case % 4 == 0 {
                // Inside, near the surface.
                c + Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5)
                    .normalize_or(Vec3A::X)
                    * r
                    * (1.0 - 1e-3 * rng.next_f32())
            } else {
                Vec3A::ZERO
            };
            // Aimed at a point within ±2 % of the silhouette's radius.
            let side = Vec3A::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5);
            let to = c - o;
            let perp = (side - to * side.dot(to) / to.length_squared().max(1e-30)).normalize_or(Vec3A::Y);
            let aim = c + perp * r * (0.98 + 0.04 * rng.next_f32());
            let ray = Ray::new(o, (aim - o).normalize_or(Vec3A::X));
            let want = sp.intersect(&ray, f32::INFINITY);
            let got = lanes.closest(&ray, f32::INFINITY).map(|(t, _)| t);
            assert_eq!(
                got.map(f32::to_bits),
                want.map(f32::to_bits),
                "case {case}: {sp:?}, {ray:?}"
            );
            hits += usize::from(want.is_some());
        }
        assert!(
            hits > 5000 && hits < 19000,
            "{hits} of 20000 grazing rays hit: not grazing"
        );
    }

    /// Only spheres and quads, at most eight of each, get lanes.
    #[test]
    fn lanes_only_for_small_analytic_sets() {
        let mut rng = Rng::new(1, 1);
        assert!(ShapeLanes::new(&shapes(&mut rng, 8, 8)).is_some());
        assert!(ShapeLanes::new(&shapes(&mut rng, 9, 0)).is_none());
        assert!(ShapeLanes::new(&[]).is_none());
        let mut sh = shapes(&mut rng, 2, 0);
        sh.push(Shape::Sdf(0));
        assert!(ShapeLanes::new(&sh).is_none());
    }
}
