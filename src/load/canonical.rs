//! Canonical text of a scene (`ronray fmt`) in RON or JSON.
//!
//! ron does not keep comments through parse → serialise, so formatting a
//! file that has comments would silently drop them; `fmt` refuses unless
//! told to drop them.

use crate::desc::SceneDesc;

/// Canonical RON: fields in declaration order, four-space indentation, small
/// values (vectors, colours, list elements) kept on one line.
pub fn to_ron(desc: &SceneDesc) -> Result<String, String> {
    let cfg = ron::ser::PrettyConfig::new()
        .depth_limit(3)
        .indentor("    ")
        .struct_names(false)
        .extensions(ron::extensions::Extensions::IMPLICIT_SOME);
    let body = ron::ser::to_string_pretty(desc, cfg).map_err(|e| e.to_string())?;
    // The attribute is implied by ronray's parser; keep files free of it.
    let body = body.trim_start_matches("#![enable(implicit_some)]").trim_start();
    Ok(format!("Scene{body}\n"))
}

/// Canonical JSON (`ronray fmt --json`): pretty-printed, fields in declaration
/// order, newline-terminated; ronray reads it as it reads RON.
pub fn to_json(desc: &SceneDesc) -> Result<String, String> {
    serde_json::to_string_pretty(desc)
        .map(|s| s + "\n")
        .map_err(|e| e.to_string())
}

/// `out`, the canonical text of the scene read from `src`, with each number
/// spelled as `src` spells it at the same scene path when both read as the
/// same `f32`. The canonical text prints the value the scene holds, so
/// `1e-50` became `0.0` and `40.000001` became `40.0`: the same scene to
/// ronray, but not the text its author wrote, and `fmt --canonical` ran
/// twice must not drift. Only spellings valid in both RON and JSON are
/// kept (`1e-50`, not `.5` or `1_000`).
pub fn keep_number_spellings(src: &str, out: &str) -> String {
    use crate::syntax::spans::Spans;
    let (from, to) = (Spans::scan(src), Spans::scan(out));
    let mut swaps: Vec<(std::ops::Range<usize>, &str)> = to
        .iter()
        .filter_map(|(path, r)| {
            let written = &src[from.get(path)?];
            let printed = &out[r.clone()];
            let same = is_plain_number(written)
                && is_plain_number(printed)
                && written != printed
                && written.parse::<f64>().ok()? as f32 == printed.parse::<f64>().ok()? as f32;
            same.then_some((r, written))
        })
        .collect();
    swaps.sort_by_key(|(r, _)| std::cmp::Reverse(r.start));
    let mut text = out.to_string();
    for (r, written) in swaps {
        text.replace_range(r, written);
    }
    text
}

/// A JSON number (`-12`, `0.5`, `1e-50`), which RON reads too.
fn is_plain_number(t: &str) -> bool {
    let b = t.strip_prefix('-').unwrap_or(t).as_bytes();
    let digits = |i: &mut usize| {
        let s = *i;
        while *i < b.len() && b[*i].is_ascii_digit() {
            *i += 1;
        }
        *i > s
    };
    let mut i = 0;
    if !digits(&mut i) || (b[0] == b'0' && i > 1) {
        return false;
    }
    if b.get(i) == Some(&b'.') {
        i += 1;
        if !digits(&mut i) {
            return false;
        }
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        i += 1;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        if !digits(&mut i) {
            return false;
        }
    }
    i == b.len()
}

/// Whether RON/JSON text has comments (outside strings).
pub fn has_comments(text: &str) -> bool {
    let b = text.as_bytes();
    let mut i = 0;
    let mut in_str = false;
    while i < b.len() {
        match b[i] {
            b'\\' if in_str => i += 1,
            b'"' => in_str = !in_str,
            b'/' if !in_str && matches!(b.get(i + 1), Some(b'/') | Some(b'*')) => return true,
            _ => {}
        }
        i += 1;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    /// parse → serialise → parse gives the same scene, for every shipped one.
    #[test]
    fn scene_desc_round_trips_through_ron_and_json() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let mut n = 0;
        for e in std::fs::read_dir(dir).expect("scenes/").flatten() {
            let p = e.path();
            if p.extension().is_none_or(|x| x != "ron") {
                continue;
            }
            let text = std::fs::read_to_string(&p).expect("read");
            let opts =
                ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
            let a: crate::desc::SceneDesc = opts
                .from_str(&text)
                .unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            let ron_text = to_ron(&a).expect("serialise");
            let b: crate::desc::SceneDesc = opts
                .from_str(&ron_text)
                .unwrap_or_else(|e| panic!("{}: {e}\n{ron_text}", p.display()));
            assert_eq!(a, b, "{} changed through RON", p.display());
            let json = to_json(&a).expect("json");
            let c: crate::desc::SceneDesc =
                serde_json::from_str(&json).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            assert_eq!(a, c, "{} changed through JSON", p.display());
            n += 1;
        }
        assert!(n >= 4);
    }

    #[test]
    fn comments_are_detected_outside_strings_only() {
        assert!(has_comments("Scene( // x\n)"));
        assert!(has_comments("Scene( /* x */ )"));
        assert!(!has_comments(r#"Scene(output: "a//b.png")"#));
    }
}
