//! Scene loading: bytes → parse → includes → validate → build.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| ronray::fuzzing::scene(data));
