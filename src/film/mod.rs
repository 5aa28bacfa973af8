//! How camera samples become pixels: the pixel reconstruction filter.
//! ([`crate::view::Film`] holds the image size and sampling; tone mapping
//! is an output step, in `imageio/tonemap.rs`.)

pub mod filter;

pub use filter::{Filter, FilterKind};
