//! The one place scene text is parsed, RON or JSON, for the top file and
//! included files alike, and the one place a problem becomes a located
//! diagnostic.
//!
//! Text nested past the limit ([`nesting`]) is refused before anything
//! recursive reads it. A file that parses as a whole is done in one step.
//! One that does not is read once as a [`crate::syntax::tree`]
//! ([`parser::read`]) and checked for unbalanced brackets (`brackets.rs`),
//! the only mistake that stops reading; otherwise it is read section by
//! section along the tree's outline (`sections.rs`) so that every mistake
//! in it is reported at once, in the user's words (`words.rs`).

use super::brackets;
use super::document::{Document, Gaps};
pub use super::format::Format;
use super::sections;
use super::set::SetProblem;
pub use super::slip::Slip;
use crate::desc::SceneDesc;
use crate::diagnostic::{Diagnostic, LineIndex, Problem, Report};
use crate::syntax::outline::Outline;
use crate::syntax::spans::Spans;
use crate::syntax::{nesting, parser};
use std::borrow::Cow;
use std::path::Path;

/// A file read as far as it could be: a (possibly partial) description,
/// what was left out of it, and the mistakes found on the way. A partial
/// description is only for checking; there is a diagnostic for every gap.
pub struct Parsed<T> {
    /// What was read (stand-ins where entries were broken).
    pub desc: T,
    /// The entries left out or replaced, so later problems keep the
    /// indices the user wrote.
    pub gaps: Gaps,
    /// The parse mistakes found.
    pub diagnostics: Vec<Diagnostic>,
}

/// A UTF-8 byte-order mark is not a mistake: it reads as spaces, which
/// keeps every byte offset (and so every diagnostic) in place.
fn without_bom(text: &str) -> Cow<'_, str> {
    match text.strip_prefix('\u{feff}') {
        Some(rest) => Cow::Owned(format!("   {rest}")),
        None => Cow::Borrowed(text),
    }
}

/// Largest scene or included file read, in bytes. Hand-written scenes are
/// kilobytes; raise it here for generated ones.
pub const MAX_SCENE_FILE_BYTES: u64 = 64 << 20;

/// Reads a scene or included file as text. Regular files only: a FIFO or a
/// device would block or never end (`metadata` does not open the file, so
/// asking cannot block). Larger than [`MAX_SCENE_FILE_BYTES`] is an error.
pub fn read_text(path: &Path) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    if meta.len() > MAX_SCENE_FILE_BYTES {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("larger than {} MiB", MAX_SCENE_FILE_BYTES >> 20),
        ));
    }
    let mut text = String::new();
    std::fs::File::open(path)?
        .take(MAX_SCENE_FILE_BYTES + 1)
        .read_to_string(&mut text)?;
    if text.len() as u64 > MAX_SCENE_FILE_BYTES {
        return Err(Error::new(
            ErrorKind::InvalidData,
            format!("larger than {} MiB", MAX_SCENE_FILE_BYTES >> 20),
        ));
    }
    Ok(text)
}

/// Reads a scene or included file. Only a broken structure (unbalanced
/// brackets, or no recognisable top level) is an `Err`; every other mistake
/// is in [`Parsed::diagnostics`], beside what could be read.
pub fn read<T: Document>(path: &Path, text: &str) -> Result<Parsed<T>, Report> {
    let clean = without_bom(text);
    // Before serde, which recurses per bracket (serde_json with no limit of
    // its own); the tree read below checks its own tokens again.
    if let Err(deep) = nesting::check(&clean, nesting::limit()) {
        let slip = brackets::too_deep(&deep);
        return Err(Report {
            diagnostics: vec![slip.diagnostic(path, &LineIndex::new(text), &Spans::default().nesting())],
            sources: vec![(path.to_path_buf(), text.to_string())],
        });
    }
    let format = Format::of(path, &clean);
    let mut whole = match format.read::<T>(&clean, 0..clean.len()) {
        Ok(desc) => {
            let (gaps, diagnostics) = (Gaps::default(), Vec::new());
            return Ok(Parsed {
                desc,
                gaps,
                diagnostics,
            });
        }
        Err(slip) => slip,
    };
    if clean.trim().is_empty() {
        let help = Some("a scene is written `Scene(camera: (…), objects: […])`".to_string());
        whole = Slip::new(0..0, "the file is empty".into(), help);
    }
    // One read of the text's structure serves the bracket check, the
    // outline and the location of every mistake (through the line index and
    // the sorted values: linear in the number of mistakes).
    let tree = parser::read(&clean);
    let spans = Spans::of(&tree);
    let (lines, values) = (LineIndex::new(text), spans.nesting());
    let located = |slips: Vec<Slip>| -> Vec<Diagnostic> {
        slips
            .into_iter()
            .map(|s| s.diagnostic(path, &lines, &values))
            .collect()
    };
    let stop = |slip: Slip| Report {
        diagnostics: located(vec![slip]),
        sources: vec![(path.to_path_buf(), text.to_string())],
    };
    if let Some(broken) = brackets::check(&clean, &tree) {
        return Err(stop(broken));
    }
    let Some(outline) = Outline::of(&tree) else {
        return Err(stop(whole));
    };
    let (desc, gaps, slips) = sections::read::<T>(&format, &clean, &outline, whole);
    let diagnostics = located(slips);
    Ok(Parsed {
        desc,
        gaps,
        diagnostics,
    })
}

/// RON or JSON text → [`SceneDesc`], or every mistake in it.
pub fn parse(path: &Path, text: &str) -> Result<SceneDesc, Report> {
    let parsed = read::<SceneDesc>(path, text)?;
    if parsed.diagnostics.is_empty() {
        return Ok(parsed.desc);
    }
    Err(Report {
        diagnostics: parsed.diagnostics,
        sources: vec![(path.to_path_buf(), text.to_string())],
    })
}

/// A problem found in a parsed file, located by its scene path.
pub fn locate(file: &Path, lines: &LineIndex, spans: &Spans, p: &Problem) -> Diagnostic {
    let mut d = Diagnostic::indexed(file, lines, spans.find(&p.path), p.message.clone());
    d.path = Some(p.path.clone());
    d.help = p.help.clone();
    d
}

/// Semantic problems → diagnostics located through the file's text.
pub fn located(path: &Path, text: &str, problems: &[Problem]) -> Report {
    let spans = Spans::scan(text);
    let lines = LineIndex::new(text);
    Report {
        diagnostics: problems.iter().map(|p| locate(path, &lines, &spans, p)).collect(),
        sources: vec![(path.to_path_buf(), text.to_string())],
    }
}

/// Problems in command-line overrides: located at the `--set` argument
/// that caused each (`--set film.spp=abc`), not in any file.
pub fn command_line(problems: &[SetProblem]) -> Report {
    let diagnostics = problems
        .iter()
        .map(|s| {
            // A flag of its own (`--tonemap X`) is named as written.
            let file = if s.arg.starts_with("--") {
                s.arg.clone()
            } else {
                format!("--set {}", s.arg)
            };
            let mut d = Diagnostic::new(Path::new(&file), "", None, s.problem.message.clone());
            d.path = Some(s.problem.path.clone()).filter(|p| !p.is_empty());
            d.help = s.problem.help.clone();
            d
        })
        .collect();
    Report {
        diagnostics,
        sources: Vec::new(),
    }
}
