//! χ² goodness-of-fit of a sampler against its own pdf, after Mitsuba 3's
//! `ChiSquareTest` (<https://github.com/mitsuba-renderer/mitsuba3/blob/master/src/python/python/chi2.py>).
//!
//! The sphere is cut into θ×φ cells; each cell's expected count is the pdf
//! integrated over it (2-D Simpson, refined until it stops changing), cells
//! expecting fewer than 5 samples are pooled, and samples the sampler
//! rejected form one more cell (expected `N·(1 − ∫pdf)`). The statistic's
//! p-value comes from the regularised upper incomplete gamma function.

use glam::Vec3A;
use std::f64::consts::PI;

pub const THETA_BINS: usize = 20;
pub const PHI_BINS: usize = 40;
const POOL_BELOW: f64 = 5.0;
const SIGNIFICANCE: f64 = 0.01;
/// Number of χ² runs in the crate, for the Šidák correction: each run is
/// tested at `1 − (1 − 0.01)^(1/RUNS)` so that the whole suite has a 1 %
/// false-alarm rate. Count (update when adding runs): Lambert 3,
/// Oren–Nayar 6, Phong 12, Blinn–Phong 18, Cook–Torrance 19,
/// MetalPlastic 27, uniform sphere 1, RoughPlastic 21, RoughGlass 30.
pub const RUNS: u32 = 137;

/// Cell index of a unit direction.
pub fn cell_of(w: Vec3A) -> usize {
    let theta = (w.z as f64).clamp(-1.0, 1.0).acos();
    let phi = (w.y as f64).atan2(w.x as f64) + PI;
    let ti = ((theta / PI * THETA_BINS as f64) as usize).min(THETA_BINS - 1);
    let pi = ((phi / (2.0 * PI) * PHI_BINS as f64) as usize).min(PHI_BINS - 1);
    ti * PHI_BINS + pi
}

fn dir(theta: f64, phi: f64) -> Vec3A {
    // φ measured from −π, matching `cell_of`.
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = (phi - PI).sin_cos();
    Vec3A::new((st * cp) as f32, (st * sp) as f32, ct as f32)
}

/// ∫∫ pdf sinθ dθ dφ over one cell by composite Simpson with `n` intervals.
/// The cell is shrunk by a relative 1e-5 so edge nodes see the pdf's limit
/// from inside: at θ = 90° the pdf jumps, and f32 cos(π/2) is not 0.
fn simpson(pdf: &dyn Fn(Vec3A) -> f32, t0: f64, t1: f64, p0: f64, p1: f64, n: usize) -> f64 {
    const INSET: f64 = 1e-5;
    let (t0, t1) = (t0 + INSET * (t1 - t0), t1 - INSET * (t1 - t0));
    let (ht, hp) = ((t1 - t0) / n as f64, (p1 - p0) / n as f64);
    let w = |i: usize| {
        if i == 0 || i == n {
            1.0
        } else if i % 2 == 1 {
            4.0
        } else {
            2.0
        }
    };
    let mut sum = 0.0;
    for i in 0..=n {
        let t = t0 + i as f64 * ht;
        let mut row = 0.0;
        for j in 0..=n {
            row += w(j) * pdf(dir(t, p0 + j as f64 * hp)) as f64;
        }
        sum += w(i) * t.sin() * row;
    }
    sum * ht * hp / 9.0 / (1.0 - 2.0 * INSET)
}

/// Expected probability of every cell.
pub fn cell_probabilities(pdf: &dyn Fn(Vec3A) -> f32) -> Vec<f64> {
    let (dt, dp) = (PI / THETA_BINS as f64, 2.0 * PI / PHI_BINS as f64);
    let mut out = Vec::with_capacity(THETA_BINS * PHI_BINS);
    for ti in 0..THETA_BINS {
        for pi in 0..PHI_BINS {
            let (t0, p0) = (ti as f64 * dt, pi as f64 * dp);
            // Double the resolution until two estimates agree.
            let mut n = 8;
            let mut prev = simpson(pdf, t0, t0 + dt, p0, p0 + dp, n);
            loop {
                n *= 2;
                let next = simpson(pdf, t0, t0 + dt, p0, p0 + dp, n);
                let done = (next - prev).abs() <= 1e-7 + 1e-4 * next.abs();
                prev = next;
                if done || n >= 512 {
                    break;
                }
            }
            out.push(prev);
        }
    }
    out
}

/// Runs the test; `hist` counts samples per cell, `n` is the number of
/// draws including rejected ones. Returns (statistic, dof, p-value).
pub fn test(pdf: &dyn Fn(Vec3A) -> f32, hist: &[u64], n: u64) -> Result<(f64, u32, f64), String> {
    let probs = cell_probabilities(pdf);
    let mut cells: Vec<(f64, f64)> = Vec::with_capacity(probs.len() + 1);
    for (i, (&p, &obs)) in probs.iter().zip(hist).enumerate() {
        if p == 0.0 && obs > 0 {
            let (ti, pi) = (i / PHI_BINS, i % PHI_BINS);
            return Err(format!("{obs} samples in cell θ#{ti} φ#{pi} where the pdf is 0"));
        }
        cells.push((p * n as f64, obs as f64));
    }
    let total: f64 = probs.iter().sum();
    if total > 1.0 + 1e-3 {
        return Err(format!("pdf integrates to {total} > 1 over the sphere"));
    }
    let accepted: u64 = hist.iter().sum();
    cells.push(((1.0 - total).max(0.0) * n as f64, (n - accepted) as f64));
    // The worst cells (last = rejected samples), for the failure message.
    let mut worst: Vec<(f64, usize)> = cells
        .iter()
        .enumerate()
        .filter(|(_, c)| c.0 >= POOL_BELOW)
        .map(|(i, &(e, o))| ((o - e) * (o - e) / e, i))
        .collect();
    worst.sort_by(|a, b| b.0.total_cmp(&a.0));
    let worst: Vec<String> = worst
        .iter()
        .take(3)
        .map(|&(_, i)| {
            let (e, o) = cells[i];
            match i {
                i if i == probs.len() => format!("rejected: {o} vs {e:.1}"),
                i => format!("θ#{} φ#{}: {o} vs {e:.1}", i / PHI_BINS, i % PHI_BINS),
            }
        })
        .collect();

    // Pool the smallest cells until the pool expects at least 5.
    cells.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (mut pool_e, mut pool_o, mut stat, mut dof) = (0.0, 0.0, 0.0, 0i64);
    for (e, o) in cells {
        if e < POOL_BELOW || (pool_e > 0.0 && pool_e < POOL_BELOW) {
            pool_e += e;
            pool_o += o;
        } else {
            stat += (o - e) * (o - e) / e;
            dof += 1;
        }
    }
    if pool_e > 0.0 {
        stat += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        dof += 1;
    }
    dof -= 1;
    if dof <= 0 {
        return Ok((stat, 0, 1.0));
    }
    let p = gamma_q(dof as f64 / 2.0, stat / 2.0);
    let alpha = 1.0 - (1.0 - SIGNIFICANCE).powf(1.0 / RUNS as f64);
    if p < alpha {
        let worst = worst.join(", ");
        return Err(format!(
            "χ² = {stat:.1}, {dof} dof: p = {p:.2e} < {alpha:.2e}; worst {worst}"
        ));
    }
    Ok((stat, dof as u32, p))
}

/// ln Γ(x), Lanczos approximation (g = 7, n = 9), |error| < 1e-13.
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return (PI / (PI * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + 7.5;
    let a = C[0] + (1..9).map(|i| C[i] / (x + i as f64)).sum::<f64>();
    0.5 * (2.0 * PI).ln() + (x + 0.5) * t.ln() - t + a.ln()
}

/// Regularised upper incomplete gamma Q(a, x) = Γ(a, x)/Γ(a): the χ² tail
/// probability is Q(dof/2, χ²/2). Series below a + 1, continued fraction
/// (modified Lentz) above, as in Numerical Recipes §6.2.
pub fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let prefactor = (-x + a * x.ln() - ln_gamma(a)).exp();
    if x < a + 1.0 {
        let (mut ap, mut del) = (a, 1.0 / a);
        let mut sum = del;
        for _ in 0..10_000 {
            ap += 1.0;
            del *= x / ap;
            sum += del;
            if del.abs() < sum.abs() * 1e-15 {
                break;
            }
        }
        (1.0 - sum * prefactor).max(0.0)
    } else {
        const TINY: f64 = 1e-300;
        let mut b = x + 1.0 - a;
        let (mut c, mut d) = (1.0 / TINY, 1.0 / b);
        let mut h = d;
        for i in 1..10_000 {
            let an = -(i as f64) * (i as f64 - a);
            b += 2.0;
            d = an * d + b;
            d = if d.abs() < TINY { TINY } else { d };
            c = b + an / c;
            c = if c.abs() < TINY { TINY } else { c };
            d = 1.0 / d;
            let del = d * c;
            h *= del;
            if (del - 1.0).abs() < 1e-15 {
                break;
            }
        }
        prefactor * h
    }
}

#[test]
fn chi2_gamma_q_matches_tables() {
    // Q(1, x) = e^{−x}; χ² critical values: (dof 1, 3.841) → 0.05,
    // (dof 10, 23.209) → 0.01, (dof 100, 124.342) → 0.05.
    for x in [0.1, 1.0, 5.0, 30.0] {
        assert!((gamma_q(1.0, x) - (-x).exp()).abs() < 1e-12, "Q(1,{x})");
    }
    for (dof, stat, p) in [
        (1.0, 3.841_46, 0.05),
        (10.0, 23.209_3, 0.01),
        (100.0, 124.342, 0.05),
    ] {
        let got = gamma_q(dof / 2.0, stat / 2.0);
        assert!(
            (got - p).abs() < 1e-4,
            "dof {dof}, χ² {stat}: p = {got}, want {p}"
        );
    }
}

#[test]
fn chi2_uniform_sphere_passes_and_wrong_pdf_fails() {
    use crate::math::{Pcg32, sampling};
    let mut rng = Pcg32::new(11, 3);
    let n = 100_000u64;
    let mut hist = vec![0u64; THETA_BINS * PHI_BINS];
    for _ in 0..n {
        hist[cell_of(sampling::uniform_sphere(rng.next_vec2()))] += 1;
    }
    let uniform = |_: Vec3A| sampling::UNIFORM_SPHERE_PDF;
    test(&uniform, &hist, n).expect("uniform samples against the uniform pdf");
    let tilted = |w: Vec3A| sampling::UNIFORM_SPHERE_PDF * (1.0 + 0.1 * w.z);
    assert!(test(&tilted, &hist, n).is_err(), "a 10 % tilt must be detected");
}
