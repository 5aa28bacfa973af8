//! Bad SDF objects give diagnostics whose paths follow the scene's own tree
//! and whose line:column land on the offending value.

use ronray::load::{LoadError, Overrides, load_str};
use std::path::Path;

/// One mistake per object; each line is `(object, expected path, the text
/// the diagnostic must point at, a word of its message)`.
const SCENE: &str = r#"Scene(
    camera: (eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40),
    materials: { "m": Lambert(albedo: (0.5, 0.5, 0.5)) },
    objects: [
        Sdf(shape: Sphere(radius: -1), material: "m"),
        Sdf(shape: Union(of: []), material: "m"),
        Sdf(shape: SmoothUnion(k: -0.1, of: [Sphere(radius: 1), Box(half_extents: (1, -2, 1))]), material: "m"),
        Sdf(shape: Mandelbulb(power: 40, iterations: 0), material: "m"),
        Sdf(shape: Transform(scale: 0, of: Torus(major: 1, minor: -0.2)), material: "m"),
        Sdf(shape: Menger(iterations: 9), material: "m"),
        Sdf(shape: Difference(of: [Transform(translate: (1, 0, 0), of: Intersection(of: [])), Sphere(radius: 1)]), material: "m"),
        Sdf(shape: Union(of: [Sphere(radius: 1), Plane(normal: (0, 1, 0))]), material: "m"),
        Sdf(shape: Sphere(radius: 1), material: "m", transform: [Scale((1, 2, 1))]),
        Sdf(shape: Sphere(radius: 1), material: "m", march: (max_steps: 0, estimate_step: 1.5)),
        Sdf(shape: RoundBox(half_extents: (1, 1, 1), radius: 2), material: "m", transform: [Scale((-1, -1, -1))]),
    ],
)"#;

/// `(path, text it points at (first match at or after the object's line), word in the message)`.
const EXPECTED: &[(&str, &str, &str)] = &[
    ("objects[0].shape.radius", "-1", "positive"),
    ("objects[1].shape.of", "[]", "nothing to combine"),
    ("objects[2].shape.k", "-0.1", "at least 0"),
    ("objects[2].shape.of[1].half_extents", "(1, -2, 1)", "positive"),
    ("objects[3].shape.power", "40", "[2, 16]"),
    ("objects[3].shape.iterations", "0", "[1, 64]"),
    ("objects[4].shape.scale", "0", "positive"),
    ("objects[4].shape.of.minor", "-0.2", "positive"),
    ("objects[5].shape.iterations", "9", "[0, 6]"),
    ("objects[6].shape.of[0].of.of", "[]", "nothing to combine"),
    ("objects[7].shape.of[1]", "Plane(", "unbounded"),
    ("objects[8].transform", "[Scale", "keep its shape"),
    ("objects[9].march.max_steps", "0", "1..=100000"),
    ("objects[9].march.estimate_step", "1.5", "(0, 1]"),
    ("objects[10].shape.radius", "2", "[0, 1]"),
    ("objects[10].transform", "[Scale", "mirror"),
];

/// 1-based line and character column of the first `needle` on the line of
/// object `i` (line 5 + i in [`SCENE`]), after its `shape:` or field name.
fn locate(i: usize, path: &str, needle: &str) -> (usize, usize) {
    let line_no = 5 + i;
    let line = SCENE.lines().nth(line_no - 1).unwrap();
    // Start after the last field named in the path, so `0` in `scale: 0`
    // is not found inside an earlier number.
    let field = path.rsplit(['.', '[']).next().unwrap().trim_end_matches(']');
    let from = if field.parse::<usize>().is_ok() {
        0
    } else {
        line.find(&format!("{field}:")).map_or(0, |k| k + field.len() + 1)
    };
    let at = from
        + line[from..]
            .find(needle)
            .unwrap_or_else(|| panic!("{needle} in {line}"));
    (line_no, line[..at].chars().count() + 1)
}

#[test]
fn sdf_validation_locates_every_mistake() {
    let report = match load_str(Path::new("bad_sdf.ron"), SCENE, &Overrides::default()) {
        Err(LoadError::Invalid(r)) => r,
        Err(e) => panic!("expected diagnostics, got {e}"),
        Ok(_) => panic!("a scene full of mistakes loaded"),
    };
    // The errors (a warning, no light, comes with them).
    let got: Vec<_> = report
        .diagnostics
        .iter()
        .filter(|d| d.severity == ronray::diagnostic::Severity::Error)
        .map(|d| {
            (
                d.path.clone().unwrap_or_default(),
                d.line,
                d.column,
                d.message.clone(),
            )
        })
        .collect();
    assert_eq!(
        got.len(),
        EXPECTED.len(),
        "every mistake, and nothing else, is reported:\n{}",
        report.render(false)
    );
    for (&(path, needle, word), (got_path, line, column, message)) in EXPECTED.iter().zip(&got) {
        assert_eq!(got_path, path, "diagnostics in order:\n{}", report.render(false));
        let object: usize = path["objects[".len()..path.find(']').unwrap()].parse().unwrap();
        let want = locate(object, path, needle);
        assert_eq!(
            (*line, *column),
            want,
            "{path} should point at `{needle}`: {message}"
        );
        assert!(
            message.contains(word),
            "{path}: `{message}` should mention `{word}`"
        );
    }
}

#[test]
fn sdf_unbounded_intersection_is_accepted_once_cut() {
    // A plane cut by a box is bounded; a plane minus a sphere is not.
    let scene = |shape: &str| {
        let text = SCENE.replace(
            &SCENE[SCENE.find("    objects: [").unwrap()..SCENE.rfind("    ],").unwrap()],
            &format!("    objects: [Sdf(shape: {shape}, material: \"m\"),\n"),
        );
        load_str(Path::new("cut.ron"), &text, &Overrides::default())
    };
    assert!(
        scene("Intersection(of: [Plane(normal: (0, 1, 1), offset: 0.1), Box(half_extents: (1, 1, 1))])")
            .is_ok()
    );
    let Err(LoadError::Invalid(r)) = scene("Difference(of: [Plane(normal: (0, 1, 0)), Sphere(radius: 1)])")
    else {
        panic!("an unbounded difference loaded");
    };
    let error = r
        .diagnostics
        .iter()
        .find(|d| d.severity == ronray::diagnostic::Severity::Error)
        .expect("an error");
    assert_eq!(error.path.as_deref(), Some("objects[0].shape.of[0]"));
}
