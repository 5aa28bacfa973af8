//! Integrators against closed-form answers.

use crate::common;

use glam::Vec3A;
use ronray::load::{Overrides, load_str};
use ronray::math::Ray;
use std::f32::consts::PI;
use std::path::Path;

use common::{load_text as scene, mean_li};

#[test]
fn direct_point_light_on_lambert_plane_matches_closed_form() {
    // Plane y = 0, albedo 0.5; point light 2 above the origin, I = 10 W/sr.
    let s = scene(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 20),
        film: (width: 33, height: 33, spp: 16),
        integrator: Direct(light_samples: 1),
        materials: { "grey": Lambert(albedo: (0.5, 0.5, 0.5)) },
        lights: [Point(position: (0, 2, 0), intensity: (10, 10, 10))],
        objects: [Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey")],
    )"#,
    );
    // The pixel at the image centre sees the origin, straight below the light.
    let (img, _) = ronray::frame::render_whole(&s.scene, &s.view, &Default::default());
    let got = img.get(16, 16);
    let expected = 0.5 / PI * 10.0 * 1.0 / 4.0;
    for c in 0..3 {
        let rel = (got[c] - expected).abs() / expected;
        assert!(
            rel < 0.01,
            "channel {c}: expected {expected}, got {} ({:.2}% off)",
            got[c],
            rel * 100.0
        );
    }
    // And the exact point, from a ray aimed at it: cos θ / r² off axis too.
    let x = Vec3A::new(1.5, 0.0, 0.0);
    let got = mean_li(
        &s,
        Ray::new(
            Vec3A::new(1.5, 1.0, 1.0),
            (x - Vec3A::new(1.5, 1.0, 1.0)).normalize(),
        ),
        1,
    );
    let r2 = 1.5f32 * 1.5 + 4.0;
    let expected = 0.5 / PI * 10.0 * (2.0 / r2.sqrt()) / r2;
    assert!(
        (got.x - expected).abs() / expected < 1e-3,
        "off-axis: expected {expected}, got {}",
        got.x
    );
}

/// A directional light on a Lambert plane: `ρ/π · E cos θ` everywhere it
/// is not shadowed, with every integrator, under any number of suns (their
/// sum, whichever the light tree picks); a ball's shadow falls where the
/// light, travelling along `direction`, would have left it.
#[test]
fn directional_light_on_lambert_plane_matches_closed_form() {
    let text = |integrator: &str, lights: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 4, 0.001), target: (0, 0, 0), fov_y_degrees: 60),
            film: (width: 33, height: 33, spp: 16),
            integrator: {integrator},
            materials: {{ "grey": Lambert(albedo: (0.5, 0.5, 0.5)) }},
            lights: [{lights}],
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                // Far off to the side, out of view, casting its shadow at x ≈ -3.
                Sphere(center: (3, 3, 0), radius: 0.5, material: "grey"),
            ],
        )"#
        )
    };
    // 60° from the zenith, travelling toward −x and down: cos θ = 0.5.
    let sun = "Directional(direction: (-0.866, -0.5, 0), irradiance: (4, 2, 1))";
    let weak = "Directional(direction: (0, -1, 0), irradiance: (1, 1, 1))";
    for integrator in [
        "Direct(light_samples: 1)",
        "Path(max_depth: 2)",
        "Path(max_depth: 2, light_selection: Power)",
    ] {
        for (lights, want) in [
            (sun.to_string(), Vec3A::new(4.0, 2.0, 1.0) * 0.5),
            (
                format!("{sun}, {weak}"),
                Vec3A::new(4.0, 2.0, 1.0) * 0.5 + Vec3A::ONE,
            ),
        ] {
            let s = scene(&text(integrator, &lights));
            let expected = want * (0.5 / PI);
            // The origin, and a point far out on the plane: the same.
            for x in [0.0f32, 2.5] {
                let at = Vec3A::new(x, 0.0, 0.5);
                let from = Vec3A::new(x, 1.0, 1.5);
                let got = mean_li(&s, Ray::new(from, (at - from).normalize()), 4096);
                for c in 0..3 {
                    assert!(
                        (got[c] - expected[c]).abs() <= 0.02 * expected[c],
                        "{integrator}, [{lights}], x = {x}, channel {c}: {} against {}",
                        got[c],
                        expected[c]
                    );
                }
            }
        }
        // In the ball's shadow, 1.5 × 1.732 = 5.2 along −x from below it:
        // only the sky-less weak sun would light it, and it is not there.
        let s = scene(&text(integrator, sun));
        let at = Vec3A::new(3.0 - 3.0 * 1.732, 0.0, 0.0);
        let from = at + Vec3A::new(0.0, 1.0, 0.5);
        let got = mean_li(&s, Ray::new(from, (at - from).normalize()), 16);
        assert!(got.max_element() < 1e-6, "{integrator}: shadow at {at} is {got}");
    }
}

/// A sun with a size (`angle_degrees`: a disk of angular radius θ at the
/// zenith) over a floor, half of it shaded by a large roof 1 above it that
/// ends at x = 0: the floor sees the share of the disk the roof's edge
/// leaves, (acos t − t√(1 − t²))/π with t = −x/(h tan θ) — half under the
/// edge, all past the penumbra, none before it. Away from the roof it
/// receives E, as a hard sun gives; Direct and Path agree.
#[test]
fn a_sun_with_a_size_casts_the_penumbra_of_its_disk() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (3, 2, 3), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: {integrator},
            materials: {{ "grey": Lambert(albedo: (0.5, 0.5, 0.5)) }},
            lights: [Directional(direction: (0, -1, 0), irradiance: (2, 2, 2), angle_degrees: 10)],
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                // The roof: x ∈ [−40, 0] at height 1.
                Rect(center: (-20, 1, 0), half_u: (20, 0, 0), half_v: (0, 0, -40), material: "grey"),
            ],
        )"#
        )
    };
    // An angle that is no angle is a located error.
    for bad in ["200", "-1", "NaN"] {
        let t = text("Path()").replace("angle_degrees: 10", &format!("angle_degrees: {bad}"));
        match load_str(Path::new("scenes/sun.ron"), &t, &Overrides::default()) {
            Ok(_) => panic!("angle_degrees {bad} loaded"),
            Err(e) => assert!(
                format!("{e:?}").contains("lights[0].angle_degrees"),
                "angle_degrees {bad}: {e:?}"
            ),
        }
    }
    let r = 5f32.to_radians().tan();
    let share = |x: f32| {
        let t = (-x / r).clamp(-1.0, 1.0);
        (t.acos() - t * (1.0 - t * t).sqrt()) / PI
    };
    for integrator in ["Direct(light_samples: 1)", "Path(max_depth: 2)"] {
        let s = scene(&text(integrator));
        for x in [-1.2 * r, -0.5 * r, 0.0, 0.5 * r, 1.2 * r, 3.0] {
            let at = Vec3A::new(x, 0.0, 0.5);
            // From the lit side, above the floor and past the roof's edge.
            let from = Vec3A::new(x + 0.6, 0.5, 1.5);
            let got = mean_li(&s, Ray::new(from, (at - from).normalize()), 20_000).x;
            let want = 2.0 * share(x) * 0.5 / PI;
            assert!(
                (got - want).abs() <= 0.02 * (2.0 * 0.5 / PI),
                "{integrator}, x = {x}: {got}, expected {want} (share {})",
                share(x)
            );
        }
    }
}

/// A generated family of suns and roofs: for every angular diameter (from
/// the real sun's to 120°) and roof height, the floor under the roof's edge
/// gets exactly half the irradiance (the disk and the cosine are symmetric
/// about the edge's plane), past the penumbra all of it, before it none.
#[test]
fn suns_of_every_size_shade_half_under_a_roof_edge() {
    for degrees in [0.53f32, 3.0, 10.0, 40.0, 120.0] {
        for h in [0.3f32, 1.0, 4.0] {
            let text = format!(
                r#"Scene(
                camera: (eye: (3, 2, 3), target: (0, 0, 0), fov_y_degrees: 40),
                integrator: Direct(light_samples: 1),
                materials: {{ "grey": Lambert(albedo: (0.5, 0.5, 0.5)) }},
                lights: [Directional(direction: (0, -1, 0), irradiance: (2, 2, 2), angle_degrees: {degrees})],
                objects: [
                    Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                    Rect(center: (-50, {h}, 0), half_u: (50, 0, 0), half_v: (0, 0, -100), material: "grey"),
                ],
            )"#
            );
            let s = scene(&text);
            let reach = h * (0.5 * degrees).to_radians().tan();
            let lit = 2.0 * 0.5 / PI;
            for (x, share) in [
                (0.0, 0.5),
                (1.05 * reach + 0.01, 1.0),
                (-1.05 * reach - 0.01, 0.0),
            ] {
                let at = Vec3A::new(x, 0.0, 0.5);
                // From just above the floor, beside the point: under the roof.
                let from = at + Vec3A::new(0.05, 0.02, 0.05);
                let got = mean_li(&s, Ray::new(from, (at - from).normalize()), 20_000).x;
                assert!(
                    (got - share * lit).abs() <= 0.02 * lit,
                    "{degrees}°, roof at {h}, x = {x}: {got}, expected {} of {lit}",
                    share
                );
            }
        }
    }
}

/// Irradiance from a uniform, one-sided Lambertian polygon emitter of radiance
/// `l` at point `x` with normal `n` (Lambert's formula: E = L/2 Σ βᵢ n·γᵢ).
fn polygon_irradiance(x: Vec3A, n: Vec3A, verts: &[Vec3A], l: f32) -> f32 {
    let mut sum = 0.0;
    for i in 0..verts.len() {
        let a = (verts[i] - x).normalize();
        let b = (verts[(i + 1) % verts.len()] - x).normalize();
        let beta = a.dot(b).clamp(-1.0, 1.0).acos();
        sum += beta * n.dot(a.cross(b).normalize());
    }
    0.5 * l * sum.abs()
}

#[test]
fn direct_quad_light_irradiance_matches_polygon_formula() {
    // A 0.8 × 1 light 1.5 above the floor, off to the side, facing down
    // (edge_u × edge_v = x × z = −y).
    let s = scene(
        r#"Scene(
        camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 20),
        integrator: Direct(light_samples: 64),
        materials: { "white": Lambert(albedo: (1, 1, 1)) },
        lights: [Quad(corner: (0.2, 1.5, -0.4), edge_u: (0.8, 0, 0), edge_v: (0, 0, 1), radiance: (5, 5, 5))],
        objects: [Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "white")],
    )"#,
    );
    let verts = [
        Vec3A::new(0.2, 1.5, -0.4),
        Vec3A::new(1.0, 1.5, -0.4),
        Vec3A::new(1.0, 1.5, 0.6),
        Vec3A::new(0.2, 1.5, 0.6),
    ];
    for x in [Vec3A::ZERO, Vec3A::new(0.6, 0.0, 0.1), Vec3A::new(-1.0, 0.0, 0.5)] {
        let e = polygon_irradiance(x, Vec3A::Y, &verts, 5.0);
        let expected = e / PI; // Lambert, albedo 1: L = E/π
        let o = x + Vec3A::new(-0.3, 1.0, 1.0);
        let got = mean_li(&s, Ray::new(o, (x - o).normalize()), 2048);
        let rel = (got.x - expected).abs() / expected;
        assert!(
            rel < 0.01,
            "at {x}: expected {expected}, got {} ({:.2}% off)",
            got.x,
            rel * 100.0
        );
    }
}

/// Inside a closed Lambert sphere (albedo ρ = 0.5, radius 1) with a point
/// light of intensity π at its centre, every wall receives E = π/r² = π
/// directly: direct lighting sees ρE/π = 0.5; with every bounce the
/// radiosity is B = ρE/(1 − ρ), so path tracing sees B/π = 1.
#[test]
fn closed_sphere_direct_and_path_match_closed_forms() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 0, 0), target: (0, 0, -1), fov_y_degrees: 60),
            film: (width: 8, height: 8, spp: 1),
            integrator: {integrator},
            materials: {{ "half": Lambert(albedo: (0.5, 0.5, 0.5)) }},
            lights: [Point(position: (0, 0, 0), intensity: (3.14159265, 3.14159265, 3.14159265))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "half")],
        )"#
        )
    };
    let ray = Ray::new(Vec3A::ZERO, Vec3A::new(0.3, -0.2, -1.0).normalize());
    let direct = mean_li(&scene(&text("Direct(light_samples: 1)")), ray, 16);
    assert!(
        (direct.x - 0.5).abs() < 0.005,
        "direct: expected 0.5, got {}",
        direct.x
    );
    let path = mean_li(&scene(&text("Path(max_depth: -1, rr_depth: 5)")), ray, 200_000);
    assert!((path.x - 1.0).abs() < 0.01, "path: expected 1.0, got {}", path.x);
    let two = mean_li(&scene(&text("Path(max_depth: 2, rr_depth: 5)")), ray, 16);
    assert!(
        (two.x - 0.5).abs() < 0.005,
        "path max_depth 2 is direct lighting: got {}",
        two.x
    );
}

/// White furnace: inside a closed box whose six walls all emit Le = 1 and
/// reflect with albedo ρ = 0.5, radiance is Le/(1 − ρ) = 2 everywhere.
#[test]
fn furnace_emitting_enclosure_gives_le_over_one_minus_rho() {
    let s = scene(&common::furnace("Lambert(albedo: (0.5, 0.5, 0.5))"));
    for d in [Vec3A::new(0.1, 0.2, -1.0), Vec3A::new(0.9, -0.7, 0.2)] {
        let got = mean_li(&s, Ray::new(Vec3A::new(0.1, 0.0, 0.2), d.normalize()), 100_000);
        assert!((got.x - 2.0).abs() < 0.02, "expected 2.0, got {}", got.x);
    }
}

/// Without mirrors or glass, Whitted shades exactly like direct lighting.
#[test]
fn whitted_equals_direct_without_specular_surfaces() {
    let text = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.ron"))
        .expect("scene");
    let render = |integrator: &str| {
        let t = text.replace("integrator: Path(max_depth: 8, rr_depth: 5)", integrator);
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cornell.ron");
        let o = Overrides {
            spp: Some(4),
            size: Some((32, 32)),
            seed: Some(5),
            ..Default::default()
        };
        let l = load_str(&path, &t, &o).expect("scene loads");
        ronray::frame::render_whole(&l.scene, &l.view, &Default::default()).0
    };
    let direct = render("integrator: Direct(light_samples: 2)");
    let whitted = render("integrator: Whitted(max_depth: 5, light_samples: 2)");
    assert!(direct.pixels.iter().any(|p| p.x > 0.0), "the image is not black");
    assert_eq!(
        direct, whitted,
        "Whitted differs from Direct on a purely diffuse scene"
    );
}

// ---- Light from everywhere (issue 14) ----

/// White furnace: a convex Lambert sphere (albedo ρ) under a constant
/// environment L receives E = πL from its hemisphere everywhere, so it has
/// radiance ρL; rays that miss see L. Every integrator, within 1%.
#[test]
fn diffuse_sphere_under_constant_environment_has_radiance_rho_l() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: {integrator},
            materials: {{ "half": Lambert(albedo: (0.5, 0.25, 0.75)) }},
            lights: [Environment(radiance: (0.8, 0.8, 0.8))],
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "half")],
        )"#
        )
    };
    let want = Vec3A::new(0.4, 0.2, 0.6);
    let o = Vec3A::new(0.0, 0.0, 4.0);
    for (integrator, n) in [
        ("Path(max_depth: -1, rr_depth: 5)", 20_000),
        ("Direct(light_samples: 4)", 20_000),
        ("Whitted(max_depth: 5, light_samples: 4)", 20_000),
    ] {
        let s = scene(&text(integrator));
        for target in [
            Vec3A::ZERO,
            Vec3A::new(0.7, 0.5, 0.2),
            Vec3A::new(-0.2, -0.9, 0.1),
        ] {
            let got = mean_li(&s, Ray::new(o, (target - o).normalize()), n);
            for c in 0..3 {
                assert!(
                    (got[c] - want[c]).abs() < 0.01 * want[c],
                    "{integrator} toward {target}: channel {c} expected {}, got {}",
                    want[c],
                    got[c]
                );
            }
        }
        let miss = mean_li(&s, Ray::new(o, Vec3A::new(0.0, 0.8, -1.0).normalize()), 1);
        assert!(
            (miss - Vec3A::splat(0.8)).length() < 1e-6,
            "{integrator}: the sky is {miss}"
        );
    }
}

/// The same furnace with the environment given as an image of one value
/// (importance sampled through its tables), and hidden behind a background.
#[test]
fn diffuse_sphere_under_uniform_map_has_radiance_rho_l() {
    let dir = tempfile::tempdir().expect("temp dir");
    let img = image::Rgb32FImage::from_pixel(32, 16, image::Rgb([0.8, 0.8, 0.8]));
    img.save(dir.path().join("grey.exr")).expect("write exr");
    let s = common::load_in(
        dir.path(),
        r#"Scene(
        camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40),
        integrator: Path(max_depth: -1, rr_depth: 5),
        materials: { "half": Lambert(albedo: (0.5, 0.5, 0.5)) },
        lights: [Environment(map: "grey.exr", strength: 2, rotation_degrees: 70, visible: false, background: (0.1, 0.2, 0.3))],
        objects: [Sphere(center: (0, 0, 0), radius: 1, material: "half")],
    )"#,
        &Overrides::default(),
    );
    let o = Vec3A::new(0.0, 0.0, 4.0);
    for target in [Vec3A::ZERO, Vec3A::new(0.6, -0.6, 0.3)] {
        let got = mean_li(&s, Ray::new(o, (target - o).normalize()), 20_000);
        assert!(
            (got.x - 0.8).abs() < 0.008,
            "toward {target}: expected 0.8, got {}",
            got.x
        );
    }
    let miss = mean_li(&s, Ray::new(o, Vec3A::Y), 1);
    assert!(
        (miss - Vec3A::new(0.1, 0.2, 0.3)).length() < 1e-6,
        "background {miss}"
    );
}

/// An emissive sphere of radiance L and radius r, entirely above a point of
/// a plane, gives it the irradiance of a point of intensity L·πr² at its
/// centre: E = π L r² cos θ / d². A white Lambert plane then has radiance
/// E/π. Direct lighting (cone sampling alone) and path tracing cut to direct
/// light (cone and BSDF sampling by MIS) both, within 1%.
#[test]
fn emissive_sphere_gives_closed_form_irradiance_on_a_plane() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 5), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: {integrator},
            materials: {{ "white": Lambert(albedo: (1, 1, 1)), "black": Lambert(albedo: (0, 0, 0)) }},
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "white"),
                Sphere(center: (0.2, 1.5, -0.3), radius: 0.4, material: "black", emission: (radiance: (3, 2, 1))),
            ],
        )"#
        )
    };
    let c = Vec3A::new(0.2, 1.5, -0.3);
    for integrator in ["Direct(light_samples: 4)", "Path(max_depth: 2, rr_depth: 5)"] {
        let s = scene(&text(integrator));
        for x in [
            Vec3A::ZERO,
            Vec3A::new(1.2, 0.0, 0.5),
            Vec3A::new(-0.4, 0.0, -1.5),
        ] {
            let to_c = c - x;
            let d2 = to_c.length_squared();
            let e = PI * 3.0 * 0.16 * (to_c.y / d2.sqrt()) / d2;
            let want = e / PI;
            let o = x + Vec3A::new(0.3, 1.0, 1.0);
            let got = mean_li(&s, Ray::new(o, (x - o).normalize()), 20_000);
            assert!(
                (got.x - want).abs() < 0.01 * want,
                "{integrator} at {x}: expected {want}, got {}",
                got.x
            );
            assert!((got.y / got.x - 2.0 / 3.0).abs() < 1e-3, "colour kept");
        }
        // Seen directly, the sphere shows its radiance.
        let o = Vec3A::new(0.0, 1.5, 3.0);
        let got = mean_li(&s, Ray::new(o, (c - o).normalize()), 1);
        assert!(
            (got - Vec3A::new(3.0, 2.0, 1.0)).length() < 1e-5,
            "{integrator}: {got}"
        );
    }
}

/// One map written as Radiance `.hdr` and as OpenEXR renders the same image:
/// the values are exact in RGBE (an 8-bit mantissa under a shared exponent),
/// so the two files hold the same floats.
#[test]
fn hdr_and_exr_of_the_same_map_render_the_same_image() {
    let dir = tempfile::tempdir().expect("temp dir");
    let img = image::Rgb32FImage::from_fn(32, 16, |i, j| {
        // The largest channel has mantissa 128..=255, the others fewer bits.
        let scale = 2f32.powi((i as i32 % 5) - 2) / 256.0;
        let m = 128 + (7 * i + 13 * j) % 128;
        image::Rgb([m as f32 * scale, (m / 2) as f32 * scale, (j * 8) as f32 * scale])
    });
    img.save(dir.path().join("map.exr")).expect("write exr");
    img.save(dir.path().join("map.hdr")).expect("write hdr");
    let render = |file: &str| {
        let text = format!(
            r#"Scene(
            camera: (eye: (0, 0.5, 4), target: (0, 0, 0), fov_y_degrees: 50),
            film: (width: 24, height: 16, spp: 4),
            integrator: Path(max_depth: 4, rr_depth: 5),
            materials: {{ "grey": Lambert(albedo: (0.6, 0.6, 0.6)), "gold": CookTorrance(roughness: 0.3, fresnel: Metal(Gold)) }},
            lights: [Environment(map: "{file}", rotation_degrees: 25)],
            objects: [
                Sphere(center: (-0.6, 0, 0), radius: 0.5, material: "grey"),
                Sphere(center: (0.6, 0, 0), radius: 0.5, material: "gold"),
            ],
        )"#
        );
        common::render_loaded(&common::load_in(dir.path(), &text, &Overrides::default()))
    };
    // The same RGBE file with the `#?RGBE` signature some tools write.
    let hdr = std::fs::read(dir.path().join("map.hdr")).expect("read hdr");
    let rest = &hdr[hdr.iter().position(|&b| b == b'\n').expect("a header line")..];
    std::fs::write(dir.path().join("rgbe.hdr"), [b"#?RGBE".as_slice(), rest].concat()).expect("write");
    let (exr, hdr) = (render("map.exr"), render("map.hdr"));
    assert!(exr.pixels.iter().any(|p| p.x > 0.0), "the image is not black");
    assert_eq!(exr, hdr, "the .hdr and .exr maps give different images");
    assert_eq!(
        render("rgbe.hdr"),
        hdr,
        "a `#?RGBE` file reads like a `#?RADIANCE` one"
    );
}

/// An emissive SDF sphere (sampled through its bounding sphere's cone and
/// marched) gives the same closed-form irradiance as the analytic one.
#[test]
fn emissive_sdf_sphere_gives_closed_form_irradiance() {
    let text = |integrator: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 5), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: {integrator},
            materials: {{ "white": Lambert(albedo: (1, 1, 1)), "black": Lambert(albedo: (0, 0, 0)) }},
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "white"),
                Sdf(shape: Sphere(radius: 0.4), material: "black", transform: [Translate((0.2, 1.5, -0.3))],
                    emission: (radiance: (3, 2, 1))),
            ],
        )"#
        )
    };
    let c = Vec3A::new(0.2, 1.5, -0.3);
    for integrator in ["Direct(light_samples: 4)", "Path(max_depth: 2, rr_depth: 5)"] {
        let s = scene(&text(integrator));
        for x in [Vec3A::ZERO, Vec3A::new(1.2, 0.0, 0.5)] {
            let to_c = c - x;
            let d2 = to_c.length_squared();
            let want = 3.0 * 0.16 * (to_c.y / d2.sqrt()) / d2;
            let o = x + Vec3A::new(0.3, 1.0, 1.0);
            // Two thirds of the bounding cone misses the sphere: more samples.
            let got = mean_li(&s, Ray::new(o, (x - o).normalize()), 60_000);
            assert!(
                (got.x - want).abs() < 0.02 * want,
                "{integrator} at {x}: expected {want}, got {}",
                got.x
            );
        }
    }
}

/// A mirroring transform must not turn a one-sided emissive mesh inside out:
/// the octahedron mirrored in x (baked `Mesh` or `Instance`) lights the
/// mirrored floor point as the original lights the original point.
#[test]
fn mirrored_emissive_mesh_still_emits_outward() {
    let text = |object: &str| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 5), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Direct(light_samples: 4),
            materials: {{ "white": Lambert(albedo: (1, 1, 1)), "black": Lambert(albedo: (0, 0, 0)) }},
            meshes: {{ "octa": (file: "assets/glow_octahedron.obj") }},
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "white"),
                {object},
            ],
        )"#
        )
    };
    let at = |object: &str, x: Vec3A| {
        let s = scene(&text(object));
        let o = x + Vec3A::new(0.0, 1.0, 1.5);
        mean_li(&s, Ray::new(o, (x - o).normalize()), 20_000).z
    };
    let emission = r#"material: "black", emission: (radiance: (2, 4, 9))"#;
    let here = Vec3A::new(0.6, 0.0, -0.2);
    let there = Vec3A::new(-0.6, 0.0, -0.2);
    let original = at(
        &format!(r#"Mesh(file: "assets/glow_octahedron.obj", {emission})"#),
        here,
    );
    assert!(original > 0.1, "the octahedron lights the floor: {original}");
    for mirrored in [
        format!(r#"Mesh(file: "assets/glow_octahedron.obj", {emission}, transform: [Scale((-1, 1, 1))])"#),
        format!(r#"Instance(mesh: "octa", {emission}, transform: [Scale((-1, 1, 1))])"#),
    ] {
        let got = at(&mirrored, there);
        assert!(
            (got - original).abs() < 0.015 * original,
            "{mirrored}: {got} vs the original's {original}"
        );
    }
}

/// A thin glass pane (`Glass(thin: true)`) between the eye and a sunlit
/// Lambert floor passes (1 − R)·tint of the floor's radiance ρE/π and
/// mirrors R of it (the floor beyond the pane), with R = 2F/(1 + F) (both
/// faces' reflections, Mitsuba's `thindielectric`) and the ray not bent; the same pane as a solid's boundary (not thin)
/// bends the ray into the glass and scales its radiance by 1/η², which
/// this must tell apart.
#[test]
fn thin_glass_pane_passes_one_minus_r_of_the_light_tinted() {
    let text = |thin: bool| {
        format!(
            r#"Scene(
            camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 40),
            integrator: Path(max_depth: 3, caustics: PathOnly),
            materials: {{
                "grey": Lambert(albedo: (0.5, 0.5, 0.5)),
                "pane": Glass(ior: 1.5, tint: (0.9, 0.5, 0.2), thin: {thin}),
            }},
            lights: [Directional(direction: (0, -1, 0), irradiance: (1, 1, 1))],
            objects: [
                Plane(point: (0, 0, 0), normal: (0, 1, 0), material: "grey"),
                // Upright at z = 1, across the view, beside the sun's way.
                Rect(center: (0, 1.1, 1), half_u: (2, 0, 0), half_v: (0, 0.9, 0), material: "pane"),
            ],
        )"#
        )
    };
    let from = Vec3A::new(0.0, 1.0, 3.0);
    let ray = Ray::new(from, (Vec3A::ZERO - from).normalize());
    // F at the pane, from the ray's cosine to its normal (3/√10).
    let cos = 3.0 / 10f32.sqrt();
    let (sin_t, n) = ((1.0 - cos * cos).sqrt() / 1.5, 1.5f32);
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = ((cos - n * cos_t) / (cos + n * cos_t)).powi(2);
    let rp = ((n * cos - cos_t) / (n * cos + cos_t)).powi(2);
    let f = 0.5 * (rs + rp);
    let r = 2.0 * f / (1.0 + f);
    let floor = 0.5 / PI;
    // What the pane reflects (white, down onto the floor beyond it) is
    // the same sunlit floor.
    let want = (Vec3A::new(0.9, 0.5, 0.2) * (1.0 - r) + Vec3A::splat(r)) * floor;
    let got = mean_li(&scene(&text(true)), ray, 40_000);
    for c in 0..3 {
        assert!(
            (got[c] - want[c]).abs() <= 0.02 * want[c],
            "channel {c}: {} against ((1 − R)·tint + R)·ρE/π = {}",
            got[c],
            want[c]
        );
    }
    let solid = mean_li(&scene(&text(false)), ray, 4_000);
    assert!(
        solid.x < 0.6 * want.x,
        "a solid's boundary scales by 1/η² (and stays inside): {solid} against {want}"
    );
}
