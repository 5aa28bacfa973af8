//! The loader's diagnostics for an open buffer, as the protocol publishes
//! them: the same errors and warnings `ronray validate` prints, with their
//! help lines, run on the unsaved text under the document's real path (so
//! includes and OBJ files resolve), grouped by the file they point into.

use super::text::range_in;
use crate::diagnostic::{Diagnostic, LineIndex, Severity};
use crate::load::{LoadError, Overrides, pipeline::load_str_with_meshes};
use crate::watch::mesh_cache::MeshCache;
use lsp_types::{DiagnosticSeverity, Position, Range};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Every diagnostic of loading `text` as the file `path`, by file; `path`
/// itself is always present (with an empty list once it is clean).
pub fn check(path: &Path, text: &str, meshes: &MeshCache) -> BTreeMap<PathBuf, Vec<lsp_types::Diagnostic>> {
    let mut out: BTreeMap<PathBuf, Vec<lsp_types::Diagnostic>> = BTreeMap::new();
    out.insert(path.to_path_buf(), Vec::new());
    if is_include_file(text) {
        out.entry(path.to_path_buf())
            .or_default()
            .extend(include_errors(path, text));
        return out;
    }
    let report = match load_str_with_meshes(path, text, &Overrides::default(), &|p| meshes.load(p)) {
        Ok(l) => l.warnings,
        Err(LoadError::Invalid(r)) => r,
        Err(e @ LoadError::Io { .. }) => {
            out.entry(path.to_path_buf())
                .or_default()
                .push(plain(Range::default(), e.to_string()));
            return out;
        }
    };
    // Each file's lines indexed once for all its diagnostics.
    let mut lines: Vec<(&Path, LineIndex)> = report
        .sources
        .iter()
        .map(|(p, s)| (p.as_path(), LineIndex::new(s)))
        .collect();
    if !lines.iter().any(|(p, _)| *p == path) {
        lines.push((path, LineIndex::new(text)));
    }
    for d in &report.diagnostics {
        let source = lines.iter().find(|(p, _)| *p == d.file).map(|(_, l)| l);
        // `--set` problems and the like have no file of their own.
        let file = if d.file.extension().is_some() {
            d.file.clone()
        } else {
            path.to_path_buf()
        };
        out.entry(file).or_default().push(convert(d, source));
    }
    out
}

fn plain(range: Range, message: String) -> lsp_types::Diagnostic {
    lsp_types::Diagnostic {
        range,
        severity: Some(DiagnosticSeverity::ERROR),
        source: Some("ronray".into()),
        message,
        ..Default::default()
    }
}

/// One loader diagnostic: its span (or line and column), severity, scene
/// path, message and help.
pub fn convert(d: &Diagnostic, source: Option<&LineIndex>) -> lsp_types::Diagnostic {
    let r = match (&d.span, source) {
        (Some(span), Some(lines)) => range_in(lines, span.clone()),
        _ if d.line > 0 => {
            let p = Position::new(d.line as u32 - 1, d.column.saturating_sub(1) as u32);
            Range::new(p, p)
        }
        _ => Range::default(),
    };
    let mut message = match &d.path {
        Some(p) if !p.is_empty() => format!("{p}: {}", d.message),
        _ => d.message.clone(),
    };
    if let Some(h) = &d.help {
        message += &format!("\nhelp: {h}");
    }
    lsp_types::Diagnostic {
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
            Severity::Note => DiagnosticSeverity::INFORMATION,
        }),
        ..plain(r, message)
    }
}

/// An included file (`Include(...)`) is checked by the scenes that include
/// it; on its own only its syntax and field names are (every mistake, as the
/// loader reads it).
fn is_include_file(text: &str) -> bool {
    let toks = crate::syntax::lex::tokenize_lenient(text);
    toks.iter()
        .find(|t| t.kind == crate::syntax::lex::Kind::Word)
        .is_some_and(|t| t.text(text) == "Include")
}

fn include_errors(path: &Path, text: &str) -> Vec<lsp_types::Diagnostic> {
    let diagnostics = match crate::load::source::read::<crate::desc::IncludeDesc>(path, text) {
        Ok(parsed) => parsed.diagnostics,
        Err(report) => report.diagnostics,
    };
    let lines = LineIndex::new(text);
    diagnostics.iter().map(|d| convert(d, Some(&lines))).collect()
}
