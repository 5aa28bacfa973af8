//! `Sdf` objects: implicit surfaces as a tree of shapes and operators.
//! [`check`] validates the tree on the scene's own paths; [`build`] lowers it
//! to the engine's node arena. The scene-file vocabulary is `desc/sdf.rs`,
//! the engine `geometry/sdf/`.

pub mod build;
pub mod check;

pub(super) use build::build_sdf;
pub use build::{half_pixel, leaf, operator, similarity_parts};
pub use check::validate_sdf;
