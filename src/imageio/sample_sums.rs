//! Exact per-pixel sample sums over a rectangle of a frame: what a render
//! holds before dividing by the sample count, what progressive passes add
//! to, and what pieces of a frame carry and add up.

use super::{Image, PixelRect};
use crate::math::ExactSum;

/// Per-pixel sample sums over a rectangle of the frame: what a render
/// produces before the division by the sample count, and what pieces of a
/// frame add up.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleSums {
    /// The pixels summed.
    pub rect: PixelRect,
    /// Row-major over `rect`.
    pub sums: Vec<ExactSum>,
}

impl SampleSums {
    /// Zero sums over `rect`.
    pub fn new(rect: PixelRect) -> Self {
        Self {
            rect,
            sums: vec![ExactSum::ZERO; rect.area() as usize],
        }
    }

    /// The sum at pixel (x, y) in image coordinates.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> ExactSum {
        self.sums[self.rect.index(x, y)]
    }

    /// Adds `other`'s sums at the pixels it covers, which must lie inside.
    pub fn add(&mut self, other: &SampleSums) {
        debug_assert!(self.rect.contains(&other.rect));
        let r = other.rect;
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let i = self.rect.index(x, y);
                self.sums[i].add(&other.get(x, y));
            }
        }
    }

    /// The mean over `n` samples per pixel, as an image of `rect`'s size.
    pub fn mean(&self, n: u32) -> Image {
        Image {
            width: self.rect.width(),
            height: self.rect.height(),
            pixels: self.sums.iter().map(|s| s.mean(n)).collect(),
        }
    }
}
