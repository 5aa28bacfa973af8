//! Adaptive sampling (`film.noise_threshold`): pixels stop once their noise
//! is low enough, never take more than `spp`, and the image still does not
//! depend on the thread count.

use crate::common;

use common::{load_text, report};
use ronray::frame::{Plan, RenderOptions, Request, render_whole};
use ronray::math::Rgb;
use std::sync::atomic::AtomicBool;

/// A diffuse box lit by a small area light: noisy where the light is seen
/// indirectly, smooth elsewhere.
fn box_scene(film: &str) -> String {
    box_scene_from("eye: (0, 0, 3.9), target: (0, 0, 0), fov_y_degrees: 37.5", film)
}

/// [`box_scene`] through the camera `camera`.
fn box_scene_from(camera: &str, film: &str) -> String {
    format!(
        r#"Scene(
            camera: ({camera}),
            film: ({film}),
            integrator: Path(max_depth: 5),
            materials: {{ "w": Lambert(albedo: (0.8, 0.8, 0.8)), "r": Lambert(albedo: (0.7, 0.1, 0.1)) }},
            lights: [Rect(center: (0, 0.99, 0), half_u: (0.25, 0, 0), half_v: (0, 0, 0.25), radiance: (15, 15, 15))],
            objects: [
                Rect(center: (0, -1, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "w"),
                Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), material: "w"),
                Rect(center: (0, 0, -1), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "w"),
                Rect(center: (-1, 0, 0), half_u: (0, 1, 0), half_v: (0, 0, 1), material: "r"),
                Sphere(center: (0.3, -0.6, 0), radius: 0.4, material: "w"),
            ],
        )"#
    )
}

fn opts(threads: usize) -> RenderOptions {
    RenderOptions {
        threads: Some(threads),
        ..Default::default()
    }
}

#[test]
fn a_flat_image_stops_at_min_spp_and_stays_exact() {
    let l = load_text(
        "Scene(
            camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
            film: (width: 24, height: 16, spp: 256, noise_threshold: 0.01, min_spp: 16),
            lights: [Rect(center: (0, 0, 0), half_u: (10, 0, 0), half_v: (0, 10, 0), radiance: (0.5, 0.5, 0.5))],
        )",
    );
    let (img, stats) = render_whole(&l.scene, &l.view, &opts(2));
    assert_eq!(stats.samples, 24 * 16 * 16, "every pixel converged at min_spp");
    assert!(img.pixels.iter().all(|p| *p == Rgb::splat(0.5)));
}

#[test]
fn noisy_pixels_take_more_samples_than_smooth_ones_within_spp() {
    let (w, h, spp, min) = (32u64, 32u64, 128u64, 16u64);
    let l = load_text(&box_scene(&format!(
        "width: {w}, height: {h}, spp: {spp}, sampler: Independent, noise_threshold: 0.02, min_spp: {min}"
    )));
    let (one, s1) = render_whole(&l.scene, &l.view, &opts(1));
    let (two, s2) = render_whole(&l.scene, &l.view, &opts(2));
    assert_eq!(
        one.pixels, two.pixels,
        "adaptive images depend on the thread count"
    );
    assert_eq!(s1.samples, s2.samples);
    let mean_spp = s1.samples as f64 / (w * h) as f64;
    report(&format!(
        "adaptive box 32x32, threshold 0.02, min 16, max 128: mean {mean_spp:.1} spp"
    ));
    assert!(
        s1.samples > w * h * min && s1.samples < w * h * spp,
        "mean spp {mean_spp} should lie strictly between {min} and {spp}"
    );

    // Same image on average as the full render: the stopping rule changes
    // which samples are taken, not what they estimate.
    let full = load_text(&box_scene(&format!(
        "width: {w}, height: {h}, spp: {spp}, sampler: Independent, allocation: Even"
    )));
    let (reference, sf) = render_whole(&full.scene, &full.view, &opts(2));
    assert_eq!(sf.samples, w * h * spp);
    let mean = |px: &[Rgb]| px.iter().map(|p| f64::from(p.x + p.y + p.z)).sum::<f64>() / px.len() as f64;
    let (a, b) = (mean(&one.pixels), mean(&reference.pixels));
    report(&format!("image mean: adaptive {a:.5}, every sample {b:.5}"));
    assert!((a - b).abs() < 0.01 * b, "adaptive mean {a} vs {b}");
}

#[test]
fn a_threshold_nothing_meets_gives_the_plain_render_exactly() {
    // Looking down at the lit floor from inside the box: every pixel is
    // noisy (a pixel of constant value, such as the light or the black
    // outside, rightly stops at any threshold).
    let camera = "eye: (-0.5, 0.2, 0.5), target: (-0.5, -1, 0.3), fov_y_degrees: 30";
    let base = "width: 16, height: 16, spp: 40, sampler: Sobol, allocation: Even";
    let plain = load_text(&box_scene_from(camera, base));
    let strict = load_text(&box_scene_from(
        camera,
        &format!("{base}, noise_threshold: 0.0000001, min_spp: 8"),
    ));
    let (a, sa) = render_whole(&plain.scene, &plain.view, &opts(2));
    let (b, sb) = render_whole(&strict.scene, &strict.view, &opts(2));
    assert_eq!(sa.samples, sb.samples);
    assert_eq!(a.pixels, b.pixels);
}

#[test]
fn sample_ranges_take_every_sample() {
    // Farm pieces and watch-mode passes add exact sums of fixed counts.
    let l = load_text(&box_scene(
        "width: 8, height: 8, spp: 64, noise_threshold: 0.5, min_spp: 4",
    ));
    let rect = ronray::imageio::PixelRect::full(8, 8);
    let piece = Request::Piece {
        rect,
        samples: (0, 64),
    };
    let plan = Plan::new(&l.scene, &l.view, piece, false).expect("a piece of the frame");
    let (_, stats) = ronray::frame::render(
        &l.scene,
        &l.view,
        &plan,
        &opts(2),
        &AtomicBool::new(false),
        &|_| {},
    );
    assert_eq!(stats.samples, 8 * 8 * 64);
    let (_, adaptive) = render_whole(&l.scene, &l.view, &opts(2));
    assert!(adaptive.samples < 8 * 8 * 64);
}

#[test]
fn the_command_line_render_is_adaptive_and_says_how_many_samples_it_took() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = dir.path().join("box.ron");
    std::fs::write(
        &scene,
        box_scene("width: 24, height: 24, spp: 64, noise_threshold: 0.05"),
    )
    .expect("write scene");
    let out = common::ronray_in(
        dir.path(),
        &["render", "box.ron", "-o", "box.pfm", "--threads", "2"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let mean: f64 = err
        .split("adaptive: ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no adaptive summary in: {err}"));
    assert!((16.0..64.0).contains(&mean), "mean spp {mean}: {err}");
    // The same scene split into tiles for a farm renders every sample.
    let piece = common::ronray_in(
        dir.path(),
        &[
            "render",
            "box.ron",
            "--tile",
            "0/2",
            "-o",
            "piece.exr",
            "--threads",
            "2",
        ],
    );
    let piece_err = String::from_utf8_lossy(&piece.stderr);
    assert!(piece.status.success(), "{piece_err}");
    assert!(
        piece_err.contains("noise_threshold is ignored for pieces"),
        "{piece_err}"
    );
}
