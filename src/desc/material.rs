//! Materials, referred to by name from objects.
//!
//! Colour parameters accept constants or textures (see [`ColorDesc`]), and so do
//! number parameters ([`ScalarDesc`]); `NormalMap`, `Bump` and `Cutout` wrap
//! any material, and `Blend` mixes two.

use super::color::ColorDesc;
use super::texture::ScalarDesc;
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
        sigma: ScalarDesc,
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
        exponent: ScalarDesc,
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
        exponent: ScalarDesc,
    },
    /// Microfacet reflection (Smith height-correlated masking-shadowing).
    /// `roughness` ∈ [0, 1], α = roughness².
    CookTorrance {
        /// Microfacet normal distribution (default `Ggx`).
        #[serde(default)]
        distribution: DistributionDesc,
        /// Perceptual roughness in [0, 1]: 0 is polished, 1 very rough; the
        /// distribution's α is roughness² (see `roughness_unit`).
        roughness: ScalarDesc,
        /// What `roughness` holds (default `Perceptual`: α = roughness²; `Alpha`:
        /// the distribution's α itself, Mitsuba's `alpha`).
        #[serde(default, skip_serializing_if = "RoughnessUnitDesc::is_perceptual")]
        roughness_unit: RoughnessUnitDesc,

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
        /// Perceptual roughness in [0, 1]; GGX α = roughness² (see `roughness_unit`).
        roughness: ScalarDesc,
        /// What `roughness` holds (default `Perceptual`: α = roughness²; `Alpha`:
        /// the distribution's α itself, Mitsuba's `alpha`).
        #[serde(default, skip_serializing_if = "RoughnessUnitDesc::is_perceptual")]
        roughness_unit: RoughnessUnitDesc,
        /// 0 is plastic (diffuse base, 4% specular coat), 1 is metal (coloured
        /// specular, no diffuse); values between blend the two.
        metalness: ScalarDesc,
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
        ior: ScalarDesc,
        /// Colour of transmitted light, applied once per refraction, per channel in
        /// [0, 1] (default white); reflections stay white.
        #[serde(default = "white")]
        tint: ColorDesc,
        /// Which Fresnel formula decides between reflection and refraction (default
        /// `Exact`).
        #[serde(default)]
        fresnel: DielectricFresnelDesc,
        /// A thin sheet (a window pane, a soap film) instead of the boundary of
        /// a solid: light passes straight through, and what both faces reflect
        /// adds up (Mitsuba's `thindielectric`). Default false.
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        thin: bool,
        /// Coloured glass: what light keeps of each channel after `distance`
        /// inside (Beer–Lambert absorption in the solid; glTF's
        /// `KHR_materials_volume`). None (the default) is clear. Needs a
        /// closed surface, and not `thin`.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        attenuation: Option<AttenuationDesc>,
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
        /// Perceptual roughness of the coat in [0, 1]; α = roughness² (see
        /// `roughness_unit`). A constant: the coat's tables are integrated per
        /// α at load.
        roughness: ScalarDesc,
        /// What `roughness` holds (default `Perceptual`: α = roughness²; `Alpha`:
        /// the distribution's α itself, Mitsuba's `alpha`).
        #[serde(default, skip_serializing_if = "RoughnessUnitDesc::is_perceptual")]
        roughness_unit: RoughnessUnitDesc,
        /// Index of refraction of the coat over the outside, in (0, 10]
        /// (default 1.5; Mitsuba's `int_ior/ext_ior`); a constant, as `roughness`.
        #[serde(default = "glass_ior")]
        ior: ScalarDesc,
    },
    /// Rough dielectric (Walter et al. 2007): frosted glass. `ior` = η inside /
    /// η outside (≠ 1), `tint` colours transmitted light, `roughness` ∈ [0, 1]
    /// with α = roughness².
    RoughGlass {
        /// Index of refraction η(inside)/η(outside), in (0, 10] and ≠ 1
        /// (default 1.5).
        #[serde(default = "glass_ior")]
        ior: ScalarDesc,
        /// Colour of transmitted light, applied once per refraction, per
        /// channel in [0, 1] (default white); reflections stay white.
        #[serde(default = "white")]
        tint: ColorDesc,
        /// Microfacet normal distribution (default `Ggx`).
        #[serde(default)]
        distribution: DistributionDesc,
        /// Perceptual roughness in [0, 1]; α = roughness² (see `roughness_unit`).
        roughness: ScalarDesc,
        /// What `roughness` holds (default `Perceptual`: α = roughness²; `Alpha`:
        /// the distribution's α itself, Mitsuba's `alpha`).
        #[serde(default, skip_serializing_if = "RoughnessUnitDesc::is_perceptual")]
        roughness_unit: RoughnessUnitDesc,
        /// Coloured glass: what light keeps of each channel after `distance`
        /// inside (as `Glass`'s). None (the default) is clear.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        attenuation: Option<AttenuationDesc>,
    },
    /// A tangent-space normal map over `material`: the map's texels (linear
    /// unless `colorspace` says otherwise) give the shading normal
    /// `normalize(2c − 1)` in the frame (tangent along +u, bitangent, normal).
    NormalMap {
        /// The normal map (usually `Image(file: "…")`).
        map: ColorDesc,
        /// Factor on the map's tilt, ≥ 0 (default 1; 0 is the unmapped surface).
        #[serde(default = "one")]
        strength: f32,
        /// Negate the green channel: for DirectX-style maps (default false).
        #[serde(default)]
        flip_green: bool,
        /// Where a mesh's tangent frame comes from (default `Vertex`: the
        /// mesh's own tangents, else MikkTSpace; `Triangle`: each triangle's
        /// ∂p/∂u, as Mitsuba 3 does). Other shapes have one analytic frame.
        #[serde(default, skip_serializing_if = "TangentFrameDesc::is_vertex")]
        tangents: TangentFrameDesc,
        /// The material whose shading normal is mapped.
        material: Box<MaterialDesc>,
    },
    /// A bump map over `material`: the surface is displaced along its normal
    /// by `height × scale` (scene units) for shading only.
    Bump {
        /// Height, usually a greyscale image or a pattern.
        height: ScalarDesc,
        /// Scene units per unit of `height` (default 1).
        #[serde(default = "one")]
        scale: f32,
        /// The material whose shading normal is bumped.
        material: Box<MaterialDesc>,
    },
    /// An alpha cut-out: where `opacity` is 0 the surface is not there for
    /// any ray (camera, bounce or shadow).
    Cutout {
        /// Opacity in [0, 1], usually a greyscale image or an image's `A` channel.
        opacity: ScalarDesc,
        /// How partial opacity is resolved (default `Stochastic`).
        #[serde(default)]
        mode: CutoutModeDesc,
        /// The material where the surface is present.
        material: Box<MaterialDesc>,
    },
    /// A mix of two materials (pbrt-v4's `MixMaterial`, Mitsuba's
    /// `blendbsdf`): where `weight` is w the surface reflects as
    /// (1 − w)·`a` plus w·`b`. Each ray's hit is shaded by one of the two,
    /// `b` with probability w, so both may be any material, wrappers and
    /// blends included; a `NormalMap`, `Bump` or `Cutout` around the blend
    /// applies to both.
    Blend {
        /// The share of `b` in [0, 1]: a number, or a greyscale texture
        /// (a dirt or wear mask).
        weight: ScalarDesc,
        /// The material where `weight` is 0.
        a: Box<MaterialDesc>,
        /// The material where `weight` is 1.
        b: Box<MaterialDesc>,
    },
}

fn one() -> f32 {
    1.0
}

/// What a material's `roughness` number or texture holds.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum RoughnessUnitDesc {
    /// Perceptual roughness r in [0, 1] (glTF, Substance, Blender): α = r².
    #[default]
    Perceptual,
    /// The microfacet distribution's α itself (Mitsuba's `alpha`).
    Alpha,
}

impl RoughnessUnitDesc {
    fn is_perceptual(&self) -> bool {
        *self == RoughnessUnitDesc::Perceptual
    }
}

/// How a `Cutout` resolves an opacity between 0 and 1.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum CutoutModeDesc {
    /// The surface is there with probability `opacity` per ray (Mitsuba's
    /// `mask`): soft edges average out.
    #[default]
    Stochastic,
    /// The surface is there where `opacity` ≥ the given cut-off, in (0, 1].
    Threshold(f32),
}

fn white() -> ColorDesc {
    ColorDesc::Rgb([1.0; 3])
}

fn glass_ior() -> ScalarDesc {
    ScalarDesc::Value(1.5)
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

/// Absorption inside a dielectric solid (Beer–Lambert): light that travels
/// `distance` scene units inside keeps `color` of each channel, twice that
/// distance `color²` (glTF's `attenuationColor` and `attenuationDistance`).
/// The absorption coefficient is σ = −ln(color)/distance per channel.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AttenuationDesc {
    /// The fraction of each channel left after `distance`, in (0, 1]
    /// (1: that channel is not absorbed).
    pub color: [f32; 3],
    /// Scene units over which `color` is reached, > 0.
    pub distance: f32,
}

impl AttenuationDesc {
    /// The absorption coefficient per channel, in 1/scene units (0 for a
    /// channel of colour 1), finite: a coefficient past f32 (a tiny colour
    /// over a tiny distance) is the largest f32, which absorbs everything
    /// in any length, not infinity (∞·0 is no number) and not 0 (clear).
    pub fn sigma(&self) -> [f32; 3] {
        self.color.map(|c| {
            let s = -c.ln() / self.distance;
            if s > 0.0 { s.min(f32::MAX) } else { 0.0 }
        })
    }
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

/// What a material description holds inside it.
#[derive(Clone, Copy, Debug)]
pub enum MaterialInner<'a> {
    /// A reflection model: nothing.
    Model,
    /// A wrapper's (`NormalMap`, `Bump`, `Cutout`) material.
    Wrapped(&'a MaterialDesc),
    /// A `Blend`'s two materials.
    Blend(&'a MaterialDesc, &'a MaterialDesc),
}

impl MaterialDesc {
    /// The materials inside this one, for checks that walk the tree
    /// without a match of their own over every model.
    pub fn inner(&self) -> MaterialInner<'_> {
        match self {
            MaterialDesc::NormalMap { material, .. }
            | MaterialDesc::Bump { material, .. }
            | MaterialDesc::Cutout { material, .. } => MaterialInner::Wrapped(material),
            MaterialDesc::Blend { a, b, .. } => MaterialInner::Blend(a, b),
            MaterialDesc::Lambert { .. }
            | MaterialDesc::OrenNayar { .. }
            | MaterialDesc::Phong { .. }
            | MaterialDesc::BlinnPhong { .. }
            | MaterialDesc::CookTorrance { .. }
            | MaterialDesc::MetalPlastic { .. }
            | MaterialDesc::Mirror { .. }
            | MaterialDesc::Glass { .. }
            | MaterialDesc::RoughPlastic { .. }
            | MaterialDesc::RoughGlass { .. } => MaterialInner::Model,
        }
    }

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
            MaterialDesc::NormalMap { map, material, .. } => {
                let mut v = vec![map];
                v.extend(material.color_params_mut());
                v
            }
            MaterialDesc::Bump { material, .. } | MaterialDesc::Cutout { material, .. } => {
                material.color_params_mut()
            }
            MaterialDesc::Blend { a, b, .. } => {
                let mut v = a.color_params_mut();
                v.extend(b.color_params_mut());
                v
            }
        }
    }

    /// Every number parameter that may be a texture, nested materials
    /// included (as [`MaterialDesc::color_params_mut`]).
    pub fn scalar_params_mut(&mut self) -> Vec<&mut ScalarDesc> {
        match self {
            MaterialDesc::Lambert { .. } | MaterialDesc::Mirror { .. } => Vec::new(),
            MaterialDesc::OrenNayar { sigma, .. } => vec![sigma],
            MaterialDesc::Phong { exponent, .. } | MaterialDesc::BlinnPhong { exponent, .. } => {
                vec![exponent]
            }
            MaterialDesc::CookTorrance { roughness, .. } => vec![roughness],
            MaterialDesc::MetalPlastic {
                roughness, metalness, ..
            } => vec![roughness, metalness],
            MaterialDesc::Glass { ior, .. } => vec![ior],
            MaterialDesc::RoughPlastic { roughness, ior, .. }
            | MaterialDesc::RoughGlass { roughness, ior, .. } => {
                vec![roughness, ior]
            }
            MaterialDesc::NormalMap { material, .. } => material.scalar_params_mut(),
            MaterialDesc::Bump { height, material, .. } => {
                let mut v = vec![height];
                v.extend(material.scalar_params_mut());
                v
            }
            MaterialDesc::Cutout {
                opacity, material, ..
            } => {
                let mut v = vec![opacity];
                v.extend(material.scalar_params_mut());
                v
            }
            MaterialDesc::Blend { weight, a, b } => {
                let mut v = vec![weight];
                v.extend(a.scalar_params_mut());
                v.extend(b.scalar_params_mut());
                v
            }
        }
    }

    /// Calls `f` on every texture file the material names (to resolve them
    /// against an included file's folder).
    pub fn for_each_file(&mut self, f: &mut impl FnMut(&mut String)) {
        for c in self.color_params_mut() {
            c.file_mut().map(&mut *f);
        }
        for c in self.scalar_params_mut() {
            c.file_mut().map(&mut *f);
        }
    }
}

/// Where a normal map's tangent frame comes from on a mesh.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum TangentFrameDesc {
    /// Per-vertex tangents, interpolated: the asset's own (glTF `TANGENT`),
    /// else MikkTSpace (the convention glTF, Blender and Substance bake in).
    #[default]
    Vertex,
    /// Each triangle's own ∂p/∂u from its positions and UVs: Mitsuba 3's
    /// frame, for twins of Mitsuba scenes.
    Triangle,
}

impl TangentFrameDesc {
    fn is_vertex(&self) -> bool {
        *self == TangentFrameDesc::Vertex
    }
}
