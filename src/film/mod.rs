//! How camera samples become pixels: the pixel reconstruction filter, and
//! when a pixel has enough of them (adaptive sampling).
//! ([`crate::view::Film`] holds the image size and sampling; tone mapping
//! is an output step, in `imageio/tonemap.rs`.)

pub mod adaptive;
pub mod filter;

pub use adaptive::{Adaptive, PixelNoise};
pub use filter::{Filter, FilterKind};
