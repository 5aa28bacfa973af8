//! The runtime SDF tree: a flat arena of nodes that refer to their children by
//! `u32` index, so evaluation is a `match` with no boxes and no dynamic
//! dispatch.
//!
//! Invariant (checked by [`crate::geometry::sdf::validate()`] and asserted by
//! [`crate::geometry::sdf::Sdf::new`]): a child's index is smaller than its
//! parent's. Building the arena in post-order gives it for free, and it rules
//! out cycles, so recursion depth is bounded by the number of nodes.
//!
//! Lengths are in scene units, in the node's own (object) space. Every shape
//! is centred on the origin; place it with [`SdfNode::Transform`].

use glam::{Quat, Vec3A};

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SdfNode {
    // Primitives: exact Euclidean distances.
    Sphere {
        radius: f32,
    },
    /// Axis-aligned box from `-half_extents` to `half_extents`.
    Box {
        half_extents: Vec3A,
    },
    /// A box of the same outer size as `Box`, its edges rounded by `radius`
    /// (`0 ≤ radius ≤` the smallest half extent).
    RoundBox {
        half_extents: Vec3A,
        radius: f32,
    },
    /// Ring in the xz plane around the y axis: `major` is the distance from
    /// the centre to the tube's centre line, `minor` the tube's radius.
    Torus {
        major: f32,
        minor: f32,
    },
    /// Segment from `a` to `b` swept by a ball of `radius`.
    Capsule {
        a: Vec3A,
        b: Vec3A,
        radius: f32,
    },
    /// Capped cylinder along y, from `-half_height` to `half_height`.
    Cylinder {
        radius: f32,
        half_height: f32,
    },
    /// The half-space `dot(p, normal) ≤ offset`. Unbounded: intersect it with
    /// (or subtract it from) a bounded shape, otherwise [`Sdf::bounds`] is
    /// infinite and the BVH cannot cull it. `Sdf::new` normalises `normal`.
    ///
    /// [`Sdf::bounds`]: crate::geometry::sdf::Sdf::bounds
    Plane {
        normal: Vec3A,
        offset: f32,
    },

    // Fractals.
    /// White–Nylander Mandelbulb `z ← zⁿ + p` (polar axis y). Its distance
    /// is an *estimate*, so the tree is marched with a safety factor.
    Mandelbulb {
        power: f32,
        iterations: u32,
        bailout: f32,
    },
    /// Menger sponge filling the cube `[-1, 1]³`; a bound, not exact.
    Menger {
        iterations: u32,
    },

    // Operators: bounds (never more than the true distance), not exact.
    Union {
        children: [u32; 2],
    },
    Intersection {
        children: [u32; 2],
    },
    /// `children[0]` minus `children[1]`.
    Difference {
        children: [u32; 2],
    },
    /// Quilez's quadratic smooth minimum; `k` is the blend radius in scene
    /// units (`k = 0` is the sharp operator).
    SmoothUnion {
        children: [u32; 2],
        k: f32,
    },
    SmoothIntersection {
        children: [u32; 2],
        k: f32,
    },
    SmoothDifference {
        children: [u32; 2],
        k: f32,
    },
    /// `parent_from_child`: scale uniformly, then rotate, then translate.
    /// `Sdf::new` normalises `rotate`.
    Transform {
        child: u32,
        translate: Vec3A,
        rotate: Quat,
        scale: f32,
    },
}

impl SdfNode {
    /// Child indices (empty for primitives and fractals).
    pub fn children(&self) -> &[u32] {
        match self {
            Self::Union { children }
            | Self::Intersection { children }
            | Self::Difference { children }
            | Self::SmoothUnion { children, .. }
            | Self::SmoothIntersection { children, .. }
            | Self::SmoothDifference { children, .. } => children,
            Self::Transform { child, .. } => std::slice::from_ref(child),
            _ => &[],
        }
    }

    /// The variant's name in snake_case, as used in validation paths.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Sphere { .. } => "sphere",
            Self::Box { .. } => "box",
            Self::RoundBox { .. } => "round_box",
            Self::Torus { .. } => "torus",
            Self::Capsule { .. } => "capsule",
            Self::Cylinder { .. } => "cylinder",
            Self::Plane { .. } => "plane",
            Self::Mandelbulb { .. } => "mandelbulb",
            Self::Menger { .. } => "menger",
            Self::Union { .. } => "union",
            Self::Intersection { .. } => "intersection",
            Self::Difference { .. } => "difference",
            Self::SmoothUnion { .. } => "smooth_union",
            Self::SmoothIntersection { .. } => "smooth_intersection",
            Self::SmoothDifference { .. } => "smooth_difference",
            Self::Transform { .. } => "transform",
        }
    }
}
