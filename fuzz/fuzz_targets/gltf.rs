//! glTF import: the bytes as a `.glb` or `.gltf` asset.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::gltf(data);
});
