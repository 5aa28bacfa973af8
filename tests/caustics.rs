//! Caustics seen directly are light-traced (`integrator: Path(caustics:
//! LightTracing)`, the default): the same expected image as the path tracer
//! alone, region by region, less noise, the same image on any number of
//! threads, and nothing changed where there is nothing to light-trace.

use crate::common;

use common::{blocks, load_text, report};
use ronray::frame::{Plan, RenderOptions, Request, render_whole};

/// A box lit by a small rectangle, with a mirror sphere and a glass sphere
/// whose caustics land on the floor and walls; `extra` goes into the
/// integrator, `film` into the film, `mirror` and `glass` are the spheres'
/// materials.
fn scene(film: &str, extra: &str, mirror: &str, glass: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 0, 3.9), target: (0, 0, 0), fov_y_degrees: 37.5),
            film: ({film}),
            integrator: Path(max_depth: 8, {extra}),
            materials: {{
                "w": Lambert(albedo: (0.8, 0.8, 0.8)),
                "r": Lambert(albedo: (0.7, 0.1, 0.1)),
                "mirror": {mirror},
                "glass": {glass},
            }},
            lights: [Rect(center: (0, 0.99, 0), half_u: (0.2, 0, 0), half_v: (0, 0, 0.2), radiance: (20, 20, 20))],
            objects: [
                Rect(center: (0, -1, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: "w"),
                Rect(center: (0, 1, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), material: "w"),
                Rect(center: (0, 0, -1), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "w"),
                Rect(center: (-1, 0, 0), half_u: (0, 1, 0), half_v: (0, 0, 1), material: "r"),
                Sphere(center: (-0.45, -0.6, -0.3), radius: 0.35, material: "mirror"),
                Sphere(center: (0.35, -0.6, 0.3), radius: 0.4, material: "glass"),
            ],
        )"#
    )
}

fn glass_scene(film: &str, extra: &str) -> String {
    scene(film, extra, "Mirror()", "Glass(ior: 1.5)")
}

fn threads(n: usize) -> RenderOptions {
    RenderOptions {
        threads: Some(n),
        ..Default::default()
    }
}

#[test]
fn light_traced_caustics_keep_the_image_region_by_region() {
    keeps_the_image("");
}

#[test]
fn light_traced_caustics_keep_the_image_with_split_paths() {
    // Each continuation of a split path drops the paths the light tracer
    // counts on its own (`integrator: Path(splits: 2)`).
    keeps_the_image("splits: 2");
}

/// The path tracer alone against the light-traced split with `extra` in
/// the integrator.
fn keeps_the_image(extra: &str) {
    // The path tracer alone at many samples against the split at fewer:
    // whole image within 1%, each quadrant (12 × 12 pixels) within 3%.
    // Dropping the path tracer's share without adding the light tracer's
    // darkens this image by about 6%; a wrong pixel normalisation moves the
    // caustic quadrants more.
    let w = 24;
    let film =
        |spp: u32, seed: u32| format!("width: {w}, height: {w}, spp: {spp}, seed: {seed}, allocation: Even");
    let alone = load_text(&glass_scene(&film(2048, 3), "caustics: PathOnly"));
    assert!(Plan::whole(&alone.scene, &alone.view).light_trace.is_none());
    let (truth, _) = render_whole(&alone.scene, &alone.view, &threads(2));
    let split = load_text(&glass_scene(&film(1024, 4), extra));
    assert!(Plan::whole(&split.scene, &split.view).light_trace.is_some());
    let (img, _) = render_whole(&split.scene, &split.view, &threads(2));
    same_image(
        &truth.pixels,
        &img.pixels,
        w,
        &format!("caustic box 24x24 ({extra})"),
    );
}

/// Asserts that `img` (a `w`-pixel-wide render) is `truth` in expectation:
/// the whole image's mean within 1%, each quadrant's within 3%; reports
/// both as `what`.
fn same_image(truth: &[ronray::math::Rgb], img: &[ronray::math::Rgb], w: usize, what: &str) {
    let (a, b) = (blocks(truth, w, w), blocks(img, w, w));
    report(&format!("{what}: whole {:.5} (truth), {:.5}", a[0], b[0]));
    assert!(
        (a[0] - b[0]).abs() < 0.01 * a[0],
        "{what}: whole image {} vs {}",
        b[0],
        a[0]
    );
    let (qa, qb) = (blocks(truth, w, w / 2), blocks(img, w, w / 2));
    for (k, (x, y)) in qa.iter().zip(&qb).enumerate() {
        report(&format!("{what}: quadrant {k} {x:.5} (truth), {y:.5}"));
        assert!((x - y).abs() < 0.03 * x, "{what}: quadrant {k}: {y} vs {x}");
    }
}

#[test]
fn light_traced_caustics_lower_the_noise() {
    // The reference scene `cornell_specular` (a mirror and a glass sphere):
    // seed-to-seed difference of two renders, whose RMSE is √2 times each
    // render's noise. At 256², 128 spp the noise off the light is 0.0387
    // without light tracing and 0.0307 with it. One path per camera sample
    // (the default, written out): with two (`splits: 2`) the path tracer
    // finds these caustics twice as often and the gain here is smaller
    // (0.0378 against 0.0412).
    let text = std::fs::read_to_string(common::root().join("scenes/cornell_specular.ron")).expect("scene");
    let film = "film: (width: 256, height: 256, spp: 64, sampler: Independent)";
    let integrator = "integrator: Path(max_depth: 16, rr_depth: 5)";
    assert!(
        text.contains(film) && text.contains(integrator),
        "scenes/cornell_specular.ron changed"
    );
    let w = 48;
    let noise = |caustics: &str| {
        let render_seed = |seed: u32| {
            let t = text
                .replace(
                    film,
                    &format!("film: (width: {w}, height: {w}, spp: 64, seed: {seed}, allocation: Even)"),
                )
                .replace(
                    integrator,
                    &format!("integrator: Path(max_depth: 16, rr_depth: 5, caustics: {caustics}, splits: 1)"),
                );
            let l = load_text(&t);
            render_whole(&l.scene, &l.view, &threads(2)).0.pixels
        };
        let (a, b) = (render_seed(1), render_seed(2));
        let se: f64 = a
            .iter()
            .zip(&b)
            .map(|(p, q)| f64::from((*p - *q).length_squared()))
            .sum();
        (se / (3 * a.len()) as f64 / 2.0).sqrt()
    };
    let (alone, split) = (noise("PathOnly"), noise("LightTracing"));
    report(&format!(
        "cornell_specular 48x48, 64 spp: noise path tracer alone {alone:.5}, light-traced caustics {split:.5}"
    ));
    assert!(
        split < 0.9 * alone,
        "noise {split} with light tracing, {alone} without"
    );
}

/// A glass ball and a mirror ball on a floor under the shipped sky map,
/// whose sun (5° wide) the glass focuses onto the floor beside it: the
/// sky's caustics, light-traced as parallel beams through the balls
/// (`lights/caustic.rs`, "The sky").
fn sky_scene(film: &str, extra: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 1.6, 6), target: (0, 0.5, 0), fov_y_degrees: 35),
            film: ({film}),
            integrator: Path(max_depth: 8, {extra}),
            materials: {{
                "floor": Lambert(albedo: (0.6, 0.6, 0.6)),
                "glass": Glass(ior: 1.5),
                "mirror": Mirror(),
            }},
            lights: [Environment(map: "assets/sky_sun.exr")],
            objects: [
                Rect(center: (0, 0, 0), half_u: (5, 0, 0), half_v: (0, 0, -5), material: "floor"),
                Sphere(center: (-0.8, 0.6, 0), radius: 0.6, material: "glass"),
                Sphere(center: (0.8, 0.45, 0.2), radius: 0.45, material: "mirror"),
            ],
        )"#
    )
}

#[test]
fn light_traced_sky_caustics_keep_the_image_region_by_region() {
    // As `keeps_the_image`, with the sky the only light: the path tracer
    // alone at many samples against the split at fewer, whole image within
    // 1%, each quadrant within 3%. Dropping the path tracer's share of the
    // sky's caustics without adding the light tracer's darkens the whole
    // image by 3% (checked: 1.6345 against 1.5857).
    let w = 24;
    let film =
        |spp: u32, seed: u32| format!("width: {w}, height: {w}, spp: {spp}, seed: {seed}, allocation: Even");
    let alone = load_text(&sky_scene(&film(2048, 3), "caustics: PathOnly"));
    assert!(Plan::whole(&alone.scene, &alone.view).light_trace.is_none());
    let (truth, _) = render_whole(&alone.scene, &alone.view, &threads(2));
    let split = load_text(&sky_scene(&film(1024, 4), ""));
    assert!(Plan::whole(&split.scene, &split.view).light_trace.is_some());
    let (img, _) = render_whole(&split.scene, &split.view, &threads(2));
    same_image(
        &truth.pixels,
        &img.pixels,
        w,
        "sky caustics 24x24, path tracer alone vs split",
    );
}

#[test]
fn light_traced_sky_caustics_lower_the_noise() {
    // Seed-to-seed RMSE of two renders (√2 × each one's noise), one path per
    // camera sample, independent numbers. A constant sky of the same
    // scene is not light traced (its caustics are as soft as the sky).
    let w = 48;
    let noise = |caustics: &str| {
        let render_seed = |seed: u32| {
            let film = format!(
                "width: {w}, height: {w}, spp: 64, seed: {seed}, sampler: Independent, allocation: Even"
            );
            let l = load_text(&sky_scene(&film, &format!("caustics: {caustics}, splits: 1")));
            render_whole(&l.scene, &l.view, &threads(2)).0.pixels
        };
        let (a, b) = (render_seed(1), render_seed(2));
        let se: f64 = a
            .iter()
            .zip(&b)
            .map(|(p, q)| f64::from((*p - *q).length_squared()))
            .sum();
        (se / (3 * a.len()) as f64 / 2.0).sqrt()
    };
    let (alone, split) = (noise("PathOnly"), noise("LightTracing"));
    report(&format!(
        "sky caustics 48x48, 64 spp: noise path tracer alone {alone:.5}, light-traced caustics {split:.5}"
    ));
    assert!(
        split < 0.9 * alone,
        "noise {split} with light tracing, {alone} without"
    );
    // The sky's beams draw from the light tracer's own streams: the same
    // image on one thread as on two.
    let l = load_text(&sky_scene("width: 16, height: 12, spp: 16", ""));
    assert!(Plan::whole(&l.scene, &l.view).light_trace.is_some());
    let (one, two) = (
        render_whole(&l.scene, &l.view, &threads(1)).0,
        render_whole(&l.scene, &l.view, &threads(2)).0,
    );
    assert_eq!(
        one.pixels, two.pixels,
        "the sky's caustics depend on the thread count"
    );
    let constant = sky_scene("width: 8, height: 8, spp: 4", "").replace(
        r#"Environment(map: "assets/sky_sun.exr")"#,
        "Environment(radiance: (1, 1, 1))",
    );
    let l = load_text(&constant);
    assert!(l.scene.caustics.is_none() && Plan::whole(&l.scene, &l.view).light_trace.is_none());
}

/// A glass ball on a floor lit by `light` from above and to the side: the
/// ball focuses it onto the floor in its shadow.
fn point_scene(film: &str, light: &str, object: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 2.2, 3.2), target: (0, 0.2, -0.2), fov_y_degrees: 40),
            film: ({film}),
            integrator: Path(max_depth: 8),
            materials: {{
                "floor": Lambert(albedo: (0.7, 0.7, 0.7)),
                "glass": Glass(ior: 1.5),
                "lamp": Lambert(albedo: (0, 0, 0)),
            }},
            lights: [{light}],
            objects: [
                Rect(center: (0, 0, 0), half_u: (2, 0, 0), half_v: (0, 0, -2), material: "floor"),
                Sphere(center: (0, 0.4, 0), radius: 0.4, material: "glass"),
                {object}
            ],
        )"#
    )
}

#[test]
fn a_point_lights_caustic_is_that_of_a_tiny_sphere_light() {
    // No BSDF sample reaches a point, so only the light tracer draws a
    // point light's caustics: the glass ball's shadow would be black
    // without it. Against a sphere light of radius 0.005 at the same place
    // and of the same intensity (radiance I / πr²), whose caustics the
    // light tracer also draws: whole image within 1%, each quadrant within
    // 3%. Without the point light's light paths the image is 13% darker
    // (checked: 0.1669 against 0.1912).
    let w = 24;
    let film = |spp: u32| format!("width: {w}, height: {w}, spp: {spp}, seed: 2, allocation: Even");
    let at = "(0.9, 1.6, -0.9)";
    let point = load_text(&point_scene(
        &film(512),
        &format!("Point(position: {at}, intensity: (3, 3, 3))"),
        "",
    ));
    let radiance = 3.0 / (std::f32::consts::PI * 0.005 * 0.005);
    let sphere = load_text(&point_scene(
        &film(1024),
        "",
        &format!(
            "Sphere(center: {at}, radius: 0.005, material: \"lamp\", emission: (radiance: ({radiance}, {radiance}, {radiance}))),"
        ),
    ));
    for l in [&point, &sphere] {
        assert!(Plan::whole(&l.scene, &l.view).light_trace.is_some());
    }
    let (a, b) = (
        render_whole(&sphere.scene, &sphere.view, &threads(2)).0,
        render_whole(&point.scene, &point.view, &threads(2)).0,
    );
    same_image(&a.pixels, &b.pixels, w, "tiny sphere light vs point light");
}

#[test]
fn light_traced_caustics_do_not_depend_on_threads() {
    let l = load_text(&glass_scene("width: 24, height: 16, spp: 32", ""));
    assert!(Plan::whole(&l.scene, &l.view).light_trace.is_some());
    let (one, _) = render_whole(&l.scene, &l.view, &threads(1));
    let (two, _) = render_whole(&l.scene, &l.view, &threads(2));
    assert_eq!(one.pixels, two.pixels, "the image depends on the thread count");
    assert!(one.pixels.iter().all(|p| p.is_finite()));
}

#[test]
fn nothing_to_light_trace_renders_as_the_path_tracer_alone() {
    let opts = threads(2);
    // No perfect-specular surface (the glass is rough): no light paths,
    // and the image is the path tracer's bit for bit.
    let rough = |extra: &str| {
        scene(
            "width: 16, height: 16, spp: 16",
            extra,
            "CookTorrance(roughness: 0.2, fresnel: Conductor(eta: (0.2, 0.4, 1.4), k: (4, 2.4, 1.6)))",
            "RoughGlass(ior: 1.5, roughness: 0.3)",
        )
    };
    let (a, b) = (load_text(&rough("")), load_text(&rough("caustics: PathOnly")));
    assert!(a.scene.caustics.is_none());
    assert_eq!(
        render_whole(&a.scene, &a.view, &opts).0.pixels,
        render_whole(&b.scene, &b.view, &opts).0.pixels
    );
    // Another filter, a thin lens, part of the samples: no light paths.
    let gaussian = load_text(&glass_scene(
        "width: 16, height: 16, spp: 16, filter: Gaussian()",
        "",
    ));
    assert!(Plan::whole(&gaussian.scene, &gaussian.view).light_trace.is_none());
    let mut lens = load_text(&glass_scene("width: 16, height: 16, spp: 16", ""));
    lens.view.camera.aperture_radius = 0.05;
    assert!(Plan::whole(&lens.scene, &lens.view).light_trace.is_none());
    // Half the samples of the whole frame, as a farm piece.
    let piece = |l: &ronray::load::Loaded| {
        let rect = ronray::imageio::PixelRect::full(l.view.film.width, l.view.film.height);
        Plan::new(
            &l.scene,
            &l.view,
            Request::Piece {
                rect,
                samples: (0, 8),
            },
            false,
        )
        .expect("a piece")
    };
    let l = load_text(&glass_scene("width: 16, height: 16, spp: 16", ""));
    assert!(piece(&l).light_trace.is_none());
    // A piece says what it leaves out: the same expected value with a lamp,
    // a point light's caustics missing with one (the path tracer cannot
    // find them).
    let piece_notes = |l: &ronray::load::Loaded| piece(l).piece_notes(&l.view);
    let lamp = piece_notes(&l);
    assert!(lamp.iter().any(|n| n.contains("same expected value")), "{lamp:?}");
    let point = load_text(&point_scene(
        "width: 16, height: 16, spp: 16",
        "Point(position: (0.9, 1.6, -0.9), intensity: (3, 3, 3))",
        "",
    ));
    let notes = piece_notes(&point);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("point, spot or directional light"))
            && !notes.iter().any(|n| n.contains("same expected value")),
        "{notes:?}"
    );
}

/// A floor under the shipped sky map inside a glass sphere of radius
/// 10,000 (the camera inside it too), `lights` beside the sky.
fn dome_scene(integrator: &str, lights: &str) -> String {
    format!(
        r#"Scene(
            camera: (eye: (0, 1.5, 5), target: (0, 0.5, 0), fov_y_degrees: 40),
            film: (width: 16, height: 16, spp: 64, seed: 3),
            integrator: Path(max_depth: 8, {integrator}),
            materials: {{
                "floor": Lambert(albedo: (0.6, 0.6, 0.6)),
                "glass": Glass(ior: 1.5),
            }},
            lights: [Environment(map: "assets/sky_sun.exr"), {lights}],
            objects: [
                Rect(center: (0, 0, 0), half_u: (5, 0, 0), half_v: (0, 0, -5), material: "floor"),
                Sphere(center: (0, 0, 0), radius: 10000, material: "glass"),
            ],
        )"#
    )
}

#[test]
fn a_light_whose_light_paths_miss_the_film_is_left_to_the_path_tracer() {
    // The sky's beams cross the dome's disk, three million times the floor's
    // area, and almost none lands in the picture: the light tracer leaves
    // the sky to the path tracer (`integrators/caustic_reach.rs`), and the
    // image is the path tracer's alone, bit for bit. Before, the sky stayed
    // light-traced, the path tracer dropped the sky seen through the dome,
    // and the floor rendered at 2% of its brightness at 256 spp (0.03
    // against 1.37).
    let l = load_text(&dome_scene("", ""));
    assert!(l.scene.caustics.is_none(), "the sky is still light-traced");
    assert!(Plan::whole(&l.scene, &l.view).light_trace.is_none());
    let alone = load_text(&dome_scene("caustics: PathOnly", ""));
    let opts = threads(2);
    let (a, b) = (
        render_whole(&l.scene, &l.view, &opts).0,
        render_whole(&alone.scene, &alone.view, &opts).0,
    );
    assert_eq!(a.pixels, b.pixels, "not the path tracer's image");
    // A point light under the same dome keeps its light paths, whatever
    // their share (nothing else finds a point light's caustics).
    let l = load_text(&dome_scene(
        "",
        "Point(position: (1, 2, 0), intensity: (3, 3, 3))",
    ));
    let em = l.scene.caustics.as_ref().expect("the point light's caustics");
    assert_eq!(em.emitters(), &[1]);
    assert!(!em.is_sky(0));
}
