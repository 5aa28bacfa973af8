//! Hover and completion on JSON scenes and half-typed RON (the binary is
//! driven over stdio in `tests/lsp.rs`).

use super::completion::complete;
use super::hover::hover;
use super::schema::Schema;
use crate::syntax::lex::tokenize_lenient;

fn labels(src: &str, at: usize, json: bool) -> Vec<(String, String)> {
    let toks = tokenize_lenient(src);
    complete(&Schema::new(), src, &toks, at, json, &[])
        .into_iter()
        .map(|i| (i.label, i.insert_text.unwrap_or_default()))
        .collect()
}

#[test]
fn lsp_json_completes_quoted_keys_and_variant_tags() {
    let src =
        r#"{"camera": {"eye": [0, 1, 4], }, "objects": [{ }], "integrator": {"Path": {"max_depth": 3}}}"#;
    let keys = labels(src, src.find("], }").expect("camera") + 3, true);
    assert!(
        keys.contains(&("target".into(), "\"target\": ".into())),
        "{keys:?}"
    );
    assert!(!keys.iter().any(|(k, _)| k == "eye"), "{keys:?}");
    let tags = labels(src, src.find("[{ }]").expect("objects") + 3, true);
    assert!(tags.contains(&("Sphere".into(), "\"Sphere\"".into())), "{tags:?}");
    let toks = tokenize_lenient(src);
    let (md, _) = hover(
        &Schema::new(),
        src,
        &toks,
        src.find("max_depth").expect("key") + 2,
    )
    .expect("hover");
    assert!(md.contains("max_depth") && md.contains("default: `8`"), "{md}");
}

#[test]
fn lsp_completes_while_typing_ron() {
    // An unterminated string and a half-typed key still complete.
    let src = "Scene(\n    materials: { \"white\": Lambert(albedo: 0.8) },\n    objects: [Sphere(center: (0, 0, 0), radi";
    let fields = labels(src, src.len(), false);
    assert!(
        fields.contains(&("radius".into(), "radius: ".into())),
        "{fields:?}"
    );
    let src =
        "Scene(\n    materials: { \"white\": Lambert(albedo: 0.8) },\n    objects: [Sphere(material: \"wh\n";
    let names = labels(src, src.rfind("\"wh").expect("string") + 3, false);
    assert_eq!(names, [("white".to_string(), "white".to_string())]);
    let src = "Scene(camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (sampler: ))";
    let samplers = labels(src, src.find("sampler: ").expect("key") + 9, false);
    assert!(samplers.iter().any(|(l, _)| l == "Sobol"), "{samplers:?}");
}

#[test]
fn lsp_completes_film_aovs_and_denoise() {
    let src = "Scene(camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (width: 64, ))";
    let fields = labels(src, src.find("64, ").expect("film") + 4, false);
    for f in ["aovs", "denoise"] {
        assert!(fields.iter().any(|(l, _)| l == f), "{f} missing: {fields:?}");
    }
    let src =
        "Scene(camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (aovs: [Albedo, ]))";
    let layers = labels(src, src.find("Albedo, ").expect("aovs") + 8, false);
    for l in ["Normal", "Depth", "Position", "MaterialIndex"] {
        assert!(layers.iter().any(|(x, _)| x == l), "{l} missing: {layers:?}");
    }
}

#[test]
fn lsp_completes_texture_forms_in_an_emission_radiance() {
    // The radiance of a light and of an emitting object takes a texture.
    for src in [
        "Scene(materials: { \"m\": Lambert(albedo: ) })",
        "Scene(lights: [Rect(center: (0, 1, 0), radiance: )])",
        "Scene(objects: [Sphere(radius: 1, emission: (radiance: ))])",
    ] {
        let at = src.find(": )").expect("key") + 2;
        let forms = labels(src, at, false);
        for f in ["Image", "Checker", "Pattern"] {
            assert!(
                forms.iter().any(|(l, _)| l == f),
                "{f} missing in {src}: {forms:?}"
            );
        }
    }
    // Inside a texture, its fields.
    let src = "Scene(lights: [Rect(radiance: Image(file: \"sign.png\", ))])";
    let fields = labels(src, src.find("png\", ").expect("file") + 6, false);
    for f in ["colorspace", "scale", "uv"] {
        assert!(fields.iter().any(|(l, _)| l == f), "{f} missing: {fields:?}");
    }
}

#[test]
fn lsp_completes_media_names_and_medium_fields() {
    let src = "Scene(\n    media: { \"fog\": Homogeneous(sigma_t: (1, 1, 1)) },\n    objects: [Sphere(center: (0, 0, 0), radius: 1, interior: \"f\n";
    let names = labels(src, src.rfind("\"f").expect("string") + 2, false);
    assert_eq!(names, [("fog".to_string(), "fog".to_string())]);
    let src = "Scene(media: { \"fog\": Homogeneous(sigma_t: (1, 1, 1), ) })";
    let fields = labels(src, src.find("), )").expect("fields") + 3, false);
    assert!(fields.iter().any(|(l, _)| l == "albedo"), "{fields:?}");
    assert!(fields.iter().any(|(l, _)| l == "g"), "{fields:?}");
}
