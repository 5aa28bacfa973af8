//! A mistake in the structure of scene text, as the tree builder meets it:
//! the formatter stops at the first ([`super::parser::parse`]), the loader
//! records each and reads on ([`super::parser::read`]) and words the bracket
//! ones itself (`load/brackets.rs`). Nesting past the limit stops both.

use super::lex::{Kind, LexError};
use super::nesting::TooDeep;

/// A mistake in the structure. [`parse`] stops at the first; [`read`]
/// records each and reads on as the scanners before it did.
#[derive(Clone, Debug, PartialEq)]
pub enum Fault {
    /// A bracket still open at the end of the text (the innermost).
    NeverClosed {
        /// The bracket.
        open: char,
        /// Its offset.
        at: usize,
    },
    /// A closing bracket that does not match the innermost open one; it is
    /// read as closing it.
    Mismatch {
        /// The closing bracket.
        close: char,
        /// Its offset.
        at: usize,
        /// The brackets open at that point, outermost first.
        open: Vec<(char, usize)>,
    },
    /// A closing bracket, comma or colon outside any bracket; skipped.
    Stray {
        /// What it is.
        kind: Kind,
        /// Its offset.
        at: usize,
    },
    /// A comma with no entry before it; skipped.
    LeadingComma {
        /// Its offset.
        at: usize,
    },
    /// Two values with no comma between them; the second starts an entry.
    MissingComma {
        /// The start of the second.
        at: usize,
    },
    /// An entry that starts with `:`; the colon is its value.
    StrayColon {
        /// Its offset.
        at: usize,
    },
    /// Brackets nested past the limit: nothing is read (the tree is empty),
    /// since reading them would recurse that deep.
    TooDeep(TooDeep),
}

impl Fault {
    /// The formatter's words for it, at its byte.
    pub(super) fn lex_error(&self) -> LexError {
        let (at, message) = match self {
            Fault::NeverClosed { open, at } => (*at, format!("`{open}` is never closed")),
            Fault::Mismatch { close, at, open } => {
                let inner = open.last().map_or('(', |o| o.0);
                (*at, format!("`{close}` closes `{inner}`"))
            }
            Fault::Stray { at, .. } => (*at, "unexpected token outside any bracket".into()),
            Fault::LeadingComma { at } => (*at, "a comma with nothing before it".into()),
            Fault::MissingComma { at } | Fault::StrayColon { at } => {
                (*at, "expected `,` between two values".into())
            }
            Fault::TooDeep(deep) => (deep.at, deep.to_string()),
        };
        LexError { at, message }
    }
}
