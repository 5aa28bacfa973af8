//! Scene loading: bytes → parse → includes → validate → build.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::scene(data);
});
