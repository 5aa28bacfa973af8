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
