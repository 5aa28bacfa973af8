//! The scene content hash that pieces of one frame share.
//!
//! Two machines agree on it when they render the same picture, wherever the
//! scene sits on disk and however it is written: it is the SHA-256 of the
//! composed scene description after includes and overrides, in canonical
//! RON (`ronray fmt`'s text, so comments, layout and field order do not
//! count), followed by the SHA-256 of every other file the scene reads
//! (meshes, textures), sorted, so their paths do not count either.

use crate::desc::SceneDesc;
use sha2::{Digest, Sha256};
use std::path::PathBuf;

/// `sha256:` and 64 hex digits. `files` are the files the scene was read
/// from (`Loaded::files`); scene files (`.ron`, `.json`) are already in
/// `desc` and are skipped.
pub fn scene_hash(desc: &SceneDesc, files: &[PathBuf]) -> Result<String, String> {
    let text = crate::load::canonical::to_ron(desc)?;
    let mut assets = Vec::new();
    for f in files {
        let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ext.eq_ignore_ascii_case("ron") || ext.eq_ignore_ascii_case("json") {
            continue;
        }
        let bytes = std::fs::read(f).map_err(|e| format!("cannot read {}: {e}", f.display()))?;
        assets.push(hex(&Sha256::digest(&bytes)));
    }
    assets.sort();
    assets.dedup();
    let mut h = Sha256::new();
    h.update(b"ronray scene v1\n");
    h.update(text.as_bytes());
    for a in &assets {
        h.update(b"\nasset ");
        h.update(a.as_bytes());
    }
    Ok(format!("sha256:{}", hex(&h.finalize())))
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn desc(text: &str) -> SceneDesc {
        let opts = ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        opts.from_str(text).expect("scene parses")
    }

    #[test]
    fn scene_hash_ignores_layout_and_sees_content() {
        let a = "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (spp: 4))";
        let b = "// same scene\nScene(\n  film: (spp: 4),\n  camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),\n)";
        let c = "Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (spp: 8))";
        let h = |t: &str| scene_hash(&desc(t), &[]).expect("hash");
        assert_eq!(h(a), h(b), "comments and field order changed the hash");
        assert_ne!(h(a), h(c), "a different spp kept the hash");
        assert!(h(a).starts_with("sha256:") && h(a).len() == 7 + 64);
    }
}
