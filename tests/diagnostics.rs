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
