//! How a scene file is written, RON (with the extensions its header
//! enables) or JSON, and how a slice of it is deserialised with its
//! mistake located in the whole file.

use super::slip::{Slip, widen};
use super::words;
use crate::diagnostic::offset_of;
use crate::syntax::lex::{Kind, tokenize_recovering};
use serde::de::DeserializeOwned;
use std::ops::Range;
use std::path::Path;

/// How a file is written: RON (with the extensions it enables) or JSON.
pub enum Format {
    /// RON, with the options (extensions) the file enables.
    Ron(ron::Options),
    /// JSON (chosen by the `.json` extension).
    Json,
}

impl Format {
    /// JSON for `.json` files, else RON with `implicit_some` (optional
    /// fields written bare: `focus_distance: 3.5`) and whatever the file's
    /// `#![enable(…)]` header adds, so that a slice read alone gets them too.
    pub fn of(path: &Path, text: &str) -> Self {
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
            return Format::Json;
        }
        let mut ext = ron::extensions::Extensions::IMPLICIT_SOME;
        let mut rest = text.trim_start();
        while let Some(attr) = rest.strip_prefix("#![enable(") {
            let Some((names, after)) = attr.split_once(")]") else {
                break;
            };
            for name in names.split(',') {
                ext |= ron::extensions::Extensions::from_ident(name.trim()).unwrap_or_default();
            }
            rest = after.trim_start();
        }
        Format::Ron(
            ron::Options::default()
                .with_default_extension(ext)
                .with_recursion_limit(serde_depth()),
        )
    }

    /// Deserialises `text[range]` on its own; an error is located in `text`.
    pub(super) fn read<T: DeserializeOwned>(&self, text: &str, range: Range<usize>) -> Result<T, Slip> {
        let slice = text.get(range.clone()).unwrap_or("");
        let (span, (message, help)) = match self {
            Format::Ron(opts) => {
                let e = match opts.from_str::<T>(slice) {
                    Ok(v) => return Ok(v),
                    Err(e) => e,
                };
                let mut start = offset_of(slice, e.span.start.line, e.span.start.col);
                let end = offset_of(slice, e.span.end.line, e.span.end.col).max(start);
                // ron points past the sign of a negative number it rejects.
                if e.code == ron::Error::IntegerOutOfBounds && slice[..start].ends_with('-') {
                    start -= 1;
                }
                (start..end, words::ron_error(&e.code, &slice[start..]))
            }
            Format::Json => {
                let mut de = serde_json::Deserializer::from_str(slice);
                // The text passed the nesting check (`source::read`); serde_json's
                // own fixed limit of 128 would not follow a raised one.
                de.disable_recursion_limit();
                let e = match T::deserialize(&mut de).and_then(|v| de.end().map(|()| v)) {
                    Ok(v) => return Ok(v),
                    Err(e) => e,
                };
                let at = json_offset(slice, e.line(), e.column());
                (token_at(slice, at), words::serde_message(&e.to_string()))
            }
        };
        let span = widen(text, span.start + range.start..span.end + range.start);
        let help = words::odd_character(&text[span.start..]).or(help);
        Err(Slip::new(span, message, help))
    }
}

/// How deep `ron` may recurse: it counts an enum, its variant's struct and
/// an implicit `Some` apart, up to three levels for one bracket, so four
/// per bracket of the nesting limit keeps the bracket limit (checked first,
/// with its own message) the one a file meets.
fn serde_depth() -> usize {
    4 * crate::syntax::nesting::limit()
}

/// Byte offset of serde_json's 1-based line and byte column (the last byte
/// it read).
fn json_offset(text: &str, line: usize, col: usize) -> usize {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    (start + col.saturating_sub(1)).min(text.len())
}

/// The token holding byte `at`, or the character there.
fn token_at(text: &str, at: usize) -> Range<usize> {
    tokenize_recovering(text)
        .tokens
        .into_iter()
        .find(|t| t.span.contains(&at) && !t.is_comment() && t.kind != Kind::Attribute)
        .map_or(at..at, |t| t.span)
}
