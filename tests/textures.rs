//! Textures, normal maps and cut-outs in whole renders: a flat normal map
//! changes nothing, a cut-out's shadow is its mask's, and the reference
//! comparison catches an sRGB map read as linear.

use crate::common;

use common::root;
use ronray::frame::render_whole;
use ronray::imageio::{Image, blocks, compare, read_image};
use ronray::load::{Overrides, load_str};

/// Renders scene `text` (as if it were a file in `scenes/`) at 64×64.
fn render_text(text: &str, spp: u32, seed: u64) -> Image {
    let o = Overrides {
        spp: Some(spp),
        size: Some((64, 64)),
        seed: Some(seed),
        ..Default::default()
    };
    let loaded = load_str(&root().join("scenes/test.ron"), text, &o)
        .unwrap_or_else(|e| panic!("scene loads: {e}\n{text}"));
    render_whole(&loaded.scene, &loaded.view, &Default::default()).0
}

fn scene(materials: &str, objects: &str) -> String {
    format!(
        "Scene(
            camera: (eye: (0, 3, 4), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 4),
            materials: {{ {materials} }},
            lights: [Rect(center: (0, 3, 0), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (20, 20, 20))],
            objects: [{objects}],
        )"
    )
}

#[test]
fn flat_normal_map_renders_byte_identical_to_no_map() {
    let objects = r#"Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: "m"),
                     Sphere(center: (0, 0.5, 0), radius: 0.5, material: "m")"#;
    let plain = render_text(&scene(r#""m": Lambert(albedo: 0.6)"#, objects), 4, 1);
    let mapped = render_text(
        &scene(
            r#""m": NormalMap(map: (0.5, 0.5, 1), material: Lambert(albedo: 0.6))"#,
            objects,
        ),
        4,
        1,
    );
    let bits =
        |i: &Image| -> Vec<[u32; 3]> { i.pixels.iter().map(|p| p.to_array().map(f32::to_bits)).collect() };
    assert!(
        bits(&plain) == bits(&mapped),
        "a flat normal map changed the image"
    );
}

#[test]
fn cutout_quad_shadow_matches_its_mask() {
    // A quad with a 2 × 2 checker opacity between the light and the floor,
    // against the same two opaque squares as plain geometry.
    let materials = r#""floor": Lambert(albedo: 0.7),
        "solid": Lambert(albedo: 0.3),
        "cut": Cutout(opacity: Checker(a: 1, b: 0, scale: 2), mode: Threshold(0.5), material: Lambert(albedo: 0.3))"#;
    let floor = r#"Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: "floor")"#;
    let cut_scene = scene(
        materials,
        &format!(
            r#"{floor}, Quad(corner: (-1, 1, 1), edge_u: (2, 0, 0), edge_v: (0, 0, -2), material: "cut")"#
        ),
    );
    let squares = render_text(
        &scene(
            materials,
            &format!(
                r#"{floor}, Quad(corner: (-1, 1, 1), edge_u: (1, 0, 0), edge_v: (0, 0, -1), material: "solid"),
                Quad(corner: (0, 1, 0), edge_u: (1, 0, 0), edge_v: (0, 0, -1), material: "solid")"#
            ),
        ),
        16,
        1,
    );
    let (a, b) = (render_text(&cut_scene, 16, 2), render_text(&cut_scene, 16, 3));
    let noise = blocks(&a, &b, 8).expect("same size");
    let mut bad = Vec::new();
    for (r, n) in blocks(&a, &squares, 8).expect("same size").iter().zip(&noise) {
        for ch in 0..3 {
            // σ of a block mean of one render: E[(a − b)²]/2 per pixel.
            let sigma = (n.sum_sq_diff[ch] / 2.0).sqrt() / r.pixels as f64;
            let tol = 5.0 * sigma * 2f64.sqrt() + 0.02 * r.mean_b[ch] + 0.001;
            if (r.mean_a[ch] - r.mean_b[ch]).abs() > tol {
                bad.push(format!(
                    "block ({}, {}) channel {ch}: {:.4} vs {:.4} (tolerance {tol:.4})",
                    r.x, r.y, r.mean_a[ch], r.mean_b[ch]
                ));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "cut-out shadow differs from the opaque squares':\n{}",
        bad.join("\n")
    );
    // And the holes are really open: without the cut-out the shadow is whole.
    let solid = render_text(&cut_scene.replace("Checker(a: 1, b: 0, scale: 2)", "1"), 16, 2);
    let open = compare(&a, &solid, None).expect("same size");
    assert!(
        open.mean_a[0] > 1.05 * open.mean_b[0],
        "holes let no light through: {:?}",
        open.mean_a
    );
}

#[test]
fn srgb_map_read_as_linear_is_caught_by_the_reference() {
    let text = std::fs::read_to_string(root().join("scenes/textured_spheres.ron")).expect("scene");
    let wrong = text.replace(
        r#"albedo: Image(file: "../assets/textures/ts_floor_albedo.png", origin: TopLeft"#,
        r#"albedo: Image(file: "../assets/textures/ts_floor_albedo.png", colorspace: Linear, origin: TopLeft"#,
    );
    assert_ne!(wrong, text, "the floor albedo is where the test expects it");
    let reference = read_image(&root().join("tests/fixtures/refs/textured_spheres_64.pfm")).expect("fixture");
    let mean_error = |t: &str| {
        let c = compare(&render_text(t, 16, 1), &reference, None).expect("same size");
        (0..3)
            .map(|ch| ((c.mean_a[ch] - c.mean_b[ch]) / c.mean_b[ch]).abs())
            .fold(0.0, f64::max)
    };
    let (right, wrong) = (mean_error(&text), mean_error(&wrong));
    assert!(right < 0.01, "as authored: mean off by {right:.4}");
    assert!(
        wrong > 0.05,
        "an sRGB albedo read as linear moved the mean by only {wrong:.4}"
    );
}

/// A floor lit by `lights`, seen from below the lights' plane (y = 1), so
/// camera rays see their undersides too.
fn lit_floor(lights: &str) -> String {
    format!(
        "Scene(
            camera: (eye: (0, 0.9, 4), target: (0, 0.3, 0), fov_y_degrees: 60),
            integrator: Path(max_depth: 3),
            materials: {{ \"floor\": Lambert(albedo: 0.7) }},
            lights: [{lights}],
            objects: [Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: \"floor\")],
        )"
    )
}

/// Block-by-block means of `a` (and a second seed `a2` of it, for the
/// noise) against `b`: the blocks further apart than 5σ.
fn blocks_apart(a: &Image, a2: &Image, b: &Image) -> Vec<String> {
    let noise = blocks(a, a2, 8).expect("same size");
    let mut bad = Vec::new();
    for (r, n) in blocks(a, b, 8).expect("same size").iter().zip(&noise) {
        for ch in 0..3 {
            let sigma = (n.sum_sq_diff[ch] / 2.0).sqrt() / r.pixels as f64;
            let tol = 5.0 * sigma * 2f64.sqrt() + 0.02 * r.mean_b[ch] + 0.001;
            if (r.mean_a[ch] - r.mean_b[ch]).abs() > tol {
                bad.push(format!(
                    "block ({}, {}) channel {ch}: {:.4} vs {:.4} (tolerance {tol:.4})",
                    r.x, r.y, r.mean_a[ch], r.mean_b[ch]
                ));
            }
        }
    }
    bad
}

#[test]
fn checker_emission_lights_the_floor_as_its_lit_squares_do() {
    // A 2 × 2 checker of radiance 10 and 0 on a light 1 above the floor
    // (near enough for its solid-angle sampling), against the two lit
    // squares as constant lights.
    let textured = lit_floor(
        "Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1),
              radiance: Checker(a: (10, 10, 10), b: (0, 0, 0), scale: 2))",
    );
    let squares = lit_floor(
        "Rect(center: (-0.5, 1, -0.5), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (10, 10, 10)),
         Rect(center: (0.5, 1, 0.5), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (10, 10, 10))",
    );
    let (a, a2) = (render_text(&textured, 16, 2), render_text(&textured, 16, 3));
    let b = render_text(&squares, 16, 1);
    let bad = blocks_apart(&a, &a2, &b);
    assert!(
        bad.is_empty(),
        "textured light differs from its squares:\n{}",
        bad.join("\n")
    );
    // The pattern shows: the floor under a lit square is brighter than under a dark one.
    let c = compare(
        &a,
        &render_text(&textured.replace("b: (0, 0, 0)", "b: (10, 10, 10)"), 16, 2),
        None,
    )
    .expect("same size");
    assert!(
        c.mean_a[0] < 0.8 * c.mean_b[0],
        "half the light dark, yet the floor is as bright: {:?} vs {:?}",
        c.mean_a,
        c.mean_b
    );
}

#[test]
fn image_emission_on_a_small_far_quad_lights_as_its_average() {
    // A small emitter far above the floor lights it as a constant of the
    // texture's average would (every floor point sees the whole flat quad
    // under nearly one angle); the image is a 2 × 1 white-and-black PNG
    // whose bilinear average is half its white. Spheres, whose texels each
    // floor point sees a different half of, are tested against brute force
    // in `lights/tests.rs`.
    let dir = std::env::temp_dir().join(format!("ronray-emission-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let png = dir.join("half.png");
    image::RgbImage::from_raw(2, 1, vec![255, 255, 255, 0, 0, 0])
        .expect("2 × 1")
        .save(&png)
        .expect("write png");
    let scene = |radiance: &str| {
        format!(
            "Scene(
                camera: (eye: (0, 4, 3), target: (0, 0, 0), fov_y_degrees: 50),
                integrator: Path(max_depth: 2),
                materials: {{ \"floor\": Lambert(albedo: 0.7), \"black\": Lambert(albedo: 0) }},
                objects: [
                    Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: \"floor\"),
                    Rect(center: (0, 6, 0), half_u: (0.05, 0, 0), half_v: (0, 0, 0.05), material: \"black\",
                         emission: (radiance: {radiance}, two_sided: true)),
                ],
            )"
        )
    };
    let file = png.to_str().expect("utf-8 temp path").replace('\\', "/");
    let textured = scene(&format!(
        "Image(file: \"{file}\", colorspace: Linear, scale: 3200)"
    ));
    let constant = scene("(1600, 1600, 1600)");
    let (a, a2) = (render_text(&textured, 16, 2), render_text(&textured, 16, 3));
    let b = render_text(&constant, 16, 1);
    let _ = std::fs::remove_dir_all(&dir);
    let bad = blocks_apart(&a, &a2, &b);
    assert!(
        bad.is_empty(),
        "textured emitters differ from their average:\n{}",
        bad.join("\n")
    );
}

#[test]
fn shadow_rays_pass_cut_outs_and_stop_at_opaque_shapes_through_the_scene_bvh() {
    // Twelve opaque spheres (more shapes than the SIMD lanes take, so the
    // scene BVH orders them), a quad with a 2 × 2 checker cut-out and a
    // mesh whose cut-out is all hole: shadow rays ask each shape whether
    // it may let them through, by its index in the BVH's order.
    let spheres: Vec<String> = (0..12)
        .map(|k| {
            format!(
                r#"Sphere(center: ({}, 5, 0), radius: 0.2, material: "solid")"#,
                -3.0 + 0.5 * k as f32
            )
        })
        .collect();
    let text = |block_opacity: &str| {
        format!(
            r#"Scene(
                camera: (eye: (0, 3, 6), target: (0, 0, 0), fov_y_degrees: 40),
                materials: {{
                    "solid": Lambert(albedo: 0.3),
                    "cut": Cutout(opacity: Checker(a: 1, b: 0, scale: 2), mode: Threshold(0.5), material: Lambert(albedo: 0.3)),
                    "block": Cutout(opacity: {block_opacity}, mode: Threshold(0.5), material: Lambert(albedo: 0.3)),
                }},
                lights: [Rect(center: (0, 9, 0), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (20, 20, 20))],
                objects: [
                    {},
                    Quad(corner: (-1, 1, 1), edge_u: (2, 0, 0), edge_v: (0, 0, -2), material: "cut"),
                    Mesh(file: "../assets/short_block.obj", material: "block"),
                ],
            )"#,
            spheres.join(",\n")
        )
    };
    let load = |t: &str| {
        load_str(&root().join("scenes/test.ron"), t, &Overrides::default())
            .unwrap_or_else(|e| panic!("scene loads: {e}"))
            .scene
    };
    let down = |x: f32, y: f32, z: f32| ronray::math::Ray::new(glam::Vec3A::new(x, y, z), -glam::Vec3A::Y);
    for (opacity, block_blocks) in [("0", false), ("1", true)] {
        let scene = load(&text(opacity));
        // The quad's four checker cells, from above, stopping short of the block.
        let cells: Vec<bool> = [(-0.5, 0.5), (0.5, 0.5), (-0.5, -0.5), (0.5, -0.5)]
            .iter()
            .map(|&(x, z)| scene.occluded(&down(x, 3.0, z), 2.5))
            .collect();
        assert_eq!(
            cells.iter().filter(|&&b| b).count(),
            2,
            "checker cells blocked: {cells:?}"
        );
        assert!(
            cells[0] == cells[3] && cells[1] == cells[2] && cells[0] != cells[1],
            "not a checker: {cells:?}"
        );
        // Every sphere blocks a ray through its centre.
        for k in 0..12 {
            let x = -3.0 + 0.5 * k as f32;
            assert!(
                scene.occluded(&down(x, 6.0, 0.0), 2.0),
                "sphere {k} let a shadow ray through"
            );
        }
        // Through the block (y −1 to −0.4), below the quad.
        assert_eq!(
            scene.occluded(&down(0.35, 0.0, 0.38), 2.0),
            block_blocks,
            "the block with opacity {opacity}"
        );
    }
}
