//! Reading a glTF asset's files: the `.gltf`/`.glb` itself, its buffers
//! (the GLB's BIN chunk, data URIs, or files beside it) and, for the
//! material step, its images. Every file goes through the same rules as
//! OBJ and MTL files: regular files only, the `--root` fence, and one byte
//! budget ([`MAX_GLTF_BYTES`]) for the asset and everything it names, so a
//! hostile asset cannot make the loader read or allocate without bound.

use gltf::Document;
use std::path::{Path, PathBuf};

/// Bytes one asset may read in all (the file, its buffers and images): 1
/// GiB, as an OBJ file.
pub const MAX_GLTF_BYTES: u64 = crate::geometry::obj::MAX_OBJ_FILE_BYTES;

/// A parsed asset with its buffers loaded.
pub struct Asset {
    /// The parsed (and validated) document.
    pub doc: Document,
    /// Each buffer's bytes, at least as long as the buffer says.
    pub buffers: Vec<Vec<u8>>,
    /// Reads what the asset names (its images, after the buffers).
    pub files: Files,
}

/// The files an asset names: where they are, which were read, and how many
/// bytes may still be.
pub struct Files {
    /// The asset's folder: relative URIs resolve against it.
    pub dir: PathBuf,
    /// Every file read (the asset, its buffers, later its images), for watch mode.
    pub files: Vec<PathBuf>,
    /// Bytes still allowed.
    budget: u64,
    root: Option<PathBuf>,
}

/// A GLB header's total length below the header's own 12 bytes: `gltf`
/// 1.4.1 subtracts 12 from it unchecked (`Glb::from_slice`), an overflow
/// panic wherever overflow checks are on (found by the `gltf` fuzz target,
/// `fuzz/regressions/gltf/glb_length_below_header`).
fn check_glb_length(bytes: &[u8]) -> Result<(), String> {
    if let Some(len) = bytes
        .strip_prefix(b"glTF")
        .and_then(|rest| rest.get(4..8))
        .and_then(|b| <[u8; 4]>::try_from(b).ok())
        .map(u32::from_le_bytes)
        && len < 12
    {
        return Err(format!(
            "invalid glTF: the GLB header gives the file a length of {len} bytes, less than the header's own 12"
        ));
    }
    Ok(())
}

/// Reads `path` and its buffers.
pub fn read(path: &Path, root: Option<&Path>) -> Result<Asset, String> {
    let bytes =
        crate::files::read_regular(path, MAX_GLTF_BYTES).map_err(|e| format!("cannot read glTF: {e}"))?;
    check_glb_length(&bytes)?;
    let gltf = gltf::Gltf::from_slice_without_validation(&bytes).map_err(describe)?;
    let mut json = gltf.document.into_json();
    // `KHR_mesh_quantization` asks only that integer positions, normals,
    // tangents and texture coordinates be read, which the accessor reader
    // does (`primitive.rs`); the `gltf` crate does not list it, and its
    // validation would refuse the file.
    json.extensions_required.retain(|e| e != "KHR_mesh_quantization");
    // `gltf-json` 1.4.1's validation indexes `accessors` by POSITION's
    // accessor unchecked (a panic on a hostile index): checked first.
    for (m, mesh) in json.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            let pos = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
            if let Some(a) = prim.attributes.get(&pos)
                && a.value() >= json.accessors.len()
            {
                return Err(format!(
                    "invalid glTF: meshes[{m}].primitives[{p}].attributes.POSITION: accessor {} does not exist",
                    a.value()
                ));
            }
        }
    }
    // `gltf` 1.4.1's `Image::source` unwraps the image's `uri` when it has
    // no `bufferView`, and its `mimeType` when it has one; validation checks
    // neither (found by the `gltf` fuzz target): checked here.
    for (i, image) in json.images.iter().enumerate() {
        match (&image.buffer_view, &image.uri, &image.mime_type) {
            (None, None, _) => {
                return Err(format!(
                    "invalid glTF: images[{i}] has neither a uri nor a bufferView"
                ));
            }
            (Some(_), _, None) => {
                return Err(format!(
                    "invalid glTF: images[{i}] is in a bufferView without a mimeType (image/png or image/jpeg)"
                ));
            }
            _ => {}
        }
    }
    check_unvalidated(&json)?;
    let doc = gltf::Document::from_json(json).map_err(describe)?;
    let mut asset = Asset {
        doc,
        buffers: Vec::new(),
        files: Files {
            dir: path.parent().unwrap_or(Path::new("")).to_path_buf(),
            files: vec![path.to_path_buf()],
            budget: MAX_GLTF_BYTES.saturating_sub(bytes.len() as u64),
            root: root.map(Path::to_path_buf),
        },
    };
    let mut blob = gltf.blob;
    let sources: Vec<(usize, usize, Option<String>)> = asset
        .doc
        .buffers()
        .map(|b| {
            let uri = match b.source() {
                gltf::buffer::Source::Bin => None,
                gltf::buffer::Source::Uri(u) => Some(u.to_string()),
            };
            (b.index(), b.length(), uri)
        })
        .collect();
    for (i, length, uri) in sources {
        let data = match uri {
            None => blob
                .take()
                .ok_or_else(|| format!("buffers[{i}]: no URI and the file has no GLB binary chunk"))?,
            Some(uri) => asset
                .files
                .uri_bytes(&uri)
                .map_err(|e| format!("buffers[{i}]: {e}"))?,
        };
        if data.len() < length {
            return Err(format!(
                "buffers[{i}]: {} bytes where the asset says {length} (truncated?)",
                data.len()
            ));
        }
        asset.buffers.push(data);
    }
    Ok(asset)
}

/// What `gltf-json` 1.4.1's validation leaves unchecked and `gltf` 1.4.1
/// unwraps (a panic on a hostile file; found by the `gltf` fuzz target
/// once cameras were read): an animation channel's target node and
/// property, and a camera's projection object of its `type`.
fn check_unvalidated(json: &gltf::json::Root) -> Result<(), String> {
    use gltf::json::camera::Type;
    use gltf::json::validation::Checked;
    for (a, anim) in json.animations.iter().enumerate() {
        for (c, channel) in anim.channels.iter().enumerate() {
            let at = format!("invalid glTF: animations[{a}].channels[{c}].target");
            if channel.target.node.value() >= json.nodes.len() {
                return Err(format!(
                    "{at}.node: node {} does not exist",
                    channel.target.node.value()
                ));
            }
            if !matches!(channel.target.path, Checked::Valid(_)) {
                return Err(format!(
                    "{at}.path: not one of translation, rotation, scale, weights"
                ));
            }
        }
    }
    for (i, camera) in json.cameras.iter().enumerate() {
        let (ok, wanted) = match camera.type_ {
            Checked::Valid(Type::Perspective) => (camera.perspective.is_some(), "perspective"),
            Checked::Valid(Type::Orthographic) => (camera.orthographic.is_some(), "orthographic"),
            Checked::Invalid => (false, "perspective or orthographic"),
        };
        if !ok {
            return Err(format!(
                "invalid glTF: cameras[{i}] has no `{wanted}` object for its type"
            ));
        }
    }
    Ok(())
}

impl Files {
    /// The bytes a URI names: a base64 data URI, or a file relative to the
    /// asset (percent-escapes decoded), fenced and counted in the budget.
    pub fn uri_bytes(&mut self, uri: &str) -> Result<Vec<u8>, String> {
        if let Some(rest) = uri.strip_prefix("data:") {
            let (head, data) = rest.split_once(',').ok_or("a data URI without a comma")?;
            if !head.ends_with(";base64") {
                return Err("a data URI that is not base64".into());
            }
            if data.len() as u64 / 4 * 3 > self.budget {
                return Err(format!(
                    "more than the {} MiB an asset may read",
                    MAX_GLTF_BYTES >> 20
                ));
            }
            let bytes = base64(data).ok_or("a data URI with invalid base64")?;
            self.budget -= bytes.len() as u64;
            return Ok(bytes);
        }
        if uri.contains("://") || uri.starts_with('/') {
            return Err(format!("`{uri}`: only relative file names are read"));
        }
        let path = self.dir.join(percent_decode(uri));
        if let Some(why) = self
            .root
            .as_deref()
            .and_then(|r| crate::files::outside_root(r, &path))
        {
            return Err(format!("glTF file {why}"));
        }
        self.files.push(path.clone());
        let bytes = crate::files::read_regular(&path, self.budget)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        self.budget -= bytes.len() as u64;
        Ok(bytes)
    }
}

/// The bytes of buffer view `view`, checked against its buffer.
pub fn view_bytes<'b>(buffers: &'b [Vec<u8>], view: &gltf::buffer::View) -> Result<&'b [u8], String> {
    let data = buffers
        .get(view.buffer().index())
        .ok_or_else(|| format!("bufferViews[{}]: its buffer was not loaded", view.index()))?;
    view.offset()
        .checked_add(view.length())
        .and_then(|end| data.get(view.offset()..end))
        .ok_or_else(|| format!("bufferViews[{}] runs past its buffer (truncated?)", view.index()))
}

/// The `gltf` crate's error as one sentence; validation errors name their
/// JSON path (an unknown required extension among them).
fn describe(e: gltf::Error) -> String {
    match e {
        gltf::Error::Validation(list) => {
            let parts: Vec<String> = list
                .iter()
                .take(8)
                .map(|(path, err)| format!("{path}: {err}"))
                .collect();
            let more = list.len().saturating_sub(8);
            let tail = if more > 0 {
                format!(" (and {more} more)")
            } else {
                String::new()
            };
            format!("invalid glTF: {}{tail}", parts.join("; "))
        }
        other => format!("invalid glTF: {other}"),
    }
}

/// `%xx` escapes decoded (glTF URIs are RFC 3986); invalid ones kept.
fn percent_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        let hex = |c: u8| (c as char).to_digit(16);
        if b[i] == b'%'
            && i + 2 < b.len()
            && let (Some(h), Some(l)) = (hex(b[i + 1]), hex(b[i + 2]))
        {
            out.push((h * 16 + l) as u8);
            i += 3;
            continue;
        }
        out.push(b[i]);
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Standard base64 (padding optional, whitespace refused).
fn base64(s: &str) -> Option<Vec<u8>> {
    let val = |c: u8| -> Option<u32> {
        Some(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' | b'-' => 62,
            b'/' | b'_' => 63,
            _ => return None,
        } as u32)
    };
    let s = s.trim_end_matches('=').as_bytes();
    let mut out = Vec::with_capacity(s.len() / 4 * 3 + 3);
    for chunk in s.chunks(4) {
        let mut acc = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            acc |= val(c)? << (18 - 6 * k);
        }
        let bytes = acc.to_be_bytes();
        match chunk.len() {
            4 => out.extend_from_slice(&bytes[1..4]),
            3 => out.extend_from_slice(&bytes[1..3]),
            2 => out.push(bytes[1]),
            _ => return None,
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_decodes_with_and_without_padding() {
        assert_eq!(base64("aGVsbG8=").as_deref(), Some(&b"hello"[..]));
        assert_eq!(base64("aGVsbG8").as_deref(), Some(&b"hello"[..]));
        assert_eq!(base64("AAECAw==").as_deref(), Some(&[0u8, 1, 2, 3][..]));
        assert_eq!(base64("a b"), None);
    }

    #[test]
    fn percent_escapes_decode() {
        assert_eq!(percent_decode("my%20file.bin"), "my file.bin");
        assert_eq!(percent_decode("100%"), "100%");
    }

    /// A GLB whose header claims fewer bytes than the header is refused
    /// with a message, before `gltf` subtracts 12 from it (a panic in any
    /// build with overflow checks, as the tests are).
    #[test]
    fn a_glb_length_below_its_header_is_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        for len in [0u32, 11] {
            let mut glb = b"glTF".to_vec();
            glb.extend(2u32.to_le_bytes());
            glb.extend(len.to_le_bytes());
            glb.extend(b"\x00\x00\x00\x00JSON{}");
            let path = dir.path().join("short.glb");
            std::fs::write(&path, &glb).expect("write");
            let e = read(&path, None).err().expect("refused");
            assert!(e.contains("less than the header's own 12"), "{e}");
        }
        // 12 and above go on to the crate's own checks.
    }

    /// An image with neither a uri nor a bufferView, or in a bufferView
    /// without a mimeType, is refused: `gltf` unwrapped both.
    #[test]
    fn images_without_a_source_or_a_mime_type_are_refused() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("bad.gltf");
        for (image, says) in [
            (r#"{"name": "nothing"}"#, "neither a uri nor a bufferView"),
            (r#"{"bufferView": 0}"#, "without a mimeType"),
        ] {
            let text = format!(
                r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"byteLength": 4, "uri": "data:application/octet-stream;base64,AAAAAA=="}}],
                   "bufferViews": [{{"buffer": 0, "byteLength": 4}}], "images": [{image}]}}"#
            );
            std::fs::write(&path, text).expect("write");
            let e = read(&path, None).err().expect("refused");
            assert!(e.contains("images[0]") && e.contains(says), "{e}");
        }
        assert!(check_glb_length(b"glTF\x02\x00\x00\x00\x0c\x00\x00\x00").is_ok());
    }
}
