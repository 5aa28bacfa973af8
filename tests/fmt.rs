//! `ronray fmt`: every shipped scene and fixture means the same after
//! formatting, keeps every comment, and formats to itself a second time.

mod common;

use common::{ronray_in, root};
use ronray::syntax::format;
use ronray::syntax::lex::tokenize;
use std::path::{Path, PathBuf};

/// Every `.ron` and `.json` file under `scenes/` and `tests/fixtures/`
/// (the OBJ corpus aside).
fn scene_files() -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut dirs = vec![root().join("scenes"), root().join("tests/fixtures")];
    while let Some(d) = dirs.pop() {
        for e in std::fs::read_dir(&d).expect("dir").flatten() {
            let p = e.path();
            if p.is_dir() && !p.ends_with("obj-corpus") {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "ron" || x == "json") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

fn is_json(p: &Path) -> bool {
    p.extension().is_some_and(|x| x == "json")
}

fn comments(text: &str) -> Vec<String> {
    let toks = tokenize(text).expect("tokenizes");
    toks.iter()
        .filter(|t| t.is_comment())
        .map(|t| t.text(text).trim_end().to_string())
        .collect()
}

/// What the loader makes of a file: the parsed scene, or its parse error.
fn meaning(path: &Path, text: &str) -> String {
    match ronray::load::source::parse(path, text) {
        Ok(desc) => format!("{desc:?}"),
        Err(r) => format!("error: {}", r.diagnostics[0].message),
    }
}

#[test]
fn fmt_keeps_meaning_comments_and_is_idempotent_on_every_scene() {
    let files = scene_files();
    assert!(files.len() >= 15, "{} files", files.len());
    let mut formatted = 0;
    for p in &files {
        let text = std::fs::read_to_string(p).expect("read");
        let out = match format(&text, is_json(p)) {
            Ok(o) => o,
            Err(e) => {
                // Only a file the loader cannot parse either may be refused.
                assert!(
                    ronray::load::source::parse(p, &text).is_err(),
                    "{}: refused a file that parses: {e}",
                    p.display()
                );
                continue;
            }
        };
        formatted += 1;
        assert_eq!(
            meaning(p, &text),
            meaning(p, &out),
            "{} changed meaning:\n{out}",
            p.display()
        );
        assert_eq!(
            comments(&text),
            comments(&out),
            "{} lost or moved a comment",
            p.display()
        );
        assert_eq!(
            format(&out, is_json(p)).as_ref(),
            Ok(&out),
            "{}: not idempotent",
            p.display()
        );
        if is_json(p) {
            let a: serde_json::Value = serde_json::from_str(&text).expect("json");
            let b: serde_json::Value = serde_json::from_str(&out).expect("still JSON");
            assert_eq!(a, b, "{}", p.display());
        }
    }
    assert!(formatted >= 14);
}

#[test]
fn fmt_keeps_what_the_author_wrote() {
    let text = std::fs::read_to_string(root().join("scenes/cornell.ron")).expect("scene");
    let out = format(&text, false).expect("formats");
    assert_eq!(out, text, "the hand-written Cornell box is already formatted");
    let materials = std::fs::read_to_string(root().join("scenes/materials.ron")).expect("scene");
    let out = format(&materials, false).expect("formats");
    assert!(out.contains("exponent: 60"), "integers stay integers");
    assert!(!out.contains("aperture_radius"), "omitted defaults stay omitted");
}

/// `--check` prints a unified diff and changes nothing; a JSON scene is
/// formatted as JSON; the write goes through a fresh temporary file.
#[test]
fn fmt_cli_check_diff_json_and_safe_write() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    let messy = "// keep me\nScene(camera:(eye:(0,1,4),target:(0,0,0),fov_y_degrees:40),\n)\n";
    std::fs::write(d.join("a.ron"), messy).expect("write");
    let o = ronray_in(d, &["fmt", "--check", "a.ron"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        out.contains("--- a.ron") && out.contains("+++ a.ron (formatted)"),
        "{out}"
    );
    assert!(
        out.contains("-Scene(camera:(eye:(0,1,4)") && out.contains("+    camera: (eye: (0, 1, 4)"),
        "{out}"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("a.ron")).expect("read"),
        messy,
        "--check writes nothing"
    );

    // A symlink planted where the old formatter put its temporary file is
    // left alone.
    #[cfg(unix)]
    {
        std::fs::write(d.join("victim.txt"), "untouched").expect("write");
        std::os::unix::fs::symlink(d.join("victim.txt"), d.join("a.fmt.tmp")).expect("symlink");
    }
    let o = ronray_in(d, &["fmt", "a.ron"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let formatted = std::fs::read_to_string(d.join("a.ron")).expect("read");
    assert!(
        formatted.starts_with("// keep me\nScene(\n    camera: (eye: (0, 1, 4),"),
        "{formatted}"
    );
    #[cfg(unix)]
    assert_eq!(
        std::fs::read_to_string(d.join("victim.txt")).expect("read"),
        "untouched"
    );
    assert!(
        ronray_in(d, &["fmt", "--check", "a.ron"]).status.success(),
        "formatted twice: no diff"
    );
    let leftovers: Vec<_> = std::fs::read_dir(d)
        .expect("dir")
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(".ronray-fmt"))
        .collect();
    assert!(leftovers.is_empty(), "no temporary file is left behind");

    std::fs::copy(root().join("tests/fixtures/cornell.json"), d.join("c.json")).expect("copy");
    let o = ronray_in(d, &["fmt", "c.json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json = std::fs::read_to_string(d.join("c.json")).expect("read");
    let v: serde_json::Value = serde_json::from_str(&json).expect("fmt scene.json writes JSON");
    assert!(v.get("camera").is_some());
    assert!(
        json.contains("\"eye\": [0.0, 0.0, 3.9]"),
        "short vectors on one line:\n{json}"
    );
    let o = ronray_in(d, &["fmt", "--canonical", "c.json"]);
    assert!(o.status.success());
    serde_json::from_str::<serde_json::Value>(&std::fs::read_to_string(d.join("c.json")).expect("read"))
        .expect("--canonical keeps a .json file JSON");

    // The canonical rewrite still refuses to drop comments silently.
    let o = ronray_in(d, &["fmt", "--canonical", "a.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&o.stderr).contains("drops comments"));
}

/// `fmt` once dropped the `#![schema]` header without `--drop-comments`
/// and rounded `16777217` (not an `f32`) and `1e-50` (below the smallest
/// `f32`) silently: the layout printer keeps every spelling and the header,
/// in RON and JSON alike.
#[test]
fn fmt_keeps_the_schema_header_and_exact_numbers() {
    let dir = tempfile::tempdir().expect("tmp");
    let d = dir.path();
    let ron = "#![schema = \"../schema/scene.schema.json\"]\nScene(camera:(eye:(0,1,16777217),target:(0,0,1e-50),fov_y_degrees:40),film:(seed:16777217))\n";
    let json = "{\"camera\":{\"eye\":[0,1,16777217],\"target\":[0,0,1e-50],\"fov_y_degrees\":40},\"film\":{\"seed\":16777217}}\n";
    std::fs::write(d.join("a.ron"), ron).expect("write");
    std::fs::write(d.join("a.json"), json).expect("write");
    for f in ["a.ron", "a.json"] {
        let o = ronray_in(d, &["fmt", f]);
        assert!(o.status.success(), "{f}: {}", String::from_utf8_lossy(&o.stderr));
        let out = std::fs::read_to_string(d.join(f)).expect("read");
        assert_eq!(out.matches("16777217").count(), 2, "{f}: {out}");
        assert!(out.contains("1e-50"), "{f}: {out}");
        if f == "a.ron" {
            assert!(
                out.starts_with("#![schema = \"../schema/scene.schema.json\"]\n"),
                "{out}"
            );
        }
    }
}

#[test]
fn fmt_canonical_and_json_keep_the_numbers_as_written() {
    // `1e-50` reads as the f32 0 and `40.000001` as 40: the canonical text
    // printed those values (`0.0`, `40.0`), not what the author wrote.
    let dir = tempfile::tempdir().expect("temp dir");
    let numbers = ["1e-50", "40.000001", "0.1", "-2.5e-3"];
    let ron = "Scene(camera: (eye: (0, 1, 4), target: (0, -2.5e-3, 1e-50), fov_y_degrees: 40.000001), \
               objects: [Sphere(center: (0.1, 0, 0), radius: 1)])\n";
    let json = r#"{"camera": {"eye": [0, 1, 4], "target": [0, -2.5e-3, 1e-50], "fov_y_degrees": 40.000001}, "objects": [{"Sphere": {"center": [0.1, 0, 0], "radius": 1}}]}
"#;
    std::fs::write(dir.path().join("n.ron"), ron).expect("write");
    std::fs::write(dir.path().join("n.json"), json).expect("write");
    for args in [
        vec!["fmt", "--canonical", "--stdout", "n.json"],
        vec!["fmt", "--canonical", "--stdout", "n.ron"],
        vec!["fmt", "--json", "--stdout", "n.ron"],
        vec!["fmt", "--stdout", "n.json"],
    ] {
        let file = *args.last().expect("file");
        let out = ronray_in(dir.path(), &args);
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{args:?}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        for n in numbers {
            assert!(text.contains(n), "{args:?} lost `{n}`:\n{text}");
        }
        // What was printed reads back as the same scene.
        let again = dir.path().join(if args.contains(&"--json") || file == "n.json" {
            "again.json"
        } else {
            "again.ron"
        });
        std::fs::write(&again, text.as_bytes()).expect("write");
        let src = dir.path().join(file);
        assert_eq!(
            meaning(&again, &text),
            meaning(&src, &std::fs::read_to_string(&src).expect("read")),
            "{args:?} changed the scene"
        );
    }
}
