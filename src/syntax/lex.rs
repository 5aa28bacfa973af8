//! A lossless tokenizer for RON and JSON scene text: every byte belongs to
//! a token or to the whitespace between two, and comments and `#![...]`
//! attributes are tokens, so the formatter can lay them out again and the
//! language server can find what a position points at.

use std::ops::Range;

/// What a token is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// `(`, `[` or `{`.
    Open(char),
    /// `)`, `]` or `}`.
    Close(char),
    /// `:`.
    Colon,
    /// `,`.
    Comma,
    /// An identifier, `true`, a number (`40`, `-1.5e3`, `0x1F`).
    Word,
    /// A string (`"…"`, `r#"…"#`, `b"…"`) or a char (`'a'`).
    Str,
    /// `// …` up to the end of the line.
    LineComment,
    /// `/* … */`, nesting as RON allows.
    BlockComment,
    /// `#![…]` (`#![schema = "…"]`, `#![enable(implicit_some)]`).
    Attribute,
}

/// One token: what it is and where.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// What the token is.
    pub kind: Kind,
    /// Its bytes in the source.
    pub span: Range<usize>,
    /// Newlines between the previous token (or the start) and this one.
    pub newlines_before: usize,
}

impl Token {
    /// The token as written in `src`.
    pub fn text<'a>(&self, src: &'a str) -> &'a str {
        &src[self.span.clone()]
    }

    /// Whether the token is a `//` or `/* */` comment.
    pub fn is_comment(&self) -> bool {
        matches!(self.kind, Kind::LineComment | Kind::BlockComment)
    }
}

/// Why text could not be tokenized, with the byte where it happened.
#[derive(Clone, Debug, PartialEq)]
pub struct LexError {
    /// Byte offset of the problem.
    pub at: usize,
    /// What is wrong, in words.
    pub message: String,
}

/// A string, character or block comment that runs to the end of the text.
#[derive(Clone, Debug, PartialEq)]
pub struct Unclosed {
    /// Its opening (`"`, `'`, `r#"`, `/*`).
    pub span: Range<usize>,
    /// What it is.
    pub what: Literal,
}

/// The kinds of text that have an opening and an end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Literal {
    /// `"…"`.
    String,
    /// `'…'`.
    Char,
    /// `r"…"`, `r#"…"#`.
    RawString,
    /// `/* … */`.
    Comment,
}

/// The tokens of text the loader reads: every token before the first
/// unclosed literal, and that literal.
#[derive(Clone, Debug, Default)]
pub struct Recovered {
    /// The tokens, in order.
    pub tokens: Vec<Token>,
    /// The string or comment that swallowed the rest of the text.
    pub unclosed: Option<Unclosed>,
}

/// How strict the tokenizer is; one scanner serves the formatter, the
/// language server and the loader.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// The formatter: any doubt is an error, nothing is guessed.
    Strict,
    /// Text being typed: every doubt is resolved on the same line.
    Lenient,
    /// The loader's structure scan of text serde rejected: never fails.
    /// A stray character joins the word around it (`a@b` is one value, so
    /// no comma is reported missing inside it), Unicode spaces and a
    /// byte-order mark separate tokens (the diagnostic names them), `#`
    /// starts an attribute up to its `]`, and an unclosed literal ends the
    /// tokens (it is [`Recovered::unclosed`]).
    Recover,
}

/// Tokenizes `src`. Only an unterminated string, comment or attribute, or a
/// byte that no scene file can hold, is an error.
pub fn tokenize(src: &str) -> Result<Vec<Token>, LexError> {
    lex(src, Mode::Strict).map(|r| r.tokens)
}

/// Tokenizes text being typed: an unterminated string or attribute ends at
/// the end of its line, an unterminated comment at the end of the text, and
/// a stray character is a word of its own.
pub fn tokenize_lenient(src: &str) -> Vec<Token> {
    lex(src, Mode::Lenient).map(|r| r.tokens).unwrap_or_default()
}

/// Tokenizes a scene file that did not parse, to find where its parts are
/// (see [`Mode::Recover`]). Never fails.
pub fn tokenize_recovering(src: &str) -> Recovered {
    lex(src, Mode::Recover).unwrap_or_default()
}

fn lex(src: &str, mode: Mode) -> Result<Recovered, LexError> {
    let lenient = mode == Mode::Lenient;
    let recover = mode == Mode::Recover;
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    let mut newlines = 0;
    let unclosed = |out: Vec<Token>, start: usize, len: usize, what: Literal| Recovered {
        tokens: out,
        unclosed: Some(Unclosed {
            span: start..start + len,
            what,
        }),
    };
    let line_end = |at: usize| src[at..].find('\n').map_or(src.len(), |n| at + n);
    // In lenient mode an error ends the token at `fallback` instead.
    let err = |at: usize, what: &str| LexError {
        at,
        message: what.to_string(),
    };
    let or_lenient = |r: Option<usize>, at: usize, fallback: usize, what: &str| match r {
        Some(end) => Ok(end),
        None if lenient => Ok(fallback.max(at + 1).min(src.len())),
        None => Err(err(at, what)),
    };
    while i < b.len() {
        let c = b[i];
        let start = i;
        let kind = match c {
            b'\n' => {
                newlines += 1;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' => {
                i += 1;
                continue;
            }
            0x80.. if recover && odd_space(src, i) > 0 => {
                i += odd_space(src, i);
                continue;
            }
            b'(' | b'[' | b'{' => {
                i += 1;
                Kind::Open(c as char)
            }
            b')' | b']' | b'}' => {
                i += 1;
                Kind::Close(c as char)
            }
            b':' => {
                i += 1;
                Kind::Colon
            }
            b',' => {
                i += 1;
                Kind::Comma
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                // A `\r` before the newline is line ending, not comment.
                if i > start && b[i - 1] == b'\r' {
                    i -= 1;
                }
                Kind::LineComment
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                if recover && block_comment_end(b, i).is_none() {
                    return Ok(unclosed(out, start, 2, Literal::Comment));
                }
                i = or_lenient(
                    block_comment_end(b, i),
                    start,
                    b.len(),
                    "unterminated `/*` comment",
                )?;
                Kind::BlockComment
            }
            b'#' if recover => {
                // As serde would skip it: up to the attribute's end, else
                // its first `]`.
                i = attribute_end(b, i)
                    .or_else(|| b[i..].iter().position(|&x| x == b']').map(|k| i + k + 1))
                    .unwrap_or(b.len());
                Kind::Attribute
            }
            b'#' if b.get(i + 1) == Some(&b'!') => {
                i = or_lenient(
                    attribute_end(b, i),
                    start,
                    line_end(start),
                    "unterminated `#![` attribute",
                )?;
                Kind::Attribute
            }
            b'"' | b'\'' if recover && quoted_end(b, i).is_none() => {
                let what = if c == b'"' { Literal::String } else { Literal::Char };
                return Ok(unclosed(out, start, 1, what));
            }
            b'r' | b'b' if recover && raw_or_byte_string(b, i) && prefixed_string_end(b, i).is_none() => {
                let hashes = b[i + 1..].iter().take_while(|&&c| c == b'#').count();
                return Ok(match c {
                    b'r' => unclosed(out, start, hashes + 2, Literal::RawString),
                    _ => unclosed(out, start + 1, 1, Literal::String),
                });
            }
            b'"' | b'\'' => {
                // While typing, a string does not run on past its line.
                let end = quoted_end(b, i).filter(|&e| !lenient || !src[start..e].contains('\n'));
                i = or_lenient(end, start, line_end(start), "unterminated string")?;
                Kind::Str
            }
            b'r' | b'b' if raw_or_byte_string(b, i) => {
                i = or_lenient(
                    prefixed_string_end(b, i),
                    start,
                    line_end(start),
                    "unterminated string",
                )?;
                Kind::Str
            }
            // A lone `/` is a word of its own.
            b'/' if recover => {
                i += 1;
                Kind::Word
            }
            _ if recover => {
                i += src[i..].chars().next().map_or(1, char::len_utf8);
                while i < b.len() && is_recovered_word_byte(src, i, start) {
                    i += 1;
                }
                Kind::Word
            }
            _ if is_word_byte(c) => {
                while i < b.len()
                    && (is_word_byte(b[i]) || (b[i] == b'#' && i == start + 1 && b[start] == b'r'))
                {
                    i += 1;
                }
                Kind::Word
            }
            _ => {
                let ch = src[i..].chars().next().unwrap_or('?');
                if !lenient {
                    return Err(err(i, &format!("unexpected character `{ch}`")));
                }
                i += ch.len_utf8();
                Kind::Word
            }
        };
        out.push(Token {
            kind,
            span: start..i,
            newlines_before: newlines,
        });
        newlines = 0;
    }
    Ok(Recovered {
        tokens: out,
        unclosed: None,
    })
}

/// In [`Mode::Recover`], a word runs to the next delimiter or space
/// (`r#name` is one word).
fn is_recovered_word_byte(src: &str, i: usize, start: usize) -> bool {
    let b = src.as_bytes();
    let raw_ident = b[i] == b'#' && i == start + 1 && b[start] == b'r';
    raw_ident || (!b" \t\r\n()[]{}:,\"'/#".contains(&b[i]) && (b[i] < 0x80 || odd_space(src, i) == 0))
}

/// Bytes of Unicode whitespace or a byte-order mark at `i`, 0 if none.
fn odd_space(src: &str, i: usize) -> usize {
    src.get(i..)
        .and_then(|s| s.chars().next())
        .filter(|c| c.is_whitespace() || *c == '\u{feff}')
        .map_or(0, char::len_utf8)
}

/// Letters, digits and the signs, dots and underscores of numbers; any
/// non-ASCII byte (an identifier in another script is still one word).
fn is_word_byte(c: u8) -> bool {
    c.is_ascii_alphanumeric() || matches!(c, b'_' | b'.' | b'+' | b'-') || c >= 0x80
}

/// The index just after the nested block comment starting at `i`, or
/// `None` when it runs to the end.
fn block_comment_end(b: &[u8], mut i: usize) -> Option<usize> {
    let mut depth = 0;
    while i < b.len() {
        if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
            depth += 1;
            i += 2;
        } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
            depth -= 1;
            i += 2;
            if depth == 0 {
                return Some(i);
            }
        } else {
            i += 1;
        }
    }
    None
}

/// `#![ … ]` with brackets and strings inside balanced.
fn attribute_end(b: &[u8], mut i: usize) -> Option<usize> {
    i += 2;
    let mut depth = 0;
    while i < b.len() {
        match b[i] {
            b'[' => depth += 1,
            b']' => {
                depth -= 1;
                if depth == 0 {
                    return Some(i + 1);
                }
            }
            b'"' => {
                i = quoted_end(b, i)?;
                continue;
            }
            b'\n' if depth == 0 => return None,
            _ => {}
        }
        i += 1;
    }
    None
}

/// Past the closing quote of the string or char opening at `i`.
fn quoted_end(b: &[u8], mut i: usize) -> Option<usize> {
    let q = b[i];
    i += 1;
    while i < b.len() {
        match b[i] {
            b'\\' => i += 2,
            c if c == q => return Some(i + 1),
            _ => i += 1,
        }
    }
    None
}

/// `r"…"`, `r#"…"#`, `b"…"`, `br#"…"#` start at `i`.
fn raw_or_byte_string(b: &[u8], i: usize) -> bool {
    let j = if b[i] == b'b' && b.get(i + 1) == Some(&b'r') {
        i + 2
    } else {
        i + 1
    };
    match b.get(j) {
        Some(b'"') => true,
        Some(b'#') if b[j - 1] == b'r' => {
            let mut k = j;
            while b.get(k) == Some(&b'#') {
                k += 1;
            }
            b.get(k) == Some(&b'"')
        }
        _ => false,
    }
}

fn prefixed_string_end(b: &[u8], mut i: usize) -> Option<usize> {
    if b[i] == b'b' {
        i += 1;
        if b.get(i) == Some(&b'"') {
            return quoted_end(b, i);
        }
    }
    // Raw: r, hashes, quote … quote, the same hashes.
    i += 1;
    let mut hashes = 0;
    while b.get(i) == Some(&b'#') {
        hashes += 1;
        i += 1;
    }
    i += 1;
    while i < b.len() {
        if b[i] == b'"' && b.len() >= i + 1 + hashes && b[i + 1..i + 1 + hashes].iter().all(|&c| c == b'#') {
            return Some(i + 1 + hashes);
        }
        i += 1;
    }
    None
}

/// The string value of a `Str` token's text, without quotes; escapes are
/// kept as written (names in scene files have none).
pub fn unquote(text: &str) -> &str {
    let prefixed = text
        .strip_prefix("br")
        .or(text.strip_prefix('r'))
        .or(text.strip_prefix('b'));
    let t = match prefixed {
        Some(rest) if rest.starts_with(['"', '#']) => rest.trim_matches('#'),
        _ => text,
    };
    t.strip_prefix(['"', '\''])
        .and_then(|t| t.strip_suffix(['"', '\'']))
        .unwrap_or(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<(Kind, &str)> {
        tokenize(src)
            .expect("tokenizes")
            .iter()
            .map(|t| (t.kind, t.text(src)))
            .collect()
    }

    #[test]
    fn lex_keeps_comments_attributes_and_number_spellings() {
        let src = "#![schema = \"../s.json\"]\n// hi\nScene(a: -1.5e3, /* b /* nested */ */ c: [0x1F, r#\"x\"y\"#])";
        let k = kinds(src);
        assert_eq!(k[0], (Kind::Attribute, "#![schema = \"../s.json\"]"));
        assert_eq!(k[1], (Kind::LineComment, "// hi"));
        assert_eq!(k[2], (Kind::Word, "Scene"));
        assert!(k.contains(&(Kind::Word, "-1.5e3")));
        assert!(k.contains(&(Kind::BlockComment, "/* b /* nested */ */")));
        assert!(k.contains(&(Kind::Word, "0x1F")));
        assert!(k.contains(&(Kind::Str, "r#\"x\"y\"#")));
        let t = tokenize(src).expect("tokenizes");
        assert_eq!(t[2].newlines_before, 1);
    }

    #[test]
    fn lex_reports_unterminated_strings() {
        let e = tokenize("Scene(a: \"x)").expect_err("unterminated");
        assert_eq!(e.at, 9);
        assert!(tokenize("/* open").is_err());
        assert_eq!(unquote("\"white\""), "white");
        assert_eq!(unquote("r#\"a\"#"), "a");
        assert_eq!(unquote("radius"), "radius", "a word is its own text");
    }
}
