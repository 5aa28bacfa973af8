//! Scene-format versions and `ronray migrate`: bringing a scene file written
//! for an older format to the current one, as a text edit that keeps every
//! comment, spelling and layout the author wrote.
//!
//! | version | what changed |
//! |---|---|
//! | 1 | the format before issue 40 (a file without `version` is read as this) |
//! | 2 | every number and emission radiance may be a texture; nothing renamed |
//!
//! A step from version `n` to `n + 1` is one entry of [`STEPS`]: its
//! rewrites, as edits of the token stream (renaming a key, wrapping a value),
//! come back as [`Edit`]s so the rest of the file stays byte for byte. Step
//! 1 → 2 has none: version 2 only added forms, so a version 1 file means the
//! same under version 2, loads without a warning, and `migrate` only stamps
//! it. A later step that renames something lists its edits here, and the
//! loader will warn about files it would change, naming `ronray migrate`.
//!
//! ```
//! let old = "Scene(\n    // the lens\n    camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n)\n";
//! let m = ronray::migrate::migrate_text(old).unwrap();
//! assert_eq!((m.from, m.to), (1, ronray::migrate::CURRENT));
//! assert!(m.text.starts_with("Scene(\n    version: 2,\n    // the lens\n"));
//! ```

use crate::syntax::lex::{Kind, Token, tokenize};

/// The scene-format version this build writes and reads natively.
pub const CURRENT: u32 = 2;

/// The version of a file that states none: the format before versions.
pub const UNSTATED: u32 = 1;

/// A replacement of `src[start..end]` by `text`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edit {
    /// First byte replaced.
    pub start: usize,
    /// One past the last byte replaced (`start` for an insertion).
    pub end: usize,
    /// What goes there.
    pub text: String,
}

/// One step between consecutive versions.
pub struct Step {
    /// The version the step produces (it reads `to − 1`).
    pub to: u32,
    /// What the step changes, for `migrate`'s report.
    pub summary: &'static str,
    /// The edits that bring a file's text (and tokens) to `to`, beyond the
    /// version stamp.
    pub rewrite: fn(&str, &[Token]) -> Vec<Edit>,
}

/// Every step, oldest first.
pub const STEPS: &[Step] = &[Step {
    to: 2,
    summary: "textures on every number and on emission (only new forms: nothing to rewrite)",
    rewrite: |_, _| Vec::new(),
}];

/// A migrated file.
#[derive(Clone, Debug, PartialEq)]
pub struct Migrated {
    /// The version the file was in.
    pub from: u32,
    /// The version it is in now ([`CURRENT`]).
    pub to: u32,
    /// The file's new text (the old text when nothing changed).
    pub text: String,
    /// What each step applied did.
    pub steps: Vec<&'static str>,
}

/// Why a file cannot be migrated.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum MigrateError {
    /// The text does not tokenize.
    #[error("{0}")]
    Syntax(String),
    /// No top-level `Scene(…)` or `{…}`.
    #[error("no scene found: expected `Scene(` or `{{` at the top")]
    NotAScene,
    /// An included file (`Include(…)`): it follows its scene's version.
    #[error("an included file has no version of its own: migrate the scene that includes it")]
    Include,
    /// `version` is not a whole number this build knows.
    #[error("version `{0}` is not one this ronray reads (1 to {CURRENT})")]
    UnknownVersion(String),
}

/// The top-level bracket of a scene: the index of its opening token, and
/// whether the file is JSON (`{`).
fn top_open(src: &str, toks: &[Token]) -> Result<(usize, bool), MigrateError> {
    let mut it = toks
        .iter()
        .enumerate()
        .filter(|(_, t)| !t.is_comment() && t.kind != Kind::Attribute);
    match it.next() {
        Some((i, t)) if t.kind == Kind::Open('{') => Ok((i, true)),
        Some((i, t)) if t.kind == Kind::Open('(') => Ok((i, false)),
        Some((_, t)) if t.kind == Kind::Word && t.text(src) == "Include" => Err(MigrateError::Include),
        Some((_, t)) if t.kind == Kind::Word => match it.next() {
            Some((i, t)) if t.kind == Kind::Open('(') => Ok((i, false)),
            _ => Err(MigrateError::NotAScene),
        },
        _ => Err(MigrateError::NotAScene),
    }
}

/// The index of the value token of the top-level `version` key, if any.
fn version_token(src: &str, toks: &[Token], open: usize) -> Option<usize> {
    let mut depth = 0usize;
    for (i, t) in toks.iter().enumerate().skip(open + 1) {
        match t.kind {
            Kind::Open(_) => depth += 1,
            Kind::Close(_) if depth == 0 => return None,
            Kind::Close(_) => depth -= 1,
            Kind::Word | Kind::Str if depth == 0 && crate::syntax::lex::unquote(t.text(src)) == "version" => {
                let mut rest = toks[i + 1..].iter().enumerate().filter(|(_, t)| !t.is_comment());
                if let (Some((_, c)), Some((k, _))) = (rest.next(), rest.next())
                    && c.kind == Kind::Colon
                {
                    return Some(i + 1 + k);
                }
            }
            _ => {}
        }
    }
    None
}

/// The version `src` states (or [`UNSTATED`]).
pub fn version_of(src: &str) -> Result<u32, MigrateError> {
    let toks = tokenize(src).map_err(|e| MigrateError::Syntax(e.message))?;
    let (open, _) = top_open(src, &toks)?;
    stated(src, &toks, open)
}

fn stated(src: &str, toks: &[Token], open: usize) -> Result<u32, MigrateError> {
    match version_token(src, toks, open) {
        None => Ok(UNSTATED),
        Some(k) => {
            let text = toks[k].text(src);
            match text.parse::<u32>() {
                Ok(v) if (1..=CURRENT).contains(&v) => Ok(v),
                _ => Err(MigrateError::UnknownVersion(text.to_string())),
            }
        }
    }
}

/// Brings scene text `src` to [`CURRENT`]: the steps' edits, then the
/// version stamped (its number replaced, or `version: N,` inserted as the
/// first field, on its own line when the next field is on one). Comments,
/// spellings and layout elsewhere are untouched; a current file comes back
/// unchanged.
pub fn migrate_text(src: &str) -> Result<Migrated, MigrateError> {
    let toks = tokenize(src).map_err(|e| MigrateError::Syntax(e.message))?;
    let (open, json) = top_open(src, &toks)?;
    let from = stated(src, &toks, open)?;
    let mut edits = Vec::new();
    let mut steps = Vec::new();
    for s in STEPS.iter().filter(|s| s.to > from) {
        edits.extend((s.rewrite)(src, &toks));
        steps.push(s.summary);
    }
    if from < CURRENT {
        edits.push(stamp(src, &toks, open, json));
    }
    Ok(Migrated {
        from,
        to: CURRENT,
        text: apply(src, edits),
        steps,
    })
}

/// The edit that makes the file say `version: CURRENT`.
fn stamp(src: &str, toks: &[Token], open: usize, json: bool) -> Edit {
    if let Some(k) = version_token(src, toks, open) {
        return Edit {
            start: toks[k].span.start,
            end: toks[k].span.end,
            text: CURRENT.to_string(),
        };
    }
    let key = if json { "\"version\"" } else { "version" };
    let mut at = toks[open].span.end;
    let field = match toks.get(open + 1) {
        // An empty scene: no comma (JSON allows none).
        Some(t) if matches!(t.kind, Kind::Close(_)) => format!("{key}: {CURRENT}"),
        // The next token on its own line: the same indentation.
        Some(t) if t.newlines_before > 0 => {
            let line = src[..t.span.start].rfind('\n').map_or(0, |n| n + 1);
            let indent = &src[line..t.span.start];
            format!("\n{indent}{key}: {CURRENT},")
        }
        // On the same line: before the next token, after any spaces.
        Some(t) => {
            at = t.span.start;
            format!("{key}: {CURRENT}, ")
        }
        None => format!("{key}: {CURRENT}"),
    };
    Edit {
        start: at,
        end: at,
        text: field,
    }
}

/// `src` with non-overlapping `edits` applied.
fn apply(src: &str, mut edits: Vec<Edit>) -> String {
    edits.sort_by_key(|e| (e.start, e.end));
    let mut out = String::with_capacity(src.len() + 32);
    let mut at = 0;
    for e in edits {
        if e.start < at {
            debug_assert!(false, "overlapping migration edits");
            continue;
        }
        out.push_str(&src[at..e.start]);
        out.push_str(&e.text);
        at = e.end;
    }
    out.push_str(&src[at..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn migrate_stamps_ron_and_json_and_keeps_the_rest() {
        let ron = "// lit\nScene( camera: (eye: (0, 0, 1), target: (0, 0, 0)) ) // end\n";
        let m = migrate_text(ron).expect("migrates");
        assert_eq!(
            m.text,
            "// lit\nScene( version: 2, camera: (eye: (0, 0, 1), target: (0, 0, 0)) ) // end\n"
        );
        let json = "{\n  \"camera\": {\"eye\": [0, 0, 1], \"target\": [0, 0, 0]}\n}\n";
        let m = migrate_text(json).expect("migrates");
        assert_eq!(
            m.text,
            "{\n  \"version\": 2,\n  \"camera\": {\"eye\": [0, 0, 1], \"target\": [0, 0, 0]}\n}\n"
        );
        assert_eq!(migrate_text("Scene()").expect("empty").text, "Scene(version: 2)");
    }

    #[test]
    fn migrate_is_idempotent_and_reads_a_stated_version() {
        let once = migrate_text("Scene(\n    film: (width: 8),\n)")
            .expect("migrates")
            .text;
        let twice = migrate_text(&once).expect("again");
        assert_eq!((twice.from, twice.text.as_str()), (CURRENT, once.as_str()));
        let stated = migrate_text("(version: 1, film: (width: 8))").expect("version 1");
        assert_eq!(
            (stated.from, stated.text.as_str()),
            (1, "(version: 2, film: (width: 8))")
        );
        // A nested `version` is not the scene's.
        assert_eq!(version_of("Scene(test: (version: 9))"), Ok(UNSTATED));
    }

    #[test]
    fn migrate_refuses_what_it_cannot_read() {
        assert_eq!(
            migrate_text("Scene(version: 7)"),
            Err(MigrateError::UnknownVersion("7".into()))
        );
        assert_eq!(
            migrate_text("Scene(version: 0)"),
            Err(MigrateError::UnknownVersion("0".into()))
        );
        assert_eq!(migrate_text("Include(objects: [])"), Err(MigrateError::Include));
        assert_eq!(migrate_text("42"), Err(MigrateError::NotAScene));
        assert!(matches!(
            migrate_text("Scene(\"open"),
            Err(MigrateError::Syntax(_))
        ));
    }
}
