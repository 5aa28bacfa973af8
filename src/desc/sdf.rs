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
    Sphere {
        radius: f32,
    },
    /// Axis-aligned box from `-half_extents` to `half_extents`.
    Box {
        half_extents: V3,
    },
    /// A `Box` of the same outer size with edges rounded by `radius`.
    RoundBox {
        half_extents: V3,
        radius: f32,
    },
    /// Ring around the y axis: `major` to the tube's centre line, `minor`
    /// the tube's radius.
    Torus {
        major: f32,
        minor: f32,
    },
    /// Segment from `a` to `b` swept by a ball of `radius`.
    Capsule {
        a: V3,
        b: V3,
        radius: f32,
    },
    /// Capped cylinder along y, from `-half_height` to `half_height`.
    Cylinder {
        radius: f32,
        half_height: f32,
    },
    /// The half-space `dot(p, normal) ≤ offset`. Unbounded, so it must be
    /// intersected with (or subtracted from) a bounded shape.
    Plane {
        normal: V3,
        #[serde(default)]
        offset: f32,
    },
    /// White–Nylander Mandelbulb in a ball of radius about 1.1 (power 8).
    Mandelbulb {
        #[serde(default = "default_power")]
        power: f32,
        #[serde(default = "default_bulb_iterations")]
        iterations: u32,
        #[serde(default = "default_bailout")]
        bailout: f32,
    },
    /// Menger sponge filling the cube `[-1, 1]³`.
    Menger {
        #[serde(default = "default_menger_iterations")]
        iterations: u32,
    },
    Union {
        of: Vec<SdfDesc>,
    },
    Intersection {
        of: Vec<SdfDesc>,
    },
    /// The first shape minus every other one.
    Difference {
        of: Vec<SdfDesc>,
    },
    /// Union blended over `k` scene units (`k = 0` is a sharp union).
    SmoothUnion {
        k: f32,
        of: Vec<SdfDesc>,
    },
    SmoothIntersection {
        k: f32,
        of: Vec<SdfDesc>,
    },
    SmoothDifference {
        k: f32,
        of: Vec<SdfDesc>,
    },
    /// `of`, scaled uniformly, then rotated, then moved.
    Transform {
        #[serde(default)]
        translate: V3,
        #[serde(default)]
        rotate: RotationDesc,
        #[serde(default = "one")]
        scale: f32,
        of: Box<SdfDesc>,
    },
}

/// Right-handed rotation about `axis` (need not be unit length).
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RotationDesc {
    pub axis: V3,
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
