//! Axis-aligned bounding box, and the ray/box slab test every traversal step
//! runs.
//!
//! Inputs are assumed NaN-free. Infinite extents are allowed only in
//! [`Aabb::EMPTY`], which contains no point.

use glam::Vec3A;

/// An axis-aligned box, in whatever space its points are given (world space in the
/// scene's BVH). `min > max` on some axis means empty.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Corner with the smallest coordinate on every axis.
    pub min: Vec3A,
    /// Corner with the largest coordinate on every axis.
    pub max: Vec3A,
}

/// Direction components smaller than this are replaced by ±this before
/// inverting, so `1 / d` is large but finite and `0 * inv_d` can never be
/// `0 * inf = NaN`. A ray tilted by 1e-30 is the same ray at every scale f32
/// can represent.
const MIN_DIR: f32 = 1e-30;

/// `1 + 2γ(3)` (pbrt-v3 §3.9, γ(n) = nε / (1 - nε)): widening the exit
/// distance by this makes the slab test conservative under rounding, so a box
/// whose primitive is hit is never culled, even a flat one.
/// Ize 2013, "Robust BVH Ray Traversal", <https://jcgt.org/published/0002/02/02/>.
pub(crate) const FAR_SCALE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

impl Aabb {
    /// The box containing nothing: the identity of [`Aabb::union`] and
    /// [`Aabb::grow_point`], so a fold can start from it.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    /// The smallest box containing every point ([`Aabb::EMPTY`] for none).
    pub fn from_points(points: &[Vec3A]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow_point(p))
    }

    /// The smallest box containing `self` and `p`.
    #[inline]
    pub fn grow_point(self, p: Vec3A) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box containing both boxes.
    #[inline]
    pub fn union(self, o: Aabb) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// Centre of the box; what the BVH build bins primitives by.
    #[inline]
    pub fn centroid(&self) -> Vec3A {
        0.5 * (self.min + self.max)
    }

    /// True if the box contains no point (`min > max` on some axis), as
    /// [`Aabb::EMPTY`]; a flat box (`min == max` on an axis) is not empty.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Whether `o` lies inside `self` (boundaries included). Empty boxes
    /// contain nothing, not even other empty boxes.
    #[inline]
    pub fn contains(&self, o: &Aabb) -> bool {
        !o.is_empty() && self.min.cmple(o.min).all() && o.max.cmple(self.max).all()
    }

    /// Size along each axis (`max − min`); negative for an empty box.
    #[inline]
    pub fn extent(&self) -> Vec3A {
        self.max - self.min
    }

    /// Total area of the six faces (0 for an empty box): by the surface area
    /// heuristic, proportional to the chance that a random ray hits the box.
    pub fn surface_area(&self) -> f32 {
        if self.is_empty() {
            return 0.0;
        }
        let d = self.max - self.min;
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// `self` grown outward by a few ulps (and 1e-20 absolute). Traversal
    /// tilts zero direction components by `MIN_DIR` (see [`safe_inv_dir`]);
    /// a ray running exactly along a face would then leave the slab at
    /// `t = 0`. On the padded box the true face is strictly inside, by at
    /// least `1e-20 / MIN_DIR = 1e10` in `t`. The BVH stores padded boxes.
    #[inline]
    pub fn padded(self) -> Self {
        let pad = self.min.abs().max(self.max.abs()) * (2.0 * f32::EPSILON) + Vec3A::splat(1e-20);
        Self {
            min: self.min - pad,
            max: self.max + pad,
        }
    }

    /// Entry distance of the ray `o + t d` into the box for `t` in
    /// `[0, t_max]`, or `None`. `inv_d` must come from [`safe_inv_dir`]; the
    /// test is conservative (see `FAR_SCALE`), so a ray grazing an edge may
    /// report a hit it does not strictly have, never the reverse.
    #[inline]
    pub fn intersect(&self, o: Vec3A, inv_d: Vec3A, t_max: f32) -> Option<f32> {
        if self.is_empty() {
            return None;
        }
        let b = self.padded();
        let t = slab(b.min, b.max, o, inv_d, t_max);
        (t < f32::INFINITY).then_some(t)
    }
}

/// `1 / d` with near-zero components pushed away from zero (keeping the
/// sign, so `-0.0` still means "going down"), so the slab test sees no NaN.
#[inline]
pub fn safe_inv_dir(d: Vec3A) -> Vec3A {
    let tiny = d.abs().cmplt(Vec3A::splat(MIN_DIR));
    Vec3A::select(tiny, Vec3A::splat(MIN_DIR).copysign(d), d).recip()
}

/// Kay & Kajiya slab test on a non-empty box: entry distance, or `INFINITY`
/// for a miss. Min/max per axis rather than a sign select, because SSE2 has
/// `minps`/`maxps` but no cheap blend; with a finite `inv_d` no lane is NaN.
/// Also used by the BVH traversal, where node boxes are never empty and
/// already [`Aabb::padded`].
#[inline(always)]
pub(crate) fn slab(min: Vec3A, max: Vec3A, o: Vec3A, inv_d: Vec3A, t_max: f32) -> f32 {
    let t0 = (min - o) * inv_d;
    let t1 = (max - o) * inv_d;
    let near = t0.min(t1).max_element().max(0.0);
    let far = (t0.max(t1).min_element() * FAR_SCALE).min(t_max);
    if near <= far { near } else { f32::INFINITY }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb {
            min: Vec3A::ZERO,
            max: Vec3A::ONE,
        }
    }

    fn hit(b: &Aabb, o: [f32; 3], d: [f32; 3]) -> Option<f32> {
        b.intersect(
            Vec3A::from_array(o),
            safe_inv_dir(Vec3A::from_array(d)),
            f32::INFINITY,
        )
    }

    /// Entry distances are conservative by a few ulps (`Aabb::padded`).
    fn near(got: Option<f32>, want: f32) -> bool {
        got.is_some_and(|t| t <= want && t >= want - 1e-6 * (1.0 + want))
    }

    #[test]
    fn aabb_intersect_entry_distance() {
        let t = hit(&unit(), [-1.0, 0.5, 0.5], [1.0, 0.0, 0.0]);
        assert!(near(t, 1.0), "expected entry at t = 1, got {t:?}");
        let t = hit(&unit(), [0.5, 0.5, 0.5], [0.0, -1.0, 0.0]);
        assert!(near(t, 0.0), "origin inside: expected t = 0, got {t:?}");
        let t = hit(&unit(), [-1.0, 0.5, 0.5], [-1.0, 0.0, 0.0]);
        assert_eq!(t, None, "box behind the ray: expected a miss, got {t:?}");
        let t = unit().intersect(Vec3A::new(-1.0, 0.5, 0.5), Vec3A::X, 0.5);
        assert_eq!(t, None, "box beyond t_max: expected a miss, got {t:?}");
    }

    #[test]
    fn aabb_intersect_axis_parallel_on_face() {
        // Origin on the x = 0 face, moving along z with d.x = ±0: the naive
        // test computes 0 * inf = NaN on x and may cull the box.
        for dx in [0.0, -0.0] {
            let t = hit(&unit(), [0.0, 0.5, -1.0], [dx, 0.0, 1.0]);
            assert!(near(t, 1.0), "d.x = {dx}: expected entry at t = 1, got {t:?}");
            let t = hit(&unit(), [1.0, 1.0, 2.0], [dx, -0.0, -1.0]);
            assert!(
                near(t, 1.0),
                "edge, d.x = {dx}: expected entry at t = 1, got {t:?}"
            );
        }
        let t = hit(&unit(), [1.5, 0.5, -1.0], [0.0, 0.0, 1.0]);
        assert_eq!(t, None, "parallel outside the x slab: expected a miss, got {t:?}");
    }

    #[test]
    fn aabb_intersect_flat_and_empty() {
        let flat = Aabb {
            min: Vec3A::new(0.0, 0.0, 2.0),
            max: Vec3A::new(1.0, 1.0, 2.0),
        };
        let t = hit(&flat, [0.25, 0.75, 0.0], [0.0, 0.0, 1.0]);
        assert!(near(t, 2.0), "flat box: expected entry at t = 2, got {t:?}");
        let t = hit(&Aabb::EMPTY, [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]);
        assert_eq!(t, None, "empty box: expected a miss, got {t:?}");
        let t = hit(&Aabb::EMPTY, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        assert_eq!(
            t, None,
            "empty box, axis-parallel ray: expected a miss, got {t:?}"
        );
    }

    #[test]
    fn aabb_contains_and_union() {
        let a = unit();
        let b = Aabb {
            min: Vec3A::splat(2.0),
            max: Vec3A::splat(3.0),
        };
        let u = a.union(b);
        assert!(
            u.contains(&a) && u.contains(&b),
            "union {u:?} should contain {a:?} and {b:?}"
        );
        assert!(!a.contains(&b), "{a:?} should not contain {b:?}");
        assert!(!a.contains(&Aabb::EMPTY), "nothing contains the empty box");
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
    }
}
