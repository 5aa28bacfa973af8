//! The rough dielectric coat of [`super::RoughPlastic`] and its two
//! precomputed quantities, integrated once per coat at load by the rule
//! Mitsuba 3's `roughplastic` uses in `parameters_changed`
//! (<https://github.com/mitsuba-renderer/mitsuba3/blob/master/src/bsdfs/roughplastic.cpp>,
//! `eval_transmittance` / `eval_reflectance` in `include/mitsuba/render/microfacet.h`).
//!
//! * **t(μ)**, the rough interface's transmittance: of the light arriving from
//!   outside at cos θ = μ, the fraction that crosses the rough boundary
//!   (single scattering, unoccluded on the way in). Over the visible normals
//!   `D_wo(m) = G1(wo)·⟨wo·m⟩·D(m)/cos θo`,
//!   `t(μ) = ∫ D_wo(m) (1 − F(wo·m; η)) G1(wt(m)) dm`, with `wt` the refracted
//!   direction (0 if it does not go down). Tabulated at `μ_j = max(10⁻⁶, j/63)`,
//!   j = 0…63, and linearly interpolated (Mitsuba's
//!   `MI_ROUGH_TRANSMITTANCE_RES` = 64 and `lerp_gather`).
//! * **R_int**, the internal diffuse reflectance: the directional reflectance
//!   `r(μ) = ∫ D_wo(m) F(wo·m; 1/η) G1(wr(m)) dm` of the same interface seen
//!   from inside (wr the mirrored direction, 0 if it does not go back down),
//!   averaged over a cosine-weighted hemisphere. Mitsuba defines it as
//!   `R_int = 2 · mean_j(r(μ_j)·μ_j)` over the same 64-point grid, and so do we.
//!
//! # Integration
//! Each directional integral is taken over the unit square of a visible-normal
//! warp with an n × n Gauss–Legendre rule: n = 32 when light enters the denser
//! side (no total internal reflection) and 128 otherwise (its kink needs more
//! nodes), Mitsuba's choice. The warp is Mitsuba's GGX visible-normal sampler
//! (Heitz 2018, <https://jcgt.org/published/0007/04/01/>, concentric-disk
//! form), under which the GGX integrand is exactly the bracket above. Beckmann
//! uses the same warp as a proposal, weighted by its visible-normal density
//! over GGX's at equal α: `G1ᴮ(wo)/G1ᴳ(wo) · e^{−x}(1+x)²`, `x = tan²θm/α²`,
//! smooth and at most 4/e; it takes n = 64 where GGX takes 32 to be as
//! accurate. Mitsuba samples Beckmann's visible normals directly, which
//! normalises them with the *exact* (erf) Smith G1ᴮ(wo); so do we, while the
//! outgoing G1 in the integrand is Walter's rational fit, as in Mitsuba.
//!
//! # Accuracy
//! * Against Mitsuba (GGX α 0.1, η 1.5, the tables its `roughplastic` builds):
//!   every t(μ_j) within 1.7·10⁻⁵ (2.9·10⁻⁵ relative), R_int within 10⁻⁹
//!   relative: the same rule, in f32 (test `rough_coat_matches_mitsuba_tables`).
//!   Mitsuba 3.9.1's `roughplastic` evaluated directly (GGX α 0.1, 0.3) gives
//!   the same values and pdfs within 4·10⁻⁶; Beckmann (α 0.3), whose warp
//!   differs, within 4·10⁻⁴ (`rough_plastic_matches_mitsuba_eval_and_pdf`).
//! * Against converged integrals (n = 256), for GGX and Beckmann, α 0.01–1,
//!   η 0.8–2.4: t within 4.3·10⁻⁴, worst at μ = 1, where the warp's edge in
//!   slope space is steepest; plain Monte Carlo over ronray's own samplers
//!   agrees within its noise. Mitsuba's 64-point mean for R_int is 0.5–1.5 %
//!   *below* the converged cosine-weighted average (0.5519 vs 0.5600 for the
//!   reference coat), which makes the diffuse lobe 0.5–2 % darker. We
//!   keep Mitsuba's rule on purpose, so that ronray's rough plastic is
//!   Mitsuba's and renders match its references (test
//!   `rough_coat_rule_error_is_bounded` pins both figures).
//! * Linear interpolation between the 64 points adds up to 5·10⁻⁴ (α 0.1)
//!   and 3·10⁻³ (α ≤ 0.01 near grazing, or η < 1 near μ = 1); more only in
//!   the first cell (within 0.9° of grazing), where the cosine hides it.
//!
//! Cost: 64 × (32² + 128²) ≈ 1.1 M integrand evaluations (Beckmann 1.3 M),
//! 50–110 ms on two cores (the μ rows run on the rayon pool); the loader
//! builds one coat per distinct (distribution, α, η) and materials share it.

use super::{Distribution, Microfacet, fresnel, reflect};
use crate::math::sampling::concentric_disk;
use glam::{Vec2, Vec3A};
use rayon::prelude::*;

/// Points in the t(μ) table (Mitsuba's `MI_ROUGH_TRANSMITTANCE_RES`).
pub const TABLE_POINTS: usize = 64;

/// A rough dielectric coat and its tabulated transmittance t(μ) and internal
/// reflectance R_int (see the module docs).
#[derive(Clone, Debug)]
pub struct RoughCoat {
    /// The coat's microfacet distribution and α.
    pub microfacet: Microfacet,
    /// η(inside)/η(outside) of the coat.
    pub eta: f32,
    /// t(μ_j) at μ_j = max(10⁻⁶, j/63).
    pub transmittance: [f32; TABLE_POINTS],
    /// R_int: the coat's cosine-weighted reflectance seen from inside.
    pub internal_reflectance: f32,
}

impl RoughCoat {
    /// Integrates both tables (see the module docs); `eta` > 0.
    pub fn new(microfacet: Microfacet, eta: f32) -> Self {
        let mu = |j: usize| (j as f32 / (TABLE_POINTS - 1) as f32).max(1e-6);
        let t_rule = GaussLegendre::new(nodes(microfacet.distribution, eta));
        let r_rule = GaussLegendre::new(nodes(microfacet.distribution, 1.0 / eta));
        let rows: Vec<(f32, f64)> = (0..TABLE_POINTS)
            .into_par_iter()
            .map(|j| {
                let t = albedo(&microfacet, mu(j), eta, Lobe::Transmission, &t_rule);
                let r = albedo(&microfacet, mu(j), 1.0 / eta, Lobe::Reflection, &r_rule);
                (t as f32, r * mu(j) as f64)
            })
            .collect();
        let mut transmittance = [0.0; TABLE_POINTS];
        for (slot, (t, _)) in transmittance.iter_mut().zip(&rows) {
            *slot = *t;
        }
        let mean = rows.iter().map(|(_, rm)| rm).sum::<f64>() / TABLE_POINTS as f64;
        Self {
            microfacet,
            eta,
            transmittance,
            internal_reflectance: (2.0 * mean) as f32,
        }
    }

    /// t(cos θ) for cos θ ∈ [0, 1], linearly interpolated in the table.
    #[inline]
    pub fn t(&self, cos: f32) -> f32 {
        let x = cos.clamp(0.0, 1.0) * (TABLE_POINTS - 1) as f32;
        let i = (x as usize).min(TABLE_POINTS - 2);
        let (a, b) = (self.transmittance[i], self.transmittance[i + 1]);
        a + (b - a) * (x - i as f32)
    }
}

/// Gauss–Legendre order per axis: Mitsuba's 32 without total internal
/// reflection (`eta` > 1) and 128 with it; Beckmann, reweighted from the GGX
/// warp, needs 64 to stay as accurate as GGX at 32.
pub(crate) fn nodes(distribution: Distribution, eta: f32) -> usize {
    match (eta > 1.0, distribution) {
        (false, _) => 128,
        (true, Distribution::Ggx) => 32,
        (true, Distribution::Beckmann) => 64,
    }
}

#[derive(Clone, Copy, PartialEq)]
pub(crate) enum Lobe {
    Reflection,
    Transmission,
}

/// Single-scattering albedo of one lobe of a rough dielectric boundary for
/// light arriving at `cos θ = mu` from the side where η(other)/η(this) =
/// `eta`, by `rule` × `rule` over the visible-normal warp.
pub(crate) fn albedo(m: &Microfacet, mu: f32, eta: f32, lobe: Lobe, rule: &GaussLegendre) -> f64 {
    let wo = Vec3A::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
    // Beckmann: visible-normal density over GGX's proposal, the G1 part;
    // the exact G1 normalises Beckmann's visible normals, as Mitsuba's sampler does.
    let ggx = Microfacet {
        distribution: Distribution::Ggx,
        alpha: m.alpha,
    };
    let g1_ratio = (beckmann_g1_exact(m.alpha as f64, mu as f64) / ggx.g1(wo) as f64) as f32;
    let mut sum = 0.0f64;
    for (&xa, &wa) in rule.nodes.iter().zip(&rule.weights) {
        for (&xb, &wb) in rule.nodes.iter().zip(&rule.weights) {
            let wm = ggx_visible_normal(m.alpha, wo, Vec2::new(xa, xb));
            let mut value = integrand(m, wo, wm, eta, lobe);
            if m.distribution == Distribution::Beckmann && value != 0.0 {
                // D_beckmann/D_ggx at equal α, in closed form (both ∝ 1/cos⁴θm).
                let x = (wm.x * wm.x + wm.y * wm.y) / (wm.z * wm.z * m.alpha * m.alpha);
                let ratio = (-x).exp() * (1.0 + x) * (1.0 + x);
                value *= if ratio.is_finite() { g1_ratio * ratio } else { 0.0 };
            }
            sum += value as f64 * wa * wb;
        }
    }
    sum
}

/// Beckmann's exact Smith G1 = 1/(1 + Λ) at `cos θ = mu`, with
/// Λ = (erf(a) − 1)/2 + e^{−a²}/(2a√π), a = 1/(α tan θ) (Walter et al. 2007,
/// eq. 27; the renderer uses their rational fit, within 0.35 % of it).
fn beckmann_g1_exact(alpha: f64, mu: f64) -> f64 {
    let tan = (1.0 - mu * mu).max(0.0).sqrt() / mu;
    if tan == 0.0 {
        return 1.0;
    }
    let a = 1.0 / (alpha * tan);
    let lambda = -0.5 * erfc(a) + (-a * a).exp() / (2.0 * a * std::f64::consts::PI.sqrt());
    1.0 / (1.0 + lambda.max(0.0))
}

/// Complementary error function, relative error < 1.2·10⁻⁷ (Chebyshev fit of
/// Press et al., *Numerical Recipes*, 3rd ed., §6.2.2).
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -1.26551223
        + t * (1.00002368
            + t * (0.37409196
                + t * (0.09678418
                    + t * (-0.18628806
                        + t * (0.27886807
                            + t * (-1.13520398 + t * (1.48851587 + t * (-0.82215223 + t * 0.17087277))))))));
    let r = t * (-z * z + poly).exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

/// (1 − F)·G1(wt) or F·G1(wr) for one microfacet normal `wm` visible from `wo`.
fn integrand(m: &Microfacet, wo: Vec3A, wm: Vec3A, eta: f32, lobe: Lobe) -> f32 {
    let c = wo.dot(wm);
    if c <= 0.0 {
        return 0.0;
    }
    let f = fresnel::dielectric(c, eta);
    match lobe {
        Lobe::Reflection => {
            let wr = reflect(wo, wm);
            if wr.z <= 0.0 { 0.0 } else { f * m.g1(wr) }
        }
        Lobe::Transmission => {
            // Snell about wm; F = 1 under total internal reflection.
            let sin2_t = (1.0 - c * c) / (eta * eta);
            if f >= 1.0 || sin2_t >= 1.0 {
                return 0.0;
            }
            let cos_t = (1.0 - sin2_t).sqrt();
            let wt = -wo / eta + (c / eta - cos_t) * wm;
            if wt.z >= 0.0 { 0.0 } else { (1.0 - f) * m.g1(wt) }
        }
    }
}

/// Mitsuba's GGX visible-normal warp (Heitz 2018, slope-space form with the
/// concentric disk), for `wo.z` ≥ 0. It differs from
/// [`Microfacet::sample_wm`]'s spherical caps only in how it lays the square
/// over the normals, which changes the quadrature's error, not its limit.
pub(crate) fn ggx_visible_normal(alpha: f32, wo: Vec3A, u: Vec2) -> Vec3A {
    // Stretch to the α = 1 configuration.
    let w = Vec3A::new(alpha * wo.x, alpha * wo.y, wo.z).normalize();
    let (cos_t, sin2_t) = (w.z, w.x * w.x + w.y * w.y);
    let sin_t = sin2_t.sqrt();
    let (cos_phi, sin_phi) = if sin2_t > 4.0 * f32::EPSILON {
        ((w.x / sin_t).clamp(-1.0, 1.0), (w.y / sin_t).clamp(-1.0, 1.0))
    } else {
        (1.0, 0.0)
    };
    // A disk point, its upper half squeezed toward the visible projection.
    let p = concentric_disk(u);
    let s = 0.5 * (1.0 + cos_t);
    let lower = (1.0 - p.x * p.x).max(0.0).sqrt();
    let py = lower + (p.y - lower) * s;
    let z = (1.0 - p.x * p.x - py * py).max(0.0).sqrt();
    // Back to slopes, rotated to wo's azimuth and unstretched.
    let norm = 1.0 / (sin_t * py + cos_t * z);
    let (sx, sy) = ((cos_t * py - sin_t * z) * norm, p.x * norm);
    let sx_r = (cos_phi * sx - sin_phi * sy) * alpha;
    let sy_r = (sin_phi * sx + cos_phi * sy) * alpha;
    Vec3A::new(-sx_r, -sy_r, 1.0).normalize()
}

/// Gauss–Legendre nodes and weights mapped to [0, 1] (weights sum to 1).
pub(crate) struct GaussLegendre {
    nodes: Vec<f32>,
    weights: Vec<f64>,
}

impl GaussLegendre {
    /// Newton's method on the Legendre recurrence from Tricomi's initial
    /// guesses, converged to f64 precision.
    pub(crate) fn new(n: usize) -> Self {
        let (mut nodes, mut weights) = (Vec::with_capacity(n), Vec::with_capacity(n));
        for i in 1..=n {
            let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            let mut dp = 1.0;
            for _ in 0..100 {
                // P_n(x) and its derivative by the three-term recurrence.
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-15 {
                    break;
                }
            }
            nodes.push((0.5 * x + 0.5) as f32);
            weights.push(1.0 / ((1.0 - x * x) * dp * dp));
        }
        Self { nodes, weights }
    }
}

#[cfg(test)]
#[path = "tests/rough_coat.rs"]
pub(crate) mod tests;
