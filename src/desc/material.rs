//! Materials, referred to by name from objects.
//!
//! Colour parameters accept constants or textures (see [`ColorDesc`]).

use super::color::ColorDesc;
use serde::{Deserialize, Serialize};

#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum MaterialDesc {
    /// Ideal diffuse: f = albedo/π. Channels in [0, 1].
    Lambert { albedo: ColorDesc },
    /// Rough diffuse (Fujii's energy-conserving Oren–Nayar). `sigma` is a
    /// unitless roughness ≥ 0 (0 = Lambert; useful up to about 1), not an angle.
    OrenNayar {
        albedo: ColorDesc,
        #[schemars(range(min = 0, max = 2))]
        sigma: f32,
    },
    /// Energy-normalised (modified) Phong: diffuse/π + specular·(n+2)/(2π)·cosⁿα.
    Phong {
        diffuse: ColorDesc,
        specular: ColorDesc,
        exponent: f32,
    },
    /// Energy-normalised Blinn–Phong: diffuse/π + specular·(n+2)/(8π)·cosⁿθh.
    BlinnPhong {
        diffuse: ColorDesc,
        specular: ColorDesc,
        exponent: f32,
    },
    /// Microfacet reflection (Smith height-correlated masking-shadowing).
    /// `roughness` ∈ [0, 1], α = roughness².
    CookTorrance {
        #[serde(default)]
        distribution: DistributionDesc,
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
        fresnel: FresnelDesc,
    },
    /// The report's metal/plastic: a diffuse base under a GGX coat, mixed by
    /// `metalness` ∈ [0, 1] as in glTF's metallic–roughness model.
    MetalPlastic {
        base_color: ColorDesc,
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
        metalness: f32,
    },
    /// Perfect specular reflection.
    Mirror {
        #[serde(default = "white")]
        tint: ColorDesc,
    },
    /// Smooth dielectric; `ior` = η inside / η outside (outside is where the
    /// surface normal points).
    Glass {
        #[serde(default = "glass_ior")]
        ior: f32,
        #[serde(default = "white")]
        tint: ColorDesc,
        #[serde(default)]
        fresnel: DielectricFresnelDesc,
    },
    /// Mitsuba 3's `roughplastic` (`nonlinear: false`): a `diffuse` base under
    /// a rough dielectric coat of index `ior` (η coat / η outside), whose
    /// reflection is scaled by `specular` (keep 1 for a physical coat).
    /// `roughness` ∈ [0, 1] with α = roughness², as for `CookTorrance`: Mitsuba's
    /// `alpha` a is `roughness: sqrt(a)` (α 0.1 → 0.3162).
    RoughPlastic {
        /// Reflectance of the diffuse base per channel, in [0, 1].
        diffuse: ColorDesc,
        /// Factor on the coat's reflection per channel, in [0, 1] (default
        /// white: a physical coat; Mitsuba's `specular_reflectance`).
        #[serde(default = "white")]
        specular: ColorDesc,
        /// Microfacet normal distribution of the coat (default `Ggx`).
        #[serde(default)]
        distribution: DistributionDesc,
        /// Perceptual roughness of the coat in [0, 1]; α = roughness².
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
        /// Index of refraction of the coat over the outside, in (0, 10]
        /// (default 1.5; Mitsuba's `int_ior/ext_ior`).
        #[serde(default = "glass_ior")]
        ior: f32,
    },
    /// Rough dielectric (Walter et al. 2007): frosted glass. `ior` = η inside /
    /// η outside (≠ 1), `tint` colours transmitted light, `roughness` ∈ [0, 1]
    /// with α = roughness².
    RoughGlass {
        /// Index of refraction η(inside)/η(outside), in (0, 10] and ≠ 1
        /// (default 1.5).
        #[serde(default = "glass_ior")]
        ior: f32,
        /// Colour of transmitted light, applied once per refraction, per
        /// channel in [0, 1] (default white); reflections stay white.
        #[serde(default = "white")]
        tint: ColorDesc,
        /// Microfacet normal distribution (default `Ggx`).
        #[serde(default)]
        distribution: DistributionDesc,
        /// Perceptual roughness in [0, 1]; α = roughness².
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
    },
}

fn white() -> ColorDesc {
    ColorDesc::Rgb([1.0; 3])
}

fn glass_ior() -> f32 {
    1.5
}

#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum DistributionDesc {
    #[default]
    Ggx,
    Beckmann,
}

#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum DielectricFresnelDesc {
    /// The exact Fresnel equations for unpolarised light.
    #[default]
    Exact,
    /// Schlick's approximation.
    Schlick,
}

/// Fresnel reflectance of a microfacet surface.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum FresnelDesc {
    /// A conductor with complex IOR η + ik per RGB channel.
    Conductor { eta: [f32; 3], k: [f32; 3] },
    /// A named conductor: `Gold`, `Silver`, `Copper` or `Aluminium`.
    Metal(MetalDesc),
    /// Schlick's approximation from the reflectance at normal incidence.
    Schlick { f0: [f32; 3] },
}

#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum MetalDesc {
    Gold,
    Silver,
    Copper,
    Aluminium,
}

impl MaterialDesc {
    /// Every colour parameter, so that code which rewrites texture paths
    /// (includes resolve them against their own folder) does not need a
    /// match over the models: a new material lists its parameters here.
    pub fn color_params_mut(&mut self) -> Vec<&mut ColorDesc> {
        match self {
            MaterialDesc::Lambert { albedo } | MaterialDesc::OrenNayar { albedo, .. } => vec![albedo],
            MaterialDesc::Phong {
                diffuse, specular, ..
            }
            | MaterialDesc::BlinnPhong {
                diffuse, specular, ..
            } => vec![diffuse, specular],
            MaterialDesc::MetalPlastic { base_color, .. } => vec![base_color],
            MaterialDesc::Mirror { tint } | MaterialDesc::Glass { tint, .. } => vec![tint],
            MaterialDesc::CookTorrance { .. } => Vec::new(),
            MaterialDesc::RoughPlastic {
                diffuse, specular, ..
            } => vec![diffuse, specular],
            MaterialDesc::RoughGlass { tint, .. } => vec![tint],
        }
    }
}
