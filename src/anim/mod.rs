//! Time: keys, their interpolation, and the time a camera sample is traced at.
//!
//! A scene file gives keys (`frame`, value) on the things that move; this
//! module turns them into values at any time, in frames (fractional times
//! are between frames). Transforms are decomposed into translation,
//! rotation (a unit quaternion) and stretch, and the parts interpolated
//! apart, as pbrt-v4's `AnimatedTransform` does
//! (<https://pbr-book.org/4ed/Geometry_and_Transformations/Animating_Transformations>):
//! interpolating matrix entries would shear and shrink a turning object.
//!
//! - [`track`]: a list of keys sorted by time, the segment a time falls in,
//!   linear or smooth (Catmull-Rom) interpolation of vectors.
//! - [`trs`]: a matrix split into translate · rotate · stretch and put back.
//! - [`motion`]: a keyed transform: its value at a time (a key's own matrix,
//!   exactly, at that key) and the box it sweeps over a time interval.
//! - [`clock`]: the time of the camera sample this thread is tracing.

pub mod clock;
pub mod motion;
pub mod track;
pub mod trs;

pub use motion::TransformTrack;
pub use track::{Interpolation, MAX_KEYS, Track};
pub use trs::Trs;
