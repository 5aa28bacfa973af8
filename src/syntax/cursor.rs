//! What a position in scene text points at, for the language server: the
//! chain of brackets around it (each with the key or index that reached it
//! and the variant name written before it), the token under it, and whether
//! a key or a value is being written there. Works on broken text too: the
//! tokens before the position are all it reads.

use super::lex::{Kind, Token, unquote};

/// How a bracket is reached from the one around it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Step {
    /// `key: (` — a field, a map entry or (in JSON) a variant tag.
    Named(String),
    /// The n-th element of a list or tuple (0-based).
    Index(usize),
}

/// One open bracket around the position, outermost first.
#[derive(Clone, Debug, PartialEq)]
pub struct Frame {
    /// The bracket: `(`, `[` or `{`.
    pub open: char,
    /// Index of the opening token.
    pub token: usize,
    /// `None` for the outermost bracket.
    pub step: Option<Step>,
    /// The identifier written just before the bracket (`Sphere(`).
    pub variant: Option<String>,
    /// Entries before the position (commas seen).
    pub index: usize,
    /// The key of the entry being written, once its `:` is seen.
    pub key: Option<String>,
}

/// Where the position is.
#[derive(Clone, Debug, PartialEq)]
pub struct Context {
    /// The open brackets around the position, outermost first.
    pub frames: Vec<Frame>,
    /// The token the position is in or touches, if any.
    pub token: Option<usize>,
    /// The token is a key (followed by `:`).
    pub on_key: bool,
}

impl Context {
    /// The innermost bracket.
    pub fn frame(&self) -> Option<&Frame> {
        self.frames.last()
    }

    /// The step from the innermost bracket to the value at the position:
    /// the entry's key once `key:` is written, else its index.
    pub fn value_step(&self) -> Option<Step> {
        let f = self.frame()?;
        Some(match &f.key {
            Some(k) => Step::Named(k.clone()),
            None => Step::Index(f.index),
        })
    }
}

/// The next token after `i` that is not a comment.
pub fn next_significant(toks: &[Token], i: usize) -> Option<usize> {
    (i + 1..toks.len()).find(|&j| !toks[j].is_comment())
}

/// The context of byte `offset` in `src`, tokenized as `toks`.
pub fn at(src: &str, toks: &[Token], offset: usize) -> Context {
    let mut frames: Vec<Frame> = Vec::new();
    let mut pending_variant: Option<String> = None;
    let mut token = None;
    for (i, t) in toks.iter().enumerate() {
        // The token under the position (its end counts: `radi|`).
        if t.span.start <= offset && offset <= t.span.end && !matches!(t.kind, Kind::Comma | Kind::Colon) {
            token = Some(i);
        }
        if t.span.end > offset || (t.span.end == offset && matches!(t.kind, Kind::Word | Kind::Str)) {
            break;
        }
        let next = next_significant(toks, i).map(|j| toks[j].kind);
        match t.kind {
            Kind::Open(c) => {
                let step = frames.last().map(|f| match &f.key {
                    Some(k) => Step::Named(k.clone()),
                    None => Step::Index(f.index),
                });
                frames.push(Frame {
                    open: c,
                    token: i,
                    step,
                    variant: pending_variant.take(),
                    index: 0,
                    key: None,
                });
            }
            Kind::Close(_) => {
                frames.pop();
                pending_variant = None;
            }
            Kind::Comma => {
                if let Some(f) = frames.last_mut() {
                    f.index += 1;
                    f.key = None;
                }
                pending_variant = None;
            }
            Kind::Word | Kind::Str if next == Some(Kind::Colon) => {
                if let Some(f) = frames.last_mut() {
                    f.key = Some(unquote(t.text(src)).to_string());
                }
            }
            Kind::Word if matches!(next, Some(Kind::Open(_))) => {
                pending_variant = Some(t.text(src).to_string());
            }
            _ => {}
        }
    }
    let on_key = token.is_some_and(|i| {
        matches!(toks[i].kind, Kind::Word | Kind::Str)
            && next_significant(toks, i).is_some_and(|j| toks[j].kind == Kind::Colon)
    });
    Context {
        frames,
        token,
        on_key,
    }
}

/// The keys written directly inside the bracket opening at token `open`.
pub fn keys_in(src: &str, toks: &[Token], open: usize) -> Vec<String> {
    let mut depth = 0;
    let mut keys = Vec::new();
    for i in open + 1..toks.len() {
        match toks[i].kind {
            Kind::Open(_) => depth += 1,
            Kind::Close(_) if depth == 0 => break,
            Kind::Close(_) => depth -= 1,
            Kind::Word | Kind::Str
                if depth == 0 && next_significant(toks, i).is_some_and(|j| toks[j].kind == Kind::Colon) =>
            {
                keys.push(unquote(toks[i].text(src)).to_string());
            }
            _ => {}
        }
    }
    keys
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::lex::tokenize;

    const SRC: &str = "Scene(\n    objects: [\n        Sphere(center: (0, 0, 0), radius: 1, material: \"white\"),\n    ],\n)";

    fn ctx(marker: &str, delta: usize) -> (Context, Vec<Token>) {
        let toks = tokenize(SRC).expect("tokenizes");
        let off = SRC.find(marker).expect("marker") + delta;
        (at(SRC, &toks, off), toks)
    }

    #[test]
    fn cursor_names_the_chain_of_brackets() {
        let (c, toks) = ctx("radius", 3);
        let names: Vec<_> = c
            .frames
            .iter()
            .map(|f| (f.step.clone(), f.variant.clone()))
            .collect();
        assert_eq!(
            names,
            vec![
                (None, Some("Scene".into())),
                (Some(Step::Named("objects".into())), None),
                (Some(Step::Index(0)), Some("Sphere".into())),
            ]
        );
        assert!(c.on_key);
        assert_eq!(toks[c.token.expect("token")].text(SRC), "radius");
        let (c, toks) = ctx("\"white\"", 2);
        assert_eq!(c.value_step(), Some(Step::Named("material".into())));
        assert_eq!(toks[c.token.expect("token")].text(SRC), "\"white\"");
        assert!(!c.on_key);
        let (c, _) = ctx("0, 0, 0", 3);
        assert_eq!(c.frame().map(|f| f.index), Some(1));
        let sphere = c.frames[2].token;
        assert_eq!(
            keys_in(SRC, &tokenize(SRC).expect("ok"), sphere),
            ["center", "radius", "material"]
        );
    }
}
