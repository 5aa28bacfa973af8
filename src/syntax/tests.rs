//! The layout rules on small inputs; the shipped scenes are formatted in
//! `tests/fmt.rs`.

use super::{FormatError, format};

fn ron(src: &str) -> String {
    let out = format(src, false).unwrap_or_else(|e| panic!("{e}\n{src}"));
    assert_eq!(
        format(&out, false).as_ref(),
        Ok(&out),
        "formatting twice changes nothing"
    );
    out
}

#[test]
fn fmt_indents_and_keeps_comments_and_spellings() {
    let src = "#![schema = \"../schema/scene.schema.json\"]\n// top\nScene(camera:(eye:(0,1,4),target:(0,0,0),fov_y_degrees:40),\n\n\n  // lights\n  lights:[Point(position:(0,3,0),intensity:(1e1,10.,0x0A))],// end\n)";
    assert_eq!(
        ron(src),
        "#![schema = \"../schema/scene.schema.json\"]\n// top\nScene(\n    camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n\n    // lights\n    lights: [Point(position: (0, 3, 0), intensity: (1e1, 10., 0x0A))], // end\n)\n"
    );
}

#[test]
fn fmt_breaks_long_groups_and_joins_short_vectors() {
    let long = format!(
        "Scene(objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"{}\")])",
        "m".repeat(90)
    );
    let out = ron(&long);
    assert!(
        out.contains("    objects: [\n        Sphere(\n            center: (0, 0, 0),\n"),
        "{out}"
    );
    assert!(
        out.contains("\n        ),\n    ],\n)"),
        "trailing commas when broken:\n{out}"
    );
    // A vector written over lines goes on one line; a struct written over
    // lines stays over lines.
    let out = ron(
        "Scene(\n    camera: (\n        eye: (\n            0,\n            1,\n            4,\n        ),\n    ),\n)",
    );
    assert_eq!(out, "Scene(\n    camera: (\n        eye: (0, 1, 4),\n    ),\n)\n");
}

#[test]
fn fmt_keeps_a_hugging_layout() {
    let src = "Scene(\n    s: SmoothUnion(k: 0.25, of: [\n        Sphere(radius: 0.45),\n        Sphere(radius: 0.5),\n    ]),\n)\n";
    assert_eq!(ron(src), src);
}

#[test]
fn fmt_places_comments_by_line() {
    let src = "Scene(\n    materials: { // named\n        \"a\": Lambert(albedo: 0.5), /* inline */\n        // before b\n        \"b\": Lambert(albedo: /* why */ 0.25)\n        // closing\n    },\n)";
    let out = ron(src);
    assert_eq!(
        out,
        "Scene(\n    materials: { // named\n        \"a\": Lambert(albedo: 0.5), /* inline */\n        // before b\n        \"b\": Lambert(albedo: /* why */ 0.25),\n        // closing\n    },\n)\n"
    );
}

#[test]
fn fmt_writes_json_without_trailing_commas() {
    let src = "{\"camera\": {\"eye\": [\n0,\n1,\n4\n], \"fov_y_degrees\": 40}, \"objects\": [\n{\"Sphere\": {\"radius\": 1}}\n]}";
    let out = format(src, true).expect("formats");
    assert_eq!(
        out,
        "{\n    \"camera\": {\n        \"eye\": [0, 1, 4],\n        \"fov_y_degrees\": 40\n    },\n    \"objects\": [\n        { \"Sphere\": { \"radius\": 1 } }\n    ]\n}\n"
    );
    assert_eq!(format(&out, true).as_ref(), Ok(&out));
}

#[test]
fn fmt_refuses_broken_text() {
    for bad in [
        "Scene(a: (1, 2)",
        "Scene(a: 1))",
        "Scene(a: \"x)",
        "Scene(materials: { \"a\": Lambert(albedo: 1) \"b\": Lambert(albedo: 1) })",
    ] {
        assert!(
            matches!(format(bad, false), Err(FormatError::Syntax { .. })),
            "{bad}"
        );
    }
}
