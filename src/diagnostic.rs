//! Located, human-readable problems with a scene file, rendered the way
//! compilers do (file:line:col, the offending line, a caret, the fix).

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub file: PathBuf,
    /// Byte range in the file, when the problem could be located.
    pub span: Option<Range<usize>>,
    /// 1-based; 0 when unknown.
    pub line: usize,
    /// 1-based, in characters; 0 when unknown.
    pub column: usize,
    /// Path inside the scene (`objects[3].material`), for semantic problems.
    pub path: Option<String>,
    pub message: String,
    pub help: Option<String>,
}

impl Diagnostic {
    /// Locates `span` in `source` to fill line and column.
    pub fn new(file: &Path, source: &str, span: Option<Range<usize>>, message: String) -> Self {
        let (line, column) = span.as_ref().map_or((0, 0), |s| line_col(source, s.start));
        Self {
            file: file.to_path_buf(),
            span,
            line,
            column,
            path: None,
            message,
            help: None,
        }
    }

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
        write!(f, "{}: error: ", self.location())?;
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
    pub diagnostics: Vec<Diagnostic>,
    pub sources: Vec<(PathBuf, String)>,
}

impl Report {
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
            let mut b = ariadne::Report::build(ReportKind::Error, (name.clone(), span.clone()))
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
            let _ = b.finish().write((name, Source::from(src)), &mut out);
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
    pub message: String,
    /// The likely fix, phrased as advice ("did you mean `white`?").
    pub help: Option<String>,
}

impl Problem {
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
            help: None,
        }
    }

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
