//! Three scenes as a newcomer writes them (issue 46), each with several
//! realistic mistakes: one `validate` run must show every one of them —
//! warnings with errors, the other fields of a broken entry, the checks that
//! need an OBJ's content beside a missing file — each at its place.

use ronray::diagnostic::{Diagnostic, Severity};
use ronray::load::{LoadError, load};
use std::path::Path;

/// Every diagnostic of one load of `tests/fixtures/newcomer/<name>`.
fn one_run(name: &str) -> Vec<Diagnostic> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures/newcomer")
        .join(name);
    match load(&path) {
        Err(LoadError::Invalid(r)) => r.diagnostics,
        Err(e) => panic!("{name}: {e}"),
        Ok(_) => panic!("{name} is broken on purpose"),
    }
}

fn list(d: &[Diagnostic]) -> String {
    d.iter().map(|d| format!("{d}\n")).collect()
}

/// `d` holds exactly `want`: (severity, path, a fragment of the message or
/// help), in any order, and nothing else.
fn exactly(name: &str, d: &[Diagnostic], want: &[(Severity, &str, &str)]) {
    for (severity, path, fragment) in want {
        let found = d.iter().any(|d| {
            d.severity == *severity
                && d.path.as_deref() == Some(*path)
                && format!("{} {}", d.message, d.help.clone().unwrap_or_default()).contains(fragment)
        });
        assert!(
            found,
            "{name}: no {severity} at {path} saying `{fragment}`; got:\n{}",
            list(d)
        );
    }
    assert_eq!(
        d.len(),
        want.len(),
        "{name}: expected {} diagnostics, got:\n{}",
        want.len(),
        list(d)
    );
}

#[test]
fn newcomer_still_life_shows_all_six_mistakes_in_one_run() {
    let d = one_run("still_life.ron");
    exactly(
        "still_life.ron",
        &d,
        &[
            (Severity::Warning, "camera.fov_y_degrees", "40.1"),
            (Severity::Error, "materials.table", "did you mean `albedo`?"),
            (Severity::Error, "materials.clay.albedo", "divide by 255"),
            (
                Severity::Error,
                "lights[0].map",
                "did you mean `../../../assets/sky_sun.exr`?",
            ),
            (Severity::Error, "objects[1].center", "3"),
            (Severity::Error, "objects[1].material", "did you mean `glass`?"),
        ],
    );
}

#[test]
fn newcomer_obj_asset_shows_all_five_mistakes_in_one_run() {
    let d = one_run("asset/asset.ron");
    exactly(
        "asset/asset.ron",
        &d,
        &[
            (Severity::Error, "objects[1].materials.shade", "material:shade"),
            (
                Severity::Error,
                "objects[2].materials.bsae",
                "did you mean `base`?",
            ),
            (Severity::Error, "objects[3].mesh", "did you mean `lamp`?"),
            (Severity::Error, "objects[4].file", "did you mean `vase.obj`?"),
            (Severity::Error, "meshes.lamp.file", "`brass` is defined twice"),
        ],
    );
}

#[test]
fn newcomer_sdf_sculpture_shows_all_six_mistakes_in_one_run() {
    let d = one_run("sculpture.ron");
    exactly(
        "sculpture.ron",
        &d,
        &[
            (Severity::Error, "film.spp", "0"),
            (Severity::Error, "materials.stone.albedo", "above 1"),
            (Severity::Warning, "materials.chrome", "Direct"),
            (Severity::Error, "objects[1].shape.radius", "radius"),
            (
                Severity::Error,
                "objects[2].transform[0]",
                "did you mean `degrees`?",
            ),
            (Severity::Error, "objects[2].material", "did you mean `bronze`?"),
        ],
    );
}
