//! Scenes as code: schema, JSON scenes, overrides, machine-readable
//! validation and formatting.

use crate::common;

use common::{ronray, root};
use ronray::frame::render_whole;
use ronray::load::{LoadError, Overrides, load_with};
use std::path::PathBuf;

fn scenes() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "ron" || e == "json"))
        .collect();
    v.sort();
    v
}

#[test]
fn schema_file_is_up_to_date() {
    let committed = std::fs::read_to_string(root().join("schema/scene.schema.json")).expect("schema file");
    assert!(
        committed == ronray::schema::schema_json(),
        "schema/scene.schema.json is stale: run `cargo run -- schema > schema/scene.schema.json`"
    );
}

#[test]
fn every_scene_validates_against_the_schema() {
    let schema: serde_json::Value =
        serde_json::from_str(&ronray::schema::schema_json()).expect("schema is JSON");
    let validator = jsonschema::validator_for(&schema).expect("schema compiles");
    let mut files = scenes();
    files.push(root().join("tests/fixtures/cornell.json"));
    for p in files {
        let text = std::fs::read_to_string(&p).expect("read");
        let desc =
            ronray::load::pipeline::parse(&p, &text).unwrap_or_else(|r| panic!("{}: {r}", p.display()));
        let value = serde_json::to_value(&desc).expect("to JSON");
        let errors: Vec<String> = validator
            .iter_errors(&value)
            .map(|e| format!("{e} at {}", e.instance_path()))
            .collect();
        assert!(
            errors.is_empty(),
            "{} does not match the schema: {errors:#?}",
            p.display()
        );
    }
    // And the schema rejects what the loader rejects.
    let bad =
        serde_json::json!({"camera": {"eye": [0, 0, 1], "target": [0, 0, 0], "fov_y_degrees": 40, "fov": 3}});
    assert!(
        !validator.is_valid(&bad),
        "unknown fields must be rejected by the schema"
    );
}

#[test]
fn json_scene_renders_the_same_image_as_its_ron_twin() {
    let o = Overrides {
        spp: Some(2),
        size: Some((24, 24)),
        ..Default::default()
    };
    let ron = load_with(&root().join("scenes/cornell.ron"), &o).expect("RON loads");
    let json = load_with(&root().join("tests/fixtures/cornell.json"), &o).expect("JSON loads");
    assert_eq!(
        render_whole(&ron.scene, &ron.view, &Default::default()).0,
        render_whole(&json.scene, &json.view, &Default::default()).0
    );
}

#[test]
fn json_scene_errors_are_located() {
    let dir = tempfile::tempdir().expect("tmp");
    let p = dir.path().join("bad.json");
    let text = std::fs::read_to_string(root().join("tests/fixtures/cornell.json")).expect("read");
    std::fs::write(
        &p,
        text.replacen("\"radius\"", "\"raduis\"", 1)
            .replacen("\"spp\": 64", "\"spp\": 0", 1),
    )
    .expect("write");
    match load_with(&p, &Overrides::default()) {
        Err(LoadError::Invalid(r)) => {
            let d = &r.diagnostics[0];
            assert_eq!(d.path.as_deref(), Some("film.spp"), "{d}");
            assert!(d.line > 1 && d.column > 1, "located: {d}");
            let line = text.lines().nth(d.line - 1).unwrap_or("");
            assert!(line.contains("\"spp\""), "line {} is `{line}`", d.line);
        }
        Err(e) => panic!("expected diagnostics, got {e}"),
        Ok(_) => panic!("spp 0 must be rejected"),
    }
    std::fs::write(&p, text.replacen("\"fov_y_degrees\"", "\"fov_y_degree\"", 1)).expect("write");
    match load_with(&p, &Overrides::default()) {
        Err(LoadError::Invalid(r)) => {
            let d = &r.diagnostics[0];
            assert!(d.message.contains("unknown field `fov_y_degree`"), "{d}");
            assert_eq!(d.help.as_deref(), Some("did you mean `fov_y_degrees`?"), "{d}");
            assert!(d.line > 1, "{d}");
        }
        _ => panic!("a misspelled field must be rejected"),
    }
}

#[test]
fn set_overrides_nested_fields_and_rejects_missing_ones() {
    let p = root().join("scenes/cornell.ron");
    let o = Overrides {
        sets: vec![
            "materials.white.albedo=(0.2, 0.2, 0.2)".into(),
            "camera.fov_y_degrees=30".into(),
            "film.spp=3".into(),
        ],
        ..Default::default()
    };
    let l = load_with(&p, &o).expect("valid overrides");
    assert_eq!(l.desc.film.spp, 3);
    assert_eq!(l.desc.camera.fov_y_degrees, Some(30.0));
    let white = &l.desc.materials["white"];
    assert_eq!(format!("{white:?}"), "Lambert { albedo: Rgb([0.2, 0.2, 0.2]) }");
    // Typed: the CLI flag beats the file, `--spp` beats `--set film.spp`.
    let both = Overrides {
        spp: Some(5),
        sets: vec!["film.spp=3".into()],
        ..Default::default()
    };
    assert_eq!(load_with(&p, &both).expect("valid").desc.film.spp, 5);

    let bad = Overrides {
        sets: vec!["camera.fov=30".into(), "film.spp=\"many\"".into()],
        ..Default::default()
    };
    match load_with(&p, &bad) {
        Err(LoadError::Invalid(r)) => {
            let d = &r.diagnostics[0];
            assert_eq!(d.path.as_deref(), Some("camera.fov"));
            assert_eq!(d.help.as_deref(), Some("did you mean `fov_y_degrees`?"), "{d}");
        }
        _ => panic!("an override that names nothing must be an error"),
    }
    let typed = Overrides {
        sets: vec!["film.spp=\"many\"".into()],
        ..Default::default()
    };
    assert!(
        load_with(&p, &typed).is_err(),
        "a string for spp must be rejected"
    );
    // An override that makes the scene invalid is caught by validation.
    let invalid = Overrides {
        sets: vec!["objects[0].half_u=(0, 0, 0)".into()],
        ..Default::default()
    };
    assert!(load_with(&p, &invalid).is_err());
}

#[test]
fn validate_json_format_is_machine_readable() {
    let bad = root().join("tests/fixtures/broken/three_mistakes.ron");
    let o = ronray(&["validate", "--format", "json", bad.to_str().expect("utf-8")]);
    assert_eq!(o.status.code(), Some(1));
    let all: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("not JSON ({e}): {l}")))
        .collect();
    // The warning the mistakes cannot have caused (no light) comes with them.
    assert!(
        all.iter()
            .any(|l| l["severity"] == "warning" && l["path"] == "lights"),
        "{all:?}"
    );
    let lines: Vec<&serde_json::Value> = all.iter().filter(|l| l["severity"] == "error").collect();
    assert_eq!(lines.len(), 3);
    for l in &all {
        for key in [
            "file",
            "line",
            "column",
            "path",
            "severity",
            "message",
            "suggestion",
        ] {
            assert!(l.get(key).is_some(), "missing `{key}` in {l}");
        }
    }
    assert_eq!(lines[1]["path"], "film.spp");
    assert_eq!(
        (lines[1]["line"].as_u64(), lines[1]["column"].as_u64()),
        (Some(3), Some(40))
    );
}

/// `fmt` keeps comments; the canonical rewrite (`--canonical`) refuses to
/// drop them unless told to.
#[test]
fn fmt_keeps_comments_and_canonical_refuses_to_drop_them() {
    let dir = tempfile::tempdir().expect("tmp");
    let p = dir.path().join("s.ron");
    let original =
        std::fs::read_to_string(root().join("tests/fixtures/broken/unknown_material.ron")).expect("read");
    let with_comment = format!("// keep me\n{}", original.replace("whtie", "white"));
    std::fs::write(&p, &with_comment).expect("write");
    let ps = p.to_str().expect("utf-8");
    assert!(ronray(&["fmt", ps]).status.success());
    assert!(
        std::fs::read_to_string(&p)
            .expect("read")
            .starts_with("// keep me\n"),
        "fmt keeps comments"
    );
    std::fs::write(&p, &with_comment).expect("write");
    let o = ronray(&["fmt", "--canonical", ps]);
    assert_eq!(o.status.code(), Some(1), "comments must not be dropped silently");
    assert!(String::from_utf8_lossy(&o.stderr).contains("comments"));
    assert_eq!(
        std::fs::read_to_string(&p).expect("read"),
        with_comment,
        "file untouched"
    );
    assert!(
        ronray(&["fmt", "--canonical", "--drop-comments", ps])
            .status
            .success()
    );
    assert!(
        ronray(&["fmt", "--canonical", "--check", ps]).status.success(),
        "formatted output is canonical"
    );
    let once = std::fs::read_to_string(&p).expect("read");
    assert!(ronray(&["fmt", "--canonical", ps]).status.success());
    assert_eq!(
        std::fs::read_to_string(&p).expect("read"),
        once,
        "formatting is idempotent"
    );
    assert!(
        ronray(&["validate", ps]).status.success(),
        "formatted scene still valid"
    );
}
