//! Sky maps: first byte even `.exr`, odd `.hdr`, then the file.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::envmap(data);
});
