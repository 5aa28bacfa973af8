//! Placement steps, applied in the order written.

use super::V3;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum TransformDesc {
    Translate(V3),
    /// Right-handed rotation about `axis` (need not be unit length).
    Rotate {
        axis: V3,
        degrees: f32,
    },
    /// Per-axis scale factors; use equal factors to keep spheres round.
    Scale(V3),
    /// A full 4×4 matrix, written as four rows; the last row is normally
    /// `(0, 0, 0, 1)`.
    Matrix([[f32; 4]; 4]),
}
