//! Acceleration structures. `accel` knows nothing about shapes: it builds
//! from bounding boxes and asks the caller, through a closure, to intersect a
//! primitive by index. Meshes, analytic shapes and implicit surfaces share it.
//! `bvh` builds a binary SAH tree; `wide` collapses it to the 8-wide tree
//! that scene and mesh rays traverse.

pub mod aabb;
pub mod bvh;
pub mod wide;

pub use aabb::Aabb;
pub use bvh::{Bvh, BvhStats};
pub use wide::{Leaves, WideBvh};
