//! OBJ import with an MTL file: `OBJ text \0 MTL text`.
#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = ronray::fuzzing::obj(data);
});
