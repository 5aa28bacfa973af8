//! The loader: scene text → checked description ([`crate::desc`]) → runtime
//! [`crate::scene::Scene`] and [`crate::view::View`]. [`load()`] runs every
//! stage and turns each stage's problems into located diagnostics.

pub mod build;
pub mod build_material;
mod build_mesh;
mod build_mtl;
pub mod build_sdf;
pub mod format;
pub mod include;
pub mod pipeline;
pub mod set;
pub mod spans;
pub mod validate;
pub mod validate_sdf;
pub mod warnings;

pub use pipeline::{LoadError, Loaded, Overrides, load, load_str, load_with};
