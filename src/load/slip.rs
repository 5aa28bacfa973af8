//! A parse mistake located in the file's text, before it becomes a
//! diagnostic: what the bracket check (`brackets.rs`), the section reader
//! (`sections.rs`) and [`super::format::Format::read`] report.

use crate::diagnostic::{Diagnostic, LineIndex};
use crate::syntax::spans::Nesting;
use std::ops::Range;
use std::path::Path;

/// A parse mistake located in the file's text.
#[derive(Clone, Debug)]
pub struct Slip {
    /// Byte range of the mistake in the file.
    pub span: Range<usize>,
    /// What is wrong.
    pub message: String,
    /// The likely fix.
    pub help: Option<String>,
}

impl Slip {
    /// A mistake at `span`.
    pub fn new(span: Range<usize>, message: String, help: Option<String>) -> Self {
        Self { span, message, help }
    }

    /// The located diagnostic, with the scene path of the value it is in.
    pub(super) fn diagnostic(self, file: &Path, lines: &LineIndex, spans: &Nesting) -> Diagnostic {
        let span = widen(lines.text(), self.span);
        let mut d = Diagnostic::indexed(file, lines, Some(span.clone()), self.message);
        d.path = spans.path_at(span.start);
        d.help = self.help;
        d
    }
}

/// `span` on character boundaries of `text`, at least one character wide
/// (ariadne needs something to underline).
pub(super) fn widen(text: &str, span: Range<usize>) -> Range<usize> {
    let start = text.floor_char_boundary(span.start.min(text.len()));
    let mut end = text.ceil_char_boundary(span.end.clamp(start, text.len()));
    if end == start {
        end = text[start..]
            .chars()
            .next()
            .map_or(start, |c| start + c.len_utf8());
    }
    start..end
}
