//! The entry points of the `cargo fuzz` targets in `fuzz/` (thin wrappers
//! there call these), kept in the library so that `tests/fuzz_corpus.rs`
//! replays every committed corpus file on stable Rust: a crash the fuzzer
//! found stays fixed without nightly. Each returns whether the input was
//! accepted; none may panic, hang or abort on any input.

use std::path::{Path, PathBuf};

/// The folder fuzzed scenes pretend to live in: it holds `block.obj`, so
/// meshes and instances get built too.
fn scene_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/hardening")
}

/// Scene loading: the bytes as a scene file (JSON when they start with `{`,
/// else RON), through parse, includes, validation and build.
pub fn scene(data: &[u8]) -> bool {
    let Ok(text) = std::str::from_utf8(data) else {
        return false;
    };
    let name = if text.trim_start().starts_with('{') {
        "fuzz.json"
    } else {
        "fuzz.ron"
    };
    let path = scene_dir().join(name);
    crate::load::load_str(&path, text, &crate::load::Overrides::default()).is_ok()
}

/// OBJ import: `OBJ text`, a zero byte, then the text every `mtllib` of the
/// OBJ reads. An OBJ that loads has its BVH built.
pub fn obj(data: &[u8]) -> bool {
    let (obj, mtl) = match data.iter().position(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, &[][..]),
    };
    let mtl_files = |_: &Path| Ok(mtl.to_vec());
    match crate::geometry::obj::parse_obj_data(Path::new("fuzz.obj"), obj, &mtl_files) {
        Ok(mut d) => {
            d.mesh.prepare();
            true
        }
        Err(_) => false,
    }
}

/// PLY import: the bytes as a `.ply` file (ASCII or binary). A PLY that
/// loads has its BVH built.
pub fn ply(data: &[u8]) -> bool {
    match crate::geometry::ply::parse_ply(Path::new("fuzz.ply"), data) {
        Ok((mut mesh, _)) => {
            mesh.prepare();
            true
        }
        Err(_) => false,
    }
}

/// Image reading: the first byte picks the reader (`0` PNG, `1` EXR, `2`
/// HDR, `3` PFM as `diff` and `check` read them, anything else a texture
/// with its format guessed), the rest is the file.
pub fn image(data: &[u8]) -> bool {
    let Some((&kind, bytes)) = data.split_first() else {
        return false;
    };
    let ext = match kind {
        0 => "png",
        1 => "exr",
        2 => "hdr",
        3 => "pfm",
        _ => return crate::imageio::read::decode_texture_bytes(bytes).is_ok(),
    };
    crate::imageio::read::decode_image(bytes, ext).is_ok()
}

/// glTF import: the bytes as a `.glb` or `.gltf` file (the `gltf` crate
/// tells them apart), read with every check the loader makes, its meshes
/// built.
pub fn gltf(data: &[u8]) -> bool {
    crate::load::gltf::fuzz_import(data)
}

/// Between the pieces of an `assemble` input.
pub const PIECE_SEPARATOR: &[u8] = b"\n--piece--\n";

/// Assembling a frame: the bytes cut at [`PIECE_SEPARATOR`] into at most
/// four piece files, each read as `ronray assemble` and `--resume` read
/// them (header alone, then the whole piece), then assembled.
pub fn assemble(data: &[u8]) -> bool {
    let Ok(dir) = tempfile::tempdir() else {
        return false;
    };
    let mut paths = Vec::new();
    for (i, bytes) in split(data, PIECE_SEPARATOR).into_iter().take(4).enumerate() {
        let path = dir.path().join(format!("piece{i}.exr"));
        if std::fs::write(&path, bytes).is_err() {
            return false;
        }
        let _ = crate::farm::read_piece_meta(&path);
        paths.push(path);
    }
    crate::farm::assemble_files(&paths).is_ok()
}

/// `data` cut at every `sep`.
fn split<'a>(data: &'a [u8], sep: &[u8]) -> Vec<&'a [u8]> {
    let mut parts = Vec::new();
    let mut rest = data;
    while let Some(i) = rest.windows(sep.len()).position(|w| w == sep) {
        parts.push(&rest[..i]);
        rest = &rest[i + sep.len()..];
    }
    parts.push(rest);
    parts
}

/// The language server: the bytes as what a client writes to `ronray lsp`
/// (framed messages, `Content-Length: N` then the JSON body), read with the
/// server's own framing and handled by its message loop, diagnostics
/// published at the end. Whether every byte was read as a message.
pub fn lsp(data: &[u8]) -> bool {
    crate::lsp::replay(data)
}

/// Sky maps: the first byte picks the file's extension (even `.exr`, odd
/// `.hdr`, the two the loader reads), the rest is the file, read, repaired
/// and turned into sampling tables as the build step does it.
pub fn envmap(data: &[u8]) -> bool {
    let Some((&kind, bytes)) = data.split_first() else {
        return false;
    };
    let Ok(dir) = tempfile::tempdir() else {
        return false;
    };
    let path = dir.path().join(if kind % 2 == 0 { "sky.exr" } else { "sky.hdr" });
    if std::fs::write(&path, bytes).is_err() {
        return false;
    }
    crate::load::fuzz_sky_map(&path)
}
