//! Every input of the committed fuzz corpora (`fuzz/corpus/<target>/`),
//! and every crash the fuzzers found (`fuzz/regressions/<target>/`), run
//! through the same library entry points as the `cargo fuzz` targets, on
//! stable Rust: what the fuzzers fixed stays fixed without nightly. None
//! may panic; the regressions must also finish quickly (a hang is a bug).

mod common;

use std::time::{Duration, Instant};

fn inputs(kind: &str, target: &str) -> Vec<std::path::PathBuf> {
    let dir = common::root().join("fuzz").join(kind).join(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.flatten().map(|e| e.path()).filter(|p| p.is_file()).collect())
        .unwrap_or_default();
    files.sort();
    files
}

fn replay(target: &str, run: fn(&[u8]) -> bool) {
    let corpus = inputs("corpus", target);
    assert!(!corpus.is_empty(), "no corpus for {target}");
    for f in corpus.iter().chain(&inputs("regressions", target)) {
        let bytes = std::fs::read(f).expect("read");
        let t0 = Instant::now();
        let _ = run(&bytes);
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
fn image_corpus_decodes_without_panics() {
    replay("image", ronray::fuzzing::image);
}
