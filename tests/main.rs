//! The integration tests, one binary: each `tests/<name>.rs` is a module of
//! it (`cargo test --test integration <name>::` runs one file's tests), so the
//! library is linked, and its generic code instantiated, once instead of once
//! per file (docs/benchmarks.md, "CI time"). A test that panics fails alone,
//! as before; one that aborts the process stops the binary, which is why
//! anything that could overflow a stack runs in a child process
//! (`tests/nesting.rs`).
//!
//! Two files keep binaries of their own (`Cargo.toml`): `fuzz_corpus.rs`
//! installs a process-wide panic hook, and `denoise.rs` is built with the
//! `denoise` feature in CI. `tests/architecture.rs` fails when a file under
//! `tests/` is neither a module here nor a test target, since
//! `autotests = false` would skip it without a word.

mod common;

mod adaptive;
mod allocation;
mod analytic;
mod animation;
mod aov;
mod architecture;
mod bad_values;
mod baked_patterns;
mod blend;
mod bvh_bunny;
mod cameras;
mod caustic_family;
mod caustics;
mod check;
mod claims;
mod cli;
mod coloured_glass;
mod commands;
mod denormals;
mod diagnostics;
mod far_from_origin;
mod farm;
mod farm_schedulers;
mod film;
mod fmt;
mod geometry;
mod gltf;
mod hardening;
mod hostile_files;
mod include;
mod light_tree;
mod low_angle;
mod lsp;
mod media;
mod migrate;
mod mtl_maps;
mod mtl_values;
mod nesting;
mod newcomer;
mod obj_corpus;
mod obj_overrides;
mod open_scenes;
mod path_splitting;
mod paths;
mod ply;
mod readme;
mod reference;
mod scenes_as_code;
mod sdf;
mod self_hits;
mod textures;
mod unasked_writes;
mod vertex_colors;
mod watch;
mod watch_serve;
