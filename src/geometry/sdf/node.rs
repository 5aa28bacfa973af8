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

/// One node of an SDF arena: a primitive, a fractal, an operator over two children,
/// or a transform of one child. `Copy` and box-free so the tree is one flat `Vec`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SdfNode {
    // Primitives: exact Euclidean distances.
    /// Ball of `radius` around the origin.
    Sphere {
        /// Radius, > 0.
        radius: f32,
    },
    /// Axis-aligned box from `-half_extents` to `half_extents`.
    Box {
        /// Half the size along each axis, each > 0.
        half_extents: Vec3A,
    },
    /// A box of the same outer size as `Box`, its edges rounded by `radius`
    /// (`0 ≤ radius ≤` the smallest half extent).
    RoundBox {
        /// Half the outer size along each axis, each > 0.
        half_extents: Vec3A,
        /// Rounding radius of the edges.
        radius: f32,
    },
    /// Ring in the xz plane around the y axis: `major` is the distance from
    /// the centre to the tube's centre line, `minor` the tube's radius.
    Torus {
        /// Distance from the origin to the tube's centre line, > 0.
        major: f32,
        /// Radius of the tube, in (0, `major`].
        minor: f32,
    },
    /// Segment from `a` to `b` swept by a ball of `radius`.
    Capsule {
        /// One end of the segment.
        a: Vec3A,
        /// The other end of the segment.
        b: Vec3A,
        /// Radius of the swept ball, > 0.
        radius: f32,
    },
    /// Capped cylinder along y, from `-half_height` to `half_height`.
    Cylinder {
        /// Radius, > 0.
        radius: f32,
        /// Half the length along y, > 0.
        half_height: f32,
    },
    /// The half-space `dot(p, normal) ≤ offset`. Unbounded: intersect it with
    /// (or subtract it from) a bounded shape, otherwise [`Sdf::bounds`] is
    /// infinite and the BVH cannot cull it. `Sdf::new` normalises `normal`.
    ///
    /// [`Sdf::bounds`]: crate::geometry::sdf::Sdf::bounds
    Plane {
        /// Direction the plane faces, out of the solid.
        normal: Vec3A,
        /// Signed distance of the plane from the origin along `normal`.
        offset: f32,
    },

    // Fractals.
    /// White–Nylander Mandelbulb `z ← zⁿ + p` (polar axis y). Its distance
    /// is an *estimate*, so the tree is marched with a safety factor.
    Mandelbulb {
        /// Exponent n of `z ← zⁿ + p`, in [2, 16].
        power: f32,
        /// Orbit iterations, 1 to 64: more iterations, finer detail.
        iterations: u32,
        /// Escape radius of the orbit, in [2, 8].
        bailout: f32,
    },
    /// Menger sponge filling the cube `[-1, 1]³`; a bound, not exact.
    Menger {
        /// Levels of holes cut out, 0 (the cube) to 6.
        iterations: u32,
    },

    // Operators: bounds (never more than the true distance), not exact.
    /// Everything inside either child: `min(d₀, d₁)`.
    Union {
        /// Indices of the two children, both smaller than this node's.
        children: [u32; 2],
    },
    /// What is inside both children: `max(d₀, d₁)`.
    Intersection {
        /// Indices of the two children, both smaller than this node's.
        children: [u32; 2],
    },
    /// `children[0]` minus `children[1]`.
    Difference {
        /// Indices of the shape and of what is cut out of it.
        children: [u32; 2],
    },
    /// Quilez's quadratic smooth minimum; `k` is the blend radius in scene
    /// units (`k = 0` is the sharp operator).
    SmoothUnion {
        /// Indices of the two children, both smaller than this node's.
        children: [u32; 2],
        /// Blend radius in scene units, ≥ 0.
        k: f32,
    },
    /// Intersection blended with the smooth maximum over `k` (`k = 0` is sharp).
    SmoothIntersection {
        /// Indices of the two children, both smaller than this node's.
        children: [u32; 2],
        /// Blend radius in scene units, ≥ 0.
        k: f32,
    },
    /// `children[0]` minus `children[1]`, blended over `k` (`k = 0` is sharp).
    SmoothDifference {
        /// Indices of the shape and of what is cut out of it.
        children: [u32; 2],
        /// Blend radius in scene units, ≥ 0.
        k: f32,
    },
    /// `parent_from_child`: scale uniformly, then rotate, then translate.
    /// `Sdf::new` normalises `rotate`.
    Transform {
        /// Index of the transformed node, smaller than this node's.
        child: u32,
        /// Translation, applied last.
        translate: Vec3A,
        /// Rotation, applied after the scale.
        rotate: Quat,
        /// Uniform scale factor, > 0, applied first; distances are scaled by it too.
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
