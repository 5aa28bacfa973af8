//! The path tracer against Mitsuba 3 references (`tests/fixtures/refs/`:
//! the 256² references box-downsampled to 64², which with a box pixel filter
//! is the same integral as rendering at 64²).
//!
//! An unbiased renderer's error against a (nearly exact) reference is its
//! own noise: MSE(a, ref) ≈ MSE(a, b)/2 for two independent renders a, b.
//! Bias shows up as error in excess of that, so this checks for bias without
//! depending on how noisy the sampler is.
//!
//! Whole-image figures dilute a wrong region (a far floor rendered at 0.5% of
//! the reference moved the whole-image RMSE less than the noise), so every
//! 8 × 8 block is judged too: see `common::check_blocks` (the bar is shared
//! with `tests/animation.rs`, whose references are means of still renders).

use crate::common;

use common::root;
use ronray::frame::render_whole;
use ronray::imageio::{Image, compare, read_image};
use ronray::load::{Overrides, load_with};

fn render_at(scene: &str, spp: u32, seed: u64) -> Image {
    let o = Overrides {
        spp: Some(spp),
        size: Some((64, 64)),
        seed: Some(seed),
        ..Default::default()
    };
    let loaded = load_with(&root().join(scene), &o).unwrap_or_else(|e| panic!("{scene}: {e}"));
    render_whole(&loaded.scene, &loaded.view, &Default::default()).0
}

fn check(scene: &str, reference: &str, spp: u32) {
    check_within(scene, reference, spp, 0.01);
}

/// [`check`] with the channel means within `mean_rel` of the reference's;
/// returns the two renders (seeds 1 and 2) for further checks. The bar is
/// [`common::reference_bar`]'s, over all pixels and off the light.
fn check_within(scene: &str, reference: &str, spp: u32, mean_rel: f64) -> (Image, Image) {
    let fixture = |f: &str| read_image(&root().join("tests/fixtures/refs").join(f)).expect("fixture");
    let reference_img = fixture(&format!("{reference}_64.pfm"));
    let mask = fixture(&format!("{reference}_mask_64.pfm"));
    let skip: Vec<bool> = mask.pixels.iter().map(|p| p.x > 0.5).collect();
    let a = render_at(scene, spp, 1);
    let b = render_at(scene, spp, 2);
    common::reference_bar(scene, &a, &b, &reference_img, Some(&skip), mean_rel);
    (a, b)
}

#[test]
fn path_matches_mitsuba_on_a_large_floor_lit_at_low_angles() {
    check("scenes/floor_rect.ron", "floor_rect", 64);
}

#[test]
fn path_matches_mitsuba_cornell_diffuse() {
    check("scenes/cornell.ron", "cornell_diffuse", 64);
}

#[test]
fn path_matches_mitsuba_cornell_specular() {
    // 256 spp: at 64, the caustic under the glass sphere is noisy enough in
    // its heavy tail to bring one block to 0.96 of its tolerance.
    check("scenes/cornell_specular.ron", "cornell_specular", 256);
}

#[test]
fn path_matches_mitsuba_cornell_dof() {
    check("scenes/cornell_dof.ron", "cornell_dof", 64);
}

#[test]
fn path_matches_mitsuba_env_spheres() {
    check("scenes/env_spheres.ron", "env_spheres", 64);
}

#[test]
fn path_matches_mitsuba_emissive_shapes() {
    check("scenes/emissive_shapes.ron", "emissive_shapes", 64);
}

/// Textures on colours and on GGX α, a normal map, and cut-outs (Mitsuba's
/// `mask`), with Mitsuba's UV and image conventions; means within 0.5%.
#[test]
fn path_matches_mitsuba_textured_spheres() {
    check_within("scenes/textured_spheres.ron", "textured_spheres", 64, 0.005);
}

/// glTF import (issue 41): the Khronos FlightHelmet (six meshes, 94,722
/// triangles, base-colour and normal maps) under the sky, against Mitsuba 3
/// rendering the same files through `tools/gltf_to_mitsuba.py`. Both sides
/// use the material model they share (the scene's overrides: rough plastic
/// over the base-colour map, the normal map in the per-triangle ∂p/∂u
/// frame), so this judges what the importer reads: node tree, positions,
/// normals, UVs and their v flip, and which texel each lookup lands on.
/// Means within 0.5% (the image mean's noise at 64 spp is ~0.1%). At this
/// distance the normal maps are finer than a 64² pixel: the bar passes
/// without them (docs/gltf.md, "Planted defects").
#[test]
fn path_matches_mitsuba_gltf_flight_helmet() {
    check_within(
        "tests/fixtures/refs/flight_helmet.ron",
        "flight_helmet",
        64,
        0.005,
    );
}

/// The Cornell box in homogeneous fog (σ_t 0.5, albedo 0.8, camera inside)
/// against Mitsuba's `volpath`: the path tracer's volumetric branch
/// (`integrators/vol_path.rs`). The fog's image mean (0.037) is noisy: two
/// 64² renders at 1,024 spp differ by 0.45%, hence [`check_volpath`]'s
/// tolerances.
#[test]
fn path_matches_mitsuba_volpath_fog_box() {
    check_volpath("scenes/fog_box.ron", "fog_box");
}

/// A heterogeneous medium: the smooth blob of `blob.vol` (a 32³ grid,
/// trilinear, in an index-matched box; delta and ratio tracking) against
/// Mitsuba's `heterogeneous` medium reading the same file
/// (`tools/media_refs.py`). A grid read with x and z swapped fails it.
#[test]
fn path_matches_mitsuba_volpath_media_blob() {
    check_volpath("tests/fixtures/media/media_blob.ron", "media_blob");
}

/// Subsurface scattering: a glass sphere (IOR 1.5) holding a dense
/// (mean free path a tenth of the radius), nearly white medium, against
/// Mitsuba's `volpath` with max_depth 256 in both. Light reaches the inside
/// only through the refracting boundary (shadow rays from inside are
/// blocked by the glass), so this tests the boundary's medium changes, its
/// (n₁/n₂)² radiance scaling and long paths. An albedo of 0.98 instead of
/// 0.99 fails it.
#[test]
fn path_matches_mitsuba_volpath_subsurface_sphere() {
    check_volpath("tests/fixtures/media/subsurface_sphere.ron", "subsurface_sphere");
}

/// The reference bar for media scenes, whose image means converge slowly:
/// [`check_within`] at 64 and 256 spp (one render's channel means within
/// 1%), and the mean of its four renders (640 spp per pixel) within 0.5%.
fn check_volpath(scene: &str, reference: &str) {
    let (a64, b64) = check_within(scene, reference, 64, 0.01);
    let (a256, b256) = check_within(scene, reference, 256, 0.01);
    let reference_img =
        read_image(&root().join(format!("tests/fixtures/refs/{reference}_64.pfm"))).expect("fixture");
    let all = Image {
        width: a64.width,
        height: a64.height,
        pixels: (0..a64.pixels.len())
            .map(|i| {
                (64.0 * (a64.pixels[i] + b64.pixels[i]) + 256.0 * (a256.pixels[i] + b256.pixels[i])) / 640.0
            })
            .collect(),
    };
    let c = compare(&all, &reference_img, None).expect("same size");
    for ch in 0..3 {
        let rel = (c.mean_a[ch] - c.mean_b[ch]).abs() / c.mean_b[ch];
        assert!(
            rel < 0.005,
            "{reference} at 640 spp: channel {ch} mean {:.5} vs reference {:.5}",
            c.mean_a[ch],
            c.mean_b[ch]
        );
    }
}

/// `tests/fixtures/media/blob.vol`, generated: three smooth bumps
/// w (1 − d²/r²)² summed in f64 and rounded once to f32, x fastest. The
/// arithmetic is `blob_values` of `tools/media_refs.py` operation for
/// operation, so both sides produce the same bytes.
fn blob_vol() -> Vec<u8> {
    const RES: u32 = 32;
    // (centre x, y, z, radius, weight) in the grid's unit cube.
    const BUMPS: [(f64, f64, f64, f64, f64); 3] = [
        (0.5, 0.45, 0.5, 0.42, 1.0),
        (0.7, 0.68, 0.42, 0.2, 0.9),
        (0.3, 0.6, 0.72, 0.17, 0.7),
    ];
    let n = RES as f64;
    let mut values = Vec::with_capacity((RES * RES * RES) as usize);
    for k in 0..RES {
        for j in 0..RES {
            for i in 0..RES {
                let p = [(i as f64 + 0.5) / n, (j as f64 + 0.5) / n, (k as f64 + 0.5) / n];
                let mut v = 0.0f64;
                for (cx, cy, cz, r, w) in BUMPS {
                    let (dx, dy, dz) = (p[0] - cx, p[1] - cy, p[2] - cz);
                    let d2 = (dx * dx + dy * dy + dz * dz) / (r * r);
                    if d2 < 1.0 {
                        let s = 1.0 - d2;
                        v += w * (s * s);
                    }
                }
                values.push(v as f32);
            }
        }
    }
    ronray::media::vol::write_vol([RES; 3], &values, [-1.0, 0.0625, -1.0], [1.0, 2.0625, 1.0])
}

/// The committed grid is the generator's, byte for byte (Mitsuba's
/// reference was rendered from that file), and it is not symmetric under
/// swapping x and z, so a transposed read would change the image.
#[test]
fn blob_fixture_is_what_the_generator_writes() {
    let committed = std::fs::read(root().join("tests/fixtures/media/blob.vol")).expect("fixture");
    let generated = blob_vol();
    assert_eq!(committed.len(), generated.len(), "blob.vol length");
    let first = committed.iter().zip(&generated).position(|(a, b)| a != b);
    assert_eq!(
        first, None,
        "blob.vol differs from its generator from byte {first:?}"
    );
    let grid = ronray::media::vol::parse_vol(&committed).expect("parses");
    let at = |x: usize, y: usize, z: usize| grid.values[(z * 32 + y) * 32 + x];
    let asymmetry: f32 = (0..32 * 32 * 32)
        .map(|i| (at(i % 32, i / 32 % 32, i / 1024) - at(i / 1024, i / 32 % 32, i % 32)).abs())
        .sum();
    assert!(asymmetry > 100.0, "x↔z asymmetry of the blob only {asymmetry}");
}

/// Environment importance sampling (luminance × sin θ) against uniform
/// sphere sampling of the same sky, at equal samples per pixel, both with
/// MIS against BSDF sampling: the issue asks for an RMSE ratio below 0.3.
#[test]
fn environment_importance_sampling_beats_uniform_on_env_spheres() {
    use ronray::lights::{EnvSampling, Light};
    let reference_img = read_image(&root().join("tests/fixtures/refs/env_spheres_64.pfm")).expect("fixture");
    let rmse = |sampling: EnvSampling| {
        let o = Overrides {
            spp: Some(32),
            size: Some((64, 64)),
            seed: Some(7),
            ..Default::default()
        };
        let mut loaded = load_with(&root().join("scenes/env_spheres.ron"), &o).expect("scene loads");
        let i = loaded.scene.environment.expect("an environment") as usize;
        let Light::Environment(env) = &mut loaded.scene.lights[i] else {
            panic!("light {i} is the environment");
        };
        env.sampling = sampling;
        let img = render_whole(&loaded.scene, &loaded.view, &Default::default()).0;
        compare(&img, &reference_img, None).expect("same size").rmse
    };
    let (importance, uniform) = (rmse(EnvSampling::Importance), rmse(EnvSampling::Uniform));
    let ratio = importance / uniform;
    eprintln!(
        "env_spheres, 64×64 at 32 spp: RMSE {importance:.5} importance vs {uniform:.5} uniform, ratio {ratio:.3}"
    );
    assert!(
        ratio < 0.3,
        "importance sampling RMSE {importance:.5} vs uniform {uniform:.5}: ratio {ratio:.3} ≥ 0.3"
    );
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
        let loaded = ronray::load::load_str(
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
            &render_whole(&loaded.scene, &loaded.view, &Default::default()).0,
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

/// Directional lights (two suns and a dim sky over a glass ball and a red
/// ball) against Mitsuba's `ptracer`, which finds what a path tracer cannot:
/// the sun's caustic under the glass ball, and the light that caustic
/// sends on (`make_sun_caustic.py`). The particle tracer cannot see
/// through the glass from the camera, so the pixels that meet the ball are
/// left out (the mask) and every 8 × 8 block of the rest is judged as
/// [`common::check_blocks`] judges a whole image. The path tracer alone
/// (`caustics: PathOnly`) must fail the same bar: the check can see the
/// caustic.
#[test]
fn directional_lights_and_their_caustics_match_mitsuba_ptracer() {
    let scene = "tests/fixtures/refs/sun_caustic.ron";
    let fixture = |f: &str| read_image(&root().join("tests/fixtures/refs").join(f)).expect("fixture");
    let reference = fixture("sun_caustic_64.pfm");
    let skip: Vec<bool> = fixture("sun_caustic_mask_64.pfm")
        .pixels
        .iter()
        .map(|p| p.x > 0.5)
        .collect();
    let render = |seed: u64, sets: &[&str]| {
        let o = Overrides {
            spp: Some(256),
            size: Some((64, 64)),
            seed: Some(seed),
            sets: sets.iter().map(|s| s.to_string()).collect(),
            ..Default::default()
        };
        let loaded = load_with(&root().join(scene), &o).expect("scene");
        render_whole(&loaded.scene, &loaded.view, &Default::default()).0
    };
    let (a, b) = (render(1, &[]), render(2, &[]));
    let bad = common::masked_blocks_off(&a, &b, &reference, &skip);
    assert!(
        bad.is_empty(),
        "{} block(s) off the reference:\n{}",
        bad.len(),
        bad.join("\n")
    );
    // The image off the ball, as a whole, within 1%.
    let kept_mean = |img: &Image| {
        let kept = img.pixels.iter().zip(&skip).filter(|(_, s)| !**s);
        let n = kept.clone().count() as f32;
        kept.map(|(p, _)| *p).sum::<glam::Vec3A>() / n
    };
    let (got, want) = (kept_mean(&a), kept_mean(&reference));
    assert!(
        ((got - want).abs() / want).max_element() < 0.01,
        "mean off the ball {got} against {want}"
    );
    let caustics = ["integrator.caustics=PathOnly"];
    let (a, b) = (render(1, &caustics), render(2, &caustics));
    assert!(
        !common::masked_blocks_off(&a, &b, &reference, &skip).is_empty(),
        "the path tracer alone passes: the check cannot see the caustic"
    );
}
