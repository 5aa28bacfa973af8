//! `ronray migrate` on every shipped scene (the golden scenes among them):
//! the render is byte-identical before and after, every comment survives in
//! order, the file states the current version, and a second run changes
//! nothing.

use crate::common;

use common::{ronray_in, root};
use ronray::frame::render_whole;
use ronray::imageio::Image;
use ronray::load::{Overrides, load_str};
use ronray::migrate::{CURRENT, migrate_text, version_of};
use ronray::syntax::lex::tokenize;
use std::path::{Path, PathBuf};

/// Every scene the repository ships: `scenes/` (each with its golden image
/// in `scenes/golden/`), the bench scene and the JSON fixture. (The bench
/// folder's `.json` is its Mitsuba twin, not a ronray scene.)
fn shipped() -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(root().join("scenes"))
        .expect("scenes/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    files.sort();
    files.extend(
        [
            "bench/cornell_mesh/cornell_mesh.ron",
            "tests/fixtures/cornell.json",
        ]
        .map(|f| root().join(f)),
    );
    files
}

fn render(path: &Path, text: &str) -> Image {
    let o = Overrides {
        spp: Some(2),
        size: Some((16, 16)),
        seed: Some(3),
        ..Default::default()
    };
    let loaded = load_str(path, text, &o).unwrap_or_else(|e| panic!("{} loads: {e}", path.display()));
    render_whole(&loaded.scene, &loaded.view, &Default::default()).0
}

fn comments(text: &str) -> Vec<String> {
    tokenize(text)
        .expect("tokenizes")
        .iter()
        .filter(|t| t.is_comment())
        .map(|t| t.text(text).to_string())
        .collect()
}

fn bits(i: &Image) -> Vec<[u32; 3]> {
    i.pixels.iter().map(|p| p.to_array().map(f32::to_bits)).collect()
}

#[test]
fn migrate_keeps_every_shipped_scene_byte_identical_and_its_comments() {
    let files = shipped();
    assert!(files.len() >= 15, "found only {} scenes", files.len());
    let mut with_comments = 0;
    for path in files {
        let old = std::fs::read_to_string(&path).expect("readable");
        let m = migrate_text(&old).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        let name = path.display();
        assert_eq!(version_of(&m.text), Ok(CURRENT), "{name}: not stamped");
        let again = migrate_text(&m.text).expect("migrates again");
        assert_eq!(again.text, m.text, "{name}: a second migration changed it");
        let kept = comments(&old);
        with_comments += usize::from(!kept.is_empty());
        assert_eq!(comments(&m.text), kept, "{name}: comments changed");
        assert!(
            bits(&render(&path, &old)) == bits(&render(&path, &m.text)),
            "{name}: the migrated scene renders differently"
        );
    }
    assert!(
        with_comments >= 5,
        "too few scenes with comments to test that they survive"
    );
}

#[test]
fn migrate_command_rewrites_in_place_and_check_reports_what_it_would_do() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = dir.path().join("old.ron");
    let old = "Scene(\n    // the lens\n    camera: (eye: (0, 1, 4), target: (0, 0, 0)),\n)\n";
    std::fs::write(&scene, old).expect("write");
    let check = ronray_in(dir.path(), &["migrate", "--check", "old.ron"]);
    assert!(!check.status.success(), "--check on an old scene must fail");
    assert!(String::from_utf8_lossy(&check.stdout).contains("+    version: 2,"));
    assert_eq!(
        std::fs::read_to_string(&scene).expect("read"),
        old,
        "--check wrote"
    );
    let run = ronray_in(dir.path(), &["migrate", "old.ron"]);
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let new = std::fs::read_to_string(&scene).expect("read");
    assert_eq!(new, old.replace("Scene(\n", "Scene(\n    version: 2,\n"));
    let again = ronray_in(dir.path(), &["migrate", "--check", "old.ron"]);
    assert!(again.status.success(), "a current scene needs nothing");
    // A version from the future is refused with a located error by the loader.
    std::fs::write(&scene, new.replace("version: 2", "version: 9")).expect("write");
    let v = ronray_in(dir.path(), &["validate", "old.ron"]);
    let err = String::from_utf8_lossy(&v.stderr).to_string() + &String::from_utf8_lossy(&v.stdout);
    assert!(
        !v.status.success() && err.contains("version 9") && err.contains(":2:"),
        "{err}"
    );
}
