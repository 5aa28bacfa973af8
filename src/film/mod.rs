//! How camera samples become pixels: the pixel reconstruction filter, and
//! how many each pixel takes (spread by noise, or adaptive sampling).
//! ([`crate::view::Film`] holds the image size and sampling; tone mapping
//! is an output step, in `imageio/tonemap.rs`.)

pub mod adaptive;
pub mod allocation;
pub mod filter;

pub use adaptive::{Adaptive, PixelNoise};
pub use allocation::Spread;
pub use filter::{Filter, FilterKind};
