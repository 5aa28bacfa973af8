//! Geometry placed in the scene.

use super::{TransformDesc, V3};
use serde::{Deserialize, Serialize};

/// Every object names its material and may carry a `transform`: a list of
/// steps applied to the object in the order written.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum ObjectDesc {
    /// An implicit surface: a tree of SDF shapes and operators (`desc/sdf.rs`).
    Sdf {
        shape: super::SdfDesc,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
        #[serde(default, skip_serializing_if = "super::MarchDesc::is_default")]
        march: super::MarchDesc,
    },
    Sphere {
        center: V3,
        radius: f32,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Infinite plane through `point`, facing `normal`.
    Plane {
        point: V3,
        normal: V3,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Parallelogram `corner + s·edge_u + t·edge_v`, s,t ∈ [0,1].
    Quad {
        corner: V3,
        edge_u: V3,
        edge_v: V3,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Rectangle `center + s·half_u + t·half_v`, s,t ∈ [−1,1].
    Rect {
        center: V3,
        half_u: V3,
        half_v: V3,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// A Wavefront OBJ triangle mesh; `file` is relative to the scene file.
    Mesh {
        file: String,
        material: String,
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
}

impl ObjectDesc {
    pub fn material(&self) -> &str {
        match self {
            ObjectDesc::Sdf { material, .. } => material,
            ObjectDesc::Sphere { material, .. }
            | ObjectDesc::Plane { material, .. }
            | ObjectDesc::Quad { material, .. }
            | ObjectDesc::Rect { material, .. }
            | ObjectDesc::Mesh { material, .. } => material,
        }
    }

    pub fn transform(&self) -> &[TransformDesc] {
        match self {
            ObjectDesc::Sdf { transform, .. } => transform,
            ObjectDesc::Sphere { transform, .. }
            | ObjectDesc::Plane { transform, .. }
            | ObjectDesc::Quad { transform, .. }
            | ObjectDesc::Rect { transform, .. }
            | ObjectDesc::Mesh { transform, .. } => transform,
        }
    }
}
