//! Materials and their scattering functions.
//!
//! # Direction convention
//! Every BSDF works in a local shading frame whose normal is +z
//! ([`crate::math::Frame`]). `wo` points toward the camera (or the previous
//! path vertex), `wi` is the sampled or light direction; both are unit
//! vectors leaving the surface (pbrt's convention; Mitsuba names them the
//! other way round). `eval` returns the BSDF value `f(wo, wi)` **without**
//! the cosine factor; `sample` returns the weight `f·|cos θi| / pdf`.
//!
//! Opaque models are two-sided: a `wo` below the surface (z < 0) is handled as
//! if the surface were flipped, and `wi` on the other side of `wo` gives zero.
//! [`Glass`] and [`RoughGlass`] are the exception: there z < 0 is the inside
//! of the object.
//!
//! A [`Material`] is what the scene says (colours may be textures); at a hit
//! point it resolves to a [`Bsdf`], a plain value with every parameter fixed.
//! Each model file holds both halves, as pbrt-v4 keeps `DiffuseMaterial`
//! beside `DiffuseBxDF`: the lobe (`Lambert`, a [`Bxdf`]) and the scene's
//! parameters (`LambertMaterial`, a [`MaterialModel`]: its lobe at a hit,
//! its albedo for the denoiser, whether it is textured). The lobe keeps the
//! model's name because tests, χ² harness and integrators speak of lobes;
//! the parameters take pbrt's `Material` suffix.
//!
//! # Models
//! | file | model | sampling |
//! |---|---|---|
//! | `lambert.rs` | ideal diffuse | cosine |
//! | `oren_nayar.rs` | rough diffuse (Fujii's improved Oren–Nayar) | cosine |
//! | `phong.rs`, `blinn_phong.rs` | energy-normalised Phong / Blinn–Phong | cosine + lobe mixture |
//! | `cook_torrance.rs` | microfacet conductor (GGX or Beckmann) | visible normals / D·cos |
//! | `metal_plastic.rs` | glTF metallic–roughness (Lambert + GGX) | mixture |
//! | `mirror.rs`, `glass.rs` | smooth conductor / dielectric | delta |
//! | `rough_plastic.rs` (+ `rough_coat.rs`) | Mitsuba's `roughplastic`: diffuse under a rough dielectric coat | mixture |
//! | `rough_glass.rs` | rough dielectric (Walter 2007) | visible normals / D·cos, then F |
//! | `emitter.rs` | an area light's own surface: black, reflects nothing | (a black Lambert lobe) |

pub mod blinn_phong;
pub mod cook_torrance;
pub mod emitter;
pub mod fresnel;
pub mod glass;
pub mod lambert;
pub mod metal_plastic;
pub mod microfacet;
pub mod mirror;
pub mod oren_nayar;
pub mod pattern;
pub mod phong;
pub mod rough_coat;
pub mod rough_glass;
pub mod rough_plastic;
pub mod surface;
pub mod texture;

#[cfg(test)]
mod tests;

pub use blinn_phong::{BlinnPhong, BlinnPhongMaterial};
pub use cook_torrance::{CookTorrance, CookTorranceMaterial};
pub use emitter::Emitter;
pub use fresnel::{DielectricFresnel, Fresnel, Metal};
pub use glass::{Glass, GlassMaterial};
pub use lambert::{Lambert, LambertMaterial};
pub use metal_plastic::{MetalPlastic, MetalPlasticMaterial};
pub use microfacet::{Distribution, Microfacet, Roughness};
pub use mirror::{Mirror, MirrorMaterial};
pub use oren_nayar::{OrenNayar, OrenNayarMaterial};
pub use pattern::Pattern;
pub use phong::{Phong, PhongMaterial};
pub use rough_coat::RoughCoat;
pub use rough_glass::{RoughGlass, RoughGlassMaterial};
pub use rough_plastic::{RoughPlastic, RoughPlasticMaterial};
pub use surface::{Blend, Cutout, Perturb, Surface};
pub use texture::{
    Channel, ColorTex, ImageLookup, ScalarTex, Tex, TexPoint, TexProbe, Texture, UvTransform, Wrap,
};

use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// One direction drawn from a BSDF.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    /// The sampled direction, unit length, in the local shading frame (normal +z).
    pub wi: Vec3A,
    /// `f · |cos θi| / pdf`: what the path throughput is multiplied by.
    /// For refraction it already includes the radiance scaling
    /// `1/eta²` (see [`Glass`]).
    pub weight: Rgb,
    /// Solid-angle density of `wi`; for delta lobes the discrete probability
    /// of the chosen lobe.
    pub pdf: f32,
    /// True when `wi` came from a Dirac lobe (mirror, smooth glass): `eval`
    /// and `pdf` are zero for it and light sampling cannot reach it.
    pub delta: bool,
    /// Relative index of refraction `η(wi side) / η(wo side)` crossed by
    /// `wi`; 1 for reflection. An integrator that wants pbrt's `etaScale`
    /// (Russian roulette on flux rather than radiance) multiplies by `eta²`.
    pub eta: f32,
}

/// The tail of every `sample`, written once. The models differ in how they
/// choose `wi`, not in how they package it: one of these builds the result.
impl BsdfSample {
    /// A sample from a non-delta reflection lobe with BSDF value `f = f(wo, wi)`
    /// and solid-angle density `pdf`: weight `f · |wi.z| / pdf`, evaluated in
    /// that order. The order is part of the contract: it is the one every
    /// model used before this constructor existed, and regrouping it (e.g.
    /// `f · (cos / pdf)`) would change rendered images in the last bit.
    ///
    /// `None` when `pdf ≤ 0`: `wi` lies where the model does not scatter
    /// (across the horizon, on it, or outside a clipped lobe), and dividing
    /// by that pdf would make an infinite or NaN weight. A NaN or infinite
    /// pdf is not refused here (as before); a model that can produce one
    /// checks it itself (see `CookTorrance::sample`).
    #[inline]
    pub fn from_f(wi: Vec3A, f: Rgb, pdf: f32) -> Option<Self> {
        // A pdf ≤ 0 makes an inf/NaN weight here, which from_weight discards.
        Self::from_weight(wi, f * wi.z.abs() / pdf, pdf)
    }

    /// As [`BsdfSample::from_f`] for a model that knows its weight in closed
    /// form (Lambert's cosine sampling makes it exactly the albedo): the
    /// shortcut is both cheaper and rounds differently from `f·|cos|/pdf`, so
    /// such models pass their own weight rather than their `f`.
    /// `None` when `pdf ≤ 0`, for the same reason.
    #[inline]
    pub fn from_weight(wi: Vec3A, weight: Rgb, pdf: f32) -> Option<Self> {
        if pdf <= 0.0 {
            return None;
        }
        Some(Self {
            wi,
            weight,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    /// A sample from a Dirac lobe (mirror, smooth glass). There is no
    /// density to divide by: `weight` is the lobe's throughput over `prob`,
    /// the probability with which the model chose this lobe (1 for a single
    /// lobe), and `eta` is the relative IOR crossed by `wi` (1 when
    /// reflecting). It cannot fail: a model only returns a lobe it chose, and
    /// it chose it with probability > 0.
    #[inline]
    pub fn delta(wi: Vec3A, weight: Rgb, prob: f32, eta: f32) -> Self {
        debug_assert!(prob > 0.0, "a chosen delta lobe has probability {prob}");
        Self {
            wi,
            weight,
            pdf: prob,
            delta: true,
            eta,
        }
    }
}

/// The contract every scattering model implements, so tests can be generic.
pub trait Bxdf {
    /// The BSDF value `f(wo, wi)` in 1/sr, without the cosine factor; zero for delta
    /// lobes and for directions the model does not scatter into.
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb;
    /// Solid-angle density (1/sr) with which `sample` draws `wi` from `wo`; zero for
    /// delta lobes, as `eval`.
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32;
    /// `u_lobe` picks a lobe for mixtures; `u` drives the warp.
    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample>;
    /// True when every lobe is a Dirac delta (no point in light sampling).
    fn is_delta(&self) -> bool {
        false
    }
    /// Whether light can pass through the surface (some `wi` below it has a
    /// non-zero value): light sampling then looks at both sides of it.
    fn transmits(&self) -> bool {
        false
    }
}

/// A BSDF with all its parameters resolved at one hit point.
#[derive(Clone, Copy, Debug)]
pub enum Bsdf<'a> {
    /// Ideal diffuse.
    Lambert(Lambert),
    /// Rough diffuse.
    OrenNayar(OrenNayar),
    /// Modified Phong.
    Phong(Phong),
    /// Modified Blinn–Phong.
    BlinnPhong(BlinnPhong),
    /// Microfacet conductor.
    CookTorrance(CookTorrance),
    /// glTF metallic–roughness.
    MetalPlastic(MetalPlastic),
    /// Perfect mirror.
    Mirror(Mirror),
    /// Smooth dielectric.
    Glass(Glass),
    /// Diffuse base under a rough dielectric coat (Mitsuba's `roughplastic`).
    RoughPlastic(RoughPlastic<'a>),
    /// Rough dielectric boundary.
    RoughGlass(RoughGlass),
}

/// Forwards one `Bxdf` method to the variant (the match is the checklist).
macro_rules! forward {
    ($self:ident, $b:ident => $call:expr) => {
        match $self {
            Bsdf::Lambert($b) => $call,
            Bsdf::OrenNayar($b) => $call,
            Bsdf::Phong($b) => $call,
            Bsdf::BlinnPhong($b) => $call,
            Bsdf::CookTorrance($b) => $call,
            Bsdf::MetalPlastic($b) => $call,
            Bsdf::Mirror($b) => $call,
            Bsdf::Glass($b) => $call,
            Bsdf::RoughPlastic($b) => $call,
            Bsdf::RoughGlass($b) => $call,
        }
    };
}

impl Bsdf<'_> {
    /// The lobe dispatched inline ([`Bxdf for Bsdf`](Bxdf)), `None` for the
    /// out-of-line ones: the one place that names every variant, so a new
    /// one has to say which side it is on.
    #[inline(always)]
    fn inline_lobe(&self) -> Option<&Lambert> {
        match self {
            Bsdf::Lambert(b) => Some(b),
            Bsdf::OrenNayar(_)
            | Bsdf::Phong(_)
            | Bsdf::BlinnPhong(_)
            | Bsdf::CookTorrance(_)
            | Bsdf::MetalPlastic(_)
            | Bsdf::Mirror(_)
            | Bsdf::Glass(_)
            | Bsdf::RoughPlastic(_)
            | Bsdf::RoughGlass(_) => None,
        }
    }
}

/// The diffuse variant is dispatched inline and every other through an
/// out-of-line call: a Lambert lobe's methods are a few instructions, less
/// than the call and the enum copy they were behind (three calls per path
/// vertex), and inlining every variant would bloat the integrators.
impl Bxdf for Bsdf<'_> {
    #[inline(always)]
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        match self.inline_lobe() {
            Some(b) => b.eval(wo, wi),
            None => self.eval_other(wo, wi),
        }
    }
    #[inline(always)]
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        match self.inline_lobe() {
            Some(b) => b.pdf(wo, wi),
            None => self.pdf_other(wo, wi),
        }
    }
    #[inline(always)]
    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self.inline_lobe() {
            Some(b) => b.sample(wo, u_lobe, u),
            None => self.sample_other(wo, u_lobe, u),
        }
    }
    #[inline]
    fn is_delta(&self) -> bool {
        forward!(self, b => b.is_delta())
    }
    #[inline]
    fn transmits(&self) -> bool {
        forward!(self, b => b.transmits())
    }
}

impl Bsdf<'_> {
    /// The unit normal on the side a light sample from this surface is
    /// wanted (toward `wo`, local `wo.z` along `n`), or zero for both sides
    /// when the surface transmits: what [`crate::lights::Light::sample`]
    /// and the environment's density take.
    #[inline]
    pub fn light_side(&self, n: Vec3A, wo_z: f32) -> Vec3A {
        if self.transmits() {
            Vec3A::ZERO
        } else if wo_z >= 0.0 {
            n
        } else {
            -n
        }
    }
}

/// The out-of-line half of the dispatch above: every variant but the
/// inline one (which these also handle, for the exhaustive match).
impl Bsdf<'_> {
    #[inline(never)]
    fn eval_other(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        forward!(self, b => b.eval(wo, wi))
    }
    #[inline(never)]
    fn pdf_other(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        forward!(self, b => b.pdf(wo, wi))
    }
    #[inline(never)]
    fn sample_other(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        forward!(self, b => b.sample(wo, u_lobe, u))
    }
}

/// What every material's parameters answer, written beside its model (as
/// pbrt's `DiffuseMaterial` sits beside its `DiffuseBxDF`): a new material is
/// its description (`desc/material.rs`), its loader entry
/// (`load/material.rs`) and its model file, plus one line in [`Material`]
/// and one in [`forward_material`].
pub trait MaterialModel {
    /// The lobe at surface coordinates `uv`, every texture resolved.
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_>;
    /// The albedo a first hit shows (the denoiser's `albedo` input, see
    /// `aov/albedo.rs`), before clamping to [0, 1].
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb;
    /// Whether any parameter is a texture (so shading needs `uv`).
    /// Whether `f` holds for any of the parameters.
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool;
}

/// A material as the scene describes it, with textured parameters; each
/// variant's data and rules live in its model file.
///
/// Units: `roughness` ∈ [0, 1] with microfacet
/// `alpha = roughness²`, `exponent` ≥ 0, `ior` relative to the outside (> 0).
#[derive(Clone, Debug)]
pub enum Material {
    /// Ideal diffuse, `f = albedo/π`.
    Lambert(LambertMaterial),
    /// Rough diffuse (Fujii's Oren–Nayar).
    OrenNayar(OrenNayarMaterial),
    /// Energy-normalised Phong.
    Phong(PhongMaterial),
    /// Energy-normalised Blinn–Phong.
    BlinnPhong(BlinnPhongMaterial),
    /// Microfacet conductor.
    CookTorrance(CookTorranceMaterial),
    /// glTF metallic–roughness: a diffuse base under a GGX coat.
    MetalPlastic(MetalPlasticMaterial),
    /// Perfect specular reflection.
    Mirror(MirrorMaterial),
    /// Smooth dielectric boundary.
    Glass(GlassMaterial),
    /// The surface of an area light: black and non-reflecting.
    Emitter(Emitter),
    /// Diffuse base under a rough dielectric coat (Mitsuba's `roughplastic`).
    RoughPlastic(RoughPlasticMaterial),
    /// Rough dielectric boundary.
    RoughGlass(RoughGlassMaterial),
}

/// Forwards one [`MaterialModel`] method to the variant (the match is the
/// checklist).
macro_rules! forward_material {
    ($self:ident, $m:ident => $call:expr) => {
        match $self {
            Material::Lambert($m) => $call,
            Material::OrenNayar($m) => $call,
            Material::Phong($m) => $call,
            Material::BlinnPhong($m) => $call,
            Material::CookTorrance($m) => $call,
            Material::MetalPlastic($m) => $call,
            Material::Mirror($m) => $call,
            Material::Glass($m) => $call,
            Material::Emitter($m) => $call,
            Material::RoughPlastic($m) => $call,
            Material::RoughGlass($m) => $call,
        }
    };
}

impl Material {
    /// The material dispatched inline by [`Material::bsdf`], `None` for the
    /// out-of-line ones: as [`Bsdf::inline_lobe`], the one place that says
    /// which side each variant is on.
    #[inline(always)]
    fn inline_material(&self) -> Option<&LambertMaterial> {
        match self {
            Material::Lambert(m) => Some(m),
            Material::OrenNayar(_)
            | Material::Phong(_)
            | Material::BlinnPhong(_)
            | Material::CookTorrance(_)
            | Material::MetalPlastic(_)
            | Material::Mirror(_)
            | Material::Glass(_)
            | Material::Emitter(_)
            | Material::RoughPlastic(_)
            | Material::RoughGlass(_) => None,
        }
    }

    /// The absorption coefficient inside the solid this material bounds,
    /// per channel in 1/scene units, for the materials that bound a solid
    /// (`Glass` but a thin sheet, `RoughGlass`): zero for clear glass, the
    /// `attenuation`'s for coloured glass; `None` for surfaces light does
    /// not enter. Integrators multiply a path by exp(−σ·t) over each length
    /// `t` it travels inside (`integrators::interior`).
    pub fn interior(&self) -> Option<Rgb> {
        match self {
            Material::Glass(m) => (!m.thin).then_some(m.absorption),
            Material::RoughGlass(m) => Some(m.absorption),
            Material::Lambert(_)
            | Material::OrenNayar(_)
            | Material::Phong(_)
            | Material::BlinnPhong(_)
            | Material::CookTorrance(_)
            | Material::MetalPlastic(_)
            | Material::Mirror(_)
            | Material::Emitter(_)
            | Material::RoughPlastic(_) => None,
        }
    }

    /// Whether any parameter is a texture (so shading needs `uv`).
    pub fn is_textured(&self) -> bool {
        forward_material!(self, m => m.any_tex(&|t| t.is_textured()))
    }

    /// Whether any parameter reads the hit's vertex colour (so
    /// `Scene::intersect` fills it in).
    pub fn reads_vertex_color(&self) -> bool {
        forward_material!(self, m => m.any_tex(&|t| t.reads_vertex_color()))
    }

    /// The albedo a first hit shows, unclamped (see [`MaterialModel::albedo`]).
    pub fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        forward_material!(self, m => m.albedo(at, textures))
    }

    /// Resolves textures at surface coordinates `uv`. Inline for the
    /// diffuse material (see [`Bsdf`]'s dispatch), a call for the others.
    #[inline(always)]
    pub fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        match self.inline_material() {
            Some(m) => m.bsdf(at, textures),
            None => self.bsdf_other(at, textures),
        }
    }

    /// [`Material::bsdf`] for every material but the inline one (which it
    /// also handles, for the exhaustive match).
    #[inline(never)]
    fn bsdf_other(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        forward_material!(self, m => m.bsdf(at, textures))
    }
}

/// Mirror direction of `w` about the normal `n` (both leaving the surface).
#[inline]
pub(crate) fn reflect(w: Vec3A, n: Vec3A) -> Vec3A {
    2.0 * w.dot(n) * n - w
}

/// For two-sided models: mirrors `wo` and `wi` through the surface plane so
/// that `wo` is in the upper hemisphere.
#[inline]
pub(crate) fn flip_up(wo: Vec3A, wi: Vec3A) -> (Vec3A, Vec3A) {
    if wo.z < 0.0 {
        let m = Vec3A::new(1.0, 1.0, -1.0);
        (wo * m, wi * m)
    } else {
        (wo, wi)
    }
}

#[cfg(test)]
mod material_tests {
    use super::*;

    #[test]
    fn bsdf_sample_refuses_a_pdf_that_is_not_positive() {
        let (wi, f) = (Vec3A::new(0.6, 0.0, 0.8), Rgb::ONE);
        for pdf in [0.0, -0.0, -1.0, f32::NEG_INFINITY] {
            let s = BsdfSample::from_f(wi, f, pdf);
            assert!(s.is_none(), "from_f with pdf {pdf}: expected None, got {s:?}");
            let s = BsdfSample::from_weight(wi, f, pdf);
            assert!(
                s.is_none(),
                "from_weight with pdf {pdf}: expected None, got {s:?}"
            );
        }
    }

    #[test]
    fn bsdf_sample_from_f_weighs_by_cosine_over_pdf() {
        // Below the surface, so the |cos| matters; values chosen so that no
        // step rounds exactly.
        let (wi, f, pdf) = (Vec3A::new(0.6, 0.0, -0.8), Rgb::new(0.3, 0.7, 1.1), 0.37);
        let s = BsdfSample::from_f(wi, f, pdf).expect("pdf > 0 gives a sample");
        // Bit for bit the documented order, not merely close to it.
        assert_eq!(s.weight, f * wi.z.abs() / pdf);
        let want = Rgb::new(0.3 * 0.8 / 0.37, 0.7 * 0.8 / 0.37, 1.1 * 0.8 / 0.37);
        assert!(
            (s.weight - want).abs().max_element() < 1e-6,
            "weight {} ≠ f·|cos|/pdf {want}",
            s.weight
        );
        assert_eq!((s.wi, s.pdf, s.delta, s.eta), (wi, pdf, false, 1.0));
    }

    #[test]
    fn bsdf_sample_from_weight_keeps_the_given_weight() {
        let (wi, weight) = (Vec3A::new(0.0, 0.6, 0.8), Rgb::new(0.2, 0.4, 0.6));
        let s =
            BsdfSample::from_weight(wi, weight, 0.8 / std::f32::consts::PI).expect("pdf > 0 gives a sample");
        assert_eq!((s.wi, s.weight, s.delta, s.eta), (wi, weight, false, 1.0));
    }

    #[test]
    fn bsdf_sample_delta_keeps_weight_probability_and_eta() {
        let (wi, weight) = (Vec3A::new(-0.6, 0.0, -0.8), Rgb::splat(0.25));
        let s = BsdfSample::delta(wi, weight, 0.96, 1.5);
        assert_eq!(
            (s.wi, s.weight, s.pdf, s.delta, s.eta),
            (wi, weight, 0.96, true, 1.5),
            "delta must store its arguments unchanged"
        );
    }

    #[test]
    fn only_texture_parameters_make_a_material_textured() {
        let checker = ColorTex::Checker {
            a: Rgb::ONE,
            b: Rgb::ZERO,
            scale: 4.0,
            uv: UvTransform::default(),
        };
        let plain = Material::Lambert(LambertMaterial {
            albedo: ColorTex::Const(Rgb::ONE),
        });
        assert!(!plain.is_textured());
        assert!(
            Material::Lambert(LambertMaterial {
                albedo: checker.clone()
            })
            .is_textured()
        );
        assert!(
            Material::Phong(PhongMaterial {
                kd: ColorTex::Const(Rgb::ONE),
                ks: ColorTex::image(0),
                exponent: Tex::Const(10.0)
            })
            .is_textured()
        );
        assert!(
            Material::Glass(GlassMaterial {
                ior: Tex::Const(1.5),
                tint: checker,
                fresnel: DielectricFresnel::Exact,
                thin: false,
                absorption: Rgb::ZERO,
            })
            .is_textured()
        );
    }

    #[test]
    fn material_resolves_every_variant_and_texture() {
        let checker = ColorTex::Checker {
            a: Rgb::ONE,
            b: Rgb::ZERO,
            scale: 2.0,
            uv: UvTransform::default(),
        };
        let textures = [Texture {
            width: 1,
            height: 1,
            texels: vec![Rgb::splat(0.25)],
            alpha: Vec::new(),
        }];
        let materials = [
            Material::Lambert(LambertMaterial {
                albedo: checker.clone(),
            }),
            Material::OrenNayar(OrenNayarMaterial {
                albedo: ColorTex::image(0),
                sigma: Tex::Const(0.3),
            }),
            Material::Phong(PhongMaterial {
                kd: checker.clone(),
                ks: ColorTex::Const(Rgb::ONE),
                exponent: Tex::Const(10.0),
            }),
            Material::BlinnPhong(BlinnPhongMaterial {
                kd: checker.clone(),
                ks: checker.clone(),
                exponent: Tex::Const(10.0),
            }),
            Material::CookTorrance(CookTorranceMaterial {
                distribution: Distribution::Ggx,
                roughness: Roughness::perceptual(0.5),
                fresnel: Metal::Gold.fresnel(),
            }),
            Material::MetalPlastic(MetalPlasticMaterial {
                base_color: checker.clone(),
                roughness: Roughness::perceptual(0.5),
                metalness: Tex::Const(0.5),
            }),
            Material::Mirror(MirrorMaterial {
                tint: ColorTex::image(0),
            }),
            Material::Glass(GlassMaterial {
                ior: Tex::Const(1.5),
                tint: checker,
                fresnel: DielectricFresnel::Exact,
                thin: false,
                absorption: Rgb::ZERO,
            }),
            Material::Emitter(Emitter),
        ];
        let (wo, wi) = (Vec3A::new(0.6, 0.0, 0.8), Vec3A::new(-0.6, 0.0, 0.8));
        for m in &materials {
            let b = m.bsdf(&TexPoint::uv(Vec2::new(0.25, 0.25)), &textures);
            let f = b.eval(wo, wi);
            assert!(f.is_finite() && f.min_element() >= 0.0, "{m:?}: f = {f}");
            assert_eq!(
                b.is_delta(),
                matches!(m, Material::Mirror(_) | Material::Glass(_))
            );
        }
        // The checker's `a` square at uv (0.25, 0.25) is white; (0.75, 0.25) black.
        let lambert = |uv: Vec2| match materials[0].bsdf(&TexPoint::uv(uv), &textures) {
            Bsdf::Lambert(l) => l.albedo,
            other => panic!("Lambert resolved to {other:?}"),
        };
        assert_eq!(lambert(Vec2::new(0.25, 0.25)), Rgb::ONE);
        assert_eq!(lambert(Vec2::new(0.75, 0.25)), Rgb::ZERO);
        let mirror = materials[6].bsdf(&TexPoint::uv(Vec2::ZERO), &textures);
        let s = mirror.sample(wo, 0.5, Vec2::splat(0.5)).unwrap();
        assert_eq!(
            s.weight,
            Rgb::splat(0.25),
            "image texture must reach the mirror tint"
        );
        assert_eq!(
            Material::Emitter(Emitter)
                .bsdf(&TexPoint::uv(Vec2::ZERO), &[])
                .eval(wo, wi),
            Rgb::ZERO
        );
    }
}
