//! Samples spread by noise (`film.allocation: ByNoise`, the default): the
//! same number of samples as an even render, the same image on any number
//! of threads, the same expected image, and less error.

use crate::common;

use common::{load_text, report, ronray, root};
use ronray::frame::{Plan, RenderOptions, Request, render_whole};
use ronray::math::Rgb;
use std::sync::atomic::AtomicBool;

/// A diffuse box with a glass sphere under a small light: smooth walls,
/// a noisy caustic and penumbra.
fn scene(film: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 0, 3.9), target: (0, 0, 0), fov_y_degrees: 37.5),
            film: ({film}),
            integrator: Path(max_depth: 6),
            materials: {{
                "w": Lambert(albedo: (0.8, 0.8, 0.8)),
                "r": Lambert(albedo: (0.7, 0.1, 0.1)),
                "glass": Glass(ior: 1.5),
            }},
            lights: [Rect(center: (0, 0.99, 0), half_u: (0.2, 0, 0), half_v: (0, 0, 0.2), radiance: (20, 20, 20))],
            objects: [
                Rect(center: (0, -1, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "w"),
                Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), material: "w"),
                Rect(center: (0, 0, -1), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "w"),
                Rect(center: (-1, 0, 0), half_u: (0, 1, 0), half_v: (0, 0, 1), material: "r"),
                Sphere(center: (0.2, -0.6, 0), radius: 0.4, material: "glass"),
            ],
        )"#
    )
}

fn threads(n: usize) -> RenderOptions {
    RenderOptions {
        threads: Some(n),
        ..Default::default()
    }
}

fn rmse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let se: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| f64::from((*p - *q).length_squared()))
        .sum();
    (se / (3 * a.len()) as f64).sqrt()
}

#[test]
fn spread_renders_take_the_budget_and_do_not_depend_on_threads() {
    let (w, h, spp) = (32u64, 32u64, 64u64);
    let l = load_text(&scene(&format!("width: {w}, height: {h}, spp: {spp}")));
    let (one, s1) = render_whole(&l.scene, &l.view, &threads(1));
    let (two, s2) = render_whole(&l.scene, &l.view, &threads(2));
    assert_eq!(one.pixels, two.pixels, "the image depends on the thread count");
    assert_eq!(s1.samples, s2.samples);
    // Counts are rounded to multiples of 8: within 4 a pixel of the budget.
    let budget = w * h * spp;
    assert!(
        s1.samples.abs_diff(budget) <= 4 * w * h,
        "{} samples for a budget of {budget}",
        s1.samples
    );
    assert!(one.pixels.iter().all(|p| p.is_finite()));
}

#[test]
fn spreading_by_noise_lowers_the_error_and_keeps_the_mean() {
    let (w, h) = (48, 48);
    let film = |spp: u32, allocation: &str, seed: u32| {
        format!("width: {w}, height: {h}, spp: {spp}, allocation: {allocation}, seed: {seed}")
    };
    let reference = load_text(&scene(&film(2048, "Even", 7)));
    let (truth, _) = render_whole(&reference.scene, &reference.view, &threads(2));
    let mut errors = [0.0f64; 2];
    let mut means = [0.0f64; 2];
    for (k, allocation) in ["Even", "ByNoise"].into_iter().enumerate() {
        for seed in 1..=2 {
            let l = load_text(&scene(&film(64, allocation, seed)));
            let (img, stats) = render_whole(&l.scene, &l.view, &threads(2));
            assert!(stats.samples.abs_diff(64 * w * h) <= 4 * w * h);
            errors[k] += rmse(&img.pixels, &truth.pixels) / 2.0;
            means[k] +=
                img.pixels.iter().map(|p| f64::from(p.x + p.y + p.z)).sum::<f64>() / (2 * w * h) as f64;
        }
    }
    let truth_mean = truth
        .pixels
        .iter()
        .map(|p| f64::from(p.x + p.y + p.z))
        .sum::<f64>()
        / (w * h) as f64;
    report(&format!(
        "glass box 48x48, 64 spp: RMSE even {:.5}, by noise {:.5}; means {:.4} {:.4} (2048 spp: {truth_mean:.4})",
        errors[0], errors[1], means[0], means[1]
    ));
    assert!(
        errors[1] < errors[0],
        "spreading by noise did not lower the error: {errors:?}"
    );
    // Unbiased: a pixel's count never depends on its own samples.
    assert!(
        (means[1] - truth_mean).abs() < 0.01 * truth_mean,
        "{} vs {truth_mean}",
        means[1]
    );
}

#[test]
fn pieces_small_and_stratified_renders_spread_evenly() {
    // A piece of an evenly spread frame takes exactly its samples (pieces of
    // a frame spread by noise reproduce the whole render instead:
    // tests/farm.rs); below 32 spp there is nothing to spread.
    let l = load_text(&scene("width: 8, height: 8, spp: 64, allocation: Even"));
    let full = ronray::imageio::PixelRect::full(8, 8);
    let piece = Request::Piece {
        rect: full,
        samples: (0, 32),
    };
    let plan = Plan::new(&l.scene, &l.view, piece, false).expect("a piece of the frame");
    let (_, stats) = ronray::frame::render(
        &l.scene,
        &l.view,
        &plan,
        &threads(2),
        &AtomicBool::new(false),
        &|_| {},
    );
    assert_eq!(stats.samples, 8 * 8 * 32);
    let small = load_text(&scene("width: 8, height: 8, spp: 24"));
    let (_, stats) = render_whole(&small.scene, &small.view, &threads(2));
    assert_eq!(stats.samples, 8 * 8 * 24);
    // A stratified pixel's strata are laid out for exactly `spp` samples.
    let strata = load_text(&scene("width: 8, height: 8, spp: 64, sampler: Stratified"));
    let (_, stats) = render_whole(&strata.scene, &strata.view, &threads(2));
    assert_eq!(stats.samples, 8 * 8 * 64);
}

#[test]
fn the_summary_line_says_how_the_samples_were_spread() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = root().join("scenes/cornell.ron");
    let run = |spp: &str| {
        let out = dir.path().join(format!("c{spp}.png"));
        let o = ronray(&[
            "render",
            scene.to_str().expect("utf-8 path"),
            "--size",
            "16x16",
            "--spp",
            spp,
            "--progress",
            "none",
            "-o",
            out.to_str().expect("utf-8 path"),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let spread = run("32");
    assert!(
        spread.contains("32 spp spread by noise:") && spread.contains("on average"),
        "{spread}"
    );
    let even = run("16");
    assert!(even.contains("(16×16, 16 spp)"), "{even}");
}
