//! Extra image layers (arbitrary output variables) a film may write beside
//! the beauty pass.

use serde::{Deserialize, Serialize};

/// One layer of first-hit values, written to EXR outputs beside the RGB
/// beauty pass (channel names in `docs/aov.md`).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq, Hash)]
pub enum AovDesc {
    /// Reflectance at the first hit, as Open Image Denoise wants its albedo
    /// input (`albedo.R/G/B`).
    Albedo,
    /// World-space unit shading normal at the first hit, facing the camera
    /// (`N.X/Y/Z`).
    Normal,
    /// Distance along the camera ray to the first hit; +∞ where nothing is
    /// hit (`Z`).
    Depth,
    /// World-space position of the first hit (`P.X/Y/Z`).
    Position,
    /// Index of the first hit's material, the one most of the pixel's
    /// samples hit (`materialId`).
    MaterialIndex,
    /// Which scene object the first hit belongs to, the one most of the
    /// pixel's samples hit (`objectId`): 1 + its index in `objects`, then
    /// the area lights after them.
    ObjectIndex,
}
