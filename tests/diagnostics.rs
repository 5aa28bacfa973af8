//! Broken scene files give located, helpful diagnostics — all of them at once.

use ronray::diagnostic::Diagnostic;
use ronray::load::{LoadError, load};
use std::path::{Path, PathBuf};

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/broken")
        .join(name)
}

fn diagnostics(name: &str) -> (Vec<Diagnostic>, String) {
    match load(&fixture(name)) {
        Ok(_) => panic!("{name} loaded, but it is broken on purpose"),
        Err(LoadError::Invalid(r)) => (r.diagnostics.clone(), r.render(false)),
        Err(e) => panic!("{name}: expected diagnostics, got {e}"),
    }
}

#[test]
fn syntax_error_is_located_with_caret() {
    let (d, text) = diagnostics("syntax.ron");
    assert_eq!(d.len(), 1, "{d:?}");
    // The missing comma after the `white` entry is noticed at `"red"`.
    assert_eq!((d[0].line, d[0].column), (5, 9), "got {}", d[0]);
    assert!(d[0].message.contains("expected"), "message: {}", d[0].message);
    assert!(text.contains("syntax.ron:5:9"), "rendered:\n{text}");
    assert!(
        text.contains("\"red\": Lambert"),
        "the offending line is shown:\n{text}"
    );
    assert!(
        text.contains('^') || text.contains('┬') || text.contains('─'),
        "a marker under the column:\n{text}"
    );
}

#[test]
fn three_semantic_mistakes_are_reported_together() {
    let (d, text) = diagnostics("three_mistakes.ron");
    let paths: Vec<_> = d.iter().map(|d| d.path.clone().unwrap_or_default()).collect();
    assert_eq!(
        paths,
        ["camera.up", "film.spp", "objects[0].radius"],
        "rendered:\n{text}"
    );
    assert_eq!((d[0].line, d[0].column), (2, 53), "{}", d[0]);
    assert_eq!((d[1].line, d[1].column), (3, 40), "{}", d[1]);
    assert_eq!((d[2].line, d[2].column), (6, 43), "{}", d[2]);
    assert!(
        d[0].message.contains("parallel to the view direction"),
        "{}",
        d[0]
    );
    assert!(
        d[1].message.contains("1..=1048576"),
        "the limit is named: {}",
        d[1]
    );
    assert!(d[2].message.contains("radius -1 must be > 0"), "{}", d[2]);
}

#[test]
fn unknown_material_suggests_closest_name() {
    let (d, _) = diagnostics("unknown_material.ron");
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path.as_deref(), Some("objects[1].material"));
    assert_eq!((d[0].line, d[0].column), (9, 56));
    assert!(d[0].message.contains("unknown material `whtie`"), "{}", d[0]);
    assert_eq!(d[0].help.as_deref(), Some("did you mean `white`?"));
}

#[test]
fn missing_obj_prints_resolved_path() {
    let (d, _) = diagnostics("missing_obj.ron");
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path.as_deref(), Some("objects[0].file"));
    assert_eq!((d[0].line, d[0].column), (5, 20));
    let resolved = fixture("meshes/nowhere.obj");
    let help = d[0].help.clone().unwrap_or_default();
    assert!(
        help.contains(&resolved.display().to_string()),
        "help names {}: {help}",
        resolved.display()
    );
}

#[test]
fn misspelled_field_suggests_the_right_one() {
    let (d, _) = diagnostics("misspelled_field.ron");
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].line, 5, "{}", d[0]);
    assert!(
        d[0].message.contains("unknown field `radius`") || d[0].message.contains("unknown field `raduis`"),
        "{}",
        d[0]
    );
    let help = d[0].help.clone().unwrap_or_default();
    assert!(help.contains("did you mean `radius`?"), "help: {help}");
}

// ---- Warnings: scenes that load but will surprise (issue 12) ----

fn warning_fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/warnings")
        .join(name)
}

/// The warnings of a fixture that must load, and their rendered text.
fn warnings_of(name: &str) -> (Vec<Diagnostic>, String) {
    match load(&warning_fixture(name)) {
        Ok(l) => (l.warnings.diagnostics.clone(), l.warnings.render(false)),
        Err(e) => panic!("{name} should load (it only warrants warnings), got {e}"),
    }
}

/// `name` gives exactly one warning, at `path`, `line`:`column`.
fn one_warning(name: &str, path: &str, line: usize, column: usize) -> Diagnostic {
    use ronray::diagnostic::Severity;
    let (d, text) = warnings_of(name);
    assert_eq!(d.len(), 1, "{name}: expected one warning, got:\n{text}");
    assert_eq!(d[0].severity, Severity::Warning, "{}", d[0]);
    assert_eq!(d[0].path.as_deref(), Some(path), "{}", d[0]);
    assert_eq!((d[0].line, d[0].column), (line, column), "{}", d[0]);
    assert!(
        text.contains("Warning") && text.contains(&format!("{name}:{line}:{column}")),
        "rendered as a located warning:\n{text}"
    );
    d[0].clone()
}

#[test]
fn scene_without_lights_warns_at_scene_start() {
    let d = one_warning("no_light.ron", "lights", 3, 1);
    assert!(d.message.contains("no lights"), "{d}");
    assert!(d.help.as_deref().is_some_and(|h| h.contains("lights: [")), "{d}");
    assert!(
        d.to_string().contains(": warning: "),
        "Display names the severity: {d}"
    );
}

#[test]
fn lights_of_zero_power_warn_at_lights() {
    let d = one_warning("dark_lights.ron", "lights", 6, 13);
    assert!(d.message.contains("zero intensity or radiance"), "{d}");
}

#[test]
fn mirror_and_glass_under_default_direct_warn_at_each_used_material() {
    let (d, text) = warnings_of("mirror_direct.ron");
    let at: Vec<_> = d
        .iter()
        .map(|d| (d.path.clone().unwrap_or_default(), d.line, d.column))
        .collect();
    assert_eq!(
        at,
        [
            ("materials.chrome".to_string(), 7, 19),
            ("materials.window".to_string(), 8, 19)
        ],
        "the unused `spare` glass is not warned about:\n{text}"
    );
    assert!(
        d[0].message.contains("perfect mirror") && d[0].message.contains("Direct"),
        "{}",
        d[0]
    );
    let help = d[1].help.clone().unwrap_or_default();
    assert!(help.contains("Path") && help.contains("Whitted"), "help: {help}");
}

#[test]
fn area_light_facing_away_from_every_object_warns_with_swap_help() {
    let d = one_warning("light_facing_away.ron", "lights[1]", 11, 9);
    assert!(
        d.message.contains("(0.000, 1.000, 0.000)"),
        "names the normal: {d}"
    );
    assert_eq!(
        d.help.as_deref(),
        Some("a light emits on the side of `edge_u × edge_v`; swap `edge_u` and `edge_v` to flip it")
    );
}

#[test]
fn field_of_view_under_five_degrees_warns_it_is_degrees() {
    let d = one_warning("narrow_fov.ron", "camera.fov_y_degrees", 3, 64);
    let help = d.help.clone().unwrap_or_default();
    assert!(
        help.contains("in degrees") && help.contains("40.1"),
        "offers the radian reading: {help}"
    );
}

#[test]
fn albedo_on_a_0_255_scale_is_an_error_that_says_divide_by_255() {
    let (d, text) = diagnostics("byte_albedo.ron");
    assert_eq!(d.len(), 2, "{text}");
    assert_eq!(d[0].path.as_deref(), Some("materials.brick.albedo"));
    assert_eq!((d[0].line, d[0].column), (4, 34), "{}", d[0]);
    assert_eq!(
        d[0].help.as_deref(),
        Some("the channels look like 0–255 values; divide by 255: (0.698, 0.133, 0.133)")
    );
    // Just above 1 is a slip, not bytes: the ordinary help.
    assert_eq!(d[1].path.as_deref(), Some("materials.hot.albedo"));
    assert!(!d[1].help.clone().unwrap_or_default().contains("255"), "{}", d[1]);
}

#[test]
fn shipped_scenes_give_no_warnings() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("scenes/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    scenes.sort();
    assert!(scenes.len() >= 4, "found {scenes:?}");
    for p in &scenes {
        match load(p) {
            Ok(l) => assert!(
                l.warnings.diagnostics.is_empty(),
                "{} warns:\n{}",
                p.display(),
                l.warnings.render(false)
            ),
            Err(e) => panic!("{}: {e}", p.display()),
        }
    }
}

#[test]
fn validate_passes_warnings_unless_denied() {
    let scene = warning_fixture("narrow_fov.ron");
    let run = |extra: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_ronray"))
            .arg("validate")
            .args(extra)
            .arg(&scene)
            .output()
            .expect("the ronray binary runs")
    };
    let plain = run(&[]);
    let stderr = String::from_utf8_lossy(&plain.stderr);
    assert_eq!(plain.status.code(), Some(0), "warnings alone pass:\n{stderr}");
    assert!(
        stderr.contains("Warning") && stderr.contains("narrow_fov.ron:3:64"),
        "{stderr}"
    );
    let denied = run(&["--deny-warnings"]);
    assert_eq!(
        denied.status.code(),
        Some(1),
        "--deny-warnings fails:\n{}",
        String::from_utf8_lossy(&denied.stderr)
    );
    let json = run(&["--format", "json"]);
    assert_eq!(json.status.code(), Some(0));
    let line: serde_json::Value =
        serde_json::from_str(String::from_utf8_lossy(&json.stdout).trim()).expect("one JSON line");
    assert_eq!(line["severity"], "warning", "{line}");
    assert_eq!(
        (line["line"].as_u64(), line["column"].as_u64()),
        (Some(3), Some(64))
    );
}

// ---- Rough plastic and rough glass (issue 14) ----

#[test]
fn rough_material_mistakes_are_located_at_their_fields() {
    let (d, text) = diagnostics("rough_materials.ron");
    // In the order of the file, whatever order the checks run in.
    let mut got: Vec<_> = d
        .iter()
        .map(|d| (d.path.clone().unwrap_or_default(), d.line, d.column))
        .collect();
    got.sort_by_key(|&(_, line, column)| (line, column));
    let want = [
        ("materials.coat.diffuse", 4, 39),
        ("materials.coat.roughness", 4, 68),
        ("materials.coat.ior", 4, 78),
        ("materials.frost.roughness", 5, 40),
        ("materials.frost.ior", 5, 51),
        ("materials.frost.tint", 5, 60),
        ("materials.milk.specular", 6, 54),
        ("materials.milk.ior", 6, 78),
    ]
    .map(|(p, l, c)| (p.to_string(), l, c));
    assert_eq!(got, want, "rendered:\n{text}");
    let message = |path: &str| {
        d.iter()
            .find(|d| d.path.as_deref() == Some(path))
            .map(|d| d.message.clone())
            .unwrap_or_default()
    };
    assert!(message("materials.coat.diffuse").contains("negative colour"));
    assert!(message("materials.coat.roughness").contains("roughness 1.5 is outside [0, 1]"));
    assert!(message("materials.frost.roughness").contains("roughness -0.1 is outside [0, 1]"));
    assert!(message("materials.coat.ior").contains("index of refraction 0 is outside (0, 10]"));
    assert!(message("materials.milk.ior").contains("-1.5"));
    assert!(message("materials.frost.ior").contains("index of refraction 1 does not scatter"));
    assert!(message("materials.milk.specular").contains("above 1"));
    let roughness_help = d
        .iter()
        .find(|d| d.path.as_deref() == Some("materials.coat.roughness"))
        .and_then(|d| d.help.clone())
        .unwrap_or_default();
    assert!(
        roughness_help.contains("α = roughness²") && roughness_help.contains("Mitsuba's alpha"),
        "the help says how to write Mitsuba's α: {roughness_help}"
    );
}
