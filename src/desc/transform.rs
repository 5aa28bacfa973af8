//! Placement steps, applied in the order written.

use super::V3;
use serde::{Deserialize, Serialize};

/// One placement step of an object's `transform` list. Steps apply in the order
/// written: `[Scale((2, 2, 2)), Translate((1, 0, 0))]` scales about the origin, then
/// moves.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum TransformDesc {
    /// Move by `(x, y, z)` scene units.
    Translate(V3),
    /// Right-handed rotation about `axis` (need not be unit length).
    Rotate {
        /// Axis of rotation through the origin; must not be zero.
        axis: V3,
        /// Angle in degrees, counter-clockwise looking down the axis toward the
        /// origin.
        degrees: f32,
    },
    /// Per-axis scale factors; use equal factors to keep spheres round.
    Scale(V3),
    /// A full 4×4 matrix, written as four rows; the last row is normally
    /// `(0, 0, 0, 1)`.
    Matrix([[f32; 4]; 4]),
}
