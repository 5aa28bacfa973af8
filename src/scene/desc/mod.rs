//! What a scene file may say: plain serde data, nothing resolved.
//!
//! Every struct denies unknown fields so a misspelling is an error, not a
//! silently ignored line. Defaults live here (`#[serde(default)]`); name
//! references (materials) are resolved later, in `build`.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     film: (width: 64, height: 48, spp: 4),
//!     materials: { "white": Lambert(albedo: (0.8, 0.8, 0.8)) },
//!     lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))],
//!     objects: [Sphere(center: (0, 0, 0), radius: 1, material: "white")],
//! )"#;
//! let scene: ronray::scene::desc::SceneDesc = ron::from_str(text).unwrap();
//! assert_eq!(scene.objects.len(), 1);
//! ```

mod camera;
mod color;
mod light;
mod material;
mod object;
mod sdf;
mod transform;

pub use camera::{CameraDesc, FilmDesc, IntegratorDesc, LightSelectionDesc, SamplerDesc};
pub use color::ColorDesc;
pub use light::LightDesc;
pub use material::{DielectricFresnelDesc, DistributionDesc, FresnelDesc, MaterialDesc, MetalDesc};
pub use object::ObjectDesc;
pub use sdf::{MarchDesc, RotationDesc, SdfDesc};
pub use transform::TransformDesc;

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// A point or vector, written `(x, y, z)`.
pub type V3 = [f32; 3];
/// A linear RGB colour, written `(r, g, b)`.
pub type Color = [f32; 3];

/// A whole scene file.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename = "Scene", deny_unknown_fields)]
pub struct SceneDesc {
    pub camera: CameraDesc,
    #[serde(default)]
    pub film: FilmDesc,
    #[serde(default)]
    pub integrator: IntegratorDesc,
    /// Named materials; objects refer to them by name.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialDesc>,
    #[serde(default)]
    pub lights: Vec<LightDesc>,
    #[serde(default)]
    pub objects: Vec<ObjectDesc>,
}
