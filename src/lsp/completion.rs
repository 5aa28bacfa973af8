//! Completion: the fields a bracket still lacks, the variants an enum
//! takes, and the scene's own material and mesh names where a name goes.

use super::names::defined;
use super::schema::Schema;
use crate::syntax::cursor::{self, Step, keys_in};
use crate::syntax::lex::{Kind, Token};
use lsp_types::{CompletionItem, CompletionItemKind};

/// What may be written at byte `offset`; `extra` adds names defined outside
/// the text (in included files).
pub fn complete(
    schema: &Schema,
    src: &str,
    toks: &[Token],
    offset: usize,
    json: bool,
    extra: &[(&str, String)],
) -> Vec<CompletionItem> {
    let cx = cursor::at(src, toks, offset);
    let Some(frame) = cx.frame() else {
        return Vec::new();
    };
    let in_string = cx
        .token
        .is_some_and(|i| toks[i].kind == Kind::Str && toks[i].span.start < offset);
    let key = frame.key.clone();
    // A name of the scene's: `material: "…"`, `mesh: "…"`, a medium
    // (`medium`, `interior`, `exterior`), or the value of an object's
    // `materials: { "group": "…" }` map.
    let names_of = match key.as_deref() {
        Some("material") => Some("materials"),
        Some("mesh") => Some("meshes"),
        Some("medium" | "interior" | "exterior") => Some("media"),
        Some(_) if cx.frames.len() > 3 && frame.step == Some(Step::Named("materials".into())) => {
            Some("materials")
        }
        _ => None,
    };
    if let Some(map) = names_of {
        let mut names: Vec<String> = defined(src, toks, map).into_iter().map(|(n, _)| n).collect();
        names.extend(extra.iter().filter(|(m, _)| *m == map).map(|(_, n)| n.clone()));
        names.sort();
        names.dedup();
        return names
            .into_iter()
            .map(|n| CompletionItem {
                insert_text: Some(if in_string { n.clone() } else { format!("\"{n}\"") }),
                label: n,
                kind: Some(CompletionItemKind::REFERENCE),
                detail: Some(format!("defined in `{map}`")),
                ..Default::default()
            })
            .collect();
    }
    if in_string {
        return Vec::new();
    }
    let Some(node) = schema.frame(&cx) else {
        return Vec::new();
    };
    let fields = schema.fields(node);
    // Writing a key: the fields not written yet.
    if key.is_none() && !fields.is_empty() && matches!(frame.open, '(' | '{') {
        let present = keys_in(src, toks, frame.token);
        return fields
            .into_iter()
            .filter(|(k, _)| !present.iter().any(|p| p == k))
            .map(|(k, f)| CompletionItem {
                label: k.to_string(),
                kind: Some(CompletionItemKind::FIELD),
                detail: Some(schema.type_name(f)),
                insert_text: Some(if json {
                    format!("\"{k}\": ")
                } else {
                    format!("{k}: ")
                }),
                documentation: Some(lsp_types::Documentation::MarkupContent(
                    lsp_types::MarkupContent {
                        kind: lsp_types::MarkupKind::Markdown,
                        value: schema.describe(k, f, schema.required(node, k)),
                    },
                )),
                ..Default::default()
            })
            .collect();
    }
    // Writing a value: the variants of its enum.
    let value = if key.is_none() && json && frame.open == '{' {
        Some(node.value) // a JSON variant tag is written as a key
    } else {
        schema.value(&cx)
    };
    value
        .map(|v| schema.variants(v))
        .unwrap_or_default()
        .into_iter()
        .map(|(n, doc)| CompletionItem {
            insert_text: Some(if json { format!("\"{n}\"") } else { n.clone() }),
            label: n,
            kind: Some(CompletionItemKind::ENUM_MEMBER),
            documentation: doc.map(|d| lsp_types::Documentation::String(d.to_string())),
            ..Default::default()
        })
        .collect()
}
