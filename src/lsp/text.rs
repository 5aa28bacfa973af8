//! Positions and file names as the protocol writes them: lines and UTF-16
//! columns (the protocol's default encoding), `file://` URIs.

use crate::diagnostic::LineIndex;
use lsp_types::{Position, Range, Uri};
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// The protocol position of byte `offset`.
pub fn position(text: &str, offset: usize) -> Position {
    position_in(&LineIndex::new(text), offset)
}

/// The protocol range of a byte range.
pub fn range(text: &str, span: std::ops::Range<usize>) -> Range {
    range_in(&LineIndex::new(text), span)
}

/// [`position`] through a line index built once: converting each of many
/// diagnostics by scanning the text from its start was quadratic.
pub fn position_in(lines: &LineIndex, offset: usize) -> Position {
    let (line, before, ascii) = lines.line_prefix(offset);
    let character = if ascii {
        before.len()
    } else {
        before.encode_utf16().count()
    };
    Position::new(line as u32, character as u32)
}

/// [`range`] through a line index built once.
pub fn range_in(lines: &LineIndex, span: std::ops::Range<usize>) -> Range {
    Range::new(position_in(lines, span.start), position_in(lines, span.end))
}

/// The byte offset of a protocol position (clamped to its line).
pub fn offset(text: &str, pos: Position) -> usize {
    let mut start = 0;
    for _ in 0..pos.line {
        match text[start..].find('\n') {
            Some(i) => start += i + 1,
            None => return text.len(),
        }
    }
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let mut units = 0;
    for (i, c) in text[start..line_end].char_indices() {
        if units >= pos.character as usize {
            return start + i;
        }
        units += c.len_utf16();
    }
    line_end
}

/// The local file a `file://` URI names.
pub fn path_of(uri: &Uri) -> Option<PathBuf> {
    let s = uri.as_str().strip_prefix("file://")?;
    // `file://host/path` is not local; `file:///path` has an empty host.
    let s = s.strip_prefix("localhost").unwrap_or(s);
    Some(PathBuf::from(percent_decode(s)?))
}

/// The `file://` URI of an absolute path.
pub fn uri_of(path: &Path) -> Option<Uri> {
    let path = std::path::absolute(path).ok()?;
    let mut s = String::from("file://");
    for b in path.to_str()?.bytes() {
        if b.is_ascii_alphanumeric() || b"/-._~".contains(&b) {
            s.push(b as char);
        } else {
            s += &format!("%{b:02X}");
        }
    }
    Uri::from_str(&s).ok()
}

fn percent_decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'%' {
            let hex = s.get(i + 1..i + 3)?;
            out.push(u8::from_str_radix(hex, 16).ok()?);
            i += 3;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8(out).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lsp_positions_count_utf16_and_round_trip() {
        let text = "ab\n€x𝄞y\n";
        assert_eq!(
            position(text, 4),
            Position::new(1, 0) /* inside € → its start */
        );
        assert_eq!(position(text, 6), Position::new(1, 1));
        assert_eq!(position(text, 7), Position::new(1, 2));
        assert_eq!(position(text, 11), Position::new(1, 4), "𝄞 is two UTF-16 units");
        for off in [0, 1, 3, 6, 7, 11, 12] {
            assert_eq!(offset(text, position(text, off)), off);
        }
        let uri = uri_of(Path::new("/tmp/a b/scène.ron")).expect("uri");
        assert_eq!(uri.as_str(), "file:///tmp/a%20b/sc%C3%A8ne.ron");
        assert_eq!(path_of(&uri), Some(PathBuf::from("/tmp/a b/scène.ron")));
    }
}
