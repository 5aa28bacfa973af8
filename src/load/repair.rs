//! A broken list element or map entry read again with its broken fields
//! replaced, so that its other fields are still checked in the same run
//! (issue 46: `Sphere(center: (0, 0), radius: 1, material: "bal")` reported
//! the short `center` and hid the unknown material).
//!
//! The field holding the parse error is found by its span; its value is
//! replaced by the first stand-in that makes the entry parse (a number, a
//! vector, a string, an empty list or struct), or, for an unknown field,
//! the field is left out. Up to [`MAX_REPAIRS`] fields are repaired. The
//! repaired fields are returned so that the checks say nothing about their
//! stand-in values: their parse error was reported already.

use super::format::Format;
use super::slip::Slip;
use crate::syntax::spans::Spans;
use serde::de::DeserializeOwned;
use std::ops::Range;

/// Most fields replaced in one entry.
const MAX_REPAIRS: usize = 4;

/// Values tried in place of a broken one, in order.
const STAND_INS: &[&str] = &["1", "(0.25, 0.5, 0.75)", "\"\"", "[]", "()", "true", "(1, 0.5)"];

/// An entry read with some of its fields repaired.
pub(super) struct Repaired<V> {
    pub value: V,
    /// The fields that hold stand-ins.
    pub fields: Vec<String>,
    /// The parse errors found after the first (each in its own field),
    /// located in the file's text.
    pub slips: Vec<Slip>,
}

/// The entry at `value` of `text`, which does not parse, with the fields
/// named by its parse errors replaced or left out. `None` when no repair
/// makes it parse (a missing field, a wrong variant).
pub(super) fn repaired<V: DeserializeOwned>(
    format: &Format,
    text: &str,
    value: &Range<usize>,
) -> Option<Repaired<V>> {
    if matches!(format, Format::Json) {
        return None;
    }
    let mut entry = text.get(value.clone())?.to_string();
    let mut fields = Vec::new();
    let mut slips = Vec::new();
    // (end of an edit in the edited text, bytes it added), in order.
    let mut edits: Vec<(usize, isize)> = Vec::new();
    let original = |at: usize, edits: &[(usize, isize)]| {
        let added: isize = edits.iter().filter(|(end, _)| *end <= at).map(|(_, d)| d).sum();
        (at as isize - added).max(0) as usize + value.start
    };
    for round in 0..MAX_REPAIRS {
        let slip = match format.read::<V>(&entry, 0..entry.len()) {
            Ok(_) if fields.is_empty() => return None,
            Ok(v) => {
                return Some(Repaired {
                    value: v,
                    fields,
                    slips,
                });
            }
            Err(slip) => slip,
        };
        if round > 0 {
            let span = original(slip.span.start, &edits)..original(slip.span.end, &edits);
            slips.push(Slip::new(span, slip.message.clone(), slip.help.clone()));
        }
        let spans = Spans::scan(&entry);
        let path = spans.path_at(slip.span.start)?;
        let field = path
            .split(['.', '['])
            .next()
            .filter(|f| !f.is_empty())?
            .to_string();
        if fields.contains(&field) {
            return None;
        }
        let at = spans.get(&field)?;
        let (next, end) = STAND_INS
            .iter()
            .map(|s| (format!("{}{s}{}", &entry[..at.start], &entry[at.end..]), at.end))
            .find(|(t, _)| fits::<V>(format, t, &field))
            .or_else(|| without(&entry, &spans, &field))?;
        let added = next.len() as isize - entry.len() as isize;
        edits.push(((end as isize + added) as usize, added));
        entry = next;
        fields.push(field);
    }
    None
}

/// `entry` without the field `field` (its key, value and a following
/// comma), and the end of the range removed.
fn without(entry: &str, spans: &Spans, field: &str) -> Option<(String, usize)> {
    let key = spans.get(&format!("{field}#key"))?;
    let value = spans.get(field)?;
    let rest = &entry[value.end..];
    let comma = rest.len() - rest.trim_start().len();
    let end = if rest.trim_start().starts_with(',') {
        value.end + comma + 1
    } else {
        value.end
    };
    Some((format!("{}{}", &entry[..key.start], &entry[end..]), end))
}

/// Whether a stand-in for `field` is taken: the entry `text` parses with
/// it, or what fails next is another field (which the next round repairs).
fn fits<V: DeserializeOwned>(format: &Format, text: &str, field: &str) -> bool {
    match format.read::<V>(text, 0..text.len()) {
        Ok(_) => true,
        Err(slip) => Spans::scan(text).path_at(slip.span.start).is_some_and(|p| {
            p.split(['.', '['])
                .next()
                .is_some_and(|f| !f.is_empty() && f != field)
        }),
    }
}
