//! Where each value of a RON document sits, by scene path.
//!
//! serde forgets positions once a value is parsed, yet a semantic error must
//! point at the line that caused it. This is a small structural scan of the
//! RON text (it does not interpret values) that records the byte range of
//! every value under the same path syntax [`crate::diagnostic::Problem`] uses:
//! `objects[3].material`, `materials.white.albedo`. Enum variant and struct
//! names are transparent, as they are in the paths.

use std::collections::HashMap;
use std::ops::Range;

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

    /// The span of exactly `path`.
    pub fn get(&self, path: &str) -> Option<Range<usize>> {
        self.map.get(path).cloned()
    }
}

#[derive(Clone, Debug, PartialEq)]
enum Tok {
    Open(char),
    Close(char),
    Colon,
    Comma,
    /// Identifier, number, string, char: anything atomic.
    Atom {
        ident: bool,
        text: String,
    },
}

fn tokenize(src: &str) -> Vec<(Tok, Range<usize>)> {
    let b = src.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        match c {
            b' ' | b'\t' | b'\n' | b'\r' => i += 1,
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                // RON block comments nest.
                let mut depth = 0;
                while i < b.len() {
                    if b[i] == b'/' && b.get(i + 1) == Some(&b'*') {
                        depth += 1;
                        i += 2;
                    } else if b[i] == b'*' && b.get(i + 1) == Some(&b'/') {
                        depth -= 1;
                        i += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        i += 1;
                    }
                }
            }
            b'#' => {
                // `#![enable(...)]` and similar attributes: skip to the `]`.
                while i < b.len() && b[i] != b']' {
                    i += 1;
                }
                i += 1;
            }
            b'(' | b'[' | b'{' => {
                out.push((Tok::Open(c as char), i..i + 1));
                i += 1;
            }
            b')' | b']' | b'}' => {
                out.push((Tok::Close(c as char), i..i + 1));
                i += 1;
            }
            b':' => {
                out.push((Tok::Colon, i..i + 1));
                i += 1;
            }
            b',' => {
                out.push((Tok::Comma, i..i + 1));
                i += 1;
            }
            b'"' | b'\'' => {
                let start = i;
                i += 1;
                while i < b.len() && b[i] != c {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i = (i + 1).min(b.len());
                let text = src[start + 1..i.saturating_sub(1).max(start + 1)].to_string();
                out.push((Tok::Atom { ident: false, text }, start..i));
            }
            b'r' if matches!(b.get(i + 1), Some(b'"') | Some(b'#')) => {
                // Raw string r#"..."#.
                let start = i;
                i += 1;
                let mut hashes = 0;
                while i < b.len() && b[i] == b'#' {
                    hashes += 1;
                    i += 1;
                }
                i += 1;
                let body = i;
                let close = format!("\"{}", "#".repeat(hashes));
                let end = src[i..].find(&close).map_or(b.len(), |k| i + k);
                i = (end + close.len()).min(b.len());
                out.push((
                    Tok::Atom {
                        ident: false,
                        text: src[body..end].to_string(),
                    },
                    start..i,
                ));
            }
            _ => {
                let start = i;
                while i < b.len() && !b" \t\r\n()[]{}:,\"'/#".contains(&b[i]) {
                    i += 1;
                }
                if i == start {
                    i += 1;
                }
                let text = &src[start..i];
                let ident = text.chars().next().is_some_and(|c| c.is_alphabetic() || c == '_');
                out.push((
                    Tok::Atom {
                        ident,
                        text: text.to_string(),
                    },
                    start..i,
                ));
            }
        }
    }
    out
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
        self.map.entry(path.to_string()).or_insert(start..end);
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
                        .get(self.skip_value(self.pos + 2))
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

impl Scanner {
    /// Token index just past the value starting at `i`.
    fn skip_value(&self, mut i: usize) -> usize {
        let mut depth = 0i32;
        while let Some((t, _)) = self.toks.get(i) {
            match t {
                Tok::Open(_) => depth += 1,
                Tok::Close(_) => {
                    depth -= 1;
                    if depth < 0 {
                        return i;
                    }
                    if depth == 0 {
                        return i + 1;
                    }
                }
                Tok::Atom { ident: true, .. }
                    if depth == 0 && matches!(self.toks.get(i + 1), Some((Tok::Open('('), _))) => {}
                _ if depth == 0 => return i + 1,
                _ => {}
            }
            i += 1;
        }
        i
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
