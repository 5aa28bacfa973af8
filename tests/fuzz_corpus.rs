//! Every input of the committed fuzz corpora (`fuzz/corpus/<target>/`:
//! scene, obj, ply, image, gltf, assemble, lsp, envmap),
//! and every crash the fuzzers found (`fuzz/regressions/<target>/`), run
//! through the same library entry points as the `cargo fuzz` targets, on
//! stable Rust: what the fuzzers fixed stays fixed without nightly. None
//! may panic — not even inside the `catch_unwind` that guards tobj and the
//! image decoders, since a panic prints (the fuzzer counts it as a crash,
//! and so does this test); the regressions must also finish quickly.

mod common;

use std::cell::Cell;
use std::time::{Duration, Instant};

thread_local! {
    /// Panics on this thread, caught or not.
    static PANICS: Cell<usize> = const { Cell::new(0) };
}

/// Counts every panic on the thread that raises it, then lets the default
/// hook print it.
fn count_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANICS.with(|p| p.set(p.get() + 1));
            default(info);
        }));
    });
}

fn inputs(kind: &str, target: &str) -> Vec<std::path::PathBuf> {
    let dir = common::root().join("fuzz").join(kind).join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.flatten().map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    files.sort();
    files
}

fn replay(target: &str, run: fn(&[u8]) -> bool) {
    count_panics();
    let corpus = inputs("corpus", target);
    assert!(!corpus.is_empty(), "no corpus for {target}");
    for f in corpus.iter().chain(&inputs("regressions", target)) {
        let bytes = std::fs::read(f).expect("read");
        let t0 = Instant::now();
        let before = PANICS.with(Cell::get);
        let _ = run(&bytes);
        assert_eq!(PANICS.with(Cell::get), before, "{} panicked", f.display());
        assert!(
            t0.elapsed() < Duration::from_secs(20),
            "{} took {:?}",
            f.display(),
            t0.elapsed()
        );
    }
}

#[test]
fn scene_corpus_loads_without_panics() {
    replay("scene", ronray::fuzzing::scene);
}

#[test]
fn obj_corpus_imports_without_panics() {
    replay("obj", ronray::fuzzing::obj);
}

#[test]
fn ply_corpus_imports_without_panics() {
    replay("ply", ronray::fuzzing::ply);
}

#[test]
fn image_corpus_decodes_without_panics() {
    replay("image", ronray::fuzzing::image);
}

#[test]
fn gltf_corpus_imports_without_panics() {
    replay("gltf", ronray::fuzzing::gltf);
}

#[test]
fn assemble_corpus_reads_pieces_without_panics() {
    replay("assemble", ronray::fuzzing::assemble);
}

#[test]
fn lsp_corpus_is_served_without_panics() {
    replay("lsp", ronray::fuzzing::lsp);
}

#[test]
fn envmap_corpus_builds_sky_maps_without_panics() {
    replay("envmap", ronray::fuzzing::envmap);
}
