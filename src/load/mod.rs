//! The loader: scene text → checked description ([`crate::desc`]) → runtime
//! [`crate::scene::Scene`] and [`crate::view::View`]. [`load()`] runs every
//! stage and turns each stage's problems into located diagnostics.
//!
//! One file per kind of thing a scene holds, each with that kind's checks
//! and its build step: `view.rs` (camera, film, integrator), `material.rs`,
//! `light.rs`, `object.rs`, `mesh.rs` with `mtl.rs`, `sdf/`. `validate.rs`
//! and `build.rs` run them in order; every check runs before any build, so
//! `validate` and watch mode stop after checking.

pub mod build;
pub mod format;
pub mod include;
mod light;
pub mod material;
mod mesh;
mod mtl;
pub mod object;
pub mod pipeline;
pub mod sdf;
pub mod set;
pub mod spans;
pub mod validate;
mod view;
pub mod warnings;

pub use pipeline::{LoadError, Loaded, Overrides, load, load_str, load_with};
