//! Participating media a scene file declares by name (`media`), for the
//! global fog (`medium`) and for the inside of closed shapes
//! (`interior`/`exterior` on `Sphere` and `Mesh` objects).
//!
//! Coefficients are per scene unit (1/length); `scale` multiplies them all.
//!
//! ```
//! let text = r#"
//! Scene(
//!     camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
//!     integrator: Path(max_depth: 8),
//!     materials: { "white": Lambert(albedo: (0.8, 0.8, 0.8)), "glass": Glass(ior: 1.5) },
//!     media: {
//!         "fog": Homogeneous(sigma_t: (0.5, 0.5, 0.5), albedo: (0.8, 0.8, 0.8)),
//!         "milk": Homogeneous(sigma_a: (0.001, 0.002, 0.005), sigma_s: (1, 1, 1), scale: 20, g: 0.3),
//!         "smoke": Grid(file: "smoke.vol", min: (-1, 0, -1), max: (1, 2, 1), scale: 4),
//!     },
//!     medium: "fog",
//!     lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))],
//!     objects: [
//!         Sphere(center: (-1, 0, 0), radius: 0.5, material: "glass", interior: "milk"),
//!         // No material: an index-matched boundary, invisible but for its medium.
//!         Sphere(center: (1, 0, 0), radius: 0.5, interior: "smoke"),
//!     ],
//! )"#;
//! let scene: ronray::desc::SceneDesc = ron::Options::default()
//!     .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
//!     .from_str(text)
//!     .unwrap();
//! assert_eq!(scene.media.len(), 3);
//! ```

use super::{Color, V3};
use serde::{Deserialize, Serialize};

/// A participating medium.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum MediumDesc {
    /// The same coefficients everywhere. Give `sigma_t` (extinction, with an
    /// optional `albedo`, default white) or `sigma_a` and `sigma_s`
    /// (absorption and scattering), per RGB channel, per scene unit.
    Homogeneous {
        /// Extinction σ_t per channel (1/length), ≥ 0.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        sigma_t: Option<Color>,
        /// Single-scattering albedo σ_s/σ_t per channel, in [0, 1] (default 1:
        /// no absorption); only with `sigma_t`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        albedo: Option<Color>,
        /// Absorption σ_a per channel (1/length), ≥ 0; with `sigma_s`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        sigma_a: Option<Color>,
        /// Scattering σ_s per channel (1/length), ≥ 0; with `sigma_a`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        sigma_s: Option<Color>,
        /// Multiplies the coefficients (default 1): units per scene unit.
        #[serde(default = "one", skip_serializing_if = "is_one")]
        scale: f32,
        /// Henyey–Greenstein mean cosine in (−1, 1) (default 0, isotropic);
        /// > 0 scatters forward.
        #[serde(default, skip_serializing_if = "is_zero")]
        g: f32,
    },
    /// Extinction from a density grid in Mitsuba's `.vol` format (float32,
    /// one channel), filling the box `min`–`max`: σ_t = `scale` × the
    /// trilinearly interpolated value, 0 outside the box.
    Grid {
        /// The `.vol` file, relative to the scene file.
        file: String,
        /// The lowest corner of the box the grid fills (world space).
        min: V3,
        /// The highest corner.
        max: V3,
        /// σ_t per unit of grid value (1/length), ≥ 0 (default 1).
        #[serde(default = "one", skip_serializing_if = "is_one")]
        scale: f32,
        /// Single-scattering albedo per channel, in [0, 1] (default 1).
        #[serde(default = "white", skip_serializing_if = "is_white")]
        albedo: Color,
        /// Henyey–Greenstein mean cosine in (−1, 1) (default 0).
        #[serde(default, skip_serializing_if = "is_zero")]
        g: f32,
    },
}

fn one() -> f32 {
    1.0
}
fn is_one(x: &f32) -> bool {
    *x == 1.0
}
fn is_zero(x: &f32) -> bool {
    *x == 0.0
}
fn white() -> Color {
    [1.0; 3]
}
fn is_white(c: &Color) -> bool {
    *c == [1.0; 3]
}
