//! Deeply nested scene text: every reader (`validate` through serde and the
//! loader's scans, `fmt` through the syntax tree, the language server)
//! refuses it at the first bracket past the nesting limit, with a located
//! error, instead of overflowing its stack; the limit is raised with
//! `RONRAY_MAX_NESTING`, and up to its ceiling nothing overflows either.
//! Each run is a child process, so a stack overflow fails the test instead
//! of killing the test binary.

mod common;

use ronray::syntax::nesting::{MAX_NESTING, MAX_NESTING_CEILING, NESTING_VAR};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// `objects` holding one list nested `depth` deep (RON or JSON).
fn deep_scene(dir: &Path, depth: usize, json: bool) -> (PathBuf, String) {
    let (open, close) = ("[".repeat(depth), "]".repeat(depth));
    let (name, text) = if json {
        ("deep.json", format!("{{\"objects\": {open}{close}}}\n"))
    } else {
        ("deep.ron", format!("Scene(objects: {open}{close})\n"))
    };
    let path = dir.join(name);
    std::fs::write(&path, &text).expect("write");
    (path, text)
}

fn run(args: &[&str], limit: Option<usize>, stdin: Option<&[u8]>) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_ronray"));
    cmd.args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    match limit {
        Some(n) => cmd.env(NESTING_VAR, n.to_string()),
        None => cmd.env_remove(NESTING_VAR),
    };
    let mut child = cmd.spawn().expect("ronray runs");
    let mut input = child.stdin.take().expect("stdin");
    if let Some(bytes) = stdin {
        input.write_all(bytes).expect("write stdin");
    }
    drop(input);
    child.wait_with_output().expect("ronray finishes")
}

/// The process ended by itself (a stack overflow aborts on a signal).
fn exited(out: &Output, what: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert!(
        out.status.code().is_some() && !err.contains("overflowed its stack"),
        "{what} crashed ({:?}): {}",
        out.status,
        &err[err.len().saturating_sub(400)..]
    );
    err
}

/// Column (1-based) of the first bracket past `limit` on line 1.
fn column_past(text: &str, limit: usize) -> usize {
    let mut depth = 0;
    for (i, c) in text.char_indices() {
        if matches!(c, '(' | '[' | '{') {
            depth += 1;
            if depth > limit {
                return i + 1;
            }
        }
    }
    panic!("not deeper than {limit}")
}

#[test]
fn validate_refuses_30000_deep_nesting_at_the_first_bracket_past_the_limit() {
    let dir = tempfile::tempdir().expect("temp dir");
    for json in [false, true] {
        let (path, text) = deep_scene(dir.path(), 30_000, json);
        let out = run(&["validate", path.to_str().expect("path")], None, None);
        let err = exited(&out, "validate");
        assert_eq!(out.status.code(), Some(1), "{err}");
        assert!(
            err.contains(&format!("nested deeper than {MAX_NESTING}")),
            "{err}"
        );
        let at = format!(":1:{}", column_past(&text, MAX_NESTING));
        assert!(err.contains(&at), "expected the error at {at}: {err}");
    }
}

#[test]
fn fmt_refuses_30000_and_10000_deep_nesting_with_the_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    for depth in [30_000, 10_000] {
        for json in [false, true] {
            let (path, text) = deep_scene(dir.path(), depth, json);
            let p = path.to_str().expect("path");
            for args in [
                vec!["fmt", "--stdout", p],
                vec!["fmt", "--canonical", "--stdout", p],
            ] {
                let out = run(&args, None, None);
                let err = exited(&out, "fmt");
                assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
                assert!(err.contains("nested deeper than"), "{args:?}: {err}");
                if args.len() == 3 {
                    let byte = column_past(&text, MAX_NESTING) - 1;
                    assert!(err.contains(&format!("byte {byte}")), "{err}");
                }
            }
        }
    }
}

/// A whole LSP session written at once: initialize, open `text` as `uri`,
/// hover and complete inside it, shut down, exit.
fn lsp_session(uri: &str, text: &str, at: (usize, usize)) -> Vec<u8> {
    let msgs = [
        serde_json::json!({"jsonrpc": "2.0", "id": 1, "method": "initialize",
            "params": {"capabilities": {}, "processId": null, "rootUri": null}}),
        serde_json::json!({"jsonrpc": "2.0", "method": "initialized", "params": {}}),
        serde_json::json!({"jsonrpc": "2.0", "method": "textDocument/didOpen", "params": {
            "textDocument": {"uri": uri, "languageId": "ron", "version": 1, "text": text}}}),
        serde_json::json!({"jsonrpc": "2.0", "id": 2, "method": "textDocument/hover", "params": {
            "textDocument": {"uri": uri}, "position": {"line": at.0, "character": at.1}}}),
        serde_json::json!({"jsonrpc": "2.0", "id": 3, "method": "textDocument/completion", "params": {
            "textDocument": {"uri": uri}, "position": {"line": at.0, "character": at.1}}}),
        serde_json::json!({"jsonrpc": "2.0", "id": 4, "method": "shutdown"}),
        serde_json::json!({"jsonrpc": "2.0", "method": "exit"}),
    ];
    let mut out = Vec::new();
    for m in msgs {
        let body = m.to_string();
        out.extend(format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes());
    }
    out
}

#[test]
fn lsp_publishes_a_located_nesting_error_for_30000_deep_text() {
    let dir = tempfile::tempdir().expect("temp dir");
    let (path, text) = deep_scene(dir.path(), 30_000, false);
    let uri = format!("file://{}", path.display());
    let out = run(&["lsp"], None, Some(&lsp_session(&uri, &text, (0, 20_000))));
    exited(&out, "lsp");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains(&format!("nested deeper than {MAX_NESTING}")),
        "no nesting diagnostic: {}",
        &stdout[..stdout.len().min(2000)]
    );
    let col = column_past(&text, MAX_NESTING) - 1;
    assert!(
        // Either key order: serde_json writes its maps sorted unless
        // `preserve_order` is on.
        stdout.contains(&format!("\"start\":{{\"line\":0,\"character\":{col}}}"))
            || stdout.contains(&format!("\"start\":{{\"character\":{col},\"line\":0}}")),
        "not located at character {col}: {}",
        &stdout[..stdout.len().min(2000)]
    );
    assert_eq!(out.status.code(), Some(0), "lsp exits cleanly after `exit`");
}

/// An SDF of `n` nested `Transform`s: what serde recurses deepest on
/// (three `ron` levels a bracket), then validation and the SDF build.
fn deep_sdf(dir: &Path, n: usize, json: bool) -> (PathBuf, String) {
    let (name, text) = if json {
        let shape = format!(
            "{}{{\"Sphere\": {{\"radius\": 0.5}}}}{}",
            "{\"Transform\": {\"scale\": 1, \"of\": ".repeat(n),
            "}}".repeat(n)
        );
        (
            "sdf.json",
            format!(
                "{{\"camera\": {{\"eye\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y_degrees\": 40}}, \
                 \"objects\": [{{\"Sdf\": {{\"shape\": {shape}}}}}]}}\n"
            ),
        )
    } else {
        let shape = format!(
            "{}Sphere(radius: 0.5){}",
            "Transform(scale: 1, of: ".repeat(n),
            ")".repeat(n)
        );
        (
            "sdf.ron",
            format!(
                "Scene(camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40), \
                 objects: [Sdf(shape: {shape})])\n"
            ),
        )
    };
    let path = dir.join(name);
    std::fs::write(&path, &text).expect("write");
    (path, text)
}

#[test]
fn nesting_up_to_the_raised_ceiling_overflows_no_parser() {
    let dir = tempfile::tempdir().expect("temp dir");
    let limit = MAX_NESTING_CEILING;
    // Nested exactly `limit` deep: `Scene(objects: ` or `{"objects": `
    // holds one bracket, `Sdf(shape: ` or `[{"Sdf": {"shape": ` a few more.
    let files = [
        deep_scene(dir.path(), limit - 1, false),
        deep_scene(dir.path(), limit - 1, true),
        deep_sdf(dir.path(), limit - 4, false),
        deep_sdf(dir.path(), (limit - 6) / 2, true),
    ];
    for (path, text) in files {
        let p = path.to_str().expect("path");
        let validate = run(&["validate", p], Some(limit), None);
        let err = exited(&validate, &format!("validate {p} at the ceiling"));
        assert!(
            !err.contains("nested deeper"),
            "{p}: the raised limit was not applied: {err}"
        );
        let fmt = run(&["fmt", "--stdout", p], Some(limit), None);
        let err = exited(&fmt, &format!("fmt {p} at the ceiling"));
        assert_eq!(fmt.status.code(), Some(0), "{p}: {err}");
        let uri = format!("file://{}", path.display());
        let lsp = run(&["lsp"], Some(limit), Some(&lsp_session(&uri, &text, (0, limit))));
        exited(&lsp, &format!("lsp {p} at the ceiling"));
        // One past the ceiling is refused as a setting.
        let past = run(&["validate", p], Some(limit + 1), None);
        let err = String::from_utf8_lossy(&past.stderr);
        assert_eq!(past.status.code(), Some(2), "{err}");
        assert!(err.contains(NESTING_VAR), "{err}");
    }
}

#[test]
fn a_40_deep_sdf_within_the_limit_loads_in_ron() {
    // 40 nested transforms: ron's own default recursion limit (128 levels,
    // three per transform) refused this before the bracket limit existed.
    let n = 40;
    let shape = format!(
        "{}Sphere(radius: 0.5){}",
        "Transform(scale: 1, of: ".repeat(n),
        ")".repeat(n)
    );
    let ron = format!(
        "Scene(camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 40), \
         materials: {{ \"m\": Lambert(albedo: 0.5) }}, \
         lights: [Point(position: (0, 3, 0), intensity: (5, 5, 5))], \
         objects: [Sdf(shape: {shape}, material: \"m\")])"
    );
    let path = common::root().join("tests/fixtures/deep_sdf.ron");
    let loaded = ronray::load::load_str(&path, &ron, &ronray::load::Overrides::default());
    if let Err(e) = loaded {
        panic!("{}", common::message(&e));
    }
}
