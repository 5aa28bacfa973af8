//! The loader: scene text → checked description ([`crate::desc`]) → runtime
//! [`crate::scene::Scene`] and [`crate::view::View`]. [`load()`] runs every
//! stage and turns each stage's problems into located diagnostics.

mod brackets;
pub mod build;
pub mod build_material;
mod build_mesh;
mod build_mtl;
pub mod build_sdf;
pub mod document;
pub mod format;
pub mod include;
mod outline;
pub mod pipeline;
mod sections;
pub mod set;
pub mod source;
pub mod spans;
mod tokens;
pub mod validate;
pub mod validate_sdf;
mod words;

pub use pipeline::{LoadError, Loaded, Overrides, load, load_str, load_with};
