//! Rough plastic through the generic harness, and its value against
//! Mitsuba's formula with Mitsuba's own tables.

use super::*;
use crate::materials::tests::{assert_energy_sweep, check_all, incidences};
use crate::materials::{Distribution, Microfacet};

fn coat(distribution: Distribution, roughness: f32) -> RoughCoat {
    RoughCoat::new(Microfacet::from_roughness(distribution, roughness), 1.5)
}

fn white(coat: &RoughCoat) -> RoughPlastic<'_> {
    RoughPlastic {
        diffuse: Rgb::ONE,
        specular: Rgb::ONE,
        coat,
    }
}

fn chi2_agreement_energy(distribution: Distribution, seed: u64) {
    for roughness in [0.1, 0.3, 0.7] {
        let c = coat(distribution, roughness);
        for wo in incidences() {
            let name = format!("rough plastic {distribution:?} r={roughness}");
            let e = check_all(&white(&c), wo, &name, seed);
            println!("{name}, white, θo {:.0}°: E = {e:.4}", wo.z.acos().to_degrees());
        }
    }
}

#[test]
fn rough_plastic_ggx_chi2_agreement_energy() {
    chi2_agreement_energy(Distribution::Ggx, 110);
}

#[test]
fn rough_plastic_beckmann_chi2_agreement_energy() {
    chi2_agreement_energy(Distribution::Beckmann, 111);
}

/// The reference scene's blue plastic (GGX α 0.1 = roughness √0.1).
#[test]
fn rough_plastic_reference_blue_chi2_agreement_energy() {
    let c = coat(Distribution::Ggx, 0.1f32.sqrt());
    let blue = RoughPlastic {
        diffuse: Rgb::new(0.1, 0.25, 0.6),
        specular: Rgb::ONE,
        coat: &c,
    };
    for wo in incidences() {
        let e = check_all(&blue, wo, "blue rough plastic", 112);
        println!(
            "blue rough plastic, θo {:.0}°: E = {e:.4}",
            wo.z.acos().to_degrees()
        );
        assert!(e > 0.3, "the blue plastic reflects {e}");
    }
}

#[test]
fn rough_plastic_energy_sweep() {
    for distribution in [Distribution::Ggx, Distribution::Beckmann] {
        for roughness in [0.0, 0.1, 0.3, 0.5, 0.7, 1.0] {
            let c = coat(distribution, roughness);
            let name = format!("rough plastic {distribution:?} r={roughness}");
            let worst = assert_energy_sweep(&white(&c), &name);
            println!("{name}, white, θo 0°–89°: largest E = {worst:.4}");
        }
    }
}

/// Mitsuba's `roughplastic` value (its `eval` divided by cos θ), written out
/// from its source with its tables (`MITSUBA_T`, `MITSUBA_R_INT` of the coat
/// tests), against ours for the reference material.
#[test]
fn rough_plastic_matches_mitsubas_formula_with_mitsubas_tables() {
    use super::super::rough_coat::tests::{MITSUBA_R_INT, MITSUBA_T};
    let lerp = |mu: f32| {
        let x = mu as f64 * 63.0;
        let i = (x as usize).min(62);
        MITSUBA_T[i] + (MITSUBA_T[i + 1] - MITSUBA_T[i]) * (x - i as f64)
    };
    let c = coat(Distribution::Ggx, 0.1f32.sqrt());
    let rho = Rgb::new(0.1, 0.25, 0.6);
    let b = RoughPlastic {
        diffuse: rho,
        specular: Rgb::ONE,
        coat: &c,
    };
    let m = Microfacet {
        distribution: Distribution::Ggx,
        alpha: 0.1,
    };
    let dir = |deg: f32, phi: f32| {
        let (s, c) = deg.to_radians().sin_cos();
        Vec3A::new(s * phi.cos(), s * phi.sin(), c)
    };
    for (wo, wi) in [
        (dir(10.0, 0.0), dir(12.0, 3.1)),
        (dir(45.0, 0.0), dir(44.0, 3.2)),
        (dir(70.0, 0.0), dir(20.0, 1.0)),
        (dir(85.0, 0.0), dir(84.0, 3.1)),
        (dir(30.0, 0.0), dir(60.0, 0.5)),
    ] {
        let h = (wo + wi).normalize();
        let spec = fresnel::dielectric(wo.dot(h), 1.5) * m.d(h) * m.g1(wo) * m.g1(wi) / (4.0 * wo.z * wi.z);
        let diff = rho / (1.0 - MITSUBA_R_INT as f32) * (lerp(wo.z) * lerp(wi.z)) as f32
            / (std::f32::consts::PI * 1.5 * 1.5);
        let want = Rgb::splat(spec) + diff;
        let got = b.eval(wo, wi);
        let rel = ((got - want).abs() / want).max_element();
        assert!(rel < 1e-4, "wo {wo} wi {wi}: f = {got}, Mitsuba's {want}");
    }
}

/// Mitsuba 3.9.1's own `roughplastic` eval and pdf at 40 direction pairs per
/// model (`tests/fixtures/refs/rough_bsdfs.json`). GGX: the same tables and
/// sampling, so value and pdf agree to f32 rounding. Beckmann: value within
/// the tables' quadrature difference; the pdf differs on purpose (Mitsuba
/// samples Beckmann's visible normals, ronray `D cos`).
#[test]
fn rough_plastic_matches_mitsuba_eval_and_pdf() {
    use super::super::rough_coat::tests::{mitsuba_bsdfs, mitsuba_microfacet, rel_diff};
    for (model, cases) in mitsuba_bsdfs("rough_plastic") {
        let m = mitsuba_microfacet(&model);
        let rho: Vec<f32> = model["diffuse"]
            .as_array()
            .expect("diffuse")
            .iter()
            .map(|x| x.as_f64().unwrap_or(0.0) as f32)
            .collect();
        let c = RoughCoat::new(m, 1.5);
        let b = RoughPlastic {
            diffuse: Rgb::new(rho[0], rho[1], rho[2]),
            specular: Rgb::ONE,
            coat: &c,
        };
        let ggx = m.distribution == Distribution::Ggx;
        let (mut worst_f, mut worst_pdf) = (0.0f32, 0.0f32);
        for case in &cases {
            let f = b.eval(case.wo, case.wi) * case.wi.z;
            let err = (0..3).map(|k| rel_diff(f[k], case.f_cos[k])).fold(0.0, f32::max);
            assert!(
                err < if ggx { 1e-4 } else { 1e-3 },
                "{:?} α {}: wo {} wi {}: f·cos {f}, Mitsuba {}",
                m.distribution,
                m.alpha,
                case.wo,
                case.wi,
                case.f_cos
            );
            worst_f = worst_f.max(err);
            if ggx {
                let pdf = b.pdf(case.wo, case.wi);
                let err = rel_diff(pdf, case.pdf);
                assert!(
                    err < 1e-4,
                    "α {}: wo {} wi {}: pdf {pdf}, Mitsuba {}",
                    m.alpha,
                    case.wo,
                    case.wi,
                    case.pdf
                );
                worst_pdf = worst_pdf.max(err);
            }
        }
        println!(
            "{:?} α {}: f within {worst_f:.1e}, pdf within {worst_pdf:.1e} of Mitsuba (Beckmann pdf not compared)",
            m.distribution, m.alpha
        );
    }
}
