//! The coat tables against Mitsuba's, against converged integrals and
//! against Monte Carlo with ronray's own samplers.

use super::*;
use crate::math::Pcg32;

/// Mitsuba 3.9.1's tables for GGX α 0.1, int_ior 1.5, ext_ior 1, extracted
/// from `roughplastic` (the tables Mitsuba's plugin builds for that coat, rounded to
/// 10 decimals): t(μ_j) at μ_j = max(10⁻⁶, j/63), and R_int.
pub(crate) const MITSUBA_T: [f64; TABLE_POINTS] = [
    0.5719763816,
    0.5692859302,
    0.5696467263,
    0.5736802637, //
    0.5813420271,
    0.5921726962,
    0.6055084754,
    0.6206636307, //
    0.6370136185,
    0.6540358625,
    0.6713160991,
    0.6885336698, //
    0.7054532087,
    0.7219013763,
    0.7377627770,
    0.7529543807, //
    0.7674299999,
    0.7811642533,
    0.7941484347,
    0.8063889875, //
    0.8178999798,
    0.8287027101,
    0.8388193622,
    0.8482810231, //
    0.8571171075,
    0.8653590959,
    0.8730369930,
    0.8801825746, //
    0.8868265341,
    0.8929972039,
    0.8987265565,
    0.9040369233, //
    0.9089569319,
    0.9135130456,
    0.9177259235,
    0.9216188808, //
    0.9252125766,
    0.9285279651,
    0.9315828525,
    0.9343947497, //
    0.9369810695,
    0.9393549943,
    0.9415328547,
    0.9435275378, //
    0.9453526198,
    0.9470181350,
    0.9485361837,
    0.9499168004, //
    0.9511718886,
    0.9523054817,
    0.9533296801,
    0.9542518620, //
    0.9550807829,
    0.9558194925,
    0.9564757625,
    0.9570570696, //
    0.9575671521,
    0.9580144703,
    0.9583973519,
    0.9587275036, //
    0.9590044337,
    0.9592323721,
    0.9594168282,
    0.9595594742, //
];
pub(crate) const MITSUBA_R_INT: f64 = 0.5518937115950011;

/// One Mitsuba `eval`/`pdf` pair of `tests/fixtures/refs/rough_bsdfs.json`
/// (made by `make_rough_bsdfs.py` there), in ronray's direction convention.
pub(crate) struct MitsubaCase {
    pub wo: Vec3A,
    pub wi: Vec3A,
    /// f·|cos θi|.
    pub f_cos: crate::math::Rgb,
    pub pdf: f32,
}

/// The fixture's models of one kind (`rough_plastic`, `rough_dielectric`):
/// each with its distribution, α and its cases.
pub(crate) fn mitsuba_bsdfs(kind: &str) -> Vec<(serde_json::Value, Vec<MitsubaCase>)> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/refs/rough_bsdfs.json"
    );
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let json: serde_json::Value = serde_json::from_str(&text).expect("fixture is JSON");
    let v = |x: &serde_json::Value| {
        let a: Vec<f32> = x
            .as_array()
            .expect("array")
            .iter()
            .map(|c| c.as_f64().unwrap_or(0.0) as f32)
            .collect();
        Vec3A::new(a[0], a[1], a[2])
    };
    json[kind]
        .as_array()
        .expect("models")
        .iter()
        .map(|model| {
            let cases = model["cases"]
                .as_array()
                .expect("cases")
                .iter()
                .map(|c| MitsubaCase {
                    wo: v(&c["wo"]).normalize(),
                    wi: v(&c["wi"]).normalize(),
                    f_cos: v(&c["f_cos"]),
                    pdf: c["pdf"].as_f64().unwrap_or(0.0) as f32,
                })
                .collect();
            (model.clone(), cases)
        })
        .collect()
}

/// `distribution` and `alpha` of a fixture model.
pub(crate) fn mitsuba_microfacet(model: &serde_json::Value) -> Microfacet {
    Microfacet {
        distribution: match model["distribution"].as_str() {
            Some("beckmann") => Distribution::Beckmann,
            _ => Distribution::Ggx,
        },
        alpha: model["alpha"].as_f64().unwrap_or(0.0) as f32,
    }
}

/// Relative difference, with an absolute floor for values near 0.
pub(crate) fn rel_diff(a: f32, b: f32) -> f32 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-4)
}

fn ggx(alpha: f32) -> Microfacet {
    Microfacet {
        distribution: Distribution::Ggx,
        alpha,
    }
}

/// The reference coat's tables, and the largest absolute and relative errors
/// against Mitsuba's (printed with `--nocapture` for the record).
#[test]
fn rough_coat_matches_mitsuba_tables() {
    let coat = RoughCoat::new(ggx(0.1), 1.5);
    let (mut abs, mut rel) = (0.0f64, 0.0f64);
    for (j, (&t, &want)) in coat.transmittance.iter().zip(&MITSUBA_T).enumerate() {
        let err = (t as f64 - want).abs();
        assert!(err < 5e-5, "t(μ_{j}) = {t}, Mitsuba {want}");
        abs = abs.max(err);
        rel = rel.max(err / want);
    }
    let r = coat.internal_reflectance as f64;
    let r_rel = (r - MITSUBA_R_INT).abs() / MITSUBA_R_INT;
    assert!(r_rel < 1e-5, "R_int = {r}, Mitsuba {MITSUBA_R_INT}");
    println!(
        "t: max abs error {abs:.2e}, max rel {rel:.2e}; R_int {r:.7} vs {MITSUBA_R_INT:.7} (rel {r_rel:.2e})"
    );
}

#[test]
fn rough_coat_interpolates_its_table_linearly() {
    let coat = RoughCoat::new(ggx(0.1), 1.5);
    assert_eq!(coat.t(1.0), coat.transmittance[TABLE_POINTS - 1]);
    assert_eq!(coat.t(0.0), coat.transmittance[0]);
    let mid = 0.5 * (coat.transmittance[10] + coat.transmittance[11]);
    assert!((coat.t(10.5 / 63.0) - mid).abs() < 1e-6);
}

/// The documented accuracy: the n = 32/128 rule against n = 256 for t and
/// r, and Mitsuba's 64-point mean for R_int against Gauss–Legendre in μ.
#[test]
fn rough_coat_rule_error_is_bounded() {
    let fine = GaussLegendre::new(256);
    for (distribution, alpha, eta) in [
        (Distribution::Ggx, 0.1, 1.5),
        (Distribution::Ggx, 0.5, 1.5),
        (Distribution::Beckmann, 0.1, 1.5),
        (Distribution::Beckmann, 0.5, 1.33),
        (Distribution::Ggx, 0.3, 0.8),
        (Distribution::Beckmann, 0.01, 1.5),
        (Distribution::Ggx, 1.0, 2.4),
    ] {
        let m = Microfacet { distribution, alpha };
        let coat = RoughCoat::new(m, eta);
        let mut worst = 0.0f64;
        for j in [0, 4, 8, 21, 42, 55, 63] {
            let mu = (j as f32 / 63.0).max(1e-6);
            let converged = albedo(&m, mu, eta, Lobe::Transmission, &fine);
            let ours = coat.transmittance[j] as f64;
            assert!(
                (ours - converged).abs() < 5e-4,
                "{distribution:?} α {alpha} η {eta}: t({mu}) = {ours} by the rule, {converged} converged"
            );
            worst = worst.max((ours - converged).abs());
        }
        // R_int: 2∫ r(μ) μ dμ by 48-point Gauss–Legendre in μ (n = 128 inside).
        let (inner, outer) = (GaussLegendre::new(128), GaussLegendre::new(48));
        let converged: f64 = 2.0
            * outer
                .nodes
                .iter()
                .zip(&outer.weights)
                .map(|(&mu, &w)| w * mu as f64 * albedo(&m, mu, 1.0 / eta, Lobe::Reflection, &inner))
                .sum::<f64>();
        let rel = (coat.internal_reflectance as f64 - converged) / converged;
        assert!(
            (-0.03..0.0).contains(&rel),
            "{distribution:?} α {alpha} η {eta}: R_int {} vs converged {converged} ({rel:+.4})",
            coat.internal_reflectance
        );
        println!(
            "{distribution:?} α {alpha} η {eta}: t within {worst:.1e} of converged; R_int {:.5}, converged {converged:.5} ({:+.2} %)",
            coat.internal_reflectance,
            100.0 * rel
        );
    }
}

/// The quadrature (on Mitsuba's GGX warp, reweighted for Beckmann) against
/// plain Monte Carlo over ronray's own microfacet samplers: spherical-cap
/// visible normals for GGX, `D cos` for Beckmann.
#[test]
fn rough_coat_albedo_agrees_with_monte_carlo() {
    let rule = GaussLegendre::new(64);
    let mut rng = Pcg32::new(41, 7);
    for distribution in [Distribution::Ggx, Distribution::Beckmann] {
        for (alpha, eta, lobe) in [
            (0.2, 1.5, Lobe::Transmission),
            (0.6, 1.5, Lobe::Transmission),
            (0.2, 1.0 / 1.5, Lobe::Reflection),
            (0.6, 1.0 / 1.5, Lobe::Reflection),
        ] {
            let m = Microfacet { distribution, alpha };
            for mu in [0.05f32, 0.4, 0.9] {
                let wo = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                let n = 200_000;
                let (mut sum, mut sum2) = (0.0f64, 0.0f64);
                for _ in 0..n {
                    let wm = m.sample_wm(wo, rng.next_vec2());
                    let pdf = m.pdf_wm(wo, wm);
                    // Visible-normal density (exact G1, see albedo) over the sampler's.
                    let g1 = match distribution {
                        Distribution::Ggx => m.g1(wo),
                        Distribution::Beckmann => beckmann_g1_exact(alpha as f64, mu as f64) as f32,
                    };
                    let visible = g1 * wo.dot(wm).max(0.0) * m.d(wm) / wo.z;
                    let x = if pdf > 0.0 {
                        (integrand(&m, wo, wm, eta, lobe) * visible / pdf) as f64
                    } else {
                        0.0
                    };
                    sum += x;
                    sum2 += x * x;
                }
                let mean = sum / n as f64;
                let sigma = ((sum2 / n as f64 - mean * mean) / n as f64).sqrt();
                let q = albedo(&m, mu, eta, lobe, &rule);
                assert!(
                    (q - mean).abs() < 4.0 * sigma + 2e-4,
                    "{distribution:?} α {alpha} η {eta} μ {mu}: quadrature {q}, Monte Carlo {mean} ± {sigma}"
                );
            }
        }
    }
}

/// A nearly smooth coat transmits 1 − F(μ) away from grazing.
#[test]
fn rough_coat_smooth_limit_is_one_minus_fresnel() {
    for distribution in [Distribution::Ggx, Distribution::Beckmann] {
        let coat = RoughCoat::new(
            Microfacet {
                distribution,
                alpha: 1e-3,
            },
            1.5,
        );
        for j in 6..TABLE_POINTS {
            let mu = j as f32 / 63.0;
            let want = 1.0 - fresnel::dielectric(mu, 1.5);
            let t = coat.transmittance[j];
            assert!(
                (t - want).abs() < 2e-3,
                "{distribution:?}: t({mu}) = {t}, 1 − F = {want}"
            );
        }
    }
}

#[test]
fn rough_coat_exact_beckmann_g1_is_walters_fit_within_its_error() {
    // erfc against tabulated values (Abramowitz & Stegun, table 7.1).
    for (x, want) in [
        (0.0, 1.0),
        (0.5, 0.4795001222),
        (1.0, 0.1572992071),
        (2.0, 0.004677734981),
        (-1.0, 1.8427007929),
    ] {
        assert!(
            (erfc(x) - want).abs() < 2e-7 * want.max(1e-3),
            "erfc({x}) = {}, want {want}",
            erfc(x)
        );
    }
    let m = Microfacet {
        distribution: Distribution::Beckmann,
        alpha: 0.4,
    };
    for mu in [0.05f32, 0.2, 0.4, 0.7, 0.95, 1.0] {
        let w = Vec3A::new((1.0 - mu * mu).sqrt(), 0.0, mu);
        let (fit, exact) = (m.g1(w) as f64, beckmann_g1_exact(0.4, mu as f64));
        assert!(
            (fit - exact).abs() < 4e-3 * exact,
            "μ {mu}: fit {fit}, exact {exact}"
        );
    }
}
