//! The skeleton of a scene file: its top-level fields and, for list and map
//! fields, their elements and entries, each as a byte range of the text.
//!
//! This is what lets one broken entry be reported without hiding the next:
//! the loader deserialises each range on its own. It is a view of the
//! [`super::tree`], as [`super::spans`] is, for RON (`Scene(camera: …,
//! objects: [Sphere(…), …])`) and JSON (`{"camera": …, "objects":
//! [{"Sphere": …}]}`) alike, and is only asked once the brackets are known
//! to pair up.

use super::lex::unquote;
use super::tree::{Entry as Node, Fault, Group, Piece, Read};
use std::ops::Range;

/// A top-level field, or an element or entry of one.
#[derive(Debug)]
pub struct Entry {
    /// The name and where it is written (`camera`, `"white"`); elements of a
    /// list have none.
    pub key: Option<(String, Range<usize>)>,
    /// Where its value is written.
    pub value: Range<usize>,
    /// Elements of a `[…]` value, or entries of a `{…}` value.
    pub items: Vec<Entry>,
}

/// The fields of a file and where a comma is missing between its parts.
#[derive(Debug)]
pub struct Outline {
    /// The opening bracket of the file's value, where a missing field is
    /// reported.
    pub open: Range<usize>,
    /// The top-level fields, in order.
    pub fields: Vec<Entry>,
    /// Where a `,` is missing between two fields, elements or entries.
    pub missing_commas: Vec<Range<usize>>,
}

impl Outline {
    /// The outline of a tree, or `None` when its top level is not one
    /// struct of `name: value` fields (then only the whole-file error can
    /// be told).
    pub fn of(tree: &Read) -> Option<Outline> {
        // Text outside the top value: the whole-file error says so.
        if tree.faults.iter().any(|f| matches!(f, Fault::Stray { .. })) {
            return None;
        }
        let mut values = tree.values();
        let (top, None) = (values.next()?, values.next()) else {
            return None;
        };
        let g = match top.value().as_slice() {
            [Piece::Atom(name), Piece::Group(g)] if is_ident(&name.text) && g.open == '(' => g,
            [Piece::Group(g)] if g.open != '[' => g,
            _ => return None,
        };
        let mut missing_commas = Vec::new();
        let fields = group(g, true, &mut missing_commas)?;
        Some(Outline {
            open: g.span.start..g.span.start + 1,
            fields,
            missing_commas,
        })
    }
}

/// The entries of `g`. `keyed`: entries are `key: value` (structs, maps),
/// and one without a key makes the group unreadable.
fn group(g: &Group, keyed: bool, commas: &mut Vec<Range<usize>>) -> Option<Vec<Entry>> {
    let mut entries = Vec::new();
    for e in &g.entries {
        let key = match e.key() {
            Some(k) if keyed => Some((unquote(&k.text).to_string(), k.span.clone())),
            _ if keyed => return None,
            _ => None,
        };
        entries.push(entry(e, key, commas)?);
        commas.extend(e.missing_comma.clone());
    }
    Some(entries)
}

/// The value of `e`, with its items if it is a list or map.
fn entry(e: &Node, key: Option<(String, Range<usize>)>, commas: &mut Vec<Range<usize>>) -> Option<Entry> {
    let value = if key.is_some() {
        e.value_span()?
    } else {
        let all: Vec<&Piece> = e
            .pieces
            .iter()
            .filter(|p| !matches!(p, Piece::Comment(_)))
            .collect();
        all.first()?.span().start..all.last()?.span().end
    };
    let items = match e.value().as_slice() {
        [Piece::Group(g)] if key.is_some() || e.key().is_none() => match g.open {
            '[' => group(g, false, commas),
            '{' => group(g, true, commas),
            _ => None,
        },
        _ => None,
    };
    Some(Entry {
        key,
        value,
        items: items.unwrap_or_default(),
    })
}

/// `Scene`, `_x`: a name that may stand before `(`.
fn is_ident(text: &str) -> bool {
    text.starts_with(|c: char| c.is_alphabetic() || c == '_')
}

#[cfg(test)]
mod tests {
    use super::Outline;
    use crate::syntax::parser::read;

    #[test]
    fn outline_splits_fields_elements_and_entries() {
        let text = "Scene(\n camera: (eye: (0, 0, 1)),\n materials: { \"a\": Lambert(albedo: 1), \"b\": Mirror() },\n objects: [Sphere(radius: 1) Sphere(radius: 2),],\n)";
        let o = Outline::of(&read(text)).expect("an outline");
        let names: Vec<&str> = o
            .fields
            .iter()
            .filter_map(|f| f.key.as_ref())
            .map(|k| k.0.as_str())
            .collect();
        assert_eq!(names, ["camera", "materials", "objects"]);
        assert_eq!(&text[o.fields[0].value.clone()], "(eye: (0, 0, 1))");
        let m = &o.fields[1].items;
        assert_eq!(m.len(), 2);
        assert_eq!(&text[m[1].value.clone()], "Mirror()");
        let objects = &o.fields[2].items;
        assert_eq!(&text[objects[1].value.clone()], "Sphere(radius: 2)");
        assert_eq!(o.missing_commas.len(), 1);
        assert_eq!(
            o.missing_commas[0].start,
            text.find("Sphere(radius: 2)").unwrap_or(0)
        );
    }

    #[test]
    fn outline_reads_json() {
        let text = r#"{"camera": {"eye": [0, 0, 1]}, "objects": [{"Sphere": {"radius": 1}}, {"Quad": {}}]}"#;
        let o = Outline::of(&read(text)).expect("an outline");
        assert_eq!(o.fields.len(), 2);
        assert_eq!(&text[o.fields[1].items[1].value.clone()], r#"{"Quad": {}}"#);
        assert!(Outline::of(&read("[1, 2]")).is_none());
    }
}
