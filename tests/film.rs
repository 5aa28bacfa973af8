//! Pixel filters, exposure and tone mapping, and the output formats: each
//! filter integrates to 1, exposure is in stops, what is written reads back.

use crate::common;

use common::{load_text, render_loaded, report, ronray_in};
use ronray::frame::{RenderOptions, render_whole};
use ronray::imageio::{Display, Image, Tonemap, read_image, write_image, write_image_with};
use ronray::math::Rgb;

/// A plane emitting 0.5 that fills the view, through `filter`.
fn uniform_plane(filter: &str) -> String {
    format!(
        "Scene(
            camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
            film: (width: 32, height: 32, spp: 16, filter: {filter}),
            lights: [Rect(center: (0, 0, 0), half_u: (10, 0, 0), half_v: (0, 10, 0), radiance: (0.5, 0.5, 0.5))],
        )"
    )
}

#[test]
fn every_filter_integrates_to_one_on_a_uniform_plane() {
    for filter in [
        "Box",
        "Gaussian(radius: 1.5, sigma: 0.5)",
        "Mitchell(radius: 2, b: 0.3333, c: 0.3333)",
        "Mitchell(radius: 1.5, b: 0, c: 0.75)",
    ] {
        let img = render_loaded(&load_text(&uniform_plane(filter)));
        let mean = img.pixels.iter().map(|p| f64::from(p.x)).sum::<f64>() / img.pixels.len() as f64;
        report(&format!(
            "uniform plane of 0.5 through {filter}: image mean {mean:.5}"
        ));
        if filter.starts_with("Mitchell") {
            // Signed weights of constant magnitude: exact in expectation.
            assert!((mean - 0.5).abs() < 0.005, "{filter}: mean {mean}, expected 0.5");
        } else {
            // Positive filters weigh every sample exactly 1.
            assert!(
                img.pixels.iter().all(|p| *p == Rgb::splat(0.5)),
                "{filter}: not exactly 0.5 everywhere"
            );
        }
    }
}

#[test]
fn filtered_renders_do_not_depend_on_the_thread_count() {
    let text = "Scene(
        camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
        film: (width: 40, height: 24, spp: 4, filter: Mitchell()),
        materials: { \"white\": Lambert(albedo: (0.8, 0.8, 0.8)) },
        lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))],
        objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"white\")],
    )";
    let l = load_text(text);
    let one = render_whole(
        &l.scene,
        &l.view,
        &RenderOptions {
            threads: Some(1),
            ..Default::default()
        },
    )
    .0;
    let two = render_whole(
        &l.scene,
        &l.view,
        &RenderOptions {
            threads: Some(2),
            ..Default::default()
        },
    )
    .0;
    assert!(one == two, "the image changed with the thread count");
    // And the filter does something: the box image differs at the sphere's edge.
    let boxed = render_loaded(&load_text(&text.replace("filter: Mitchell()", "filter: Box")));
    assert!(boxed != one, "Mitchell and box give the same image");
}

fn ramp() -> Image {
    let mut img = Image::new(7, 3);
    for (i, p) in img.pixels.iter_mut().enumerate() {
        *p = Rgb::new(i as f32 * 0.02, 0.45 - i as f32 * 0.01, 0.013 * (i % 5) as f32);
    }
    img
}

#[test]
fn linear_formats_round_trip_exactly_and_hdr_within_its_precision() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut img = ramp();
    img.pixels[3] = Rgb::new(12.5, 1e-3, 300.0);
    for ext in ["exr", "pfm"] {
        let p = dir.path().join(format!("a.{ext}"));
        write_image(&img, &p).expect("written");
        assert!(
            read_image(&p).expect("read back") == img,
            "{ext} did not round-trip exactly"
        );
    }
    let p = dir.path().join("a.hdr");
    write_image(&img, &p).expect("written");
    let back = read_image(&p).expect("read back");
    for (a, b) in img.pixels.iter().zip(&back.pixels) {
        // RGBE: 8-bit mantissas relative to the largest channel.
        let tol = a.max_element() / 128.0 + 1e-6;
        assert!(
            (*a - *b).abs().max_element() <= tol,
            "HDR {a:?} read back as {b:?}"
        );
    }
}

#[test]
fn png_round_trips_within_its_bit_depth() {
    let dir = tempfile::tempdir().expect("temp dir");
    let img = ramp();
    for (bits, tol) in [(8u8, 4e-3f32), (16, 3e-5)] {
        let p = dir.path().join(format!("a{bits}.png"));
        let display = Display {
            png_bits: bits,
            ..Display::default()
        };
        write_image_with(&img, &p, &display).expect("written");
        let back = read_image(&p).expect("read back");
        let worst = img
            .pixels
            .iter()
            .zip(&back.pixels)
            .map(|(a, b)| (*a - *b).abs().max_element())
            .fold(0.0, f32::max);
        report(&format!("{bits}-bit PNG round trip: worst error {worst:.2e}"));
        assert!(worst < tol, "{bits}-bit PNG: worst error {worst}");
    }
}

/// +1 stop doubles the linear values a PNG holds (read back through the
/// 16-bit PNG, so quantisation does not hide it); linear outputs ignore it.
#[test]
fn one_stop_doubles_linear_values_in_png_and_leaves_exr_alone() {
    let dir = tempfile::tempdir().expect("temp dir");
    let img = ramp();
    let at = |stops: f32, name: &str| {
        let p = dir.path().join(name);
        let display = Display {
            exposure: stops,
            png_bits: 16,
            ..Display::default()
        };
        write_image_with(&img, &p, &display).expect("written");
        read_image(&p).expect("read back")
    };
    let base = at(0.0, "0.png");
    let up = at(1.0, "1.png");
    for (b, u) in base.pixels.iter().zip(&up.pixels) {
        assert!(
            (*u - 2.0 * *b).abs().max_element() < 1e-4,
            "+1 stop: {u:?}, expected 2 × {b:?}"
        );
    }
    assert!(at(3.0, "e.exr") == img, "exposure must not touch EXR");
}

#[test]
fn clamp_at_zero_stops_writes_the_same_png_bytes_as_before() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut img = ramp();
    img.pixels[0] = Rgb::new(3.0, -1.0, 0.5);
    let p = dir.path().join("a.png");
    write_image(&img, &p).expect("written");
    let bytes = image::open(&p).expect("png").to_rgb8().into_raw();
    assert_eq!(
        bytes,
        ronray::imageio::to_srgb8(&img),
        "default PNG pixels changed"
    );
}

#[test]
fn tonemaps_render_bright_scenes_without_burning_out() {
    let mut img = Image::new(3, 1);
    img.pixels = vec![Rgb::splat(0.5), Rgb::splat(4.0), Rgb::splat(40.0)];
    for t in [Tonemap::Reinhard, Tonemap::Aces, Tonemap::AgX] {
        let d = Display {
            tonemap: t,
            ..Display::default()
        };
        let v: Vec<f32> = img.pixels.iter().map(|&p| d.map(p).x).collect();
        assert!(v[0] < v[1] && v[1] < v[2] && v[2] <= 1.0, "{t:?}: {v:?}");
    }
}

/// The command line's display flags go through the loader's checks and
/// reach the PNG.
#[test]
fn cli_exposure_and_tonemap_flags_reach_the_png_and_are_checked() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(
        dir.path().join("plane.ron"),
        uniform_plane("Box").replace("0.5, 0.5, 0.5", "0.2, 0.2, 0.2"),
    )
    .expect("scene");
    let run = |args: &[&str]| ronray_in(dir.path(), args);
    let o = run(&["render", "plane.ron", "-o", "a.png", "--png-bits", "16"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run(&[
        "render",
        "plane.ron",
        "-o",
        "b.png",
        "--png-bits",
        "16",
        "--exposure",
        "1",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (a, b) = (
        read_image(&dir.path().join("a.png")).expect("a"),
        read_image(&dir.path().join("b.png")).expect("b"),
    );
    assert!(
        (b.get(5, 5).x - 2.0 * a.get(5, 5).x).abs() < 1e-3,
        "{} vs 2 × {}",
        b.get(5, 5).x,
        a.get(5, 5).x
    );
    let o = run(&["render", "plane.ron", "-o", "c.pfm", "--tonemap", "Agx"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("AgX"),
        "a misspelt tone map is refused with a suggestion:\n{err}"
    );
    for ext in ["pfm", "hdr", "exr"] {
        let out = format!("d.{ext}");
        let o = run(&["render", "plane.ron", "-o", &out, "--exposure", "2"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let img = read_image(&dir.path().join(&out)).expect("reads");
        assert!(
            (img.get(3, 3).x - 0.2).abs() < 2e-3,
            "{ext} is linear whatever the exposure: {}",
            img.get(3, 3).x
        );
    }
}
