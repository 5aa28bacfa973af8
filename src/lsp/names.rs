//! The names a scene defines (materials, meshes) and where: read from the
//! text itself, so they are found while the file is being edited, and from
//! the files it includes.

use crate::syntax::cursor::next_significant;
use crate::syntax::lex::{Kind, Token, tokenize_lenient, unquote};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// The keys of the top-level map `map` (`materials`, `meshes`), with the
/// byte range of each key.
pub fn defined(src: &str, toks: &[Token], map: &str) -> Vec<(String, Range<usize>)> {
    let mut depth = 0;
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        match toks[i].kind {
            Kind::Open(_) => depth += 1,
            Kind::Close(_) => depth -= 1,
            Kind::Word | Kind::Str if depth == 1 && unquote(toks[i].text(src)) == map => {
                let colon = next_significant(toks, i);
                let open = colon.and_then(|c| next_significant(toks, c));
                if let (Some(c), Some(o)) = (colon, open)
                    && toks[c].kind == Kind::Colon
                    && toks[o].kind == Kind::Open('{')
                {
                    out.extend(map_keys(src, toks, o));
                }
            }
            _ => {}
        }
        i += 1;
    }
    out
}

fn map_keys(src: &str, toks: &[Token], open: usize) -> Vec<(String, Range<usize>)> {
    let mut depth = 0;
    let mut out = Vec::new();
    for i in open + 1..toks.len() {
        match toks[i].kind {
            Kind::Open(_) => depth += 1,
            Kind::Close(_) if depth == 0 => break,
            Kind::Close(_) => depth -= 1,
            Kind::Word | Kind::Str
                if depth == 0 && next_significant(toks, i).is_some_and(|j| toks[j].kind == Kind::Colon) =>
            {
                out.push((unquote(toks[i].text(src)).to_string(), toks[i].span.clone()));
            }
            _ => {}
        }
    }
    out
}

/// The files `src` includes (its top-level `include: [...]`), resolved
/// against `base`.
pub fn includes(src: &str, toks: &[Token], base: &Path) -> Vec<PathBuf> {
    let mut depth = 0;
    let mut out = Vec::new();
    let mut in_list = None;
    for (i, t) in toks.iter().enumerate() {
        match t.kind {
            Kind::Open(c) => {
                depth += 1;
                if c == '['
                    && depth == 2
                    && i >= 2
                    && toks[i - 1].kind == Kind::Colon
                    && unquote(toks[i - 2].text(src)) == "include"
                {
                    in_list = Some(depth);
                }
            }
            Kind::Close(_) => {
                if in_list == Some(depth) {
                    in_list = None;
                }
                depth -= 1;
            }
            Kind::Str if in_list == Some(depth) => out.push(base.join(unquote(t.text(src)))),
            _ => {}
        }
    }
    out
}

/// Where `name` is defined in map `map`: in `src` itself, else in the files
/// it includes (depth first, as the loader merges them). Returns the file
/// (`None` for `src` itself) and the key's byte range in it.
pub fn find(src: &str, path: &Path, map: &str, name: &str) -> Option<(Option<PathBuf>, Range<usize>)> {
    let toks = tokenize_lenient(src);
    if let Some((_, r)) = defined(src, &toks, map).into_iter().find(|(n, _)| n == name) {
        return Some((None, r));
    }
    let mut stack: Vec<PathBuf> = includes(src, &toks, path.parent().unwrap_or(Path::new(".")));
    stack.reverse();
    let mut seen = 0;
    while let Some(file) = stack.pop() {
        seen += 1;
        if seen > 64 {
            break;
        }
        let Ok(text) = crate::load::source::read_text(&file) else {
            continue;
        };
        let toks = tokenize_lenient(&text);
        if let Some((_, r)) = defined(&text, &toks, map).into_iter().find(|(n, _)| n == name) {
            return Some((Some(file), r));
        }
        let mut more = includes(&text, &toks, file.parent().unwrap_or(Path::new(".")));
        more.reverse();
        stack.extend(more);
    }
    None
}
