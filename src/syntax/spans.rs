//! Where each value of a RON document sits, by scene path.
//!
//! serde forgets positions once a value is parsed, yet a semantic error must
//! point at the line that caused it. This view of the [`super::tree`] (read
//! from RON or JSON, broken or not; values are not interpreted) records the
//! byte range of every value under the path syntax
//! [`crate::diagnostic::Problem`] uses: `objects[3].material`,
//! `materials.white.albedo`. Enum variant and struct names are transparent,
//! as they are in the paths.

use super::lex::unquote;
use super::parser::read;
use super::tree::{Group, Piece, Read};
use std::collections::HashMap;
use std::ops::Range;

/// Byte ranges of a document's values by scene path.
#[derive(Debug, Default)]
pub struct Spans {
    map: HashMap<String, Range<usize>>,
}

impl Spans {
    /// Scans `src`; a malformed document yields what could be read of it
    /// (serde reports the syntax error itself).
    pub fn scan(src: &str) -> Self {
        Self::of(&read(src))
    }

    /// The spans of a tree already read.
    pub fn of(tree: &Read) -> Self {
        let mut s = Spans::default();
        if let Some(top) = tree.values().next() {
            s.value("", &top.value());
        }
        s
    }

    /// The span of `path`, or of its closest located ancestor.
    pub fn find(&self, path: &str) -> Option<Range<usize>> {
        let mut p = path;
        loop {
            if let Some(r) = self.map.get(p) {
                return Some(r.clone());
            }
            let cut = p.rfind(['.', '['])?;
            p = &p[..cut];
        }
    }

    /// The span of exactly `path`.
    pub fn get(&self, path: &str) -> Option<Range<usize>> {
        self.map.get(path).cloned()
    }

    /// The path of the innermost value whose text holds byte `offset` (a
    /// field's key counts as part of the value around it); `None` at the top.
    pub fn path_at(&self, offset: usize) -> Option<String> {
        self.map
            .iter()
            .filter(|(p, r)| !p.is_empty() && !p.ends_with("#key") && r.contains(&offset))
            .min_by_key(|(p, r)| (r.len(), std::cmp::Reverse(p.len())))
            .map(|(p, _)| p.clone())
    }

    /// One value at `path` (its pieces, comments left out); records its span.
    fn value(&mut self, path: &str, pieces: &[&Piece]) {
        let (Some(first), Some(last)) = (pieces.first(), pieces.last()) else {
            return;
        };
        // A variant or struct name (`Sphere(`) is transparent in paths.
        match pieces {
            [Piece::Atom(_), Piece::Group(g)] | [Piece::Group(g)] => self.group(path, g),
            [Piece::Atom(_)] => {}
            // A colon where a value should be: nothing to locate.
            _ => return,
        }
        let (start, end) = (first.span().start, last.span().end);
        // A value seen again under the same path is either its own outer
        // layer (JSON's `{"Sphere": {…}}`: the whole wins) or a repeated
        // field (the first wins).
        let span = self.map.entry(path.to_string()).or_insert(start..end);
        if start <= span.start && end >= span.end {
            *span = start..end;
        }
    }

    /// The entries of `( … )`, `[ … ]` or `{ … }`.
    fn group(&mut self, path: &str, g: &Group) {
        let mut index = 0;
        for e in &g.entries {
            match e.key() {
                Some(key) if g.open != '[' => {
                    let text = unquote(&key.text);
                    // JSON writes enum variants as `{"Sphere": {...}}`: a lone
                    // capitalised key is a variant name, transparent in paths.
                    let variant = g.open == '{'
                        && text.starts_with(|c: char| c.is_ascii_uppercase())
                        && g.entries.len() == 1
                        && !e.comma;
                    let child = if variant {
                        path.to_string()
                    } else {
                        join(path, text)
                    };
                    self.map.insert(format!("{child}#key"), key.span.clone());
                    self.value(&child, &e.value());
                }
                _ => {
                    self.value(&format!("{path}[{index}]"), &e.value());
                    index += 1;
                }
            }
        }
    }
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SRC: &str = r#"// a scene
Scene(
    camera: (eye: (0, 1, 4), fov_y_degrees: 40),
    materials: { "white": Lambert(albedo: (0.8, 0.8, 0.8)) },
    objects: [
        Sphere(center: (0, 0, 0), radius: 1, material: "white"), /* two */
        Mesh(file: "a.obj", material: "whte", transform: [Translate((1, 2, 3))]),
    ],
)"#;

    fn text(path: &str) -> &'static str {
        let s = Spans::scan(SRC);
        let r = s.get(path).unwrap_or_else(|| panic!("no span for {path}"));
        &SRC[r]
    }

    #[test]
    fn spans_locate_fields_elements_and_map_keys() {
        assert_eq!(text("camera.fov_y_degrees"), "40");
        assert_eq!(text("materials.white.albedo"), "(0.8, 0.8, 0.8)");
        assert_eq!(text("objects[1].material"), "\"whte\"");
        assert_eq!(text("objects[1].transform[0]"), "Translate((1, 2, 3))");
        assert_eq!(text("objects[0].radius"), "1");
        assert!(text("objects[0]").starts_with("Sphere("));
    }

    #[test]
    fn spans_read_json_with_variants_transparent() {
        let src = r#"{"objects": [{"Sphere": {"center": [0, 0, 0], "radius": -1, "material": "white"}}]}"#;
        let s = Spans::scan(src);
        let r = s
            .get("objects[0].radius")
            .expect("located through the variant layer");
        assert_eq!(&src[r], "-1");
    }

    #[test]
    fn spans_find_falls_back_to_ancestor() {
        let s = Spans::scan(SRC);
        assert_eq!(s.find("objects[1].missing"), s.get("objects[1]"));
    }
}
