//! The scene pipeline: read → parse → validate → build.
pub mod problem;
