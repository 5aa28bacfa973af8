//! The loader: scene text → checked description ([`crate::desc`]) → runtime
//! [`crate::scene::Scene`] and [`crate::view::View`]. [`load()`] runs every
//! stage and turns each stage's problems into located diagnostics.
//!
//! One file per kind of thing a scene holds, each with that kind's checks
//! and its build step: `view.rs` (camera, film, integrator), `material.rs`,
//! `light.rs`, `object.rs`, `mesh.rs` with `mtl.rs`, `sdf/`. `validate.rs`
//! and `build.rs` run them in order; every check runs before any build, so
//! `validate` and watch mode stop after checking.

mod animation;
mod brackets;
pub mod build;
mod build_context;
mod camera;
pub mod canonical;
pub mod document;
mod film;
pub mod format;
pub mod gltf;
pub mod include;
mod integrator;
mod light;
pub mod material;
mod medium;
mod mesh;
mod mesh_keys;
mod mesh_state;
mod mtl;
pub mod object;
pub mod pipeline;
mod repair;
pub mod sdf;
mod sections;
pub mod set;
mod slip;
pub mod source;
mod texels;
pub mod transform;
pub mod validate;
mod view;
pub mod warnings;
mod words;

#[doc(hidden)]
pub use light::fuzz_sky_map;
pub use pipeline::{LoadError, Loaded, Overrides, load, load_str, load_with};
