//! The skeleton of a scene file: its top-level fields and, for list and map
//! fields, their elements and entries, each as a byte range of the text.
//!
//! This is what lets one broken entry be reported without hiding the next:
//! each range is deserialised on its own ([`super::sections`]). It reads the
//! same tokens as [`super::spans`], for RON (`Scene(camera: …, objects:
//! [Sphere(…), …])`) and JSON (`{"camera": …, "objects": [{"Sphere": …}]}`)
//! alike, and is only asked once the brackets are known to pair up.

use super::tokens::{Tok, skip_value, tokenize};
use std::ops::Range;

/// A top-level field, or an element or entry of one.
#[derive(Debug)]
pub(super) struct Entry {
    /// The name and where it is written (`camera`, `"white"`); elements of a
    /// list have none.
    pub key: Option<(String, Range<usize>)>,
    pub value: Range<usize>,
    /// Elements of a `[…]` value, or entries of a `{…}` value.
    pub items: Vec<Entry>,
}

#[derive(Debug)]
pub(super) struct Outline {
    /// The opening bracket of the file's value, where a missing field is
    /// reported.
    pub open: Range<usize>,
    pub fields: Vec<Entry>,
    /// Where a `,` is missing between two fields, elements or entries.
    pub missing_commas: Vec<Range<usize>>,
}

type Toks = [(Tok, Range<usize>)];

impl Outline {
    /// The outline of `text`, or `None` when its top level is not a struct
    /// of `name: value` fields (then only the whole-file error can be told).
    pub fn of(text: &str) -> Option<Outline> {
        let toks = tokenize(text);
        let mut i = 0;
        if matches!(toks.first(), Some((Tok::Atom { ident: true, .. }, _)))
            && matches!(toks.get(1), Some((Tok::Open('('), _)))
        {
            i = 1;
        }
        let open = toks.get(i)?.1.clone();
        if !matches!(toks[i].0, Tok::Open('(') | Tok::Open('{')) {
            return None;
        }
        let mut missing_commas = Vec::new();
        let (fields, end) = group(&toks, i, true, &mut missing_commas)?;
        if end < toks.len() {
            return None; // trailing text: the whole-file error says so
        }
        Some(Outline {
            open,
            fields,
            missing_commas,
        })
    }
}

/// The entries of the group opened at token `open`, and the token after its
/// close. `keyed`: entries are `key: value` (structs, maps), else values.
fn group(
    toks: &Toks,
    open: usize,
    keyed: bool,
    commas: &mut Vec<Range<usize>>,
) -> Option<(Vec<Entry>, usize)> {
    let mut entries = Vec::new();
    let mut i = open + 1;
    loop {
        match toks.get(i)? {
            (Tok::Close(_), _) => return Some((entries, i + 1)),
            (Tok::Comma, _) if !entries.is_empty() => {
                i += 1;
                continue;
            }
            _ => {}
        }
        let key = if keyed {
            match (toks.get(i)?, toks.get(i + 1)?) {
                ((Tok::Atom { text, .. }, at), (Tok::Colon, _)) => {
                    i += 2;
                    Some((text.clone(), at.clone()))
                }
                _ => return None,
            }
        } else {
            None
        };
        let (entry, next) = value(toks, i, key, commas)?;
        entries.push(entry);
        i = next;
        match toks.get(i)? {
            (Tok::Comma | Tok::Close(_), _) => {}
            (_, at) => commas.push(at.clone()),
        }
    }
}

/// The value starting at token `i`, with its items if it is a list or map.
fn value(
    toks: &Toks,
    i: usize,
    key: Option<(String, Range<usize>)>,
    commas: &mut Vec<Range<usize>>,
) -> Option<(Entry, usize)> {
    let next = skip_value(toks, i).max(i + 1);
    let start = toks.get(i)?.1.start;
    let end = toks.get(next - 1)?.1.end;
    let items = match toks[i].0 {
        Tok::Open('[') => group(toks, i, false, commas),
        Tok::Open('{') => group(toks, i, true, commas),
        _ => None,
    };
    let entry = Entry {
        key,
        value: start..end,
        items: items.map(|(items, _)| items).unwrap_or_default(),
    };
    Some((entry, next))
}

#[cfg(test)]
mod tests {
    use super::Outline;

    #[test]
    fn outline_splits_fields_elements_and_entries() {
        let text = "Scene(\n camera: (eye: (0, 0, 1)),\n materials: { \"a\": Lambert(albedo: 1), \"b\": Mirror() },\n objects: [Sphere(radius: 1) Sphere(radius: 2),],\n)";
        let o = Outline::of(text).expect("an outline");
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
        let o = Outline::of(text).expect("an outline");
        assert_eq!(o.fields.len(), 2);
        assert_eq!(&text[o.fields[1].items[1].value.clone()], r#"{"Quad": {}}"#);
        assert!(Outline::of("[1, 2]").is_none());
    }
}
