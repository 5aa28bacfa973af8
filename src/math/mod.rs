//! Small numeric building blocks shared by every stage: colours, rays,
//! orthonormal frames, sampling warps with their densities, the random
//! number generator and exact sums of samples.

pub mod exact_sum;
pub mod float_error;
pub mod frame;
pub mod piecewise;
pub mod ray;
pub mod rng;
pub mod sampling;
pub mod trig;

pub use exact_sum::{ExactSum, SampleSum};
pub use frame::Frame;
pub use ray::Ray;
pub use rng::{Pcg32, SampleRng};

use glam::Vec3A;

/// Linear RGB (Rec.709 primaries), one radiometric quantity per channel.
///
/// A plain `Vec3A` so colour arithmetic compiles to the same SIMD as geometry.
pub type Rgb = Vec3A;

/// Luminance of a linear Rec.709 colour; used for light selection by power
/// and Russian roulette.
#[inline]
pub fn luminance(c: Rgb) -> f32 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// A margin that scales with the size of the coordinates: `1e-4·(1 + |p|max)`.
///
/// No longer how rays leave surfaces (they are offset by each hit's own
/// rounding-error bound, see [`float_error`]); kept for SDF march
/// thresholds and normal estimates, whose tolerances are of this size, and
/// for tests that step off SDF hits by it.
#[inline]
pub fn ray_epsilon(p: Vec3A) -> f32 {
    1e-4 * (1.0 + p.abs().max_element())
}
