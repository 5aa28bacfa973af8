//! Where each value of a RON document sits, by scene path.
//!
//! serde forgets positions once a value is parsed, yet a semantic error must
//! point at the line that caused it. This is a small structural scan of the
//! RON text (it does not interpret values) that records the byte range of
//! every value under the same path syntax [`crate::diagnostic::Problem`] uses:
//! `objects[3].material`, `materials.white.albedo`. Enum variant and struct
//! names are transparent, as they are in the paths.

use super::tokens::{Tok, skip_value, tokenize};
use std::collections::HashMap;
use std::ops::Range;

/// Byte ranges of a document's values by scene path.
#[derive(Debug, Default)]
pub struct Spans {
    map: HashMap<String, Range<usize>>,
}

impl Spans {
    /// Scans `src`; a malformed document yields whatever was scanned before
    /// the malformation (serde reports the syntax error itself).
    pub fn scan(src: &str) -> Self {
        let toks = tokenize(src);
        let mut s = Scanner {
            toks,
            pos: 0,
            map: HashMap::new(),
        };
        s.value("");
        Spans { map: s.map }
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
}

/// The values of a [`Spans`] in document order with their parents; see
/// [`Spans::nesting`].
pub struct Nesting<'a> {
    entries: Vec<(&'a str, &'a Range<usize>)>,
    parent: Vec<Option<usize>>,
    /// Whether no two values overlap without one holding the other (always,
    /// for the scanner's spans; otherwise lookups fall back to `path_at`).
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

struct Scanner {
    toks: Vec<(Tok, Range<usize>)>,
    pos: usize,
    map: HashMap<String, Range<usize>>,
}

impl Scanner {
    fn peek(&self, k: usize) -> Option<&Tok> {
        self.toks.get(self.pos + k).map(|t| &t.0)
    }

    fn end_of_prev(&self) -> usize {
        self.pos
            .checked_sub(1)
            .and_then(|p| self.toks.get(p))
            .map_or(0, |t| t.1.end)
    }

    /// One value at `path`; records its span.
    fn value(&mut self, path: &str) {
        let Some(start) = self.toks.get(self.pos).map(|t| t.1.start) else {
            return;
        };
        match self.peek(0).cloned() {
            Some(Tok::Atom { ident: true, .. }) if self.peek(1) == Some(&Tok::Open('(')) => {
                self.pos += 1; // variant or struct name: transparent in paths
                self.group(path, ')');
            }
            Some(Tok::Open(c)) => {
                let close = match c {
                    '(' => ')',
                    '[' => ']',
                    _ => '}',
                };
                self.group(path, close);
            }
            Some(Tok::Atom { .. }) => self.pos += 1,
            _ => {
                self.pos += 1;
                return;
            }
        }
        let end = self.end_of_prev();
        // A value seen again under the same path is either its own outer
        // layer (JSON's `{"Sphere": {…}}`: the whole wins) or a repeated
        // field (the first wins).
        let span = self.map.entry(path.to_string()).or_insert(start..end);
        if start <= span.start && end >= span.end {
            *span = start..end;
        }
    }

    /// The inside of `( … )`, `[ … ]` or `{ … }`, opening token current.
    fn group(&mut self, path: &str, close: char) {
        self.pos += 1;
        let mut index = 0;
        loop {
            match self.peek(0).cloned() {
                None => return,
                Some(Tok::Close(_)) => {
                    self.pos += 1;
                    return;
                }
                Some(Tok::Comma) => {
                    self.pos += 1;
                    continue;
                }
                _ => {}
            }
            let keyed = matches!(self.peek(0), Some(Tok::Atom { .. })) && self.peek(1) == Some(&Tok::Colon);
            if keyed && close != ']' {
                let Some((Tok::Atom { text, .. }, key_span)) = self.toks.get(self.pos).cloned() else {
                    return;
                };
                // JSON writes enum variants as `{"Sphere": {...}}`: a lone
                // capitalised key is a variant name, transparent in paths.
                let variant = close == '}'
                    && text.starts_with(|c: char| c.is_ascii_uppercase())
                    && self.pos > 0
                    && self.toks.get(self.pos - 1).is_some_and(|t| t.0 == Tok::Open('{'))
                    && self
                        .toks
                        .get(skip_value(&self.toks, self.pos + 2))
                        .is_some_and(|t| matches!(t.0, Tok::Close(_)));
                let child = if variant {
                    path.to_string()
                } else {
                    join(path, &text)
                };
                self.pos += 2;
                self.map.insert(format!("{child}#key"), key_span);
                self.value(&child);
            } else {
                let before = self.pos;
                self.value(&format!("{path}[{index}]"));
                index += 1;
                if self.pos == before {
                    self.pos += 1;
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
