//! Geometry placed in the scene, and the shared meshes `Instance`s place.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     materials: { "clay": Lambert(albedo: (0.8, 0.6, 0.5)), "red": Lambert(albedo: (0.6, 0.1, 0.1)) },
//!     meshes: { "bunny": (file: "bunny.obj", smooth: true) },
//!     objects: [
//!         // OBJ materials (MTL), with one group/material replaced.
//!         Mesh(file: "cornell.obj", materials: { "shortBox": "red" }),
//!         // One material for the whole mesh.
//!         Mesh(file: "bunny.obj", material: "clay", smooth: true),
//!         // Shared geometry, placed twice.
//!         Instance(mesh: "bunny", material: "clay", transform: [Translate((1, 0, 0))]),
//!         Instance(mesh: "bunny", transform: [Translate((-1, 0, 0))]),
//!     ],
//! )"#;
//! // As the loader reads it: optional fields are written bare (`40`, not `Some(40)`).
//! let scene: ronray::desc::SceneDesc = ron::Options::default()
//!     .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
//!     .from_str(text)
//!     .unwrap();
//! assert_eq!(scene.objects.len(), 4);
//! ```

use super::{TransformDesc, V3};
use serde::{Deserialize, Deserializer, Serialize};
use std::collections::BTreeMap;

/// A mesh loaded once and placed by any number of `Instance` objects.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MeshDesc {
    /// Wavefront OBJ (or Stanford PLY, by a `.ply` name), relative to the scene file.
    pub file: String,
    /// Replace the file's normals by area-weighted vertex normals.
    #[serde(default, skip_serializing_if = "is_false")]
    pub smooth: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// Accepts `"name"` as well as RON's `Some("name")` / `None`, so an optional
/// material reads like a required one.
fn plain_or_some<'de, D: Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    struct V;
    impl<'de> serde::de::Visitor<'de> for V {
        type Value = Option<String>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a material name (a string)")
        }
        fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Self::Value, E> {
            Ok(Some(v.to_owned()))
        }
        fn visit_none<E: serde::de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }
        fn visit_unit<E: serde::de::Error>(self) -> Result<Self::Value, E> {
            Ok(None)
        }
        fn visit_some<D2: Deserializer<'de>>(self, d: D2) -> Result<Self::Value, D2::Error> {
            String::deserialize(d).map(Some)
        }
    }
    d.deserialize_any(V)
}

/// Every object names its material and may carry a `transform`: a list of
/// steps applied to the object in the order written.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum ObjectDesc {
    /// An implicit surface: a tree of SDF shapes and operators (`desc/sdf.rs`).
    Sdf {
        /// The implicit surface: one shape, or an operator combining several.
        shape: super::SdfDesc,
        /// Name of the material in `materials`.
        material: String,
        /// Light the surface emits (default none); see `EmissionDesc`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Placement steps applied in the order written (default none). Only
        /// rotations, uniform scales and translations: a distance field cannot be
        /// stretched.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
        /// Sphere-tracing settings; the defaults suit most shapes.
        #[serde(default, skip_serializing_if = "super::MarchDesc::is_default")]
        march: super::MarchDesc,
    },
    /// A sphere of `radius` around `center`, both in scene units before `transform`.
    Sphere {
        /// Centre of the sphere.
        center: V3,
        /// Radius in scene units, > 0.
        #[schemars(range(min = 0))]
        radius: f32,
        /// Name of the material in `materials`; a sphere with an `interior`
        /// medium may leave it out to be an index-matched boundary, invisible
        /// but for its medium.
        #[serde(default, skip_serializing_if = "String::is_empty")]
        material: String,
        /// Name of the medium inside (in `media`, default none).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        interior: Option<String>,
        /// Name of the medium outside (default the scene's `medium`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        exterior: Option<String>,
        /// Light the surface emits (default none); see `EmissionDesc`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// How textures wrap the sphere (default `YUp`).
        #[serde(default, skip_serializing_if = "SphereUvDesc::is_default")]
        uv: SphereUvDesc,
        /// Placement steps applied in the order written (default none); they must
        /// keep the sphere round (equal scale factors; use a `Mesh` for an
        /// ellipsoid).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Infinite plane through `point`, facing `normal`.
    Plane {
        /// A point on the plane.
        point: V3,
        /// Direction the plane faces (its surface normal); need not be unit length.
        normal: V3,
        /// Name of the material in `materials`.
        material: String,
        /// Light the surface emits (default none); see `EmissionDesc`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Placement steps applied in the order written (default none).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Parallelogram `corner + s·edge_u + t·edge_v`, s,t ∈ `[0, 1]`.
    Quad {
        /// One corner of the parallelogram.
        corner: V3,
        /// First edge from `corner`.
        edge_u: V3,
        /// Second edge from `corner`, not parallel to `edge_u`.
        edge_v: V3,
        /// Name of the material in `materials`.
        material: String,
        /// Light the surface emits (default none); see `EmissionDesc`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Placement steps applied in the order written (default none).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// Rectangle `center + s·half_u + t·half_v`, s,t ∈ [−1,1].
    Rect {
        /// Centre of the rectangle.
        center: V3,
        /// Half of the first edge: the shape spans `center ± half_u`.
        half_u: V3,
        /// Half of the second edge: the shape spans `center ± half_v`.
        half_v: V3,
        /// Name of the material in `materials`.
        material: String,
        /// Light the surface emits (default none); see `EmissionDesc`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Placement steps applied in the order written (default none).
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// A Wavefront OBJ triangle mesh (or a Stanford PLY, by a `.ply` name);
    /// `file` is relative to the scene file.
    /// Without `material`, each OBJ group keeps its MTL material (grey if it
    /// has none); `materials` replaces some by OBJ group/object or MTL name.
    Mesh {
        /// Path of the Wavefront OBJ (or `.ply`) file, relative to the scene file.
        file: String,
        /// One scene material for every group without an entry in `materials`,
        /// replacing the MTL materials.
        #[serde(
            default,
            deserialize_with = "plain_or_some",
            skip_serializing_if = "Option::is_none"
        )]
        material: Option<String>,
        /// Scene materials by OBJ group/object name or MTL material name; these win
        /// over `material` and over the MTL file.
        #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
        materials: BTreeMap<String, String>,
        /// Light every triangle emits from its counter-clockwise front (default
        /// none); without it, groups whose MTL material has `Ke` emit that.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Replace the file's normals by area-weighted vertex normals (default
        /// false): smooth shading for faceted files.
        #[serde(default, skip_serializing_if = "is_false")]
        smooth: bool,
        /// Name of the medium inside (in `media`, default none); the mesh
        /// must be closed, its triangles counter-clockwise seen from outside.
        /// Without `material` (and `materials`) the mesh is an index-matched
        /// boundary, invisible but for its medium.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        interior: Option<String>,
        /// Name of the medium outside (default the scene's `medium`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        exterior: Option<String>,
        /// Placement steps applied in the order written (default none); the mesh is
        /// baked into world space once.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
    },
    /// A mesh from the scene's `meshes`, placed by `transform`; materials as
    /// for `Mesh`. Instances share the mesh's memory and BVH.
    Instance {
        /// Name of the entry in the scene's `meshes` to place.
        mesh: String,
        /// One scene material for every group without an entry in `materials`,
        /// replacing the MTL materials.
        #[serde(
            default,
            deserialize_with = "plain_or_some",
            skip_serializing_if = "Option::is_none"
        )]
        material: Option<String>,
        /// Scene materials by OBJ group/object name or MTL material name; these win
        /// over `material` and over the MTL file.
        #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
        materials: BTreeMap<String, String>,
        /// Light every triangle emits from its counter-clockwise front (default
        /// none); without it, groups whose MTL material has `Ke` emit that.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        emission: Option<super::EmissionDesc>,
        /// Placement steps applied in the order written (default none); this
        /// instance's object-to-world transform.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
        /// Placements at given frames, instead of `transform`: the instance
        /// moves, and is blurred while the camera's shutter is open.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        keys: Vec<super::TransformKeyDesc>,
        /// How the instance moves between `keys` (default `Linear`).
        #[serde(default, skip_serializing_if = "super::InterpolationDesc::is_default")]
        interpolation: super::InterpolationDesc,
    },
    /// A glTF 2.0 asset (`.gltf` with external or data-URI buffers, or
    /// `.glb`): the meshes of one of its scenes, placed by its node tree
    /// (a mesh used by several nodes is built once), with its
    /// metallic-roughness materials mapped onto `MetalPlastic` (see
    /// `docs/gltf.md`). `file` is relative to the scene file.
    Gltf {
        /// Path of the `.gltf` or `.glb` file, relative to the scene file.
        file: String,
        /// Index of the glTF scene to place (default the file's `scene`, else 0).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        scene: Option<u32>,
        /// One scene material for every primitive without an entry in
        /// `materials`, replacing the asset's.
        #[serde(
            default,
            deserialize_with = "plain_or_some",
            skip_serializing_if = "Option::is_none"
        )]
        material: Option<String>,
        /// Scene materials by glTF material name; these win over `material`
        /// and over the asset's own.
        #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
        materials: BTreeMap<String, String>,
        /// Placement steps applied after the asset's own node transforms, in
        /// the order written (default none). glTF is +y up, metres,
        /// right-handed, as ronray.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        transform: Vec<TransformDesc>,
        /// The asset's animation to pose it with, by name (`"Walk"`) or
        /// index (`"#0"`); default none: the rest pose. The scene's first
        /// frame shows the animation's start, and each frame after it
        /// `1/fps` seconds more (docs/gltf.md).
        #[serde(
            default,
            deserialize_with = "plain_or_some",
            skip_serializing_if = "Option::is_none"
        )]
        animation: Option<String>,
        /// Play `animation` over and over: its time wraps at its length
        /// (default false: it holds its last pose).
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        repeat: bool,
    },
}

impl ObjectDesc {
    /// The scene material named for the whole object, if any (meshes may
    /// leave it to their MTL file).
    pub fn material(&self) -> Option<&str> {
        match self {
            ObjectDesc::Sdf { material, .. } => Some(material),
            ObjectDesc::Sphere { material, .. } => Some(material.as_str()).filter(|m| !m.is_empty()),
            ObjectDesc::Plane { material, .. }
            | ObjectDesc::Quad { material, .. }
            | ObjectDesc::Rect { material, .. } => Some(material),
            ObjectDesc::Mesh { material, .. }
            | ObjectDesc::Instance { material, .. }
            | ObjectDesc::Gltf { material, .. } => material.as_deref(),
        }
    }

    /// The light the object emits, if it says so (a plane may say so, which
    /// validation refuses).
    pub fn emission(&self) -> Option<&super::EmissionDesc> {
        match self {
            ObjectDesc::Sdf { emission, .. }
            | ObjectDesc::Sphere { emission, .. }
            | ObjectDesc::Plane { emission, .. }
            | ObjectDesc::Quad { emission, .. }
            | ObjectDesc::Rect { emission, .. }
            | ObjectDesc::Mesh { emission, .. }
            | ObjectDesc::Instance { emission, .. } => emission.as_ref(),
            ObjectDesc::Gltf { .. } => None,
        }
    }

    /// The media inside and outside the object (names), if it declares them.
    pub fn media(&self) -> (Option<&str>, Option<&str>) {
        match self {
            ObjectDesc::Sphere {
                interior, exterior, ..
            }
            | ObjectDesc::Mesh {
                interior, exterior, ..
            } => (interior.as_deref(), exterior.as_deref()),
            ObjectDesc::Sdf { .. }
            | ObjectDesc::Plane { .. }
            | ObjectDesc::Quad { .. }
            | ObjectDesc::Rect { .. }
            | ObjectDesc::Instance { .. }
            | ObjectDesc::Gltf { .. } => (None, None),
        }
    }

    /// Per-group material overrides (meshes only).
    pub fn material_overrides(&self) -> Option<&BTreeMap<String, String>> {
        match self {
            ObjectDesc::Mesh { materials, .. }
            | ObjectDesc::Instance { materials, .. }
            | ObjectDesc::Gltf { materials, .. } => Some(materials),
            _ => None,
        }
    }

    /// The placement steps of any object, in the order written (empty when the scene
    /// gives none).
    pub fn transform(&self) -> &[TransformDesc] {
        match self {
            ObjectDesc::Sdf { transform, .. } => transform,
            ObjectDesc::Sphere { transform, .. }
            | ObjectDesc::Plane { transform, .. }
            | ObjectDesc::Quad { transform, .. }
            | ObjectDesc::Rect { transform, .. }
            | ObjectDesc::Mesh { transform, .. }
            | ObjectDesc::Instance { transform, .. }
            | ObjectDesc::Gltf { transform, .. } => transform,
        }
    }
}

/// Texture coordinates of a `Sphere`.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum SphereUvDesc {
    /// Poles on the y axis, v = 1 at the top (+y), u = ½ + atan2(z, x)/2π:
    /// an equirectangular image with its top row at the north pole.
    #[default]
    YUp,
    /// Mitsuba's `sphere`: poles on the z axis, v = 0 at +z, u = atan2(y, x)/2π
    /// in [0, 1); for twins of Mitsuba scenes (with `origin: TopLeft` images).
    MitsubaZUp,
}

impl SphereUvDesc {
    fn is_default(&self) -> bool {
        *self == SphereUvDesc::YUp
    }
}
