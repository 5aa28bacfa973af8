//! The scene pipeline: read → parse ([`desc`]) → [`validate`] → [`build`] →
//! runtime [`Scene`]. [`load()`] runs them all and turns each stage's problems
//! into located diagnostics.

pub mod build;
pub mod build_material;
mod build_mesh;
mod build_mtl;
pub mod build_sdf;
pub mod desc;
pub mod format;
pub mod include;
pub mod load;
pub mod problem;
pub mod runtime;
pub mod set;
pub mod spans;
pub mod validate;
pub mod validate_sdf;

pub use load::{LoadError, Loaded, Overrides, load, load_str, load_with};
pub use runtime::{Film, Scene};
