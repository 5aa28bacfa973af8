//! The implicit-surface vocabulary of a scene file: a tree of shapes and
//! operators written by hand, mapped onto the engine's
//! [`SdfNode`](crate::geometry::sdf::SdfNode) arena by `build_sdf`.
//!
//! Why it differs from the arena: a person writes `SmoothUnion(k: 0.2, of:
//! [a, b, c])`, not three binary nodes with indices. Operators take a list
//! `of: [...]` (folded left into binary nodes: `((a ∪ b) ∪ c)`), a
//! `Difference` is the first shape minus all the others, and a `Transform`
//! wraps one shape with readable translate / rotate / scale.
//!
//! ```
//! let text = r#"
//! Sdf(
//!     shape: SmoothUnion(k: 0.2, of: [
//!         Sphere(radius: 1),
//!         Transform(
//!             translate: (1, 0, 0),
//!             rotate: (axis: (0, 1, 0), degrees: 30),
//!             scale: 0.5,
//!             of: Torus(major: 1, minor: 0.25),
//!         ),
//!     ]),
//!     material: "gold",
//!     march: (max_steps: 256),
//! )"#;
//! let o: ronray::desc::ObjectDesc = ron::from_str(text).unwrap();
//! assert_eq!(o.material(), Some("gold"));
//! ```

use super::V3;
use serde::{Deserialize, Serialize};

/// One node of an SDF tree. Every shape is centred on its own origin; lengths
/// are in scene units.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum SdfDesc {
    /// Ball of `radius` around the origin.
    Sphere {
        /// Radius in scene units, > 0.
        radius: f32,
    },
    /// Axis-aligned box from `-half_extents` to `half_extents`.
    Box {
        /// Half the box's size along x, y and z, each > 0.
        half_extents: V3,
    },
    /// A `Box` of the same outer size with edges rounded by `radius`.
    RoundBox {
        /// Half the box's outer size along x, y and z, each > 0.
        half_extents: V3,
        /// Rounding radius of the edges, from 0 (sharp) to the smallest half extent.
        radius: f32,
    },
    /// Ring around the y axis: `major` to the tube's centre line, `minor`
    /// the tube's radius.
    Torus {
        /// Distance from the centre to the tube's centre line, > 0.
        major: f32,
        /// Radius of the tube, > 0 and at most `major`.
        minor: f32,
    },
    /// Segment from `a` to `b` swept by a ball of `radius`.
    Capsule {
        /// One end of the segment.
        a: V3,
        /// The other end of the segment.
        b: V3,
        /// Radius of the swept ball, > 0.
        radius: f32,
    },
    /// Capped cylinder along y, from `-half_height` to `half_height`.
    Cylinder {
        /// Radius in scene units, > 0.
        radius: f32,
        /// Half the length along y, > 0.
        half_height: f32,
    },
    /// The half-space `dot(p, normal) ≤ offset`. Unbounded, so it must be
    /// intersected with (or subtracted from) a bounded shape.
    Plane {
        /// Direction the plane faces, out of the solid; need not be unit length.
        normal: V3,
        /// Signed distance of the plane from the origin along `normal` (default 0).
        #[serde(default)]
        offset: f32,
    },
    /// White–Nylander Mandelbulb in a ball of radius about 1.1 (power 8).
    Mandelbulb {
        /// Exponent n of `z ← zⁿ + p`, in [2, 16] (default 8); higher gives more
        /// lobes.
        #[serde(default = "default_power")]
        power: f32,
        /// Orbit iterations, 1 to 64 (default 8): more gives finer detail at higher
        /// cost.
        #[serde(default = "default_bulb_iterations")]
        iterations: u32,
        /// Escape radius of the orbit, in [2, 8] (default 2).
        #[serde(default = "default_bailout")]
        bailout: f32,
    },
    /// Menger sponge filling the cube `[-1, 1]³`.
    Menger {
        /// Levels of holes cut out, 0 (a solid cube) to 6 (default 3).
        #[serde(default = "default_menger_iterations")]
        iterations: u32,
    },
    /// Everything inside any of the shapes.
    Union {
        /// The shapes to combine, at least one.
        of: Vec<SdfDesc>,
    },
    /// Only what is inside every one of the shapes.
    Intersection {
        /// The shapes to combine, at least one.
        of: Vec<SdfDesc>,
    },
    /// The first shape minus every other one.
    Difference {
        /// The shape to cut from first, then the shapes cut out of it.
        of: Vec<SdfDesc>,
    },
    /// Union blended over `k` scene units (`k = 0` is a sharp union).
    SmoothUnion {
        /// Blend radius in scene units, ≥ 0.
        k: f32,
        /// The shapes to combine, at least one.
        of: Vec<SdfDesc>,
    },
    /// Intersection with its edges blended over `k` scene units (`k = 0` is a sharp
    /// intersection).
    SmoothIntersection {
        /// Blend radius in scene units, ≥ 0.
        k: f32,
        /// The shapes to combine, at least one.
        of: Vec<SdfDesc>,
    },
    /// Difference with its edges blended over `k` scene units (`k = 0` is a sharp
    /// difference).
    SmoothDifference {
        /// Blend radius in scene units, ≥ 0.
        k: f32,
        /// The shape to cut from first, then the shapes cut out of it.
        of: Vec<SdfDesc>,
    },
    /// `of`, scaled uniformly, then rotated, then moved.
    Transform {
        /// Translation in scene units (default none), applied last.
        #[serde(default)]
        translate: V3,
        /// Rotation (default none).
        #[serde(default)]
        rotate: RotationDesc,
        /// Uniform scale factor, > 0 (default 1), applied first.
        #[serde(default = "one")]
        scale: f32,
        /// The shape to place.
        of: Box<SdfDesc>,
    },
}

/// Right-handed rotation about `axis` (need not be unit length).
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RotationDesc {
    /// Axis of rotation; need not be unit length, must not be zero.
    pub axis: V3,
    /// Angle in degrees, counter-clockwise looking down the axis toward the origin.
    pub degrees: f32,
}

impl Default for RotationDesc {
    fn default() -> Self {
        Self {
            axis: [0.0, 1.0, 0.0],
            degrees: 0.0,
        }
    }
}

/// Sphere-tracing settings of one object; every field is optional.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct MarchDesc {
    /// Steps before a ray gives up (a miss).
    pub max_steps: u32,
    /// Hit threshold per unit of distance travelled (radians): larger is
    /// faster and blurs finer fractal detail. By default 1e-4 for exact
    /// shapes, whose silhouettes it would fatten, and half a pixel's angle
    /// for trees with a Mandelbulb, whose finer detail would only alias
    /// into speckles (see `build_sdf`).
    pub eps_per_distance: Option<f32>,
    /// Over-relaxation of steps on exact distances, in `[1, 2)`.
    pub over_relax: f32,
    /// Fraction of a distance *estimate* (Mandelbulb) stepped, in `(0, 1]`.
    pub estimate_step: f32,
}

impl Default for MarchDesc {
    fn default() -> Self {
        let p = crate::geometry::sdf::MarchParams::default();
        Self {
            max_steps: p.max_steps,
            eps_per_distance: None,
            over_relax: p.over_relax,
            estimate_step: p.estimate_step,
        }
    }
}

impl MarchDesc {
    /// True when nothing differs from the defaults (kept out of serialised
    /// scenes).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

fn default_power() -> f32 {
    8.0
}
fn default_bulb_iterations() -> u32 {
    8
}
fn default_bailout() -> f32 {
    2.0
}
fn default_menger_iterations() -> u32 {
    3
}
fn one() -> f32 {
    1.0
}
