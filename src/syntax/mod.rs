//! Scene text as text: the one lossless tokenizer ([`lex`]), the one tree of
//! its tokens grouped with their comments and spans ([`tree`], built by
//! [`parser`]), the limit on how deep its brackets nest ([`nesting`]), and
//! views of it: a layout printer ([`print`]) for `ronray fmt`, the values
//! by scene path ([`spans`]) and the fields and entries ([`outline`]) for
//! the loader's diagnostics and recovery, and the position queries of the
//! language server ([`cursor`]). Nothing here knows the scene types; the
//! loader does.

pub mod cursor;
pub mod fault;
pub mod lex;
pub mod nesting;
pub mod outline;
pub mod parser;
pub mod print;
pub mod spans;
pub mod tree;

use lex::{Kind, tokenize};

/// Why a file was not formatted.
#[derive(Debug, PartialEq, thiserror::Error)]
pub enum FormatError {
    /// The text does not tokenize or its brackets do not balance.
    #[error("cannot format: {message} (byte {at})")]
    Syntax {
        /// Byte offset of the problem.
        at: usize,
        /// What is wrong, in words.
        message: String,
    },
    /// The layout would have changed a token: a bug, and nothing is written.
    #[error("internal error: formatting would change the scene's tokens ({0}); nothing was written")]
    Changed(String),
}

/// Lays out RON (or, with `json`, JSON) text again, keeping every token and
/// comment as written; see [`print`] for the rules. The result is checked to
/// hold the same tokens as `src` (trailing commas aside) before it is
/// returned.
pub fn format(src: &str, json: bool) -> Result<String, FormatError> {
    // `parse` refuses text nested past the limit before building the
    // tree, which (like its printer) recurses per bracket.
    let doc = parser::parse(src).map_err(|e| FormatError::Syntax {
        at: e.at,
        message: e.message,
    })?;
    let out = print::print(&doc, json);
    same_tokens(src, &out).map_err(FormatError::Changed)?;
    Ok(out)
}

/// Compares the tokens of two texts, ignoring commas before a closing
/// bracket and trailing spaces of comments.
pub fn same_tokens(a: &str, b: &str) -> Result<(), String> {
    let sig = |s: &str| -> Result<Vec<String>, String> {
        let toks = tokenize(s).map_err(|e| e.message)?;
        Ok(toks
            .iter()
            .enumerate()
            .filter(|(i, t)| {
                t.kind != Kind::Comma
                    || !matches!(
                        toks[i + 1..].iter().find(|t| !t.is_comment()).map(|t| t.kind),
                        Some(Kind::Close(_))
                    )
            })
            .map(|(_, t)| t.text(s).trim_end().to_string())
            .collect())
    };
    let (x, y) = (sig(a)?, sig(b)?);
    match x.iter().zip(&y).position(|(p, q)| p != q) {
        Some(i) => Err(format!("token {i}: `{}` became `{}`", x[i], y[i])),
        None if x.len() != y.len() => Err(format!("{} tokens became {}", x.len(), y.len())),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests;
