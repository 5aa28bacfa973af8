//! Emission on a shape: any sphere, quad, rectangle, mesh, instance or
//! bounded SDF object may glow.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     materials: { "black": Lambert(albedo: (0, 0, 0)) },
//!     objects: [
//!         Sphere(center: (0, 1, 0), radius: 0.25, material: "black",
//!                emission: (radiance: (12, 7, 3))),
//!     ],
//! )"#;
//! let scene: ronray::desc::SceneDesc = ron::Options::default()
//!     .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
//!     .from_str(text)
//!     .unwrap();
//! assert!(scene.objects[0].emission().is_some());
//! ```

use super::ColorDesc;
use serde::{Deserialize, Serialize};

fn is_false(b: &bool) -> bool {
    !*b
}

/// Light a shape emits from its surface: the same radiance in every direction
/// on its emitting side, constant or a texture over the shape's UVs. The object's material still
/// reflects light (give it a black one for a pure emitter).
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct EmissionDesc {
    /// Emitted radiance in W/(m²·sr) per channel, ≥ 0: a colour, or a texture
    /// looked up at the surface's UVs (quads, rectangles, spheres and meshes;
    /// not SDFs, which have none). docs/textures.md, "Emission textures".
    pub radiance: ColorDesc,
    /// Emit from both sides (default false: only from the outside of a sphere,
    /// the side of `edge_u × edge_v` of a quad, the counter-clockwise front of a
    /// mesh's triangles, the outside of an SDF).
    #[serde(default, skip_serializing_if = "is_false")]
    pub two_sided: bool,
}
