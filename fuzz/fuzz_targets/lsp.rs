//! The language server: framed client messages through its message loop.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::lsp(data);
});
