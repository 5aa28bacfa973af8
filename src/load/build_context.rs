//! The state every build step shares ([`BuildContext`]): its own file so
//! that the kinds' build steps (`material.rs`, `light.rs`, `object.rs`,
//! `mesh.rs`, `sdf/`) name it without importing the file that runs them.

use super::mesh_state::MeshState;
use super::mtl::MtlMaterials;
use crate::desc::ColorDesc;
use crate::desc::SceneDesc;
use crate::diagnostic::Problem;
use crate::geometry::obj::ObjData;
use crate::geometry::{Geometry, Shape};
use crate::lights::{Emission, Light};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// Everything the build steps share: the description, where its files are,
/// and the runtime parts built so far. One value instead of long argument
/// lists, so a new kind of thing adds a build function, not a parameter.
pub(super) struct BuildContext<'a> {
    pub desc: &'a SceneDesc,
    /// The scene file's folder; relative file names resolve against it.
    pub base: &'a Path,
    /// Reads an OBJ file (watch mode passes a cache of unchanged files).
    pub load_obj: &'a dyn Fn(&Path) -> Result<ObjData, String>,
    /// Scene material index by name.
    pub material_index: HashMap<String, u32>,
    /// Textured emissions by the scene path of their `radiance`
    /// ([`BuildContext::emission`]).
    pub emissions: HashMap<String, Emission>,
    /// The black material of area-light surfaces that name none.
    pub emitter: u32,
    /// Materials and textures created for MTL files, appended after the
    /// scene's own.
    pub mtl: MtlMaterials,
    pub lights: Vec<Light>,
    /// Index in `lights` of the environment, once built.
    pub environment: Option<u32>,
    /// Bounded shapes (they go in the BVH), in the order built.
    pub shapes: Vec<Shape>,
    /// Unbounded shapes (planes, unbounded SDFs): every ray tests them.
    pub unbounded: Vec<Shape>,
    /// The object id ([`Scene::objects`]) of each of `shapes`, then of each
    /// of `unbounded`, filled in once the entry that made them is built.
    pub object_ids: (Vec<u32>, Vec<u32>),
    pub geometry: Geometry,
    pub mesh_state: MeshState,
    /// Whether any scene material has a normal map: meshes with UVs then
    /// get MikkTSpace tangents when their file gives none.
    pub normal_maps: bool,
    /// Triangles over all placed meshes.
    pub triangles: usize,
    pub problems: Vec<Problem>,
    pub notes: Vec<String>,
    /// Environment map read and table build times, for the stats.
    pub env_times: (Duration, Duration),
    /// Image files lights read (an environment map), watched like textures.
    pub light_files: Vec<PathBuf>,
    /// MTL files the OBJ files named.
    pub mtl_files: Vec<PathBuf>,
    /// Each OBJ read and its parts, for the stats.
    pub obj_parts: Vec<(PathBuf, String)>,
}

impl BuildContext<'_> {
    /// The emission `c` written at scene path `path`: a constant, or the
    /// texture built there with the materials.
    pub fn emission(&self, path: &str, c: &ColorDesc) -> Emission {
        match c {
            ColorDesc::Rgb(c) => Emission::constant((*c).into()),
            ColorDesc::Texture(_) => self
                .emissions
                .get(path)
                .cloned()
                .unwrap_or(Emission::constant(crate::math::Rgb::ZERO)),
        }
    }
}
