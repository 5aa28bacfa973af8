//! Path splitting (`integrator: Path(splits: n)`, default 1): the same
//! expected image as one path per camera sample, region by region, less
//! noise per camera sample, the same image on any number of threads, and
//! out-of-range counts refused with a located diagnostic.

use crate::common;

use common::{blocks, load_text};
use ronray::frame::{RenderOptions, render_whole};
use ronray::load::{LoadError, Overrides, load_str};
use ronray::math::Rgb;
use std::path::Path;

/// A white box lit by a small ceiling rectangle, a red wall, a mirror
/// sphere (camera paths whose first vertex is a delta one split further
/// on) and a diffuse sphere; `integrator` fields after `max_depth`.
fn scene(film: &str, integrator: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 0, 3.9), target: (0, 0, 0), fov_y_degrees: 37.5),
            film: ({film}),
            integrator: Path(max_depth: 8, caustics: PathOnly, {integrator}),
            materials: {{
                "w": Lambert(albedo: (0.8, 0.8, 0.8)),
                "r": Lambert(albedo: (0.7, 0.1, 0.1)),
                "mirror": Mirror(),
            }},
            lights: [Rect(center: (0, 0.99, 0), half_u: (0.2, 0, 0), half_v: (0, 0, 0.2), radiance: (20, 20, 20))],
            objects: [
                Rect(center: (0, -1, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "w"),
                Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), material: "w"),
                Rect(center: (0, 0, -1), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "w"),
                Rect(center: (-1, 0, 0), half_u: (0, 1, 0), half_v: (0, 0, 1), material: "r"),
                Sphere(center: (-0.45, -0.6, -0.3), radius: 0.35, material: "mirror"),
                Sphere(center: (0.4, -0.7, 0.2), radius: 0.3, material: "w"),
            ],
        )"#
    )
}

fn render_with(text: &str, threads: usize) -> Vec<Rgb> {
    let l = load_text(text);
    let opts = RenderOptions {
        threads: Some(threads),
        ..Default::default()
    };
    let img = render_whole(&l.scene, &l.view, &opts).0;
    assert!(img.pixels.iter().all(|p| p.is_finite()));
    img.pixels
}

fn rmse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let se: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| {
            let d = *p - *q;
            f64::from(d.x * d.x + d.y * d.y + d.z * d.z) / 3.0
        })
        .sum();
    (se / a.len() as f64).sqrt()
}

fn film(w: u32, spp: u32, seed: u32) -> String {
    format!("width: {w}, height: {w}, spp: {spp}, seed: {seed}")
}

#[test]
fn splitting_keeps_the_image_region_by_region() {
    // One path per camera sample at many samples against three per camera
    // sample at fewer: whole image within 1%, each 12 × 12 quadrant within
    // 3%. A continuation weighted 1 instead of 1/3 brightens the indirect
    // light (most of the ceiling's) threefold; one that skipped the light
    // sample of its split vertex would darken the directly lit floor.
    let w = 24;
    let truth = render_with(&scene(&film(w, 2048, 3), "splits: 1"), 2);
    let split = render_with(&scene(&film(w, 1024, 4), "splits: 3"), 2);
    let (t, s) = (
        blocks(&truth, w as usize, w as usize)[0],
        blocks(&split, w as usize, w as usize)[0],
    );
    assert!((s / t - 1.0).abs() < 0.01, "whole image {s} against {t}");
    for (i, (t, s)) in blocks(&truth, w as usize, 12)
        .iter()
        .zip(blocks(&split, w as usize, 12))
        .enumerate()
    {
        assert!((s / t - 1.0).abs() < 0.03, "quadrant {i}: {s} against {t}");
    }
}

#[test]
fn splitting_lowers_the_noise_per_camera_sample() {
    // At equal camera samples, two paths each against one,
    // both measured against a 4096-spp render: the indirect light is most
    // of this box's noise, so the error falls by about 1/√2 (0.72 measured
    // on the Cornell box reference); the test asks for 0.9.
    let w = 16;
    let truth = render_with(&scene(&film(w, 4096, 7), "splits: 1"), 2);
    let one = render_with(&scene(&film(w, 64, 8), "splits: 1"), 2);
    let two = render_with(&scene(&film(w, 64, 8), "splits: 2"), 2);
    let (e1, e2) = (rmse(&one, &truth), rmse(&two, &truth));
    assert!(e2 < 0.9 * e1, "split {e2} against one path {e1}");
}

#[test]
fn split_renders_do_not_depend_on_the_thread_count() {
    let text = scene(&film(20, 40, 5), "splits: 2");
    let (a, b) = (render_with(&text, 1), render_with(&text, 2));
    assert!(a == b, "1 and 2 threads differ");
}

#[test]
fn split_counts_outside_the_limit_are_refused_where_they_are_written() {
    for bad in ["splits: 0", "splits: 17"] {
        let text = scene(&film(8, 8, 1), bad);
        match load_str(Path::new("split.ron"), &text, &Overrides::default()) {
            Err(LoadError::Invalid(r)) => {
                let d = r
                    .diagnostics
                    .iter()
                    .find(|d| d.path.as_deref() == Some("integrator.splits"))
                    .unwrap_or_else(|| {
                        panic!("{bad}: no diagnostic at integrator.splits:\n{}", r.render(false))
                    });
                assert!(d.line > 0 && d.column > 0, "{bad}: unlocated");
            }
            Ok(_) => panic!("{bad} loaded"),
            Err(e) => panic!("{bad}: {e}"),
        }
    }
}
