//! Isotropic microfacet distributions: normal distribution `D`, Smith
//! masking–shadowing and the sampling of microfacet normals.
//!
//! * **GGX / Trowbridge–Reitz** (Walter et al. 2007,
//!   <https://doi.org/10.2312/EGWR/EGSR07/195-206>), sampled by its
//!   distribution of *visible* normals with the spherical-cap method of
//!   Dupuy & Benyoub 2023 (<https://arxiv.org/abs/2306.05044>): the sample
//!   weight is `F·G2/G1 ≤ 1`, no sample is wasted behind the facet.
//! * **Beckmann**, sampled by `D·cos θm` (Walter et al. 2007, eq. 28–29).
//!
//! Shadowing is the **height-correlated Smith G2** = 1/(1 + Λ(wo) + Λ(wi)),
//! which Heitz 2014 ("Understanding the Masking-Shadowing Function",
//! <https://jcgt.org/published/0003/02/03/>) shows is the exact Smith form
//! for microsurfaces whose heights and slopes are independent; the separable
//! G1·G1 overestimates shadowing. Beckmann's Λ uses Walter's rational fit
//! (< 0.4 % error), not the erf form.
//!
//! Roughness: users give a perceptual `roughness` ∈ [0, 1] and
//! `alpha = roughness²` (Burley 2012, the glTF/Disney convention), clamped to
//! at least [`MIN_ALPHA`]; use `Mirror` for an ideally smooth surface.

use crate::math::trig::sin_cos_turns;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Below this the lobe is narrower than f32 can resolve well.
pub const MIN_ALPHA: f32 = 1e-3;

/// Shape of the microfacet normal distribution.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Distribution {
    /// Trowbridge–Reitz (GGX): long tails, sampled by visible normals.
    Ggx,
    /// Beckmann: Gaussian slopes, shorter tails, sampled by `D·cos θm`.
    Beckmann,
}

/// A distribution with its width. Directions are local (normal = +z) and
/// the functions expect `wo.z > 0` (callers flip two-sided cases).
#[derive(Clone, Copy, Debug)]
pub struct Microfacet {
    /// Which distribution.
    pub distribution: Distribution,
    /// Width α of the distribution (larger is rougher), at least [`MIN_ALPHA`].
    pub alpha: f32,
}

impl Microfacet {
    /// The distribution for a perceptual `roughness` ∈ [0, 1] (clamped):
    /// The distribution of width `alpha` itself (Mitsuba's `alpha`), clamped
    /// to [[`MIN_ALPHA`], 4].
    pub fn from_alpha(distribution: Distribution, alpha: f32) -> Self {
        Self {
            distribution,
            alpha: alpha.clamp(MIN_ALPHA, 4.0),
        }
    }

    /// `alpha = roughness²`, at least [`MIN_ALPHA`].
    pub fn from_roughness(distribution: Distribution, roughness: f32) -> Self {
        let r = roughness.clamp(0.0, 1.0);
        Self {
            distribution,
            alpha: (r * r).max(MIN_ALPHA),
        }
    }

    /// Microfacet normal density per unit projected area, ∫ D cos θm dωm = 1.
    pub fn d(&self, wm: Vec3A) -> f32 {
        if wm.z <= 0.0 {
            return 0.0;
        }
        // sin² from x, y: 1 − cos² cancels catastrophically near the pole,
        // where narrow lobes live.
        let (cos2, sin2) = (wm.z * wm.z, wm.x * wm.x + wm.y * wm.y);
        let a2 = self.alpha * self.alpha;
        match self.distribution {
            // α² / (π (sin²θ + α² cos²θ)²): no tan, finite at the horizon.
            Distribution::Ggx => {
                let t = sin2 + a2 * cos2;
                a2 / (PI * t * t)
            }
            Distribution::Beckmann => (-sin2 / (cos2 * a2)).exp() / (PI * a2 * cos2 * cos2),
        }
    }

    /// Smith Λ(w): G1 = 1/(1 + Λ).
    pub fn lambda(&self, w: Vec3A) -> f32 {
        let (cos2, sin2) = (w.z * w.z, w.x * w.x + w.y * w.y);
        if sin2 == 0.0 {
            return 0.0;
        }
        if cos2 == 0.0 {
            return f32::INFINITY;
        }
        let tan2 = sin2 / cos2;
        match self.distribution {
            Distribution::Ggx => 0.5 * ((1.0 + self.alpha * self.alpha * tan2).sqrt() - 1.0),
            Distribution::Beckmann => {
                let a = 1.0 / (self.alpha * tan2.sqrt());
                if a >= 1.6 {
                    0.0
                } else {
                    (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
                }
            }
        }
    }

    /// Smith masking of one direction `w` (z > 0): the fraction of microfacet area
    /// visible from `w`.
    pub fn g1(&self, w: Vec3A) -> f32 {
        1.0 / (1.0 + self.lambda(w))
    }

    /// Height-correlated masking–shadowing (Heitz 2014, eq. 99).
    pub fn g2(&self, wo: Vec3A, wi: Vec3A) -> f32 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }

    /// Draws a microfacet normal for `wo` (z > 0).
    pub fn sample_wm(&self, wo: Vec3A, u: Vec2) -> Vec3A {
        // (sin φ, cos φ) of φ = 2π·u.x without libm's sinf and cosf.
        let (sin_p, cos_p) = sin_cos_turns(u.x);
        match self.distribution {
            Distribution::Ggx => {
                // Stretch wo to the α = 1 configuration (a hemisphere).
                let a = self.alpha;
                let wo_std = Vec3A::new(wo.x * a, wo.y * a, wo.z).normalize();
                // Visible hemisphere normals = a spherical cap around wo_std
                // shifted by wo_std (Dupuy & Benyoub 2023, listing 3).
                let z = (1.0 - u.y) * (1.0 + wo_std.z) - wo_std.z;
                let sin = (1.0 - z * z).clamp(0.0, 1.0).sqrt();
                let h = Vec3A::new(sin * cos_p, sin * sin_p, z) + wo_std;
                // Unstretch back to roughness α.
                Vec3A::new(h.x * a, h.y * a, h.z.max(0.0)).normalize_or(Vec3A::Z)
            }
            Distribution::Beckmann => {
                // Invert the CDF of D·cos: tan²θm = −α² ln(1 − u).
                let tan2 = -self.alpha * self.alpha * (1.0 - u.y).ln();
                let cos = 1.0 / (1.0 + tan2).sqrt();
                let sin = (1.0 - cos * cos).max(0.0).sqrt();
                Vec3A::new(sin * cos_p, sin * sin_p, cos)
            }
        }
    }

    /// Density of [`Self::sample_wm`] per solid angle of `wm`.
    pub fn pdf_wm(&self, wo: Vec3A, wm: Vec3A) -> f32 {
        match self.distribution {
            // Visible normals: G1(wo) ⟨wo·wm⟩ D(wm) / cos θo.
            Distribution::Ggx => self.g1(wo) * wo.dot(wm).max(0.0) * self.d(wm) / wo.z,
            Distribution::Beckmann => self.d(wm) * wm.z.max(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫ over the upper hemisphere by the midpoint rule in (θ, φ).
    fn integrate(f: impl Fn(Vec3A) -> f32) -> f64 {
        let (nt, np) = (4000, 128);
        let (dt, dp) = (
            0.5 * std::f64::consts::PI / nt as f64,
            2.0 * std::f64::consts::PI / np as f64,
        );
        let mut sum = 0.0;
        for i in 0..nt {
            let t = (i as f64 + 0.5) * dt;
            for j in 0..np {
                let p = (j as f64 + 0.5) * dp;
                let w = Vec3A::new(
                    (t.sin() * p.cos()) as f32,
                    (t.sin() * p.sin()) as f32,
                    t.cos() as f32,
                );
                sum += f(w) as f64 * t.sin() * dt * dp;
            }
        }
        sum
    }

    #[test]
    fn microfacet_d_is_normalised_and_g1_projects_area() {
        for distribution in [Distribution::Ggx, Distribution::Beckmann] {
            for alpha in [0.1, 0.4, 1.0] {
                let m = Microfacet { distribution, alpha };
                let area = integrate(|wm| m.d(wm) * wm.z);
                assert!(
                    (area - 1.0).abs() < 2e-3,
                    "{distribution:?} α={alpha}: ∫D cos = {area}"
                );
                // Visible projected area equals the macro-surface's: ∫ G1 ⟨wo·wm⟩ D = cos θo.
                // Exact for GGX; Beckmann's Λ is a fit (Walter 2007: < 0.4 %).
                let wo = Vec3A::new(0.8f32.sin(), 0.0, 0.8f32.cos());
                let proj = integrate(|wm| m.g1(wo) * wo.dot(wm).max(0.0) * m.d(wm));
                let rel = (proj / wo.z as f64 - 1.0).abs();
                assert!(
                    rel < 5e-3,
                    "{distribution:?} α={alpha}: ∫G1⟨wo·wm⟩D / cos θo − 1 = {rel}"
                );
            }
        }
    }
}

/// A roughness parameter: a number or texture and the unit it is in.
#[derive(Clone, Debug, PartialEq)]
pub struct Roughness {
    /// The value at each point.
    pub tex: super::ScalarTex,
    /// True when the value is the distribution's α (Mitsuba's `alpha`), false
    /// for perceptual roughness r (α = r²).
    pub is_alpha: bool,
}

impl Roughness {
    /// A constant perceptual roughness.
    pub fn perceptual(r: f32) -> Self {
        Self {
            tex: super::Tex::Const(r),
            is_alpha: false,
        }
    }

    /// The distribution at texture coordinates `uv`.
    #[inline]
    pub fn microfacet(
        &self,
        distribution: Distribution,
        at: &super::TexPoint,
        textures: &[super::Texture],
    ) -> Microfacet {
        let r = self.tex.eval(at, textures);
        if self.is_alpha {
            Microfacet::from_alpha(distribution, r)
        } else {
            Microfacet::from_roughness(distribution, r)
        }
    }

    /// The perceptual roughness at `uv` (√α when the value is α).
    #[inline]
    pub fn perceptual_at(&self, at: &super::TexPoint, textures: &[super::Texture]) -> f32 {
        let r = self.tex.eval(at, textures);
        if self.is_alpha { r.max(0.0).sqrt() } else { r }
    }
}
