//! Hover: a key shows its field's documentation, type, default and range; a
//! variant name shows the variant's; a value shows its field's; a material
//! or mesh name shows where it is defined.

use super::schema::Schema;
use crate::syntax::cursor::{self, Step};
use crate::syntax::lex::{Kind, Token, unquote};
use std::ops::Range;

/// Markdown for byte `offset` of `src`, and the range it describes.
pub fn hover(schema: &Schema, src: &str, toks: &[Token], offset: usize) -> Option<(String, Range<usize>)> {
    let cx = cursor::at(src, toks, offset);
    let i = cx.token?;
    let t = &toks[i];
    let text = t.text(src);
    let frame = schema.frame(&cx)?;
    // A key: its field.
    if cx.on_key {
        let key = unquote(text);
        if let Some((_, field)) = schema.fields(frame).into_iter().find(|(k, _)| *k == key) {
            return Some((
                schema.describe(key, field, schema.required(frame, key)),
                t.span.clone(),
            ));
        }
        // A JSON variant tag (`{"Sphere": {...}}`).
        return variant_doc(schema, frame.value, key).map(|d| (d, t.span.clone()));
    }
    // A variant name before its bracket (`Sphere(`) or a unit variant.
    let value = schema.value(&cx);
    if t.kind == Kind::Word
        && let Some(v) = value
        && let Some(doc) = variant_doc(schema, v, text)
    {
        return Some((doc, t.span.clone()));
    }
    // A value: the field it is the value of.
    let Some(Step::Named(key)) = cx.value_step() else {
        return None;
    };
    let (_, field) = schema.fields(frame).into_iter().find(|(k, _)| *k == key)?;
    let mut doc = schema.describe(&key, field, schema.required(frame, &key));
    if t.kind == Kind::Str && (key == "material" || key == "mesh") {
        doc = format!("{} `{}`\n\n---\n\n{doc}", key, unquote(text));
    }
    Some((doc, t.span.clone()))
}

/// Markdown for variant `name` of the enum `v`: its documentation and the
/// fields it takes.
fn variant_doc(schema: &Schema, v: &serde_json::Value, name: &str) -> Option<String> {
    let (_, doc) = schema.variants(v).into_iter().find(|(n, _)| n == name)?;
    let payload = schema.variant(v, name)?;
    let mut s = format!("**`{name}`**: {}", schema.type_name(v));
    if let Some(d) = doc {
        s += &format!("\n\n{d}");
    }
    let p = schema.resolve(payload);
    if let Some(props) = p.get("properties").and_then(serde_json::Value::as_object)
        && !(props.len() == 1 && props.contains_key(name))
    {
        let required: Vec<&str> = p
            .get("required")
            .and_then(serde_json::Value::as_array)
            .map(|r| r.iter().filter_map(serde_json::Value::as_str).collect())
            .unwrap_or_default();
        s += "\n\nfields:";
        for (k, f) in props {
            let req = if required.contains(&k.as_str()) {
                " (required)"
            } else {
                ""
            };
            s += &format!("\n- `{k}`: {}{req}", schema.type_name(f));
        }
    }
    Some(s)
}
