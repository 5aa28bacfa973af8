//! `ronray validate`: every diagnostic, for people or as JSON lines.
use super::{print_load_error, print_out};
use crate::load::{LoadError, Overrides, load_with};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(super) fn cmd_validate(paths: &[PathBuf], json: bool) -> ExitCode {
    let mut failed = 0;
    for p in paths {
        match load_with(p, &Overrides::default()) {
            Ok(_) if json => {}
            Ok(_) => print_out(&format!("{}: ok\n", p.display())),
            Err(e) => {
                failed += 1;
                if json {
                    print_out(&json_lines(p, &e));
                } else {
                    print_load_error(&e, "");
                }
            }
        }
    }
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// One JSON object per diagnostic, for editors and CI.
pub fn json_lines(scene: &Path, e: &LoadError) -> String {
    let items: Vec<serde_json::Value> = match e.report() {
        Some(r) => r
            .diagnostics
            .iter()
            .map(|d| {
                serde_json::json!({
                    "file": d.file.display().to_string(),
                    "line": d.line,
                    "column": d.column,
                    "path": d.path,
                    "severity": "error",
                    "message": d.message,
                    "suggestion": d.help,
                })
            })
            .collect(),
        None => vec![serde_json::json!({
            "file": scene.display().to_string(), "line": 0, "column": 0, "path": null,
            "severity": "error", "message": e.to_string(), "suggestion": null,
        })],
    };
    items.iter().map(|v| format!("{v}\n")).collect()
}
