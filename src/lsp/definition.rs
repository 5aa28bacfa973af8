//! Go to definition: a material or mesh name jumps to its entry (in this
//! file or the file that includes it), an include or an OBJ/texture path to
//! the file.

use super::names;
use crate::syntax::cursor::{self, Step};
use crate::syntax::lex::{Kind, Token, unquote};
use std::ops::Range;
use std::path::{Path, PathBuf};

/// Where the name or path at byte `offset` is defined: a file (`None` for
/// this one) and a byte range in it.
pub fn definition(
    src: &str,
    toks: &[Token],
    path: &Path,
    offset: usize,
) -> Option<(Option<PathBuf>, Range<usize>)> {
    let cx = cursor::at(src, toks, offset);
    let t = &toks[cx.token?];
    if t.kind != Kind::Str || cx.on_key {
        return None;
    }
    let value = unquote(t.text(src));
    let frame = cx.frame()?;
    let base = path.parent().unwrap_or(Path::new("."));
    let top_level = cx.frames.len() == 2;
    let map = match (frame.key.as_deref(), &frame.step) {
        (Some("material"), _) => "materials",
        (Some("mesh"), _) => "meshes",
        (Some("medium" | "interior" | "exterior"), _) => "media",
        (Some("file"), _) => return existing(base.join(value)),
        (Some(_), Some(Step::Named(s))) if s == "materials" && !top_level => "materials",
        (None, Some(Step::Named(s))) if s == "include" && top_level => return existing(base.join(value)),
        _ => return None,
    };
    names::find(src, path, map, value)
}

fn existing(p: PathBuf) -> Option<(Option<PathBuf>, Range<usize>)> {
    p.is_file().then_some((Some(p), 0..0))
}
