//! Participating media against closed forms: transmittance through an
//! absorbing slab, single scattering in a thin slab, and a white furnace.
//! The slab is `tests/fixtures/media/slab.obj` (10 × 10 × 0.5, z from
//! −0.25 to 0.25), an index-matched boundary around its medium; an
//! orthographic camera looks straight through it at a constant sky.

mod common;

use common::{load_in, render_loaded, root};
use ronray::imageio::Image;
use ronray::load::Overrides;

/// Thickness of the slab fixture.
const D: f64 = 0.5;

/// Renders `text` as a file in `tests/fixtures/media/`.
fn render(text: &str) -> Image {
    let loaded = load_in(&root().join("tests/fixtures/media"), text, &Overrides::default());
    render_loaded(&loaded)
}

/// The slab filled with `medium`, seen straight on against a constant sky
/// of radiance 1, `spp` samples, paths of `max_depth` segments.
fn slab_scene(medium: &str, spp: u32, max_depth: i32) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 0, 3), target: (0, 0, 0), projection: Orthographic(view_height: 2)),
            film: (width: 32, height: 32, spp: {spp}),
            integrator: Path(max_depth: {max_depth}),
            media: {{ "m": {medium} }},
            lights: [Environment(radiance: (1, 1, 1))],
            objects: [Mesh(file: "slab.obj", interior: "m")],
        )"#
    )
}

/// The image's mean per channel.
fn mean(img: &Image) -> [f64; 3] {
    let mut m = [0.0; 3];
    for p in &img.pixels {
        for (c, v) in m.iter_mut().enumerate() {
            *v += p[c] as f64;
        }
    }
    m.map(|v| v / img.pixels.len() as f64)
}

/// E₂(x) = ∫₀¹ exp(−x/μ) dμ, the exponential integral that slab
/// transport reduces to (midpoint rule).
fn e2(x: f64) -> f64 {
    let n = 2000;
    (0..n)
        .map(|i| {
            let mu = (i as f64 + 0.5) / n as f64;
            (-x / mu).exp()
        })
        .sum::<f64>()
        / n as f64
}

#[test]
fn absorbing_slab_transmits_exp_of_minus_sigma_t_d_per_pixel() {
    let sigma = [0.5, 1.0, 2.0];
    let img = render(&slab_scene(
        "Homogeneous(sigma_a: (0.5, 1, 2), sigma_s: (0, 0, 0))",
        1,
        8,
    ));
    for (i, p) in img.pixels.iter().enumerate() {
        for c in 0..3 {
            let expected = (-sigma[c] * D).exp();
            let got = p[c] as f64;
            assert!(
                (got - expected).abs() < 1e-3 * expected,
                "pixel {i} channel {c}: expected exp(−{} × {D}) = {expected:.6}, got {got:.6}",
                sigma[c]
            );
        }
    }
}

/// With `max_depth: 2` the camera sees the sky through the slab plus light
/// scattered once: for a point at depth s, light arrives from the sky
/// through s/|μ| or (d − s)/|μ| of medium, so
/// L = e^{−σ_t d} + σ_s/2 ∫₀^d e^{−σ_t s} [E₂(σ_t s) + E₂(σ_t (d − s))] ds
/// (isotropic phase, sky radiance 1). A second scattering event would add
/// about 10% here, so a wrong depth count fails too.
#[test]
fn thin_slab_single_scattering_matches_its_closed_form() {
    let (sigma_t, sigma_s) = (1.0f64, 0.8f64);
    let n = 400;
    let single: f64 = (0..n)
        .map(|i| {
            let s = (i as f64 + 0.5) / n as f64 * D;
            (-sigma_t * s).exp() * (e2(sigma_t * s) + e2(sigma_t * (D - s)))
        })
        .sum::<f64>()
        * D
        / n as f64
        * sigma_s
        / 2.0;
    let expected = (-sigma_t * D).exp() + single;
    let img = render(&slab_scene(
        "Homogeneous(sigma_t: (1, 1, 1), albedo: (0.8, 0.8, 0.8))",
        64,
        2,
    ));
    let m = mean(&img);
    for (c, got) in m.iter().enumerate() {
        assert!(
            (got - expected).abs() < 0.005 * expected,
            "channel {c}: expected {expected:.5} (of which single scattering {single:.5}), got {got:.5}"
        );
    }
}

/// A sphere of a non-absorbing medium (albedo 1, forward-scattering
/// Henyey–Greenstein) under a constant sky of radiance 1, paths of any
/// length: every pixel sees the sky's radiance (the medium only shuffles
/// light around), within 1% on average and 5% on every 8 × 8 block.
#[test]
fn white_furnace_with_a_scattering_sphere_stays_at_the_sky_radiance() {
    let img = render(
        r#"Scene(
            camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 32),
            film: (width: 32, height: 32, spp: 64),
            integrator: Path(max_depth: -1, rr_depth: 5),
            media: { "cloud": Homogeneous(sigma_t: (2, 2, 2), g: 0.4) },
            lights: [Environment(radiance: (1, 1, 1))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, interior: "cloud")],
        )"#,
    );
    let m = mean(&img);
    for (c, got) in m.iter().enumerate() {
        assert!(
            (got - 1.0).abs() < 0.01,
            "channel {c}: image mean {got:.5}, expected 1"
        );
    }
    for by in 0..4 {
        for bx in 0..4 {
            let mut sum = 0.0f64;
            for y in 0..8 {
                for x in 0..8 {
                    sum += img.get(bx * 8 + x, by * 8 + y).x as f64;
                }
            }
            let block = sum / 64.0;
            assert!(
                (block - 1.0).abs() < 0.05,
                "block ({bx}, {by}): {block:.4}, expected 1"
            );
        }
    }
}

/// The same sphere with an absorbing medium is darker than the sky where
/// it is seen: the furnace test above can fail.
#[test]
fn absorbing_sphere_darkens_the_furnace() {
    let img = render(
        r#"Scene(
            camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 32),
            film: (width: 16, height: 16, spp: 16),
            integrator: Path(max_depth: -1),
            media: { "ink": Homogeneous(sigma_t: (2, 2, 2), albedo: (0.5, 0.5, 0.5)) },
            lights: [Environment(radiance: (1, 1, 1))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, interior: "ink")],
        )"#,
    );
    assert!(
        img.get(8, 8).x < 0.8,
        "centre {} should be well below the sky's 1",
        img.get(8, 8).x
    );
}

/// A `.vol` grid of constant density filling the slab's box, as the
/// camera's medium (σ_t = 0 outside the box): delta tracking passes a
/// fraction exp(−σ_t d) of the rays, and a half-density grid (values 0.5,
/// scale doubled) gives the same; a grid beside the view changes nothing.
#[test]
fn grid_medium_transmits_as_its_optical_depth_says() {
    let dir = std::env::temp_dir().join(format!("ronray-media-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let bytes = ronray::media::vol::write_vol([4, 4, 2], &[0.5; 32], [-5.0, -5.0, -0.25], [5.0, 5.0, 0.25]);
    std::fs::write(dir.join("half.vol"), bytes).expect("write .vol");
    let scene = |min: &str, max: &str| {
        format!(
            r#"Scene(
                camera: (eye: (0, 0, 3), target: (0, 0, 0), projection: Orthographic(view_height: 2)),
                film: (width: 32, height: 32, spp: 16),
                integrator: Path(max_depth: 8),
                media: {{ "smoke": Grid(file: "half.vol", min: {min}, max: {max}, scale: 2, albedo: (0, 0, 0)) }},
                medium: "smoke",
                lights: [Environment(radiance: (1, 1, 1))],
            )"#
        )
    };
    let img = render_loaded(&load_in(
        &dir,
        &scene("(-5, -5, -0.25)", "(5, 5, 0.25)"),
        &Overrides::default(),
    ));
    let expected = (-D).exp();
    let m = mean(&img);
    assert!(
        (m[0] - expected).abs() < 0.03 * expected,
        "mean {:.4}, expected exp(−1 × 0.5) = {expected:.4}",
        m[0]
    );
    let beside = render_loaded(&load_in(
        &dir,
        &scene("(6, -5, -0.25)", "(16, 5, 0.25)"),
        &Overrides::default(),
    ));
    assert!(
        beside.pixels.iter().all(|p| (p.x - 1.0).abs() < 1e-6),
        "a grid beside the view dimmed it"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Located errors: an undefined medium, negative coefficients, g outside
/// (−1, 1), both parametrisations at once, a grid that does not parse.
#[test]
fn media_mistakes_are_located_errors() {
    let dir = std::env::temp_dir().join(format!("ronray-media-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("bad.vol"), b"VOL\x03 not a grid").expect("write");
    let text = r#"Scene(
        camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
        integrator: Path(max_depth: 8),
        media: {
            "neg": Homogeneous(sigma_t: (1, -1, 1)),
            "hg": Homogeneous(sigma_t: (1, 1, 1), g: 1.0),
            "both": Homogeneous(sigma_t: (1, 1, 1), sigma_a: (1, 1, 1), sigma_s: (1, 1, 1)),
        },
        medium: "fgo",
        objects: [Sphere(center: (0, 0, 0), radius: 1, interior: "nope")],
    )"#;
    let err = match ronray::load::load_str(&dir.join("bad.ron"), text, &Overrides::default()) {
        Ok(_) => panic!("a scene with media mistakes loaded"),
        Err(e) => common::message(&e),
    };
    for expected in [
        "negative coefficient",
        "g 1 is outside (−1, 1)",
        "give either `sigma_t`",
        "unknown medium `fgo`",
        "unknown medium `nope`",
    ] {
        assert!(err.contains(expected), "expected `{expected}` in:\n{err}");
    }
    let grid = r#"Scene(
        camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
        integrator: Path(max_depth: 8),
        media: { "g": Grid(file: "bad.vol", min: (0, 0, 0), max: (1, 1, 1)) },
        medium: "g",
    )"#;
    let err = match ronray::load::load_str(&dir.join("grid.ron"), grid, &Overrides::default()) {
        Ok(_) => panic!("a broken grid loaded"),
        Err(e) => common::message(&e),
    };
    assert!(err.contains("bad.vol") && err.contains("header"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// An index-matched boundary (a mesh with a medium and no material) is
/// never shaded, so its OBJ groups taking the grey default earn no note;
/// the same mesh as a plain object still gets one.
#[test]
fn null_boundary_meshes_take_no_grey_material_note() {
    let notes = |object: &str| {
        let text = format!(
            r#"Scene(
                camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
                integrator: Path(max_depth: 4),
                media: {{ "m": Homogeneous(sigma_t: (1, 1, 1)) }},
                lights: [Environment(radiance: (1, 1, 1))],
                objects: [{object}],
            )"#
        );
        load_in(&root().join("tests/fixtures/media"), &text, &Overrides::default())
            .stats
            .notes
    };
    let null = notes(r#"Mesh(file: "slab.obj", interior: "m")"#);
    assert!(!null.iter().any(|n| n.contains("grey")), "notes: {null:?}");
    let shaded = notes(r#"Mesh(file: "slab.obj")"#);
    assert!(shaded.iter().any(|n| n.contains("grey")), "notes: {shaded:?}");
}
