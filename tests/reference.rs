//! The path tracer against Mitsuba 3 references (`tests/fixtures/refs/`:
//! the 256² references box-downsampled to 64², which with a box pixel filter
//! is the same integral as rendering at 64²).
//!
//! An unbiased renderer's error against a (nearly exact) reference is its
//! own noise: MSE(a, ref) ≈ MSE(a, b)/2 for two independent renders a, b.
//! Bias shows up as error in excess of that, so this checks for bias without
//! depending on how noisy the sampler is.

use ronray::imageio::{Image, compare, read_image};
use ronray::render::render;
use ronray::scene::{Overrides, load_with};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn render_at(scene: &str, spp: u32, seed: u64) -> Image {
    let o = Overrides {
        spp: Some(spp),
        size: Some((64, 64)),
        seed: Some(seed),
        ..Default::default()
    };
    let loaded = load_with(&root().join("scenes").join(scene), &o).unwrap_or_else(|e| panic!("{scene}: {e}"));
    render(&loaded.scene, &Default::default()).0
}

fn check(scene: &str, reference: &str, spp: u32) {
    let fixture = |f: &str| read_image(&root().join("tests/fixtures/refs").join(f)).expect("fixture");
    let reference_img = fixture(&format!("{reference}_64.pfm"));
    let mask = fixture(&format!("{reference}_mask_64.pfm"));
    let skip: Vec<bool> = mask.pixels.iter().map(|p| p.x > 0.5).collect();
    let a = render_at(scene, spp, 1);
    let b = render_at(scene, spp, 2);
    for (label, skip) in [("all pixels", None), ("off the light", Some(skip.as_slice()))] {
        let err = compare(&a, &reference_img, skip).expect("same size").rmse;
        let noise = compare(&a, &b, skip).expect("same size").rmse / 2f64.sqrt();
        // Reference noise at 64² is ~0.0006; allow for it and for the
        // spread of the noise estimate itself.
        let bound = 1.1 * noise + 0.002;
        assert!(
            err <= bound,
            "{scene} ({label}): RMSE vs Mitsuba {err:.5} exceeds 1.1 × own noise {noise:.5} + 0.002 — biased?"
        );
    }
    let c = compare(&a, &reference_img, None).expect("same size");
    for ch in 0..3 {
        // Half of the image mean's own noise at this spp is far below 1%.
        let rel = (c.mean_a[ch] - c.mean_b[ch]).abs() / c.mean_b[ch];
        assert!(
            rel < 0.01,
            "{scene}: channel {ch} mean {:.5} vs reference {:.5}",
            c.mean_a[ch],
            c.mean_b[ch]
        );
    }
}

#[test]
fn path_matches_mitsuba_cornell_diffuse() {
    check("cornell.ron", "cornell_diffuse", 64);
}

#[test]
fn path_matches_mitsuba_cornell_specular() {
    check("cornell_specular.ron", "cornell_specular", 64);
}

#[test]
fn path_matches_mitsuba_cornell_dof() {
    check("cornell_dof.ron", "cornell_dof", 64);
}

#[test]
fn downsampled_fixture_keeps_the_reference_mean() {
    // Guards the fixture itself: box downsampling preserves the mean.
    let img = read_image(&root().join("tests/fixtures/refs/cornell_diffuse_64.pfm")).expect("fixture");
    let mean: f64 = img.pixels.iter().map(|p| p.x as f64).sum::<f64>() / img.pixels.len() as f64;
    assert!((mean - 0.259777).abs() < 1e-4, "mean red {mean}");
}

/// The low-discrepancy sampler must beat independent sampling at equal spp.
#[test]
fn sobol_beats_independent_on_cornell() {
    let reference_img =
        read_image(&root().join("tests/fixtures/refs/cornell_diffuse_64.pfm")).expect("fixture");
    let rmse = |text: &str| {
        let path = root().join("scenes/cornell.ron");
        let loaded = ronray::scene::load_str(
            &path,
            text,
            &Overrides {
                spp: Some(16),
                size: Some((64, 64)),
                seed: Some(3),
                ..Default::default()
            },
        )
        .expect("scene loads");
        compare(
            &render(&loaded.scene, &Default::default()).0,
            &reference_img,
            None,
        )
        .expect("size")
        .rmse
    };
    let text = std::fs::read_to_string(root().join("scenes/cornell.ron")).expect("scene");
    let independent = rmse(&text);
    let sobol = rmse(&text.replace("sampler: Independent", "sampler: Sobol"));
    assert!(
        sobol < 0.9 * independent,
        "Sobol RMSE {sobol:.5} vs independent {independent:.5}"
    );
}
