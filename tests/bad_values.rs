//! Numbers that are no value, or too large to light a scene with (issue 39,
//! "silent wrong images"):
//!
//! - Texels that are NaN, infinite or negative in a float image read for a
//!   parameter (a roughness, a colour, an emission; scene and MTL textures
//!   alike) are read as 0, with a note located at the parameter that read
//!   the file and saying how many of each were repaired. Before, they went
//!   silently into the render: one NaN roughness texel put NaN in pixels.
//! - An emitted radiance or intensity above `MAX_RADIANCE` (10¹²), written
//!   in the scene, reached through a texture's scale, an environment's
//!   strength or an emission image's texels, is refused at its path.
//!   Before, values up to 10¹⁵ were accepted (and 1e38 refused as a
//!   coordinate "beyond ±1e15"), and scales and strengths of 1e38 passed,
//!   making a light's power infinite.

use crate::common;

use ronray::diagnostic::Severity;
use ronray::load::{LoadError, Loaded, Overrides, load_str};
use std::path::Path;

/// A 4×4 RGB EXR at `path`, every texel `fill` but texel (1, 2), which is
/// `bad`.
fn exr(path: &Path, fill: f32, bad: [f32; 3]) {
    exr::prelude::write_rgb_file(path, 4, 4, |x, y| {
        if (x, y) == (1, 2) {
            (bad[0], bad[1], bad[2])
        } else {
            (fill, fill, fill)
        }
    })
    .expect("an EXR");
}

/// A scene in `dir` with `materials`, `lights` and `objects` as given.
fn scene(materials: &str, lights: &str, objects: &str) -> String {
    format!(
        "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 50), \
         film: (width: 12, height: 12, spp: 8), integrator: Path(max_depth: 4), \
         materials: {{ {materials} }}, lights: [{lights}], objects: [{objects}])"
    )
}

/// The notes of a load: (scene path, message, line).
fn notes(l: &Loaded) -> Vec<(String, String, usize)> {
    l.warnings
        .diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Note)
        .map(|d| (d.path.clone().unwrap_or_default(), d.message.clone(), d.line))
        .collect()
}

/// The note at scene path `at`; fails naming every note when none is.
fn note_at(l: &Loaded, at: &str) -> (String, usize) {
    let all = notes(l);
    all.iter()
        .find(|(p, _, _)| p == at)
        .map(|(_, m, line)| (m.clone(), *line))
        .unwrap_or_else(|| panic!("no note at `{at}`; the notes are {all:#?}"))
}

#[test]
fn texels_that_are_no_value_in_parameter_textures_are_repaired_with_a_located_note() {
    let dir = tempfile::tempdir().expect("temp dir");
    exr(
        &dir.path().join("rough.exr"),
        0.3,
        [f32::NAN, f32::INFINITY, -1.0],
    );
    exr(&dir.path().join("albedo.exr"), 0.5, [0.5, f32::NAN, 0.5]);
    exr(&dir.path().join("glow.exr"), 2.0, [f32::NEG_INFINITY, 2.0, 2.0]);
    exr(&dir.path().join("clean.exr"), 0.5, [0.5, 0.5, 0.5]);
    let text = scene(
        r#""rough": MetalPlastic(base_color: Image(file: "albedo.exr"), roughness: Image(file: "rough.exr", channel: R), metalness: 0),
           "clean": Lambert(albedo: Image(file: "clean.exr"))"#,
        "Point(position: (0, 3, 2), intensity: (8, 8, 8))",
        r#"Sphere(center: (0, 0, 0), radius: 1, material: "rough"),
           Sphere(center: (-1.5, 0, 0), radius: 0.4, material: "clean"),
           Sphere(center: (1.5, 1.5, -1), radius: 0.4, material: "clean",
                  emission: (radiance: Image(file: "glow.exr")))"#,
    );
    let l = common::load_in(dir.path(), &text, &Overrides::default());
    let (m, line) = note_at(&l, "materials.rough.roughness.file");
    assert!(
        m.contains(
            "rough.exr has 1 NaN channel value, 1 infinite channel value, 1 negative channel value, read as 0"
        ),
        "{m}"
    );
    assert!(line > 0, "the roughness note is not located: {m}");
    let (m, _) = note_at(&l, "materials.rough.base_color.file");
    assert!(m.contains("albedo.exr has 1 NaN channel value, read as 0"), "{m}");
    let (m, _) = note_at(&l, "objects[2].emission.radiance.file");
    assert!(
        m.contains("glow.exr has 1 infinite channel value, read as 0"),
        "{m}"
    );
    assert!(
        !notes(&l).iter().any(|(_, m, _)| m.contains("clean.exr")),
        "a clean image earned a note: {:#?}",
        notes(&l)
    );
    for (i, t) in l.scene.textures.iter().enumerate() {
        assert!(
            t.texels.iter().all(|c| c.is_finite() && c.min_element() >= 0.0),
            "texture {i} still holds a texel that is no value"
        );
    }
    // Every pixel finite (checked by render_loaded).
    common::render_loaded(&l);
}

/// MTL maps read the same rule: a float `map_Pr` (read linear) and a float
/// `map_Kd` (read through 8 bits, where NaN became 0 and +∞ white without
/// a word) both earn a note naming the texture.
#[test]
fn texels_that_are_no_value_in_mtl_maps_are_repaired_with_a_note() {
    let dir = tempfile::tempdir().expect("temp dir");
    exr(&dir.path().join("pr.exr"), 0.4, [f32::NAN, 0.4, 0.4]);
    exr(&dir.path().join("kd.exr"), 0.5, [f32::INFINITY, 0.5, -2.0]);
    let obj = "mtllib m.mtl\n\
               v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
               usemtl pbr\nf 1/1 3/3 2/2\nf 1/1 4/4 3/3\n";
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    let mtl = "newmtl pbr\nKd 0.5 0.5 0.5\nPr 1\nmap_Pr pr.exr\nmap_Kd kd.exr\n";
    std::fs::write(dir.path().join("m.mtl"), mtl).expect("mtl");
    let text = scene(
        "",
        "Point(position: (0, 3, 2), intensity: (8, 8, 8))",
        r#"Mesh(file: "m.obj")"#,
    );
    let l = common::load_in(dir.path(), &text, &Overrides::default());
    let all = notes(&l);
    let said = |file: &str, what: &str| {
        all.iter()
            .any(|(_, m, _)| m.contains(file) && m.contains(what) && m.contains("read as 0"))
    };
    assert!(said("pr.exr", "1 NaN channel value"), "{all:#?}");
    assert!(
        said("kd.exr", "1 infinite channel value, 1 negative channel value"),
        "{all:#?}"
    );
    common::render_loaded(&l);
}

/// The refusal of scene `text` in `dir`: each diagnostic's scene path and
/// message.
fn refusal(dir: &Path, text: &str) -> Vec<(String, String)> {
    match load_str(&dir.join("test.ron"), text, &Overrides::default()) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(LoadError::Invalid(r)) => r
            .diagnostics
            .iter()
            .map(|d| (d.path.clone().unwrap_or_default(), d.message.clone()))
            .collect(),
        Err(e) => panic!("refused for another reason: {}", common::message(&e)),
    }
}

#[test]
fn emitted_radiance_above_the_limit_is_refused_at_its_path() {
    let dir = tempfile::tempdir().expect("temp dir");
    exr(&dir.path().join("hot.exr"), 1.0, [1e38, 1.0, 1.0]);
    exr(&dir.path().join("warm.exr"), 1.0, [5.0, 1.0, 1.0]);
    let black = r#""black": Lambert(albedo: (0, 0, 0))"#;
    let lamp = "Point(position: (0, 3, 2), intensity: (8, 8, 8))";
    let sphere = |emission: &str| {
        format!(
            r#"Sphere(center: (0, 0, 0), radius: 1, material: "black", emission: (radiance: {emission}))"#
        )
    };
    let cases = [
        (
            scene(
                black,
                "Quad(corner: (-1, 2, -1), edge_u: (2, 0, 0), edge_v: (0, 0, 2), radiance: (1e38, 1e38, 1e38))",
                "",
            ),
            "lights[0].radiance",
        ),
        (
            scene(black, lamp, &sphere("(1e13, 1, 1)")),
            "objects[0].emission.radiance",
        ),
        (
            scene(black, "Point(position: (0, 3, 2), intensity: (1e38, 1, 1))", ""),
            "lights[0].intensity",
        ),
        (
            scene(black, "Environment(radiance: (1, 1, 1), strength: 1e38)", ""),
            "lights[0].strength",
        ),
        (
            scene(black, lamp, &sphere(r#"Image(file: "warm.exr", scale: 1e38)"#)),
            "objects[0].emission.radiance.scale",
        ),
        (
            scene(black, lamp, &sphere(r#"Image(file: "hot.exr")"#)),
            "objects[0].emission.radiance.file",
        ),
        (
            scene(black, "Environment(map: \"warm.exr\", strength: 1e12)", ""),
            "lights[0].map",
        ),
    ];
    for (text, at) in &cases {
        let found = refusal(dir.path(), text);
        assert!(
            found
                .iter()
                .any(|(p, m)| p == at && m.contains("above the limit of 1e12")),
            "expected a refusal at `{at}` naming the limit 1e12, got {found:#?}\n{text}"
        );
    }
    // At the limit, and with the ordinary values the cases vary, all load.
    for ok in [
        scene(
            black,
            "Quad(corner: (-1, 2, -1), edge_u: (2, 0, 0), edge_v: (0, 0, 2), radiance: (1e12, 1, 1))",
            "",
        ),
        scene(black, "Environment(map: \"warm.exr\", strength: 2)", ""),
        scene(black, lamp, &sphere(r#"Image(file: "warm.exr", scale: 3)"#)),
    ] {
        if let Err(e) = load_str(&dir.path().join("test.ron"), &ok, &Overrides::default()) {
            panic!("refused:\n{}\n{ok}", common::message(&e));
        }
    }
}
