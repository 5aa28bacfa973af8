//! PLY import: the bytes as a `.ply` file.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::ply(data);
});
