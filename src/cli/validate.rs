//! `ronray validate`: every diagnostic, for people or as JSON lines.
//!
//! Errors fail a scene. Warnings (a scene that loads but will surprise) are
//! printed and pass, unless `--deny-warnings` asks CI to refuse them too.
use super::{print_load_error, print_out, print_warnings};
use crate::diagnostic::{Report, Severity};
use crate::load::{LoadError, Overrides, load_with};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(super) fn cmd_validate(
    paths: &[PathBuf],
    json: bool,
    deny_warnings: bool,
    inputs: bool,
    root: Option<&Path>,
) -> ExitCode {
    let mut failed = 0;
    let fenced = Overrides {
        root: root.map(Path::to_path_buf),
        ..Default::default()
    };
    for p in paths {
        match load_with(p, &fenced) {
            Ok(loaded) => {
                if inputs && !json {
                    print_out(&files_of(p, &loaded));
                }
                let warnings = &loaded.warnings;
                let n = warnings.count(Severity::Warning);
                let denied = deny_warnings && n > 0;
                failed += usize::from(denied);
                if json {
                    print_out(&report_lines(warnings));
                    continue;
                }
                print_warnings(warnings);
                let counted = match n {
                    0 => String::new(),
                    1 => " (1 warning)".into(),
                    n => format!(" ({n} warnings)"),
                };
                if denied {
                    eprintln!(
                        "error: {}: warnings are denied (--deny-warnings){counted}",
                        p.display()
                    );
                } else {
                    print_out(&format!("{}: ok{counted}\n", p.display()));
                }
            }
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

/// One JSON object per diagnostic of a failed load, for editors and CI.
pub fn json_lines(scene: &Path, e: &LoadError) -> String {
    match e.report() {
        Some(r) => report_lines(r),
        None => {
            let v = serde_json::json!({
                "file": scene.display().to_string(), "line": 0, "column": 0, "path": null,
                "severity": "error", "message": e.to_string(), "suggestion": null,
            });
            format!("{v}\n")
        }
    }
}

/// One JSON object per diagnostic, each with its own `severity` (`error`,
/// `warning` or `note`).
fn report_lines(r: &Report) -> String {
    r.diagnostics
        .iter()
        .map(|d| {
            let v = serde_json::json!({
                "file": d.file.display().to_string(),
                "line": d.line,
                "column": d.column,
                "path": d.path,
                "severity": d.severity.as_str(),
                "message": d.message,
                "suggestion": d.help,
            });
            format!("{v}\n")
        })
        .collect()
}

/// `validate -v`: every file the scene reads, each OBJ's groups and the MTL
/// material each wears (what `materials: { ... }` keys may name), and the
/// image `render` would write, each resolved (symlinks followed) so that what is really touched
/// is what is shown.
fn files_of(scene: &Path, loaded: &crate::load::Loaded) -> String {
    let mut out = format!("{}:\n", scene.display());
    let mut seen = std::collections::HashSet::new();
    for f in &loaded.files {
        let real = crate::files::resolved(f);
        if seen.insert(real.clone()) {
            out += &format!("  reads  {}\n", real.display());
        }
    }
    for (obj, parts) in &loaded.stats.obj_parts {
        out += &format!("  OBJ    {}: {parts}\n", crate::files::resolved(obj).display());
    }
    let target = crate::frame::Output::path(&loaded.view, scene, None, None);
    out += &format!("  writes {}\n", crate::files::resolved(&target).display());
    out
}
