//! How deeply brackets may nest in a scene file, checked over the tokens
//! before anything recursive sees the text.
//!
//! Why: every reader of scene text recurses once per bracket (serde through
//! `ron` and `serde_json`, the syntax tree's builder and its views, the
//! formatter's printer, dropping what they built), so a 60 KB file nested
//! 30,000 deep overflowed the stack of `validate`, `fmt` and `lsp`. This
//! scan is a loop: the text is refused at the first bracket past the limit,
//! with its location, and nothing recursive runs on it. The loader runs it
//! before serde ([`check`]); the tree's builder runs it on the tokens it
//! builds from ([`within`]), so no caller of [`super::parser`] can forget.
//!
//! It counts the tokens of the loader's mode ([`tokenize_recovering`]):
//! those the tree is built from, and the mode that reads strings and
//! comments as serde does (a string may span lines; text after an unclosed
//! one is never read, by serde or the tree). The language server's lenient
//! mode ends a string at its line, so a file that passes its count could
//! still nest deeper for serde and the tree.
//!
//! Hand-written scenes nest about ten deep (`Scene(objects: [Sdf(shape:
//! Union(of: [Transform(of: …`); [`MAX_NESTING`] leaves room for generated
//! CSG trees. The limit is raised, up to [`MAX_NESTING_CEILING`], with the
//! environment variable [`NESTING_VAR`] (every command reads it, the
//! language server too).

use super::lex::{Kind, Token, tokenize_recovering};

/// Brackets that may be open at once, by default.
pub const MAX_NESTING: usize = 128;

/// The highest limit [`NESTING_VAR`] may set: every parser stays within
/// the main thread's 8 MiB stack up to here (measured: see
/// `tests/nesting.rs`).
pub const MAX_NESTING_CEILING: usize = 1024;

/// The environment variable that raises (or lowers) the limit.
pub const NESTING_VAR: &str = "RONRAY_MAX_NESTING";

/// A text nested deeper than the limit.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("brackets nested deeper than {limit} (the limit on nesting)")]
pub struct TooDeep {
    /// Byte offset of the first bracket past the limit.
    pub at: usize,
    /// The limit that was passed.
    pub limit: usize,
}

impl TooDeep {
    /// How to get past the limit, in words.
    pub fn help(&self) -> String {
        format!(
            "no scene needs this many levels: flatten the nesting, or raise the limit with \
             {NESTING_VAR}=N (at most {MAX_NESTING_CEILING})"
        )
    }
}

/// The limit a value of [`NESTING_VAR`] sets: unset is [`MAX_NESTING`]; a
/// number from 1 to [`MAX_NESTING_CEILING`] is that limit; anything else
/// is an error in words (the CLI prints it and stops).
pub fn parse_limit(value: Option<&str>) -> Result<usize, String> {
    let Some(v) = value else {
        return Ok(MAX_NESTING);
    };
    match v.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_NESTING_CEILING).contains(&n) => Ok(n),
        _ => Err(format!(
            "{NESTING_VAR}={v}: the nesting limit must be a whole number from 1 to \
             {MAX_NESTING_CEILING} (default {MAX_NESTING})"
        )),
    }
}

/// The limit in force: [`NESTING_VAR`] if it is valid, else [`MAX_NESTING`]
/// (the CLI refuses an invalid value before anything reads a scene). Read
/// once per process.
pub fn limit() -> usize {
    static LIMIT: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *LIMIT.get_or_init(|| {
        let v = std::env::var(NESTING_VAR).ok();
        parse_limit(v.as_deref()).unwrap_or(MAX_NESTING)
    })
}

/// Whether `src` nests at most `limit` brackets deep; brackets in strings
/// and comments do not count. Linear in the text, no recursion.
pub fn check(src: &str, limit: usize) -> Result<(), TooDeep> {
    within(&tokenize_recovering(src).tokens, limit)
}

/// Whether `tokens` nest at most `limit` brackets deep (see [`check`]).
pub fn within(tokens: &[Token], limit: usize) -> Result<(), TooDeep> {
    let mut depth = 0usize;
    for t in tokens {
        match t.kind {
            Kind::Open(_) => {
                depth += 1;
                if depth > limit {
                    return Err(TooDeep {
                        at: t.span.start,
                        limit,
                    });
                }
            }
            Kind::Close(_) => depth = depth.saturating_sub(1),
            Kind::Colon
            | Kind::Comma
            | Kind::Word
            | Kind::Str
            | Kind::LineComment
            | Kind::BlockComment
            | Kind::Attribute => {}
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_is_refused_at_the_first_bracket_past_the_limit() {
        let src = "Scene(objects: [[[[]]]])";
        assert_eq!(check(src, 5), Ok(()));
        let e = check(src, 3).expect_err("four deep");
        assert_eq!((e.at, e.limit), (src.find("[[]]").expect("third"), 3));
        // Brackets in strings and comments are text.
        assert_eq!(check("( \"(((\" /* [[[ */ // {{{\n)", 1), Ok(()));
    }

    #[test]
    fn nesting_limit_reads_the_variable_and_refuses_nonsense() {
        assert_eq!(parse_limit(None), Ok(MAX_NESTING));
        assert_eq!(parse_limit(Some("512")), Ok(512));
        for bad in ["0", "-1", "lots", "1e9"] {
            assert!(parse_limit(Some(bad)).is_err(), "{bad} accepted");
        }
        let past = (MAX_NESTING_CEILING + 1).to_string();
        assert!(parse_limit(Some(&past)).is_err());
    }
}
