//! Image reading: PNG, EXR, HDR and PFM (`diff`, `check`) and textures.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::image(data);
});
