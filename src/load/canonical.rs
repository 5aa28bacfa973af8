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
