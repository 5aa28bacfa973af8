//! Generic checks every non-delta [`Bxdf`] runs from its own test module:
//! χ² of `sample` against `pdf`, agreement of `sample`/`eval`/`pdf`, energy,
//! reciprocity and the horizon. Models call [`check_all`] per setting.

pub mod chi2;
pub mod transmission;

use super::Bxdf;
use crate::math::{Pcg32, Rgb, sampling};
use glam::Vec3A;

/// Samples per χ² run: a few tens of milliseconds in the test profile.
const SAMPLES: u64 = 200_000;

/// The incident directions every model is tested at: θo = 10°, 45°, 80°
/// (φ off the bin edges so lobes do not straddle them).
pub fn incidences() -> [Vec3A; 3] {
    [10.0f32, 45.0, 80.0].map(|deg| {
        let (st, ct) = deg.to_radians().sin_cos();
        let phi = 0.3f32;
        Vec3A::new(st * phi.cos(), st * phi.sin(), ct)
    })
}

/// Runs every generic check at one `wo` (z > 0) and returns the energy
/// estimate `max over channels of E[f·|cos|/pdf]`, already asserted < 1.01.
pub fn check_all<B: Bxdf>(b: &B, wo: Vec3A, name: &str, seed: u64) -> f32 {
    let theta = wo.z.acos().to_degrees();
    let what = format!("{name} at θo = {theta:.0}°");
    let mut rng = Pcg32::new(seed, (theta * 100.0) as u64);
    let mut hist = vec![0u64; chi2::THETA_BINS * chi2::PHI_BINS];
    let mut sum = [0.0f64; 3];
    for _ in 0..SAMPLES {
        let Some(s) = b.sample(wo, rng.next_f32(), rng.next_vec2()) else {
            continue;
        };
        assert_agrees(b, wo, s, &what);
        hist[chi2::cell_of(s.wi)] += 1;
        for (acc, w) in sum.iter_mut().zip(s.weight.to_array()) {
            *acc += w as f64;
        }
    }
    let pdf = |wi: Vec3A| b.pdf(wo, wi);
    if let Err(e) = chi2::test(&pdf, &hist, SAMPLES) {
        panic!("{what}: sampling does not follow the pdf: {e}");
    }

    // Two-sided: from below, samples stay below and still agree.
    let below = Vec3A::new(wo.x, wo.y, -wo.z);
    for _ in 0..10_000 {
        let Some(s) = b.sample(below, rng.next_f32(), rng.next_vec2()) else {
            continue;
        };
        assert!(s.wi.z < 0.0, "{what}, from below: wi = {} went through", s.wi);
        assert_agrees(b, below, s, &what);
    }
    check_reciprocity_and_horizon(b, &mut rng, &what);

    let energy = sum
        .iter()
        .map(|s| (s / SAMPLES as f64) as f32)
        .fold(0.0, f32::max);
    assert!(energy < 1.01, "{what}: E[f·cos/pdf] = {energy}, must be < 1.01");
    energy
}

/// `weight == eval·|cos|/pdf` and `pdf == pdf(wo, wi)` for one sample.
fn assert_agrees<B: Bxdf>(b: &B, wo: Vec3A, s: super::BsdfSample, what: &str) {
    assert!(
        (s.wi.length() - 1.0).abs() < 1e-3,
        "{what}: |wi| = {}",
        s.wi.length()
    );
    assert!(
        !s.delta && s.eta == 1.0,
        "{what}: a reflection sample is neither delta nor refracted"
    );
    assert_pdf_and_weight(b, wo, &s, what);
}

/// `pdf > 0`, `pdf == pdf(wo, wi)` and `weight == eval·|cos|/pdf` for one
/// sample: the part of the agreement check every harness shares.
pub(super) fn assert_pdf_and_weight<B: Bxdf>(b: &B, wo: Vec3A, s: &super::BsdfSample, what: &str) {
    assert!(
        s.pdf > 0.0 && s.weight.is_finite(),
        "{what}: pdf {} weight {}",
        s.pdf,
        s.weight
    );
    let pdf = b.pdf(wo, s.wi);
    assert!(
        (pdf - s.pdf).abs() <= 2e-3 * s.pdf,
        "{what}: sample pdf {} but pdf(wo, wi) = {pdf} at wi = {}",
        s.pdf,
        s.wi
    );
    let want = b.eval(wo, s.wi) * s.wi.z.abs() / pdf;
    let err = (want - s.weight).abs().max_element();
    assert!(
        err <= 2e-3 * want.max_element() + 1e-6,
        "{what}: weight {} ≠ f·cos/pdf {want}",
        s.weight
    );
}

fn check_reciprocity_and_horizon<B: Bxdf>(b: &B, rng: &mut Pcg32, what: &str) {
    for _ in 0..2_000 {
        let a = sampling::uniform_hemisphere(rng.next_vec2());
        let c = sampling::uniform_hemisphere(rng.next_vec2());
        let (f_ac, f_ca) = (b.eval(a, c), b.eval(c, a));
        let tol = 1e-4 * f_ac.max_element().max(f_ca.max_element()) + 1e-7;
        assert!(
            (f_ac - f_ca).abs().max_element() <= tol,
            "{what}: f(a,c) {f_ac} ≠ f(c,a) {f_ca}"
        );
        let below = Vec3A::new(c.x, c.y, -c.z);
        assert_eq!(b.pdf(a, below), 0.0, "{what}: pdf must be 0 across the horizon");
        assert_eq!(
            b.eval(a, below),
            Rgb::ZERO,
            "{what}: f must be 0 across the horizon"
        );
    }
}

/// Energy at θo = 0°, 5°, …, 85°, 89° (importance-sampled, 20 000 samples
/// each): the claims "never reflects more than it receives" hold at every
/// incidence, not only at the three χ² angles. Returns the largest estimate.
pub fn assert_energy_sweep<B: Bxdf>(b: &B, name: &str) -> f32 {
    let mut rng = Pcg32::new(0x5eed, 1);
    let mut worst = 0.0f32;
    for deg in (0..90).step_by(5).chain([89]) {
        let (st, ct) = (deg as f32).to_radians().sin_cos();
        let wo = Vec3A::new(st, 0.0, ct);
        let n = 20_000;
        let mut sum = Rgb::ZERO;
        for _ in 0..n {
            if let Some(s) = b.sample(wo, rng.next_f32(), rng.next_vec2()) {
                sum += s.weight;
            }
        }
        let e = (sum / n as f32).max_element();
        assert!(
            e < 1.01,
            "{name} at θo = {deg}°: E[f·cos/pdf] = {e}, must be < 1.01"
        );
        worst = worst.max(e);
    }
    worst
}
