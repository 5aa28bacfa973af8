//! Farm pieces: piece files (EXR) cut at `ronray::fuzzing::PIECE_SEPARATOR`, read and assembled.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::assemble(data);
});
