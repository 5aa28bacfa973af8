//! Lights.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     lights: [
//!         // An HDR sky turned 90° about +y, at half strength.
//!         Environment(map: "sky.exr", strength: 0.5, rotation_degrees: 90),
//!     ],
//! )"#;
//! let scene: ronray::desc::SceneDesc = ron::Options::default()
//!     .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
//!     .from_str(text)
//!     .unwrap();
//! assert_eq!(scene.lights.len(), 1);
//! ```

use super::{Color, ColorDesc, V3};
use serde::{Deserialize, Serialize};

fn one() -> f32 {
    1.0
}
fn is_one(x: &f32) -> bool {
    *x == 1.0
}
fn is_zero(x: &f32) -> bool {
    *x == 0.0
}
fn yes() -> bool {
    true
}
fn is_true(b: &bool) -> bool {
    *b
}

/// A light source, in world space (lights take no `transform`). Colours are linear
/// RGB per channel, in the physical units each variant names.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum LightDesc {
    /// Isotropic point light; `intensity` in W/sr per channel (irradiance at
    /// distance d is I·cosθ/d²). Not visible to camera rays.
    Point {
        /// Where the light is, in world space.
        position: V3,
        /// Radiant intensity in W/sr per channel, the same in every direction.
        intensity: Color,
    },
    /// A point light limited to a circular cone around `direction`:
    /// `cone_degrees` is the cone's full angle, the outer `falloff_degrees`
    /// of it fade smoothly to zero. `intensity` (W/sr) is on the axis.
    Spot {
        /// Where the light is, in world space.
        position: V3,
        /// The cone's axis, the way the light shines; need not be unit length.
        direction: V3,
        /// Radiant intensity along the axis, in W/sr per channel.
        intensity: Color,
        /// Full opening angle of the cone, in degrees, in (0, 180); no light leaves
        /// outside it.
        cone_degrees: f32,
        /// Soft edge, in degrees, in [0, `cone_degrees`] (default 0, a hard edge):
        /// full intensity within the full angle `cone_degrees − falloff_degrees`,
        /// fading smoothly to zero at `cone_degrees`.
        #[serde(default)]
        falloff_degrees: f32,
    },
    /// Parallel light from infinitely far away along `direction` (a sun):
    /// a surface facing it receives `irradiance` W/m² per channel, one at
    /// angle θ to it `irradiance · cos θ`. A delta light, like `Point`: it
    /// casts hard shadows and is not seen by camera rays or in mirrors (for
    /// a visible sun, put one in an `Environment` map).
    Directional {
        /// The way the light travels, from the sky toward the scene (a sun
        /// overhead is `(0, -1, 0)`); need not be unit length.
        direction: V3,
        /// Irradiance on a surface facing the light, in W/m² per channel.
        irradiance: Color,
        /// The sun's angular diameter in degrees, in [0, 180] (default 0: a
        /// hard sun, parallel light; the real sun is about 0.53, Blender's
        /// sun `Angle`): a disk of that size gives soft shadow edges.
        #[serde(default, skip_serializing_if = "is_zero")]
        angle_degrees: f32,
    },
    /// Parallelogram `corner + s·edge_u + t·edge_v`, s,t ∈ `[0, 1]`, emitting
    /// `radiance` (W/(m²·sr)) from the side its normal `normalize(edge_u ×
    /// edge_v)` points to. Visible to camera rays.
    Quad {
        /// One corner of the light, in world space.
        corner: V3,
        /// First edge from `corner`; with `edge_u` × `edge_v` it sets the side that
        /// emits.
        edge_u: V3,
        /// Second edge from `corner`; not parallel to `edge_u`.
        edge_v: V3,
        /// Emitted radiance in W/(m²·sr) per channel, the same in every
        /// direction on the emitting side: a colour, or a texture over uv =
        /// (s, t) (docs/textures.md, "Emission textures").
        radiance: ColorDesc,
        /// The light surface's own material (a name); default: black, so the
        /// light reflects nothing.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// The same light given by its centre and half-edge vectors:
    /// `center + s·half_u + t·half_v`, s,t ∈ [−1,1]; normal `half_u × half_v`.
    Rect {
        /// Centre of the light, in world space.
        center: V3,
        /// Half of the first edge: the light spans `center ± half_u`.
        half_u: V3,
        /// Half of the second edge: the light spans `center ± half_v`.
        half_v: V3,
        /// Emitted radiance in W/(m²·sr) per channel, as for `Quad` (a
        /// texture's uv (0, 0) is at `center − half_u − half_v`).
        radiance: ColorDesc,
        /// The light surface's own material (a name); default: black, so the light
        /// reflects nothing.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        material: Option<String>,
    },
    /// Light from infinitely far away in every direction, at most one per
    /// scene: a constant `radiance`, or an equirectangular `map` (linear
    /// `.exr` or Radiance `.hdr`), times `strength`. Camera rays that miss
    /// everything see it (unless `visible: false`). The map's centre column
    /// looks along +z, its left and right edges along −z, row 0 straight up.
    Environment {
        /// Constant radiance in W/(m²·sr) per channel from every direction; give
        /// this or `map`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        radiance: Option<Color>,
        /// Equirectangular image, linear RGB, `.exr` or `.hdr`, relative to the
        /// scene file; its values are radiance in W/(m²·sr). Give this or
        /// `radiance`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        map: Option<String>,
        /// Factor on the radiance or the map, ≥ 0 (default 1).
        #[serde(default = "one", skip_serializing_if = "is_one")]
        #[schemars(range(min = 0))]
        strength: f32,
        /// Turn about the vertical (+y) axis, right-handed, in degrees (default 0):
        /// at 90, what the map shows along +z appears along +x.
        #[serde(default, skip_serializing_if = "is_zero")]
        rotation_degrees: f32,
        /// Whether camera rays that miss everything see the environment (default
        /// true). With `false` it still lights the scene (and shows in
        /// reflections and refractions), but the backdrop is `background`.
        #[serde(default = "yes", skip_serializing_if = "is_true")]
        visible: bool,
        /// What camera rays that miss see when `visible` is false: a radiance in
        /// W/(m²·sr) per channel (default black).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        background: Option<Color>,
    },
}

impl LightDesc {
    /// The file this light reads (an environment's `map`), for include
    /// handling to keep it relative to the file that wrote it.
    pub fn file_mut(&mut self) -> Option<&mut String> {
        match self {
            LightDesc::Environment { map, .. } => map.as_mut(),
            LightDesc::Point { .. }
            | LightDesc::Spot { .. }
            | LightDesc::Directional { .. }
            | LightDesc::Quad { .. }
            | LightDesc::Rect { .. } => None,
        }
    }
}
