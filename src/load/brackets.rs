//! The one mistake that stops parsing: brackets that do not pair up.
//!
//! Every other mistake is confined to the entry that holds it, so the rest
//! of the file can still be read (see [`super::sections`]). An unbalanced
//! bracket moves every later entry, so nothing after it can be trusted.
//! Parsers notice it late (at the next token, or at the end of the file);
//! this check names the bracket the user opened and where, as compilers do.
//!
//! Brackets inside strings and comments (`//`, nested `/* */`) do not count;
//! a string or comment that runs to the end of the file is reported at its
//! opening. Brackets nested past the limit stop reading too, at the first
//! bracket too deep.

use super::slip::Slip;
use crate::diagnostic::line_col;
use crate::syntax::lex::{Kind, Literal, Unclosed};
use crate::syntax::nesting::TooDeep;
use crate::syntax::tree::{Fault, Read};

/// The first unbalanced bracket (or unclosed string or comment) in `text`,
/// read as `tree`: a bracket closed wrongly before the unclosed literal,
/// else that literal, else the innermost bracket left open at the end.
pub(super) fn check(text: &str, tree: &Read) -> Option<Slip> {
    // Nothing was read past it (`source::read` refuses it before serde).
    if let Some(deep) = tree.faults.iter().find_map(|f| match f {
        Fault::TooDeep(deep) => Some(deep),
        _ => None,
    }) {
        return Some(too_deep(deep));
    }
    let wrong_close = tree.faults.iter().find_map(|f| match f {
        Fault::Mismatch { close, at, open } => Some(mismatch(text, open, *close, *at)),
        Fault::Stray {
            kind: Kind::Close(c),
            at,
        } => Some(mismatch(text, &[], *c, *at)),
        _ => None,
    });
    if wrong_close.is_some() {
        return wrong_close;
    }
    if let Some(u) = &tree.unclosed {
        return Some(unclosed_literal(u));
    }
    let (o, at) = tree.faults.iter().find_map(|f| match f {
        Fault::NeverClosed { open, at } => Some((*open, *at)),
        _ => None,
    })?;
    let (line, col) = line_col(text, text.len());
    Some(Slip::new(
        at..at + 1,
        format!("`{o}` opened here is never closed"),
        Some(format!(
            "the file ends (line {line}, column {col}) with it still open; add `{}` where it should end",
            closer(o)
        )),
    ))
}

/// Brackets nested past the limit, at the first bracket too deep.
pub(super) fn too_deep(deep: &TooDeep) -> Slip {
    Slip::new(deep.at..deep.at + 1, deep.to_string(), Some(deep.help()))
}

fn closer(open: char) -> char {
    match open {
        '(' => ')',
        '[' => ']',
        _ => '}',
    }
}

fn opener(close: char) -> char {
    match close {
        ')' => '(',
        ']' => '[',
        _ => '{',
    }
}

/// `c` at `at` does not close the innermost open bracket.
fn mismatch(text: &str, open: &[(char, usize)], c: char, at: usize) -> Slip {
    let here = |offset: usize| {
        let (l, col) = line_col(text, offset);
        format!("{l}:{col}")
    };
    let Some(&(inner, inner_at)) = open.last() else {
        return Slip::new(
            at..at + 1,
            format!("`{c}` closes nothing: no `{}` is open here", opener(c)),
            Some(format!("remove it, or add the `{}` it should close", opener(c))),
        );
    };
    match open.iter().rev().find(|(o, _)| closer(*o) == c) {
        // An outer bracket is closed first: the inner one was left open.
        Some(&(outer, outer_at)) => Slip::new(
            inner_at..inner_at + 1,
            format!("`{inner}` opened here is never closed"),
            Some(format!(
                "the `{c}` at {} closes the `{outer}` opened at {} first; add `{}` before it",
                here(at),
                here(outer_at),
                closer(inner)
            )),
        ),
        None => Slip::new(
            at..at + 1,
            format!("`{c}` where `{}` was expected", closer(inner)),
            Some(format!(
                "the `{inner}` opened at {} is the bracket still open here; close it with `{}`",
                here(inner_at),
                closer(inner)
            )),
        ),
    }
}

fn unclosed_literal(u: &Unclosed) -> Slip {
    let (kind, end) = match u.what {
        Literal::Comment => ("comment", "`*/`"),
        Literal::Char => ("character", "`'`"),
        Literal::RawString => ("raw string", "`\"#`"),
        Literal::String => ("string", "`\"`"),
    };
    Slip::new(
        u.span.clone(),
        format!("{kind} opened here is never closed"),
        Some(format!(
            "everything after it is read as part of the {kind}; end it with {end}"
        )),
    )
}

#[cfg(test)]
mod tests {
    use super::check;
    use crate::syntax::parser::read;

    fn check_text(text: &str) -> Option<super::Slip> {
        check(text, &read(text))
    }

    fn at(text: &str) -> (usize, String) {
        let s = check_text(text).unwrap_or_else(|| panic!("no structure error in {text:?}"));
        (s.span.start, s.message)
    }

    #[test]
    fn brackets_balanced_in_strings_and_comments_pass() {
        let text = "Scene( // a ( in a comment\n /* nested /* ( */ [ */ a: \"(]\", b: r#\")\"#, c: '(')";
        assert!(
            check_text(text).is_none(),
            "{:?}",
            check_text(text).map(|s| s.message)
        );
    }

    #[test]
    fn brackets_unclosed_is_reported_at_the_opening() {
        let text = "Scene(\n  objects: [\n    Sphere(radius: 1,\n    Sphere(radius: 2),\n  ],\n)";
        let (offset, message) = at(text);
        assert_eq!(offset, text.find("Sphere(radius: 1").unwrap_or(0) + 6);
        assert_eq!(message, "`(` opened here is never closed");
        let (offset, _) = at("Scene(a: (1, 2)");
        assert_eq!(offset, 5, "left open at the end of the file");
    }

    #[test]
    fn brackets_mismatched_closer_names_both() {
        let s = check_text("Scene(a: (1, 2]").expect("a mismatch");
        assert_eq!(s.span.start, 14);
        assert_eq!(s.message, "`]` where `)` was expected");
        assert!(s.help.unwrap_or_default().contains("1:10"));
        assert!(at("(a: 1))").1.contains("closes nothing"));
    }

    #[test]
    fn brackets_unclosed_string_and_comment_are_located() {
        assert_eq!(
            at("Scene(a: \"white)"),
            (9, "string opened here is never closed".into())
        );
        assert_eq!(
            at("Scene(a: 1) /* /* */"),
            (12, "comment opened here is never closed".into())
        );
        assert!(
            check_text("{\"é\": [1, 2}").is_some(),
            "non-ASCII does not confuse offsets"
        );
    }
}
