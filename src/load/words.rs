//! Parser errors in the user's words.
//!
//! ron and serde describe what they expected in Rust terms (`u32`, `struct
//! CameraDesc`, `enum MaterialDesc`) and name the Rust type around a bad
//! field. A scene author never sees those types: they wrote `spp: 3.5` or
//! `Glas(…)`. Here each error becomes a message about what was written and a
//! help line with the likely fix; where a Rust name survives it is replaced
//! by the scene word for it or dropped (the diagnostic's path already says
//! where, e.g. `camera`).

use crate::diagnostic::suggest;

/// A ron error as a message and a help line; `at` is the text from the
/// error's position on (to quote the offending token).
pub(super) fn ron_error(e: &ron::Error, at: &str) -> (String, Option<String>) {
    use ron::Error as E;
    let within = |outer: &Option<String>| match outer {
        // A variant the user wrote (`Sphere`) helps; a Rust type name does not.
        Some(o) if !o.ends_with("Desc") => format!(" in `{o}`"),
        _ => String::new(),
    };
    match e {
        E::NoSuchStructField {
            expected,
            found,
            outer,
        } => unknown("field", found, expected, &within(outer)),
        E::NoSuchEnumVariant { expected, found, .. } => unknown("variant", found, expected, ""),
        E::MissingStructField { field, outer } => missing(field, &within(outer)),
        E::DuplicateStructField { field, .. } => twice(field),
        E::ExpectedComma if decimal_at(at) => (
            "expected a whole number, found a decimal point".into(),
            Some("this field counts something: write it without a decimal point".into()),
        ),
        E::ExpectedComma => (
            "expected `,`".into(),
            Some("separate fields, elements and entries with commas".into()),
        ),
        E::Eof => (
            "unexpected end of the text".into(),
            Some("the value is not finished: a field or element is missing".into()),
        ),
        E::ExpectedDifferentLength { expected, found } => (
            format!("expected {}, found {found}", plain(expected)),
            Some("vectors and colours are written `(x, y, z)`".into()),
        ),
        E::IntegerOutOfBounds => (
            format!("`{}` is out of range here", token(at)),
            Some("this field takes a whole number from 0 up".into()),
        ),
        E::InvalidValueForType { expected, found } => {
            (format!("expected {}, found {found}", plain(expected)), None)
        }
        E::ExpectedDifferentStructName { expected, found } => (
            format!("expected `{expected}(…)`, found `{found}`"),
            Some(format!("the file starts with `{expected}(` or just `(`")),
        ),
        E::ExpectedIdentifier => ("expected a field or variant name".into(), None),
        E::ExpectedNamedStructLike(_) | E::ExpectedStructLike => ("expected `(` and its fields".into(), None),
        E::ExpectedArray => ("expected a list `[…]`".into(), None),
        E::ExpectedMap => ("expected a map `{…}`".into(), None),
        E::ExpectedMapColon => ("expected `:`".into(), None),
        E::ExpectedArrayEnd => ("expected `]`".into(), None),
        E::ExpectedMapEnd => ("expected `}`".into(), None),
        E::ExpectedStructLikeEnd | E::ExpectedOptionEnd => ("expected `)`".into(), None),
        E::UnexpectedChar(c) => (format!("unexpected `{c}`"), None),
        E::TrailingCharacters => (
            "unexpected text after the end".into(),
            Some("the file holds one value: remove what follows its closing bracket".into()),
        ),
        E::ExpectedFloat => ("expected a number".into(), None),
        E::ExpectedInteger => ("expected a whole number".into(), None),
        E::ExpectedBoolean => ("expected `true` or `false`".into(), None),
        E::ExpectedString | E::ExpectedStringEnd => (
            "expected a string in double quotes".into(),
            Some("write names and file paths as \"text\"".into()),
        ),
        E::Message(m) => serde_message(m),
        other => (sentence(&scrub(&other.to_string())), None),
    }
}

/// A serde message (serde_json's, or a custom one through ron): `invalid
/// type: string "x", expected f32` and the like, without its position.
pub(super) fn serde_message(full: &str) -> (String, Option<String>) {
    let m = full.rsplit_once(" at line ").map_or(full, |(m, _)| m);
    let names = |s: &str| {
        s.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    if let Some(rest) = m
        .strip_prefix("unknown field ")
        .or(m.strip_prefix("unknown variant "))
    {
        let kind = if m.starts_with("unknown field") {
            "field"
        } else {
            "variant"
        };
        let quoted = names(rest);
        if let Some((found, expected)) = quoted.split_first() {
            let expected: Vec<&str> = expected.iter().map(String::as_str).collect();
            return unknown(kind, found, &expected, "");
        }
    }
    if let Some(field) = m.strip_prefix("missing field ").map(names) {
        return missing(field.first().map_or("", String::as_str), "");
    }
    if let Some(field) = m.strip_prefix("duplicate field ").map(names) {
        return twice(field.first().map_or("", String::as_str));
    }
    if let Some((found, expected)) = m
        .strip_prefix("invalid type: ")
        .and_then(|r| r.split_once(", expected "))
    {
        return (format!("expected {}, found {found}", plain(expected)), None);
    }
    if let Some((found, expected)) = m
        .strip_prefix("invalid value: ")
        .and_then(|r| r.split_once(", expected "))
    {
        return (
            format!("{found} is out of range: expected {}", plain(expected)),
            None,
        );
    }
    if let Some((n, expected)) = m
        .strip_prefix("invalid length ")
        .and_then(|r| r.split_once(", expected "))
    {
        return (format!("expected {}, found {n} values", plain(expected)), None);
    }
    if m == "trailing comma" {
        let help = "JSON allows no `,` after the last element or field";
        return ("trailing comma".into(), Some(help.into()));
    }
    (scrub(m), None)
}

pub(super) fn unknown(kind: &str, found: &str, expected: &[&str], within: &str) -> (String, Option<String>) {
    let list = expected
        .iter()
        .map(|x| format!("`{x}`"))
        .collect::<Vec<_>>()
        .join(", ");
    let help = match suggest(found, expected.iter().copied()) {
        Some(s) => format!("did you mean `{s}`?"),
        None if expected.is_empty() => format!("this {kind} takes nothing here"),
        None => format!("expected one of {list}"),
    };
    (format!("unknown {kind} `{found}`{within}"), Some(help))
}

fn missing(field: &str, within: &str) -> (String, Option<String>) {
    (
        format!("missing field `{field}`{within}"),
        Some(format!("add `{field}: ...`")),
    )
}

fn twice(field: &str) -> (String, Option<String>) {
    (
        format!("field `{field}` is given twice"),
        Some("keep one of them".into()),
    )
}

/// What serde says it expected, in scene terms.
pub(super) fn plain(expected: &str) -> String {
    let variant = ["struct variant ", "tuple variant ", "newtype variant "]
        .iter()
        .find_map(|p| expected.strip_prefix(p));
    if let Some(v) = variant {
        return format!("`{}(…)`", v.rsplit("::").next().unwrap_or(v));
    }
    if let Some(v) = expected.strip_prefix("unit variant ") {
        return format!("`{}`", v.rsplit("::").next().unwrap_or(v));
    }
    match expected {
        "u8" | "u16" | "u32" | "u64" | "usize" => "a whole number ≥ 0".into(),
        "i8" | "i16" | "i32" | "i64" | "isize" => "a whole number".into(),
        "f32" | "f64" => "a number".into(),
        "a boolean" | "bool" => "`true` or `false`".into(),
        "a string" => "a string in double quotes".into(),
        "a sequence" => "a list `[…]`".into(),
        "a map" => "a map `{…}`".into(),
        "option" => "a value or `None`".into(),
        "unit" => "`()`".into(),
        e if e.starts_with("struct ") => "a group of fields".into(),
        e if e.starts_with("enum ") => "one of its variants".into(),
        e => match e.strip_prefix("an array of length ") {
            Some(n) => format!("{n} values"),
            None => scrub(e),
        },
    }
}

/// Replaces Rust type names that reach a message (`CameraDesc`) by the
/// scene's word for them.
pub(super) fn scrub(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find("Desc") {
        let head = &rest[..i];
        let start = head
            .rfind(|c: char| !c.is_alphanumeric() && c != '_')
            .map_or(0, |k| k + head[k..].chars().next().map_or(1, char::len_utf8));
        let name = &head[start..];
        let after = &rest[i + 4..];
        let whole_word = !after.starts_with(|c: char| c.is_alphanumeric() || c == '_');
        out.push_str(&head[..start]);
        if whole_word && name.starts_with(|c: char| c.is_ascii_uppercase()) {
            out.push_str(&scene_word(name));
        } else {
            out.push_str(name);
            out.push_str("Desc");
        }
        rest = after;
    }
    out.push_str(rest);
    out
}

/// `Camera` (of `CameraDesc`) → `camera`; `LightSelection` → `light selection`.
fn scene_word(name: &str) -> String {
    match name {
        "Scene" => "the scene".into(),
        "Include" => "the included file".into(),
        "Sdf" => "an SDF shape".into(),
        _ => {
            let mut w = String::new();
            for (i, c) in name.chars().enumerate() {
                if c.is_uppercase() && i > 0 {
                    w.push(' ');
                }
                w.extend(c.to_lowercase());
            }
            w
        }
    }
}

/// ron capitalises its messages; ours continue `path: `.
fn sentence(m: &str) -> String {
    let mut c = m.chars();
    c.next()
        .map_or(String::new(), |f| f.to_lowercase().chain(c).collect())
}

/// The atom at the start of `at`: a number, a name.
fn token(at: &str) -> &str {
    let end = at
        .find(|c: char| c.is_whitespace() || "()[]{}:,\"".contains(c))
        .unwrap_or(at.len());
    &at[..end]
}

/// `at` starts with the fraction of a number (`.5` after `3`).
fn decimal_at(at: &str) -> bool {
    let mut c = at.chars();
    c.next() == Some('.') && c.next().is_some_and(|d| d.is_ascii_digit())
}

/// Characters that look right in a word processor but are not RON or JSON,
/// with the fix, when the error sits on one.
pub(super) fn odd_character(at: &str) -> Option<String> {
    let c = at.chars().next()?;
    let name = match c {
        '\u{201c}' | '\u{201d}' | '\u{201e}' | '\u{ab}' | '\u{bb}' => "a typographic double quote",
        '\u{2018}' | '\u{2019}' | '\u{201a}' => "a typographic single quote",
        '\u{a0}' | '\u{202f}' | '\u{2007}' => "a non-breaking space",
        '\u{feff}' => "a byte-order mark",
        '\u{200b}' => "a zero-width space",
        c if c.is_whitespace() && !c.is_ascii() => "an unusual space",
        _ => return None,
    };
    let fix = if name.contains("quote") {
        "replace it with a plain `\"`"
    } else {
        "replace it with a plain space"
    };
    Some(format!("this is {name} (U+{:04X}); {fix}", c as u32))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_never_name_rust_types() {
        assert_eq!(plain("struct variant MaterialDesc::Lambert"), "`Lambert(…)`");
        assert_eq!(plain("u32"), "a whole number ≥ 0");
        assert_eq!(plain("struct CameraDesc"), "a group of fields");
        assert_eq!(
            scrub("bad CameraDesc in LightSelectionDesc."),
            "bad camera in light selection."
        );
        assert_eq!(scrub("Description of Descent"), "Description of Descent");
        let (m, _) = serde_message("invalid type: string \"x\", expected f32 at line 3 column 9");
        assert_eq!(m, "expected a number, found string \"x\"");
    }

    #[test]
    fn words_suggest_variants_like_fields() {
        let (m, h) = serde_message("unknown variant `Glas`, expected one of `Lambert`, `Glass`");
        assert_eq!(m, "unknown variant `Glas`");
        assert_eq!(h.as_deref(), Some("did you mean `Glass`?"));
        let (_, h) = serde_message("unknown field `zzz`, expected one of `eye`, `target`");
        assert_eq!(h.as_deref(), Some("expected one of `eye`, `target`"));
    }
}
