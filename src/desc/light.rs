//! Lights.

use super::{Color, V3};
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum LightDesc {
    /// Isotropic point light; `intensity` in W/sr per channel (irradiance at
    /// distance d is I·cosθ/d²). Not visible to camera rays.
    Point { position: V3, intensity: Color },
    /// A point light limited to a circular cone around `direction`:
    /// `cone_degrees` is the cone's full angle, the outer `falloff_degrees`
    /// of it fade smoothly to zero. `intensity` (W/sr) is on the axis.
    Spot {
        position: V3,
        direction: V3,
        intensity: Color,
        cone_degrees: f32,
        #[serde(default)]
        falloff_degrees: f32,
    },
    /// Parallelogram `corner + s·edge_u + t·edge_v`, s,t ∈ `[0, 1]`, emitting
    /// `radiance` (W/(m²·sr)) from the side its normal `normalize(edge_u ×
    /// edge_v)` points to. Visible to camera rays.
    Quad {
        corner: V3,
        edge_u: V3,
        edge_v: V3,
        radiance: Color,
        /// The light surface's own material (a name); default: black, so the
        /// light reflects nothing.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// The same light given by its centre and half-edge vectors:
    /// `center + s·half_u + t·half_v`, s,t ∈ [−1,1]; normal `half_u × half_v`.
    Rect {
        center: V3,
        half_u: V3,
        half_v: V3,
        radiance: Color,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
}
