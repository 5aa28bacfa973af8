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
//!
//! A [`Material`] is what the scene says (colours may be textures); at a hit
//! point it resolves to a [`Bsdf`], a plain value with every parameter fixed.

pub mod lambert;
pub mod texture;

pub use lambert::Lambert;
pub use texture::{ColorTex, Texture};

use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// One direction drawn from a BSDF.
#[derive(Clone, Copy, Debug)]
pub struct BsdfSample {
    pub wi: Vec3A,
    /// `f · |cos θi| / pdf`: what the path throughput is multiplied by.
    pub weight: Rgb,
    /// Solid-angle density of `wi`; for delta lobes the discrete probability
    /// of the chosen lobe.
    pub pdf: f32,
    /// True when `wi` came from a Dirac lobe (mirror, smooth glass): `eval`
    /// and `pdf` are zero for it and light sampling cannot reach it.
    pub delta: bool,
}

/// The contract every scattering model implements, so tests can be generic.
pub trait Bxdf {
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb;
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32;
    /// `u_lobe` picks a lobe for mixtures; `u` drives the warp.
    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample>;
    /// True when every lobe is a Dirac delta (no point in light sampling).
    fn is_delta(&self) -> bool {
        false
    }
}

/// A BSDF with all its parameters resolved at one hit point.
#[derive(Clone, Copy, Debug)]
pub enum Bsdf {
    Lambert(Lambert),
}

impl Bxdf for Bsdf {
    #[inline]
    fn eval(&self, wo: Vec3A, wi: Vec3A) -> Rgb {
        match self {
            Bsdf::Lambert(b) => b.eval(wo, wi),
        }
    }
    #[inline]
    fn pdf(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        match self {
            Bsdf::Lambert(b) => b.pdf(wo, wi),
        }
    }
    #[inline]
    fn sample(&self, wo: Vec3A, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match self {
            Bsdf::Lambert(b) => b.sample(wo, u_lobe, u),
        }
    }
    #[inline]
    fn is_delta(&self) -> bool {
        match self {
            Bsdf::Lambert(b) => b.is_delta(),
        }
    }
}

/// A material as the scene describes it, with textured parameters.
#[derive(Clone, Debug)]
pub enum Material {
    Lambert {
        albedo: ColorTex,
    },
    /// The surface of an area light: black and non-reflecting, as in the
    /// Mitsuba references.
    Emitter,
}

impl Material {
    /// Resolves textures at surface coordinates `uv`.
    pub fn bsdf(&self, uv: Vec2, textures: &[Texture]) -> Bsdf {
        match self {
            Material::Lambert { albedo } => Bsdf::Lambert(Lambert {
                albedo: albedo.eval(uv, textures),
            }),
            Material::Emitter => Bsdf::Lambert(Lambert { albedo: Rgb::ZERO }),
        }
    }
}
