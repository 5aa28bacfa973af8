//! Materials, referred to by name from objects.
//!
//! Colour parameters accept constants or textures (see [`ColorDesc`]).

use super::color::ColorDesc;
use serde::{Deserialize, Serialize};

/// A surface's reflection model, stored under a name in `materials` and referred to
/// by objects. Colour parameters accept a constant or a texture; reflectances are in
/// [0, 1] per channel.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum MaterialDesc {
    /// Ideal diffuse: f = albedo/π. Channels in [0, 1].
    Lambert {
        /// Diffuse reflectance per channel, in [0, 1]: the fraction of light
        /// reflected.
        albedo: ColorDesc,
    },
    /// Rough diffuse (Fujii's energy-conserving Oren–Nayar). `sigma` is a
    /// unitless roughness ≥ 0 (0 = Lambert; useful up to about 1), not an angle.
    OrenNayar {
        /// Diffuse reflectance per channel, in [0, 1].
        albedo: ColorDesc,
        /// Surface roughness, unitless, in [0, 2] (0 = Lambert, 1 = very rough).
        #[schemars(range(min = 0, max = 2))]
        sigma: f32,
    },
    /// Energy-normalised (modified) Phong: diffuse/π + specular·(n+2)/(2π)·cosⁿα.
    Phong {
        /// Diffuse reflectance per channel, in [0, 1].
        diffuse: ColorDesc,
        /// Specular reflectance per channel; `diffuse + specular` must stay ≤ 1 per
        /// channel so the surface returns no more light than it receives.
        specular: ColorDesc,
        /// Sharpness of the highlight n, in [0, 100000]: 1 is broad, 1000 nearly a
        /// mirror.
        exponent: f32,
    },
    /// Energy-normalised Blinn–Phong: diffuse/π + specular·(n+2)/(8π)·cosⁿθh.
    BlinnPhong {
        /// Diffuse reflectance per channel, in [0, 1].
        diffuse: ColorDesc,
        /// Specular reflectance per channel; `diffuse + specular` must stay ≤ 1 per
        /// channel.
        specular: ColorDesc,
        /// Sharpness of the highlight n, in [0, 100000]. Blinn–Phong needs about 4×
        /// the Phong exponent for a similar highlight.
        exponent: f32,
    },
    /// Microfacet reflection (Smith height-correlated masking-shadowing).
    /// `roughness` ∈ [0, 1], α = roughness².
    CookTorrance {
        /// Microfacet normal distribution (default `Ggx`).
        #[serde(default)]
        distribution: DistributionDesc,
        /// Perceptual roughness in [0, 1]: 0 is polished, 1 very rough; the
        /// distribution's α is roughness².
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
        /// Reflectance of the metal: a named `Metal(...)`, its complex IOR, or
        /// Schlick's `f0`.
        fresnel: FresnelDesc,
    },
    /// The report's metal/plastic: a diffuse base under a GGX coat, mixed by
    /// `metalness` ∈ [0, 1] as in glTF's metallic–roughness model.
    MetalPlastic {
        /// Diffuse colour of a plastic (metalness 0), reflectance at normal incidence
        /// of a metal (metalness 1), per channel in [0, 1].
        base_color: ColorDesc,
        /// Perceptual roughness in [0, 1]; GGX α = roughness².
        #[schemars(range(min = 0, max = 1))]
        roughness: f32,
        /// 0 is plastic (diffuse base, 4% specular coat), 1 is metal (coloured
        /// specular, no diffuse); values between blend the two.
        metalness: f32,
    },
    /// Perfect specular reflection.
    Mirror {
        /// Colour multiplying the reflection, per channel in [0, 1] (default white).
        #[serde(default = "white")]
        tint: ColorDesc,
    },
    /// Smooth dielectric; `ior` = η inside / η outside (outside is where the
    /// surface normal points).
    Glass {
        /// Index of refraction η(inside)/η(outside), in (0, 10] (default 1.5: glass;
        /// water 1.33, diamond 2.42).
        #[serde(default = "glass_ior")]
        ior: f32,
        /// Colour of transmitted light, applied once per refraction, per channel in
        /// [0, 1] (default white); reflections stay white.
        #[serde(default = "white")]
        tint: ColorDesc,
        /// Which Fresnel formula decides between reflection and refraction (default
        /// `Exact`).
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

/// Microfacet normal distribution of a `CookTorrance` surface.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum DistributionDesc {
    /// Trowbridge–Reitz (GGX): long tails, a soft glow around highlights that
    /// fits measured surfaces well.
    #[default]
    Ggx,
    /// Beckmann: shorter tails, a tighter halo around highlights.
    Beckmann,
}

/// Fresnel formula of a `Glass` surface.
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
    Conductor {
        /// Real part η of the index of refraction per channel, relative to
        /// the outside medium; > 0.
        eta: [f32; 3],
        /// Extinction coefficient k (imaginary part) per channel, ≥ 0.
        k: [f32; 3],
    },
    /// A named conductor: `Gold`, `Silver`, `Copper` or `Aluminium`.
    Metal(MetalDesc),
    /// Schlick's approximation from the reflectance at normal incidence.
    Schlick {
        /// Reflectance at normal incidence per channel, in [0, 1].
        f0: [f32; 3],
    },
}

/// Conductor presets with measured η and k (linear sRGB, from Tungsten's spectral
/// data).
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum MetalDesc {
    /// Yellow: reflects about 97% red, 80% green, 32% blue head-on.
    Gold,
    /// Nearly white: about 97% red, 96% green, 91% blue head-on.
    Silver,
    /// Orange-red: about 95% red, 62% green, 51% blue head-on.
    Copper,
    /// Neutral grey-white: about 93% red, 92% green, 92% blue head-on.
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
