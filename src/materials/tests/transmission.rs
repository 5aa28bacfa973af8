//! The generic checks of [`super::check_all`] for models that also transmit
//! (rough glass): `wi` may cross the surface, so the χ² runs over the whole
//! sphere, agreement allows a refracted `eta`, energy is counted on flux
//! (`weight·eta²`, undoing the radiance scaling) and reciprocity is the
//! generalised one of Veach 1997 (§5.2): `f(a, c)/η(a)² = f(c, a)/η(c)²`,
//! with η(x) the index on x's side (1 above the surface, `ior` below).

use super::{SAMPLES, chi2};
use crate::materials::{BsdfSample, Bxdf};
use crate::math::{Pcg32, sampling};
use glam::Vec3A;

/// Runs every check at one `wo` (either side) and returns the flux energy
/// estimate `max over channels of E[f·|cos|/pdf·eta²]`, asserted < 1.01.
pub fn check_all_transmissive<B: Bxdf>(b: &B, ior: f32, wo: Vec3A, name: &str, seed: u64) -> f32 {
    let theta = wo.z.acos().to_degrees();
    let what = format!("{name} at θo = {theta:.0}°");
    let mut rng = Pcg32::new(seed, (theta * 100.0) as u64);
    let mut hist = vec![0u64; chi2::THETA_BINS * chi2::PHI_BINS];
    let mut sum = [0.0f64; 3];
    for _ in 0..SAMPLES {
        let Some(s) = b.sample(wo, rng.next_f32(), rng.next_vec2()) else {
            continue;
        };
        assert_agrees(b, ior, wo, s, &what);
        hist[chi2::cell_of(s.wi)] += 1;
        for (acc, w) in sum.iter_mut().zip(s.weight.to_array()) {
            *acc += (w * s.eta * s.eta) as f64;
        }
    }
    let pdf = |wi: Vec3A| b.pdf(wo, wi);
    if let Err(e) = chi2::test(&pdf, &hist, SAMPLES) {
        panic!("{what}: sampling does not follow the pdf: {e}");
    }
    check_generalised_reciprocity(b, ior, &mut rng, &what);
    let energy = sum
        .iter()
        .map(|s| (s / SAMPLES as f64) as f32)
        .fold(0.0, f32::max);
    assert!(
        energy < 1.01,
        "{what}: E[f·cos/pdf·η²] = {energy}, must be < 1.01"
    );
    energy
}

/// η on the side of `w`: 1 above the surface, `ior` below.
fn eta_of(w: Vec3A, ior: f32) -> f32 {
    if w.z > 0.0 { 1.0 } else { ior }
}

/// `weight == eval·|cos|/pdf`, `pdf == pdf(wo, wi)` and `eta` is the ratio
/// of the indices crossed, for one sample.
fn assert_agrees<B: Bxdf>(b: &B, ior: f32, wo: Vec3A, s: BsdfSample, what: &str) {
    assert!(
        (s.wi.length() - 1.0).abs() < 1e-3 && !s.delta,
        "{what}: |wi| = {}, delta {}",
        s.wi.length(),
        s.delta
    );
    let eta = eta_of(s.wi, ior) / eta_of(wo, ior);
    assert!(
        (s.eta - eta).abs() <= 1e-6 * eta,
        "{what}: eta {} for wo {} → wi {}, want {eta}",
        s.eta,
        wo,
        s.wi
    );
    super::assert_pdf_and_weight(b, wo, &s, what);
}

fn check_generalised_reciprocity<B: Bxdf>(b: &B, ior: f32, rng: &mut Pcg32, what: &str) {
    let mut transmitting = 0;
    for _ in 0..4_000 {
        let a = sampling::uniform_sphere(rng.next_vec2());
        let c = sampling::uniform_sphere(rng.next_vec2());
        let (ea, ec) = (eta_of(a, ior), eta_of(c, ior));
        let (f_ac, f_ca) = (b.eval(a, c) / (ea * ea), b.eval(c, a) / (ec * ec));
        let tol = 1e-4 * f_ac.max_element().max(f_ca.max_element()) + 1e-7;
        assert!(
            (f_ac - f_ca).abs().max_element() <= tol,
            "{what}: f(a,c)/η(a)² {f_ac} ≠ f(c,a)/η(c)² {f_ca} for a {a}, c {c}"
        );
        transmitting += (a.z * c.z < 0.0 && f_ac.max_element() > 0.0) as u32;
    }
    assert!(
        transmitting > 100,
        "{what}: only {transmitting} pairs transmitted"
    );
}
