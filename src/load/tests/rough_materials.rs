//! RoughPlastic and RoughGlass through the loader: defaults, shared coats,
//! and a render.

use crate::load::{Overrides, load_str};
use crate::materials::{ColorTex, Distribution, Material, RoughGlassMaterial, RoughPlasticMaterial};
use std::path::Path;

/// Defaults fill in, equal coats are integrated once and shared, and a
/// path-traced image of both models is finite and lit.
#[test]
fn rough_materials_load_with_defaults_share_coats_and_render() {
    let text = r#"Scene(
        camera: (eye: (0, 1, 5), target: (0, 0, 0), fov_y_degrees: 40),
        film: (width: 16, height: 16, spp: 4),
        integrator: Path(max_depth: 6, rr_depth: 5),
        materials: {
            "blue": RoughPlastic(diffuse: (0.1, 0.25, 0.6), roughness: 0.3162),
            "red": RoughPlastic(diffuse: (0.6, 0.1, 0.1), roughness: 0.3162, ior: 1.5),
            "milk": RoughPlastic(diffuse: 0.8, roughness: 0.3162, distribution: Beckmann),
            "frost": RoughGlass(roughness: 0.3),
        },
        lights: [Rect(center: (0, 3, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), radiance: (5, 5, 5))],
        objects: [
            Sphere(center: (-1.2, 0, 0), radius: 0.5, material: "blue"),
            Sphere(center: (0, 0, 0), radius: 0.5, material: "red"),
            Sphere(center: (1.2, 0, 0), radius: 0.5, material: "milk"),
            Sphere(center: (0, 0, 1.5), radius: 0.5, material: "frost"),
        ],
    )"#;
    let loaded =
        load_str(Path::new("rough.ron"), text, &Overrides::default()).unwrap_or_else(|e| panic!("{e}"));
    let mut coats = Vec::new();
    for m in &loaded.scene.materials {
        if let Material::RoughPlastic(RoughPlasticMaterial { coat, specular, .. }) = m {
            assert!(
                matches!(specular, ColorTex::Const(c) if *c == crate::math::Rgb::ONE),
                "specular defaults to 1: {specular:?}"
            );
            coats.push(coat.clone());
        }
        if let Material::RoughGlass(RoughGlassMaterial {
            distribution, ior, ..
        }) = m
        {
            assert_eq!(
                (*distribution, ior),
                (Distribution::Ggx, &crate::materials::Tex::Const(1.5))
            );
        }
    }
    assert_eq!(coats.len(), 3);
    // Name order: blue, milk, red.
    assert!(
        std::sync::Arc::ptr_eq(&coats[0], &coats[2]),
        "blue and red share a coat"
    );
    assert!(
        !std::sync::Arc::ptr_eq(&coats[0], &coats[1]),
        "Beckmann has its own"
    );
    assert_eq!(coats[0].eta, 1.5);
    assert!((coats[0].microfacet.alpha - 0.1).abs() < 1e-4);
    // One path per pixel through the loaded view (the loader's tests stay
    // below the frame wing, `tests/architecture.rs`).
    let mut counters = crate::integrators::Counters::default();
    let sum: f32 = (0..16 * 16)
        .map(|i| {
            let rng = crate::math::SampleRng::new(7, u64::from(i));
            let mut sampler = crate::sampler::Sampler::independent(rng);
            let (ray, _) = loaded.view.camera_ray(i % 16, i / 16, &mut sampler);
            let li = loaded
                .view
                .integrator
                .li(&loaded.scene, &ray, &mut sampler, &mut counters);
            li.x + li.y + li.z
        })
        .sum();
    assert!(sum.is_finite() && sum > 0.0, "image sum {sum}");
}
