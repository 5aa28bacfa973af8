//! The tokens of RON and JSON text, shared by everything that reads a
//! scene's structure without deserialising it: [`super::spans`] (where each
//! value is), [`super::brackets`] (do they pair up), [`super::outline`]
//! (where each entry is).
//!
//! It works on bytes and only splits at ASCII delimiters, so every range it
//! gives starts and ends on a character boundary whatever the text holds.

use std::ops::Range;

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Tok {
    Open(char),
    Close(char),
    Colon,
    Comma,
    /// Identifier, number, string, char: anything atomic.
    Atom {
        ident: bool,
        text: String,
    },
    /// A string or block comment that runs to the end of the text; its
    /// opening (`"`, `'`, `r#"`, `/*`) is the token's text.
    Unclosed(&'static str),
}

type Token = (Tok, Range<usize>);

/// Splits RON or JSON text into brackets, separators and atoms, skipping
/// whitespace (Unicode's too, and a byte-order mark) and comments. Never
/// fails: malformed text gives whatever tokens it can, and a string or block
/// comment left open is marked [`Tok::Unclosed`].
pub(super) fn tokenize(src: &str) -> Vec<Token> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let one = |t: Tok| (t, i..i + 1);
        let (token, next) = match c {
            b' ' | b'\t' | b'\n' | b'\r' => (None, i + 1),
            0x80.. if odd_space(src, i) > 0 => (None, i + odd_space(src, i)),
            b'/' if b.get(i + 1) == Some(&b'/') => (
                None,
                b[i..].iter().position(|&x| x == b'\n').map_or(b.len(), |k| i + k),
            ),
            b'/' if b.get(i + 1) == Some(&b'*') => block_comment(b, i),
            // `#![enable(...)]` and similar attributes: skip to the `]`.
            b'#' => (
                None,
                b[i..]
                    .iter()
                    .position(|&x| x == b']')
                    .map_or(b.len(), |k| i + k + 1),
            ),
            b'(' | b'[' | b'{' => (Some(one(Tok::Open(c as char))), i + 1),
            b')' | b']' | b'}' => (Some(one(Tok::Close(c as char))), i + 1),
            b':' => (Some(one(Tok::Colon)), i + 1),
            b',' => (Some(one(Tok::Comma)), i + 1),
            b'"' | b'\'' => quoted(src, i),
            b'r' if raw_string_at(b, i) => raw_string(src, i),
            _ => atom(src, i),
        };
        out.extend(token);
        i = next;
    }
    out
}

/// A nested RON block comment starting at `i`: the index after it, or an
/// [`Tok::Unclosed`] token when it runs to the end.
fn block_comment(b: &[u8], start: usize) -> (Option<Token>, usize) {
    match crate::syntax::lex::block_comment_end(b, start) {
        Some(end) => (None, end),
        None => (Some((Tok::Unclosed("/*"), start..start + 2)), b.len()),
    }
}

/// A `"…"` string or `'…'` character starting at `start`.
fn quoted(src: &str, start: usize) -> (Option<Token>, usize) {
    let b = src.as_bytes();
    let quote = b[start];
    let mut i = start + 1;
    while i < b.len() && b[i] != quote {
        i += if b[i] == b'\\' { 2 } else { 1 };
    }
    if i >= b.len() {
        let what = if quote == b'"' { "\"" } else { "'" };
        return (Some((Tok::Unclosed(what), start..start + 1)), b.len());
    }
    let text = src[start + 1..i].to_string();
    (Some((Tok::Atom { ident: false, text }, start..i + 1)), i + 1)
}

/// A raw string `r#"…"#` starting at `start`.
fn raw_string(src: &str, start: usize) -> (Option<Token>, usize) {
    let hashes = src[start + 1..].bytes().take_while(|&c| c == b'#').count();
    let body = start + hashes + 2;
    let close = format!("\"{}", "#".repeat(hashes));
    let Some(end) = src.get(body..).and_then(|r| r.find(&close)).map(|k| body + k) else {
        return (Some((Tok::Unclosed("r#\""), start..body)), src.len());
    };
    let text = src[body..end].to_string();
    let next = end + close.len();
    (Some((Tok::Atom { ident: false, text }, start..next)), next)
}

/// An identifier, number or other run of non-delimiters starting at `start`.
fn atom(src: &str, start: usize) -> (Option<Token>, usize) {
    let b = src.as_bytes();
    let mut i = start;
    while i < b.len() && !b" \t\r\n()[]{}:,\"'/#".contains(&b[i]) && (b[i] < 0x80 || odd_space(src, i) == 0) {
        i += 1;
    }
    if i == start {
        i += 1; // a lone `/`
    }
    let text = src[start..i].to_string();
    let ident = text.chars().next().is_some_and(|c| c.is_alphabetic() || c == '_');
    (Some((Tok::Atom { ident, text }, start..i)), i)
}

/// Bytes of Unicode whitespace or a byte-order mark at `i`, 0 if none.
fn odd_space(src: &str, i: usize) -> usize {
    src.get(i..)
        .and_then(|s| s.chars().next())
        .filter(|c| c.is_whitespace() || *c == '\u{feff}')
        .map_or(0, char::len_utf8)
}

/// `r"…"` or `r#"…"#` starts at `i` (not a raw identifier `r#name`).
fn raw_string_at(b: &[u8], i: usize) -> bool {
    let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
    b.get(i + 1 + hashes) == Some(&b'"')
}

/// Token index just past the value starting at token `i` (a variant or
/// struct name belongs to the value it names).
pub(super) fn skip_value(toks: &[(Tok, Range<usize>)], mut i: usize) -> usize {
    let mut depth = 0i32;
    while let Some((t, _)) = toks.get(i) {
        match t {
            Tok::Open(_) => depth += 1,
            Tok::Close(_) => {
                depth -= 1;
                if depth < 0 {
                    return i;
                }
                if depth == 0 {
                    return i + 1;
                }
            }
            Tok::Atom { ident: true, .. }
                if depth == 0 && matches!(toks.get(i + 1), Some((Tok::Open('('), _))) => {}
            _ if depth == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    i
}
