//! [`Sdf`]: an arena of [`SdfNode`]s with its root, evaluated by recursion
//! over child indices.
//!
//! On exactness: sphere tracing needs `|d| ≤` the distance to the surface.
//! Every node here gives that except the Mandelbulb, whose distance is an
//! estimate. Min/max of bounds are bounds, and so is the quadratic smooth
//! minimum: its partial derivatives are `w` and `1 − w` with `w ∈ [½, 1]`, so
//! its gradient is a convex combination of the children's and it stays
//! 1-Lipschitz; a 1-Lipschitz function never exceeds the distance to its own
//! zero set. (`tree_is_one_lipschitz` checks this numerically.)

use super::bounding_sphere::bounding_sphere;
use super::bounds::bounds_of;
use super::fractal::{mandelbulb, menger};
use super::mandelbulb_x4::mandelbulb8_x4;
use super::node::SdfNode;
use super::primitives::{capsule, cuboid, cylinder, plane, round_box, sphere, torus};
use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Mat3A, Vec3A};

/// An SDF tree ready to march: the node arena, its root, and what the march
/// needs precomputed (exactness, bounds).
#[derive(Clone, Debug)]
pub struct Sdf {
    nodes: Vec<SdfNode>,
    root: u32,
    /// False if any node gives an estimate rather than a bound.
    is_exact: bool,
    /// World-space bounds of the surface, computed once for every trace.
    bounds: Aabb,
    /// A ball holding the surface where the tree knows one (centre, radius).
    sphere: Option<(Vec3A, f32)>,
    /// The root's chain of [`SdfNode::Transform`]s folded into one map, so
    /// a march moves its ray once instead of every point (see [`Frame`]).
    frame: Frame,
}

/// `q = local_from_world · p + offset` into the space of `inner`, the first
/// node under the root's transforms, whose distances are `scale` times
/// smaller than world ones.
///
/// Why: the loader wraps every placed shape in a transform, and undoing its
/// quaternion, translation and scale at each step cost a fifth of a
/// Mandelbulb estimate (measured: 81 M of 439 M instructions in the march,
/// callgrind, 128² at 1 spp). A ray is affine, so its points map to
/// `q(t) = q(o) + t · local_from_world · d` with the same `t`.
#[derive(Clone, Copy, Debug)]
struct Frame {
    local_from_world: Mat3A,
    offset: Vec3A,
    scale: f32,
    inner: u32,
    /// `inner`'s parameters when it is a lone Mandelbulb `(power,
    /// iterations, bailout)`: the march calls the estimate directly, without
    /// the node dispatch (4% of the instructions of a 512² render).
    bulb: Option<(f32, u32, f32)>,
}

impl Frame {
    /// Folds the transforms from `root` down: each maps `q ↦ R⁻¹(q − T)/s`.
    fn of(nodes: &[SdfNode], root: u32) -> Self {
        let mut f = Self {
            local_from_world: Mat3A::IDENTITY,
            offset: Vec3A::ZERO,
            scale: 1.0,
            inner: root,
            bulb: None,
        };
        while let SdfNode::Transform {
            child,
            translate,
            rotate,
            scale,
        } = nodes[f.inner as usize]
        {
            let m = Mat3A::from_quat(rotate.inverse()) * scale.recip();
            f.local_from_world = m * f.local_from_world;
            f.offset = m * (f.offset - translate);
            f.scale *= scale;
            f.inner = child;
        }
        if let SdfNode::Mandelbulb {
            power,
            iterations,
            bailout,
        } = nodes[f.inner as usize]
        {
            f.bulb = Some((power, iterations, bailout));
        }
        f
    }
}

impl Sdf {
    /// Takes an arena whose children come before their parents (see
    /// [`super::validate()`]), normalising plane normals and rotations.
    ///
    /// # Panics
    /// If `root` or a child index is out of order or out of range: a bug in
    /// the builder, which validates user input first.
    pub fn new(mut nodes: Vec<SdfNode>, root: u32) -> Self {
        assert!(
            (root as usize) < nodes.len(),
            "SDF root {root} outside {} nodes",
            nodes.len()
        );
        for (i, node) in nodes.iter_mut().enumerate() {
            assert!(
                node.children().iter().all(|&c| (c as usize) < i),
                "SDF node {i} has a child not before it"
            );
            match node {
                SdfNode::Plane { normal, .. } => *normal = normal.normalize_or(Vec3A::Y),
                SdfNode::Transform { rotate, .. } => *rotate = rotate.normalize(),
                _ => {}
            }
        }
        let is_exact = !nodes.iter().any(|n| matches!(n, SdfNode::Mandelbulb { .. }));
        let bounds = bounds_of(&nodes, root).0;
        let sphere = bounding_sphere(&nodes, root);
        let frame = Frame::of(&nodes, root);
        Self {
            nodes,
            root,
            is_exact,
            bounds,
            sphere,
            frame,
        }
    }

    /// A tree of one node.
    pub fn primitive(node: SdfNode) -> Self {
        Self::new(vec![node], 0)
    }

    /// Signed distance from `p` (world space) to the surface, negative inside;
    /// at most the true distance when [`Self::is_exact`].
    #[inline]
    pub fn distance(&self, p: Vec3A) -> f32 {
        let f = &self.frame;
        self.local_distance(f.local_from_world * p + f.offset)
    }

    /// [`Self::distance`] at four points; a lone power-8 Mandelbulb takes
    /// them in SIMD lanes ([`mandelbulb8_x4`]), bit for bit the same.
    #[inline]
    pub fn distance_x4(&self, points: [Vec3A; 4]) -> [f32; 4] {
        let f = &self.frame;
        self.local_distance_x4(points.map(|p| f.local_from_world * p + f.offset))
    }

    /// `ray` in the local space of [`Self::local_distance`], with the same
    /// ray parameter `t`.
    #[inline]
    pub fn local_ray(&self, ray: &Ray) -> Ray {
        let f = &self.frame;
        Ray {
            o: f.local_from_world * ray.o + f.offset,
            d: f.local_from_world * ray.d,
        }
    }

    /// [`Self::distance`] at a point `q` of [`Self::local_ray`]'s space, in
    /// world units.
    #[inline]
    pub fn local_distance(&self, q: Vec3A) -> f32 {
        let f = &self.frame;
        let d = match f.bulb {
            Some((power, iterations, bailout)) => mandelbulb(q, power, iterations, bailout),
            None => self.eval(f.inner, q),
        };
        d * f.scale
    }

    /// Whether [`Self::local_distance_x4`] evaluates its points in SIMD
    /// lanes (a lone power-8 Mandelbulb), so a march may take four at once.
    #[inline]
    pub fn has_lanes(&self) -> bool {
        matches!(self.frame.bulb, Some((8.0, _, _)))
    }

    /// [`Self::local_distance`] at four points, in SIMD lanes when
    /// [`Self::has_lanes`], bit for bit the same.
    #[inline]
    pub fn local_distance_x4(&self, q: [Vec3A; 4]) -> [f32; 4] {
        let f = &self.frame;
        match f.bulb {
            Some((8.0, iterations, bailout)) => mandelbulb8_x4(q, iterations, bailout).map(|d| d * f.scale),
            _ => q.map(|q| self.local_distance(q)),
        }
    }

    /// Conservative world-space bounds; infinite for an unbounded tree (a
    /// [`SdfNode::Plane`] not intersected with a bounded shape).
    #[inline]
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// A ball (centre, radius) holding the surface, for trees made of balls
    /// (see `bounding_sphere.rs`); `None` when only [`Self::bounds`] is known.
    #[inline]
    pub fn bounding_sphere(&self) -> Option<(Vec3A, f32)> {
        self.sphere
    }

    /// True when [`Self::distance`] never exceeds the true distance, so a ray
    /// may step by all of it; false for estimates (the Mandelbulb).
    #[inline]
    pub fn is_exact(&self) -> bool {
        self.is_exact
    }

    /// The node arena, children before parents (plane normals and rotations
    /// normalised).
    pub fn nodes(&self) -> &[SdfNode] {
        &self.nodes
    }

    /// Index of the root node in [`Sdf::nodes`].
    pub fn root(&self) -> u32 {
        self.root
    }

    fn eval(&self, i: u32, p: Vec3A) -> f32 {
        match self.nodes[i as usize] {
            SdfNode::Sphere { radius } => sphere(p, radius),
            SdfNode::Box { half_extents } => cuboid(p, half_extents),
            SdfNode::RoundBox { half_extents, radius } => round_box(p, half_extents, radius),
            SdfNode::Torus { major, minor } => torus(p, major, minor),
            SdfNode::Capsule { a, b, radius } => capsule(p, a, b, radius),
            SdfNode::Cylinder { radius, half_height } => cylinder(p, radius, half_height),
            SdfNode::Plane { normal, offset } => plane(p, normal, offset),
            SdfNode::Mandelbulb {
                power,
                iterations,
                bailout,
            } => mandelbulb(p, power, iterations, bailout),
            SdfNode::Menger { iterations } => menger(p, iterations),
            SdfNode::Union { children: [a, b] } => self.eval(a, p).min(self.eval(b, p)),
            SdfNode::Intersection { children: [a, b] } => self.eval(a, p).max(self.eval(b, p)),
            SdfNode::Difference { children: [a, b] } => self.eval(a, p).max(-self.eval(b, p)),
            SdfNode::SmoothUnion { children: [a, b], k } => smooth_min(self.eval(a, p), self.eval(b, p), k),
            // max(a, b) = −min(−a, −b), smoothed the same way.
            SdfNode::SmoothIntersection { children: [a, b], k } => {
                -smooth_min(-self.eval(a, p), -self.eval(b, p), k)
            }
            SdfNode::SmoothDifference { children: [a, b], k } => {
                -smooth_min(-self.eval(a, p), self.eval(b, p), k)
            }
            SdfNode::Transform {
                child,
                translate,
                rotate,
                scale,
            } => {
                // Into the child's space: undo the translation, rotation, scale.
                let q = rotate.inverse() * (p - translate) / scale;
                // Child distances are in child units; scale them back.
                self.eval(child, q) * scale
            }
        }
    }
}

/// Quilez's quadratic polynomial smooth minimum: `min(a, b)` minus at most
/// `k/4` where `|a − b| < k`, <https://iquilezles.org/articles/smin/>.
#[inline]
pub fn smooth_min(a: f32, b: f32, k: f32) -> f32 {
    if k <= 0.0 {
        return a.min(b);
    }
    // Blend weight: 1 where a = b, 0 once they differ by k.
    let h = (k - (a - b).abs()).max(0.0) / k;
    a.min(b) - h * h * k * 0.25
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Pcg32, sampling::uniform_sphere};
    use glam::Quat;

    #[test]
    fn transform_rescales_distance() {
        // A unit sphere scaled by 2.5 and moved is a sphere of radius 2.5.
        let (c, s) = (Vec3A::new(1.0, -2.0, 0.5), 2.5);
        let rotate = Quat::from_axis_angle(glam::Vec3::new(1.0, 1.0, 0.0).normalize(), 0.7);
        let sdf = Sdf::new(
            vec![
                SdfNode::Sphere { radius: 1.0 },
                SdfNode::Transform {
                    child: 0,
                    translate: c,
                    rotate,
                    scale: s,
                },
            ],
            1,
        );
        let mut rng = Pcg32::new(1, 1);
        for _ in 0..1000 {
            let p = c + uniform_sphere(rng.next_vec2()) * 6.0 * rng.next_f32();
            let want = (p - c).length() - s;
            let got = sdf.distance(p);
            assert!((got - want).abs() < 1e-4, "d({p}) = {got}, want {want}");
        }
    }

    #[test]
    fn tree_is_one_lipschitz() {
        // Every node but the Mandelbulb, smooth operators included.
        let rotate = Quat::from_rotation_z(0.4);
        let nodes = vec![
            SdfNode::Torus {
                major: 1.0,
                minor: 0.3,
            },
            SdfNode::RoundBox {
                half_extents: Vec3A::new(0.6, 0.4, 0.5),
                radius: 0.1,
            },
            SdfNode::SmoothUnion {
                children: [0, 1],
                k: 0.5,
            },
            SdfNode::Capsule {
                a: Vec3A::NEG_Y,
                b: Vec3A::Y,
                radius: 0.3,
            },
            SdfNode::SmoothDifference {
                children: [2, 3],
                k: 0.3,
            },
            SdfNode::Menger { iterations: 3 },
            SdfNode::Transform {
                child: 5,
                translate: Vec3A::X,
                rotate,
                scale: 0.7,
            },
            SdfNode::SmoothIntersection {
                children: [4, 6],
                k: 0.2,
            },
            SdfNode::Cylinder {
                radius: 0.4,
                half_height: 1.5,
            },
            SdfNode::Plane {
                normal: Vec3A::new(0.0, 1.0, 1.0),
                offset: 0.2,
            },
            SdfNode::Difference { children: [8, 9] },
            SdfNode::Union { children: [7, 10] },
            SdfNode::Sphere { radius: 1.2 },
            SdfNode::Intersection { children: [11, 12] },
        ];
        let sdf = Sdf::new(nodes, 13);
        assert!(sdf.is_exact());
        let mut rng = Pcg32::new(2, 2);
        for _ in 0..100_000 {
            let p = uniform_sphere(rng.next_vec2()) * 2.0 * rng.next_f32();
            let q = p + uniform_sphere(rng.next_vec2()) * 0.1 * rng.next_f32();
            let (dp, dq) = (sdf.distance(p), sdf.distance(q));
            let slope = (dp - dq).abs() / (p - q).length().max(1e-6);
            assert!(
                (dp - dq).abs() <= (p - q).length() * 1.001 + 1e-5,
                "slope {slope} > 1 between {p} and {q}"
            );
        }
    }

    #[test]
    fn smooth_min_stays_within_quarter_k() {
        let mut rng = Pcg32::new(4, 4);
        for _ in 0..10_000 {
            let (a, b, k) = (
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32() * 2.0 - 1.0,
                rng.next_f32(),
            );
            let s = smooth_min(a, b, k);
            assert!(
                s <= a.min(b) && s >= a.min(b) - 0.25 * k,
                "smin({a}, {b}, {k}) = {s}"
            );
        }
        assert_eq!(smooth_min(0.3, -0.2, 0.0), -0.2);
    }
}
