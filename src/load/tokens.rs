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

/// Splits RON or JSON text into brackets, separators and atoms, skipping
/// whitespace (Unicode's too, and a byte-order mark) and comments. Never
/// fails: malformed text gives whatever tokens it can, and a string or block
/// comment left open is marked [`Tok::Unclosed`].
pub(super) fn tokenize(src: &str) -> Vec<(Tok, Range<usize>)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        match c {
            b' ' | b'\t' | b'\n' | b'\r' => i += 1,
            0x80.. if odd_space(src, i) > 0 => i += odd_space(src, i),
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                // RON block comments nest.
                let start = i;
                let mut depth = 0;
                while i < b.len() {
                    if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                        depth += 1;
                        i += 2;
                    } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        i += 1;
                    }
                }
                if depth > 0 {
                    out.push((Tok::Unclosed("/*"), start..start + 2));
                }
            }
            b'#' => {
                // `#![enable(...)]` and similar attributes: skip to the `]`.
                while i < b.len() && b[i] != b']' {
                    i += 1;
                }
                i += 1;
            }
            b'(' | b'[' | b'{' => {
                out.push((Tok::Open(c as char), i..i + 1));
                i += 1;
            }
            b')' | b']' | b'}' => {
                out.push((Tok::Close(c as char), i..i + 1));
                i += 1;
            }
            b':' => {
                out.push((Tok::Colon, i..i + 1));
                i += 1;
            }
            b',' => {
                out.push((Tok::Comma, i..i + 1));
                i += 1;
            }
            b'"' | b'\'' => {
                let start = i;
                i += 1;
                while i < b.len() && b[i] != c {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                if i >= b.len() {
                    let quote = if c == b'"' { "\"" } else { "'" };
                    out.push((Tok::Unclosed(quote), start..start + 1));
                    break;
                }
                i += 1;
                let text = src[start + 1..i - 1].to_string();
                out.push((Tok::Atom { ident: false, text }, start..i));
            }
            b'r' if raw_string_at(b, i) => {
                // Raw string r#"..."#.
                let start = i;
                i += 1;
                let mut hashes = 0;
                while i < b.len() && b[i] == b'#' {
                    hashes += 1;
                    i += 1;
                }
                i += 1;
                let body = i;
                let close = format!("\"{}", "#".repeat(hashes));
                let Some(end) = src[i..].find(&close).map(|k| i + k) else {
                    out.push((Tok::Unclosed("r#\""), start..body));
                    break;
                };
                i = end + close.len();
                out.push((
                    Tok::Atom {
                        ident: false,
                        text: src[body..end].to_string(),
                    },
                    start..i,
                ));
            }
            _ => {
                let start = i;
                while i < b.len()
                    && !b" \t\r\n()[]{}:,\"'/#".contains(&b[i])
                    && (b[i] < 0x80 || odd_space(src, i) == 0)
                {
                    i += 1;
                }
                if i == start {
                    i += 1;
                }
                let text = &src[start..i];
                let ident = text.chars().next().is_some_and(|c| c.is_alphabetic() || c == '_');
                out.push((
                    Tok::Atom {
                        ident,
                        text: text.to_string(),
                    },
                    start..i,
                ));
            }
        }
    }
    out
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
