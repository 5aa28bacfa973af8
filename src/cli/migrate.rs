//! `ronray migrate`: brings scene files to the current scene-format version
//! (`crate::migrate`), in place or as a diff.
use super::fmt::{unified_diff, write_safely};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(super) fn cmd_migrate(paths: &[PathBuf], check: bool) -> ExitCode {
    let mut failed = false;
    for p in paths {
        match migrate_one(p, check) {
            Ok(changed) => failed |= check && changed,
            Err(e) => {
                eprintln!("error: {}: {e}", p.display());
                failed = true;
            }
        }
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Migrates one file; whether it changed (or would, with `check`).
fn migrate_one(p: &Path, check: bool) -> Result<bool, String> {
    let text = crate::load::source::read_text(p).map_err(|e| format!("cannot read: {e}"))?;
    let m = crate::migrate::migrate_text(&text).map_err(|e| e.to_string())?;
    if m.text == text {
        println!("{}: already version {}", p.display(), m.to);
        return Ok(false);
    }
    if check {
        print!("{}", unified_diff(p, &text, &m.text));
        return Ok(true);
    }
    write_safely(p, &m.text).map_err(|e| format!("cannot write: {e}"))?;
    println!("{}: version {} -> {}", p.display(), m.from, m.to);
    for s in m.steps {
        println!("  {s}");
    }
    Ok(true)
}
