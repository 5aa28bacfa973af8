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

    /// Every located path and its span, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, Range<usize>)> {
        self.map.iter().map(|(p, r)| (p.as_str(), r.clone()))
    }

    /// The span of exactly `path`.
    pub fn get(&self, path: &str) -> Option<Range<usize>> {
        self.map.get(path).cloned()
    }

    /// The path of the innermost value whose text holds byte `offset` (a
    /// field's key counts as part of the value around it); `None` at the top.
    /// It looks at every value: for many offsets, ask [`Spans::nesting`].
    pub fn path_at(&self, offset: usize) -> Option<String> {
        self.values()
            .filter(|(_, r)| r.contains(&offset))
            .min_by_key(|(p, r)| (r.len(), std::cmp::Reverse(p.len())))
            .map(|(p, _)| p.to_string())
    }

    /// The values [`Spans::path_at`] may answer: not the top, not keys.
    fn values(&self) -> impl Iterator<Item = (&str, &Range<usize>)> {
        self.map
            .iter()
            .filter(|(p, _)| !p.is_empty() && !p.ends_with("#key"))
            .map(|(p, r)| (p.as_str(), r))
    }

    /// [`Spans::path_at`] for many offsets: the values are nested (each
    /// inside its parent), so sorted once they answer each offset by a
    /// binary search and a climb up its parents, where `path_at` looks at
    /// every value (64,000 misspelt fields took minutes).
    pub fn nesting(&self) -> Nesting<'_> {
        let mut entries: Vec<(&str, &Range<usize>)> = self.values().collect();
        // Enclosing values first: by start, longer first, then the shorter
        // path (of two with one range, `path_at` prefers the longer path).
        entries.sort_by_key(|(p, r)| (r.start, std::cmp::Reverse(r.end), p.len(), *p));
        let mut parent = Vec::with_capacity(entries.len());
        let mut open: Vec<usize> = Vec::new();
        let mut nested = true;
        for (i, (_, r)) in entries.iter().enumerate() {
            while let Some(&top) = open.last() {
                let t = entries[top].1;
                if r.end <= t.end {
                    break;
                }
                nested &= t.end <= r.start;
                open.pop();
            }
            parent.push(open.last().copied());
            open.push(i);
        }
        Nesting {
            entries,
            parent,
            nested,
            spans: self,
        }
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

/// The values of a [`Spans`] in document order with their parents; see
/// [`Spans::nesting`].
pub struct Nesting<'a> {
    entries: Vec<(&'a str, &'a Range<usize>)>,
    parent: Vec<Option<usize>>,
    /// Whether no two values overlap without one holding the other (always,
    /// for spans read from one tree; otherwise lookups fall back to
    /// `path_at`).
    nested: bool,
    spans: &'a Spans,
}

impl Nesting<'_> {
    /// The same answer as [`Spans::path_at`].
    pub fn path_at(&self, offset: usize) -> Option<String> {
        if !self.nested {
            return self.spans.path_at(offset);
        }
        let last = self.entries.partition_point(|(_, r)| r.start <= offset);
        let mut at = last.checked_sub(1);
        while let Some(i) = at {
            if self.entries[i].1.contains(&offset) {
                return Some(self.entries[i].0.to_string());
            }
            at = self.parent[i];
        }
        None
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

    /// The sorted lookup gives `path_at`'s answer at every byte, in RON, in
    /// JSON (whose variant layers share a path) and in broken text.
    #[test]
    fn spans_nesting_agrees_with_path_at_everywhere() {
        let json = r#"{"objects": [{"Sphere": {"center": [0, 0, 0], "radius": -1}}, {"Quad": {}}]}"#;
        let broken = "Scene(objects: [Sphere(radius: 1) Sphere(radius: ), (a: [1 2]";
        for src in [SRC, json, broken] {
            let s = Spans::scan(src);
            let n = s.nesting();
            for offset in 0..=src.len() + 1 {
                assert_eq!(n.path_at(offset), s.path_at(offset), "byte {offset} of {src}");
            }
        }
    }

    #[test]
    fn spans_find_falls_back_to_ancestor() {
        let s = Spans::scan(SRC);
        assert_eq!(s.find("objects[1].missing"), s.get("objects[1]"));
    }
}
