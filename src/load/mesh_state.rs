//! What the mesh build step (`mesh.rs`) keeps from one object to the next,
//! held in the shared [`super::build_context::BuildContext`]: its own file so
//! that the context names it without importing the step.

use crate::geometry::obj::ObjGroup;
use std::collections::HashMap;

/// A mesh in `Geometry::meshes` with what material resolution needs.
#[derive(Clone)]
pub(super) struct LoadedMesh {
    pub mesh: u32,
    pub groups: Vec<ObjGroup>,
    /// Scene material of each MTL material of the file.
    pub mtl: Vec<u32>,
    /// Whether the mesh has vertex colours.
    pub painted: bool,
}

/// What the mesh build step keeps from one object to the next.
#[derive(Default)]
pub(super) struct MeshState {
    /// `meshes` entries already loaded, by name (`None`: it failed).
    pub shared: HashMap<String, Option<LoadedMesh>>,
    /// The grey default material, created on first use.
    pub grey: Option<u32>,
    /// The default material of a mesh with vertex colours (a Lambert of
    /// them), created on first use.
    pub painted: Option<u32>,
    /// Whether the note about the grey default was given (once per scene,
    /// and never for index-matched boundaries, which are never shaded).
    pub grey_noted: bool,
}
