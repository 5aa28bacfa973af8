//! Located, human-readable problems with a scene file, rendered the way
//! compilers do (file:line:col, the offending line, a caret, the fix).

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

/// How much a diagnostic matters. Errors stop the load; warnings and notes
/// describe a scene that loads but will probably not look as intended, so
/// commands print them and carry on (`validate --deny-warnings` refuses them).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// The scene cannot be used as written; nothing is rendered.
    #[default]
    Error,
    /// The scene loads but will probably not look as intended.
    Warning,
    /// Something the loader repaired or defaulted, for information.
    Note,
}

impl Severity {
    /// The lowercase word compilers print (`error`, `warning`, `note`), also
    /// the `severity` field of `validate --format json`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Note => "note",
        }
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One located problem: where it is, what is wrong, and the likely fix.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    /// [`Severity::Error`] unless the producer says otherwise.
    pub severity: Severity,
    /// The file it is in, as named to the user (or `--set …` for an
    /// override given on the command line).
    pub file: PathBuf,
    /// Byte range in the file, when the problem could be located.
    pub span: Option<Range<usize>>,
    /// 1-based; 0 when unknown.
    pub line: usize,
    /// 1-based, in characters; 0 when unknown.
    pub column: usize,
    /// Path inside the scene (`objects[3].material`), for semantic problems.
    pub path: Option<String>,
    /// What is wrong, in the user's words (no Rust type names).
    pub message: String,
    /// The likely fix ("did you mean `radius`?").
    pub help: Option<String>,
}

impl Diagnostic {
    /// Locates `span` in `source` to fill line and column.
    pub fn new(file: &Path, source: &str, span: Option<Range<usize>>, message: String) -> Self {
        let (line, column) = span.as_ref().map_or((0, 0), |s| line_col(source, s.start));
        Self::at(file, span, (line, column), message)
    }

    /// Locates `span` through a file's [`LineIndex`]: the way to locate
    /// many diagnostics in one file (each [`Diagnostic::new`] scans the text
    /// up to its span, and 64,000 mistakes in one file took five minutes).
    pub fn indexed(file: &Path, lines: &LineIndex, span: Option<Range<usize>>, message: String) -> Self {
        let (line, column) = span.as_ref().map_or((0, 0), |s| lines.line_col(s.start));
        Self::at(file, span, (line, column), message)
    }

    fn at(file: &Path, span: Option<Range<usize>>, (line, column): (usize, usize), message: String) -> Self {
        Self {
            severity: Severity::Error,
            file: file.to_path_buf(),
            span,
            line,
            column,
            path: None,
            message,
            help: None,
        }
    }

    /// `file:line:col`, or the file alone when the position is unknown.
    pub fn location(&self) -> String {
        if self.line == 0 {
            self.file.display().to_string()
        } else {
            format!("{}:{}:{}", self.file.display(), self.line, self.column)
        }
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}: ", self.location(), self.severity)?;
        if let Some(p) = &self.path {
            write!(f, "{p}: ")?;
        }
        write!(f, "{}", self.message)?;
        if let Some(h) = &self.help {
            write!(f, "\n  help: {h}")?;
        }
        Ok(())
    }
}

/// 1-based line and character column of byte `offset`.
pub fn line_col(source: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(source.len());
    let before = &source[..source.floor_char_boundary(offset)];
    let line = 1 + before.matches('\n').count();
    let col = 1 + before.rsplit('\n').next().map_or(0, |l| l.chars().count());
    (line, col)
}

/// Where each line of a text starts, found in one pass, so that locating
/// an offset is a binary search rather than a scan from the start of the
/// text: [`line_col`] on every one of N diagnostics is quadratic in N.
/// Columns are counted within the offset's line only, and not at all on a
/// line of ASCII (a whole scene minified onto one line stays linear).
#[derive(Clone, Debug)]
pub struct LineIndex<'a> {
    text: &'a str,
    /// Byte offset of each line's first byte; `starts[0]` is 0.
    starts: Vec<usize>,
    /// Whether each line is ASCII (bytes are characters and UTF-16 units).
    ascii: Vec<bool>,
}

impl<'a> LineIndex<'a> {
    /// Indexes `text`'s lines.
    pub fn new(text: &'a str) -> Self {
        let mut starts = vec![0];
        let mut ascii = Vec::new();
        let mut plain = true;
        for (i, b) in text.bytes().enumerate() {
            plain &= b.is_ascii();
            if b == b'\n' {
                starts.push(i + 1);
                ascii.push(plain);
                plain = true;
            }
        }
        ascii.push(plain);
        Self { text, starts, ascii }
    }

    /// The text indexed.
    pub fn text(&self) -> &'a str {
        self.text
    }

    /// 0-based line of byte `offset` (clamped to the text), and the text of
    /// that line before the offset (from a character boundary), and whether
    /// the line is ASCII.
    pub fn line_prefix(&self, offset: usize) -> (usize, &'a str, bool) {
        let offset = self.text.floor_char_boundary(offset.min(self.text.len()));
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        (line, &self.text[self.starts[line]..offset], self.ascii[line])
    }

    /// 1-based line and character column of byte `offset`, as [`line_col`].
    pub fn line_col(&self, offset: usize) -> (usize, usize) {
        let (line, before, ascii) = self.line_prefix(offset);
        let col = if ascii {
            before.len()
        } else {
            before.chars().count()
        };
        (line + 1, col + 1)
    }

    /// Byte offset where 0-based `line` starts, or `None` past the last line.
    pub fn line_start(&self, line: usize) -> Option<usize> {
        self.starts.get(line).copied()
    }
}

/// Byte offset of a 1-based line and character column.
pub fn offset_of(source: &str, line: usize, col: usize) -> usize {
    let mut off = 0;
    for (i, l) in source.split_inclusive('\n').enumerate() {
        if i + 1 == line {
            return off
                + l.char_indices()
                    .nth(col.saturating_sub(1))
                    .map_or(l.trim_end_matches('\n').len(), |(b, _)| b);
        }
        off += l.len();
    }
    source.len()
}

/// Every problem found in one attempt to load a scene, with the sources they
/// point into so they can be rendered with context.
#[derive(Clone, Debug, Default)]
pub struct Report {
    /// Every diagnostic, in the order a reader should meet them.
    pub diagnostics: Vec<Diagnostic>,
    /// Each file's path and text, for the excerpts under each diagnostic.
    pub sources: Vec<(PathBuf, String)>,
}

impl Report {
    /// The same report with every diagnostic at `severity` (the loader's
    /// warning pass locates its problems like errors, then marks them).
    pub fn with_severity(mut self, severity: Severity) -> Self {
        for d in &mut self.diagnostics {
            d.severity = severity;
        }
        self
    }

    /// How many diagnostics have `severity`.
    pub fn count(&self, severity: Severity) -> usize {
        self.diagnostics.iter().filter(|d| d.severity == severity).count()
    }

    /// The diagnostics in the order a reader meets them: those about no file
    /// (command-line overrides) first, then by file in the order of
    /// `sources`, then by position.
    pub fn sorted(mut self) -> Self {
        let file_index = |d: &Diagnostic| self.sources.iter().position(|(p, _)| *p == d.file);
        let mut keyed: Vec<_> = self
            .diagnostics
            .drain(..)
            .map(|d| ((file_index(&d), d.span.as_ref().map(|s| s.start)), d))
            .collect();
        keyed.sort_by_key(|(k, _)| *k);
        self.diagnostics = keyed.into_iter().map(|(_, d)| d).collect();
        self
    }

    /// Renders every diagnostic with the source line and a caret (colour only
    /// when asked: terminals yes, files and pipes no).
    pub fn render(&self, color: bool) -> String {
        use ariadne::{Config, IndexType, Label, ReportKind, Source};
        let mut out = Vec::new();
        // One line index per file, built once: building it per diagnostic
        // made 16,000 errors in one file take 25 s to print.
        let indexed: Vec<Source<&str>> = self
            .sources
            .iter()
            .map(|(_, s)| Source::from(s.as_str()))
            .collect();
        for d in &self.diagnostics {
            let src = self
                .sources
                .iter()
                .find(|(p, _)| *p == d.file)
                .map(|(_, s)| s.as_str());
            let (Some(src), Some(span)) = (src, d.span.clone()) else {
                out.extend_from_slice(format!("{d}\n").as_bytes());
                continue;
            };
            let name = d.file.display().to_string();
            // On character boundaries: a span from a parser may fall inside
            // a multi-byte character.
            let start = src.floor_char_boundary(span.start.min(src.len()));
            let span = start..src.ceil_char_boundary(span.end.clamp(start, src.len()));
            let msg = match &d.path {
                Some(p) => format!("{p}: {}", d.message),
                None => d.message.clone(),
            };
            let kind = match d.severity {
                Severity::Error => ReportKind::Error,
                Severity::Warning => ReportKind::Warning,
                // ariadne's own word for a note. (`Custom("Note", …)` would
                // colour the header even when colour is off, in ariadne 0.6.)
                Severity::Note => ReportKind::Advice,
            };
            let mut b = ariadne::Report::build(kind, (name.clone(), span.clone()))
                .with_config(
                    Config::default()
                        .with_color(color)
                        .with_index_type(IndexType::Byte),
                )
                .with_message(&msg)
                .with_label(Label::new((name.clone(), span)).with_message(&d.message));
            if let Some(h) = &d.help {
                b = b.with_help(h);
            }
            let Some(k) = self.sources.iter().position(|(p, _)| *p == d.file) else {
                continue;
            };
            let _ = b.finish().write((name, &indexed[k]), &mut out);
        }
        String::from_utf8_lossy(&out).into_owned()
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for d in &self.diagnostics {
            writeln!(f, "{d}")?;
        }
        Ok(())
    }
}

/// A mistake in a scene file, located by its path inside the scene
/// (`objects[3].material`); the loader turns the path into file:line:col.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// Dotted path with `[i]` for sequence elements and `.name` for map keys:
    /// `objects[3].material`, `materials.floor.albedo`.
    pub path: String,
    /// What is wrong, in the user's words.
    pub message: String,
    /// The likely fix, phrased as advice ("did you mean `white`?").
    pub help: Option<String>,
}

impl Problem {
    /// A problem at `path` with no help line yet.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
            help: None,
        }
    }

    /// The same problem with `help` as its suggested fix.
    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

/// Closest candidate by edit distance, if it is close enough to be a typo.
/// A candidate that starts with what was typed (`fov` → `fov_y_degrees`)
/// also counts.
pub fn suggest<'a>(found: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let candidates: Vec<&'a str> = candidates.into_iter().collect();
    if found.len() >= 3
        && let Some(c) = candidates.iter().find(|c| c.starts_with(found))
    {
        return Some(c);
    }
    candidates
        .into_iter()
        .map(|c| (strsim::damerau_levenshtein(found, c), c))
        .filter(|&(d, c)| d <= 2.max(c.len() / 3))
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each severity reaches both renderings; existing sites stay errors.
    /// The index agrees with the scan from the start, on multi-byte
    /// characters, at line ends and past the end.
    #[test]
    fn line_index_matches_line_col() {
        let text = "ab\n€x𝄞y\n\nlast";
        let lines = LineIndex::new(text);
        for off in 0..=text.len() + 2 {
            assert_eq!(lines.line_col(off), line_col(text, off), "offset {off}");
        }
        assert_eq!(lines.line_start(1), Some(3));
        assert_eq!(lines.line_start(4), None);
    }

    #[test]
    fn diagnostic_severity_is_rendered() {
        let text = "Scene(\n    camera: 1,\n)\n";
        let file = Path::new("s.ron");
        let d = Diagnostic::new(file, text, Some(11..17), "odd".into());
        assert_eq!(d.severity, Severity::Error, "the default");
        for (severity, word, kind) in [
            (Severity::Error, "error", "Error"),
            (Severity::Warning, "warning", "Warning"),
            (Severity::Note, "note", "Advice"),
        ] {
            let d = Diagnostic {
                severity,
                ..d.clone()
            };
            assert_eq!(d.to_string(), format!("s.ron:2:5: {word}: odd"));
            let r = Report {
                diagnostics: vec![d],
                sources: vec![(file.to_path_buf(), text.to_string())],
            };
            let shown = r.render(false);
            assert!(shown.starts_with(&format!("{kind}: odd")), "{severity}: {shown}");
        }
    }
}
