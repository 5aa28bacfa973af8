//! The scene content hash that pieces of one frame share.
//!
//! Two machines agree on it when they render the same picture, wherever the
//! scene sits on disk and however it is written: it is the SHA-256 of the
//! composed scene description after includes and overrides, in canonical
//! RON (`ronray fmt`'s text, so comments, layout and field order do not
//! count), followed by the SHA-256 of every other file the scene reads,
//! each under its path relative to the scene's folder, sorted.
//!
//! "Every other file" is [`crate::load::Loaded::files`], the one list the
//! loader keeps of what it read (watch mode watches it, `validate -v`
//! prints it): OBJ files, their MTL files and the textures those name,
//! textures, sky maps, glTF assets with their buffers and images, `.vol`
//! grids. A second list kept here would miss the next kind of file. Each
//! digest is labelled with its file's place because contents alone, sorted,
//! do not see two textures swapped.

use crate::desc::SceneDesc;
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// `sha256:` and 64 hex digits. `files` are the files the scene was read
/// from (`Loaded::files`, the scene itself first: paths are written
/// relative to its folder); scene files (`.ron`, `.json`) are already in
/// `desc` and are skipped.
pub fn scene_hash(desc: &SceneDesc, files: &[PathBuf]) -> Result<String, String> {
    let text = crate::load::canonical::to_ron(desc)?;
    let base = files.first().and_then(|f| f.parent()).unwrap_or(Path::new(""));
    let mut assets = Vec::new();
    for f in files {
        let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ext.eq_ignore_ascii_case("ron") || ext.eq_ignore_ascii_case("json") {
            continue;
        }
        let bytes = std::fs::read(f).map_err(|e| format!("cannot read {}: {e}", f.display()))?;
        let place = f
            .strip_prefix(base)
            .unwrap_or(f)
            .to_string_lossy()
            .replace('\\', "/");
        assets.push((place, hex(&Sha256::digest(&bytes))));
    }
    assets.sort();
    assets.dedup();
    let mut h = Sha256::new();
    h.update(b"ronray scene v2\n");
    h.update(text.as_bytes());
    for (place, digest) in &assets {
        // The length first: no file name can run into its digest.
        h.update(format!("\nasset {} {place} {digest}", place.len()).as_bytes());
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

    /// Two files' contents swapped keep the same sorted digests: the hash
    /// must still change (it did not when digests were hashed without
    /// their files' places).
    #[test]
    fn scene_hash_sees_files_swapped() {
        let dir = tempfile::tempdir().expect("temp dir");
        let d = desc("Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40))");
        let files: Vec<PathBuf> = ["s.ron", "a.png", "b.png"]
            .iter()
            .map(|f| dir.path().join(f))
            .collect();
        let write = |a: &str, b: &str| {
            std::fs::write(&files[1], a).expect("write");
            std::fs::write(&files[2], b).expect("write");
            scene_hash(&d, &files).expect("hash")
        };
        assert_ne!(
            write("red", "blue"),
            write("blue", "red"),
            "swapping two textures kept the hash"
        );
        // Wherever the folder is, the same files give the same hash.
        let other = tempfile::tempdir().expect("temp dir");
        let moved: Vec<PathBuf> = files
            .iter()
            .map(|f| other.path().join(f.file_name().expect("name")))
            .collect();
        std::fs::write(&moved[1], "blue").expect("write");
        std::fs::write(&moved[2], "red").expect("write");
        assert_eq!(
            scene_hash(&d, &moved).expect("hash"),
            write("blue", "red"),
            "the folder's place counted"
        );
    }
}
