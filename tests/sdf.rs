//! Implicit surfaces in scenes: golden images of the shipped SDF scenes, and
//! SDF shapes checked against analytic and tessellated twins.
//!
//! Goldens are 48×48 PNGs in `tests/fixtures/golden/`. A render is
//! deterministic for a seed, so the fresh image goes through the same PNG
//! encode/decode (8-bit sRGB, clamped to [0, 1]) and is compared in linear
//! RGB: RMSE < 0.01, about one pixel of 48×48 off by 0.5, which float noise
//! between platforms never reaches. Regenerate on purpose with
//! `RONRAY_BLESS=1 cargo test --test sdf` and review the image diff.

#[path = "sdf/geometry.rs"]
mod geometry;
#[path = "sdf/mandelbulb.rs"]
mod mandelbulb;
#[path = "sdf/torus.rs"]
mod torus;
#[path = "sdf/validation.rs"]
mod validation;

use ronray::imageio::{Image, compare, read_image, write_image};
use ronray::render::{RenderOptions, render};
use ronray::scene::{Overrides, Scene, load_str, load_with};
use std::path::{Path, PathBuf};

const GOLDEN_RMSE: f64 = 0.01;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// Loads scene text as if it were a file in `dir`, panicking with the report.
pub fn scene_in(dir: &Path, text: &str, overrides: &Overrides) -> Scene {
    match load_str(&dir.join("test.ron"), text, overrides) {
        Ok(l) => l.scene,
        Err(e) => panic!(
            "test scene must load: {e}\n{}",
            e.report().map(|r| r.render(false)).unwrap_or_default()
        ),
    }
}

pub fn scene(text: &str) -> Scene {
    scene_in(root(), text, &Overrides::default())
}

pub fn render_seed(scene: &mut Scene, seed: u64) -> Image {
    scene.film.seed = seed;
    let img = render(scene, &RenderOptions::default()).0;
    assert!(
        img.pixels.iter().all(|p| p.is_finite()),
        "a render has NaN or infinite pixels"
    );
    img
}

/// Round trip through PNG, as the goldens were stored.
fn as_stored(img: &Image, name: &str) -> Image {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(format!("{name}.png"));
    write_image(img, &path).unwrap();
    read_image(&path).unwrap()
}

fn check_golden(name: &str, spp: u32) {
    let overrides = Overrides {
        spp: Some(spp),
        size: Some((48, 48)),
        seed: Some(0),
        ..Default::default()
    };
    let loaded = load_with(&root().join(format!("scenes/{name}.ron")), &overrides)
        .unwrap_or_else(|e| panic!("scenes/{name}.ron must load: {e}"));
    let mut scene = loaded.scene;
    let img = render_seed(&mut scene, 0);
    let golden: PathBuf = root().join(format!("tests/fixtures/golden/{name}.png"));
    if std::env::var("RONRAY_BLESS").as_deref() == Ok("1") {
        std::fs::create_dir_all(golden.parent().unwrap()).unwrap();
        write_image(&img, &golden).unwrap();
        eprintln!("blessed {}", golden.display());
        return;
    }
    let want = read_image(&golden).unwrap_or_else(|e| {
        panic!(
            "no golden at {} ({e}); create it with RONRAY_BLESS=1 cargo test --test sdf",
            golden.display()
        )
    });
    let got = as_stored(&img, name);
    let c = compare(&got, &want, None).unwrap();
    if c.rmse >= GOLDEN_RMSE {
        // Leave the fresh image where a reviewer can diff it.
        let fresh = root().join(format!("target/golden-fresh/{name}.png"));
        std::fs::create_dir_all(fresh.parent().unwrap()).unwrap();
        write_image(&img, &fresh).unwrap();
        panic!(
            "{name}: RMSE {:.5} against the golden is not below {GOLDEN_RMSE}; fresh image at {} \
             (bless with RONRAY_BLESS=1 if the change is intended)",
            c.rmse,
            fresh.display()
        );
    }
}

#[test]
fn golden_sdf_shapes() {
    check_golden("sdf_shapes", 8);
}

#[test]
fn golden_mandelbulb() {
    check_golden("mandelbulb", 4);
}

#[test]
fn sdf_scenes_round_trip_through_ron() {
    for name in ["sdf_shapes", "mandelbulb"] {
        let loaded = load_with(&root().join(format!("scenes/{name}.ron")), &Overrides::default()).unwrap();
        let text = ron::ser::to_string_pretty(&loaded.desc, Default::default()).unwrap();
        let again = ronray::scene::load::parse(Path::new("again.ron"), &text)
            .unwrap_or_else(|r| panic!("{name} does not parse back:\n{}\n{text}", r.render(false)));
        assert_eq!(again, loaded.desc, "{name} changed in the round trip");
    }
}
