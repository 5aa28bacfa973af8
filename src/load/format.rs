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

    #[test]
    fn comments_are_detected_outside_strings_only() {
        assert!(has_comments("Scene( // x\n)"));
        assert!(has_comments("Scene( /* x */ )"));
        assert!(!has_comments(r#"Scene(output: "a//b.png")"#));
    }
}
