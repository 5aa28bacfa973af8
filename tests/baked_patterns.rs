//! A procedural pattern and the same pattern baked to an EXR render the same
//! image within noise, and a procedural pattern is identical on any number
//! of threads.
//!
//! The bake evaluates [`Pattern::eval`] at each texel's centre, as an offline
//! baker would, and the scene reads it back with `Image(…, scale, offset)`:
//! what differs between the two renders is only bilinear reconstruction
//! (512 texels per UV unit, 128 per noise cell) against the exact function.

use crate::common;

use common::load_in;
use glam::Vec2;
use ronray::frame::{RenderOptions, render_whole};
use ronray::imageio::{Image, blocks};
use ronray::load::Overrides;
use ronray::materials::Pattern;
use std::path::Path;

/// Texels per side of the baked image.
const SIDE: u32 = 512;
/// Noise cells per UV unit in both scenes.
const CELLS: f32 = 4.0;

/// A floor and a ball of grey albedo `albedo` under a rectangle light.
fn scene(albedo: &str) -> String {
    format!(
        "Scene(
            camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 50),
            integrator: Path(max_depth: 3),
            materials: {{ \"m\": Lambert(albedo: {albedo}) }},
            lights: [Rect(center: (0, 3, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), radiance: (8, 8, 8))],
            objects: [
                Rect(center: (0, 0, 0), half_u: (2, 0, 0), half_v: (0, 0, -2), material: \"m\"),
                Sphere(center: (0.4, 0.5, 0.2), radius: 0.5, material: \"m\"),
            ],
        )"
    )
}

/// The procedural albedo: fBm from 0.15 to 0.85, `CELLS` cells per UV unit.
fn procedural(seed: u32) -> String {
    scene(&format!(
        "Pattern(pattern: Fbm(octaves: 4), a: (0.15, 0.15, 0.15), b: (0.85, 0.85, 0.85), seed: {seed}, uv: (scale: ({CELLS}, {CELLS})))"
    ))
}

/// Bakes `pattern` over the unit UV square (as the scene's UV transform
/// scales it) into a `SIDE`² linear EXR, first row at v = 1 (the default
/// `BottomLeft` origin).
fn bake(pattern: Pattern, path: &Path) {
    let mut texels = Vec::with_capacity((SIDE * SIDE * 3) as usize);
    for row in 0..SIDE {
        for col in 0..SIDE {
            let uv = Vec2::new(
                (col as f32 + 0.5) / SIDE as f32,
                1.0 - (row as f32 + 0.5) / SIDE as f32,
            );
            let p = pattern.eval(uv * CELLS);
            texels.extend([p; 3]);
        }
    }
    image::Rgb32FImage::from_raw(SIDE, SIDE, texels)
        .expect("SIDE² texels")
        .save(path)
        .expect("write the EXR");
}

fn fbm(seed: u32) -> Pattern {
    Pattern::Fbm {
        seed,
        octaves: 4,
        lacunarity: 2.0,
        gain: 0.5,
    }
}

fn render(dir: &Path, text: &str, seed: u64, threads: usize) -> Image {
    let o = Overrides {
        spp: Some(16),
        size: Some((64, 64)),
        seed: Some(seed),
        ..Default::default()
    };
    let loaded = load_in(dir, text, &o);
    let opts = RenderOptions {
        threads: Some(threads),
        ..Default::default()
    };
    render_whole(&loaded.scene, &loaded.view, &opts).0
}

/// The blocks where `a` and `b` differ by more than 5σ of one render's
/// block mean, σ measured from `a` against `a2` (another seed of `a`).
fn blocks_apart(a: &Image, a2: &Image, b: &Image) -> Vec<String> {
    let noise = blocks(a, a2, 8).expect("same size");
    let mut bad = Vec::new();
    for (r, n) in blocks(a, b, 8).expect("same size").iter().zip(&noise) {
        // σ of a block mean of one render: E[(a − a2)²]/2 per pixel.
        let sigma = (n.sum_sq_diff[0] / 2.0).sqrt() / r.pixels as f64;
        let tol = 5.0 * sigma * 2f64.sqrt() + 1e-3;
        if (r.mean_a[0] - r.mean_b[0]).abs() > tol {
            bad.push(format!(
                "block ({}, {}): {:.4} vs {:.4} (tolerance {tol:.4})",
                r.x, r.y, r.mean_a[0], r.mean_b[0]
            ));
        }
    }
    bad
}

#[test]
fn baked_pattern_renders_as_the_procedural_one_within_noise() {
    let dir = tempfile::tempdir().expect("temp dir");
    bake(fbm(7), &dir.path().join("baked.exr"));
    bake(fbm(8), &dir.path().join("other.exr"));
    let baked = |file: &str| scene(&format!("Image(file: \"{file}\", scale: 0.7, offset: 0.15)"));
    let (a, a2) = (
        render(dir.path(), &procedural(7), 1, 2),
        render(dir.path(), &procedural(7), 2, 2),
    );
    let b = render(dir.path(), &baked("baked.exr"), 3, 2);
    let bad = blocks_apart(&a, &a2, &b);
    assert!(
        bad.is_empty(),
        "baked and procedural differ beyond noise:\n{}",
        bad.join("\n")
    );
    // The metric sees a pattern: another seed's bake is told apart.
    let other = render(dir.path(), &baked("other.exr"), 3, 2);
    assert!(
        blocks_apart(&a, &a2, &other).len() > 3,
        "the comparison cannot tell two different noises apart"
    );
}

#[test]
fn procedural_pattern_is_identical_on_any_thread_count() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text = scene(
        "Pattern(pattern: Cellular, a: (0.1, 0.2, 0.3), b: (0.9, 0.8, 0.5), seed: 3, uv: (scale: (6, 6)))",
    );
    let one = render(dir.path(), &text, 5, 1);
    let bits =
        |i: &Image| -> Vec<[u32; 3]> { i.pixels.iter().map(|p| p.to_array().map(f32::to_bits)).collect() };
    for threads in [2, 3] {
        let many = render(dir.path(), &text, 5, threads);
        assert!(bits(&one) == bits(&many), "{threads} threads changed the image");
    }
}
