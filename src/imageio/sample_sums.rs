//! Exact per-pixel sample sums over a rectangle of a frame: what a render
//! holds before dividing by the sample count, what progressive passes add
//! to, and what pieces of a frame carry and add up.
//!
//! A render spread by noise (`film.allocation: ByNoise`) takes a first pass
//! of `first` samples everywhere and then a pixel's own count; its mean is
//! the two passes' means weighted by their counts ([`two_pass_mean`]), so
//! its pieces keep the two passes' sums apart ([`SpreadSums`]) and the
//! assembled frame divides them exactly as the whole render does.

use super::{Image, PixelRect};
use crate::math::{ExactSum, Rgb};

/// Per-pixel sample sums over a rectangle of the frame: what a render
/// produces before the division by the sample count, and what pieces of a
/// frame add up.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleSums {
    /// The pixels summed.
    pub rect: PixelRect,
    /// Row-major over `rect`. For a render spread by noise, the sums of the
    /// samples of its first pass only.
    pub sums: Vec<ExactSum>,
    /// For a render spread by noise: its second pass's sums and each
    /// pixel's sample count.
    pub spread: Option<SpreadSums>,
}

/// The part of a render spread by noise that an even render does not have.
#[derive(Clone, Debug, PartialEq)]
pub struct SpreadSums {
    /// Samples every pixel takes in the first pass of the whole frame.
    pub first: u32,
    /// Row-major over the rect: the sums of the samples past `first`.
    pub late: Vec<ExactSum>,
    /// Row-major over the rect: how many samples (of both passes) are summed.
    pub counts: Vec<u32>,
}

/// The mean of a pixel of a render spread by noise: its first pass's mean
/// `m1` over `n1` samples and its second pass's sum over `n2` samples,
/// weighted by their counts. Written once, for the tile loop and for
/// assembling pieces, so that both give the same bytes.
#[inline]
pub fn two_pass_mean(m1: Rgb, n1: u32, late: &ExactSum, n2: u32) -> Rgb {
    if n2 == 0 {
        return m1;
    }
    let (a, b) = (n1 as f32, n2 as f32);
    (m1 * a + late.mean(n2) * b) / (a + b)
}

impl SampleSums {
    /// Zero sums over `rect`.
    pub fn new(rect: PixelRect) -> Self {
        Self {
            rect,
            sums: vec![ExactSum::ZERO; rect.area() as usize],
            spread: None,
        }
    }

    /// Zero sums over `rect` of a render spread by noise whose first pass
    /// takes `first` samples.
    pub fn new_spread(rect: PixelRect, first: u32) -> Self {
        let n = rect.area() as usize;
        Self {
            spread: Some(SpreadSums {
                first,
                late: vec![ExactSum::ZERO; n],
                counts: vec![0; n],
            }),
            ..Self::new(rect)
        }
    }

    /// The sum at pixel (x, y) in image coordinates.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> ExactSum {
        self.sums[self.rect.index(x, y)]
    }

    /// Adds `other`'s sums at the pixels it covers, which must lie inside.
    /// Both are spread by noise or neither is (the farm's checks refuse a
    /// mix before adding); a spread part on one side only is left out.
    pub fn add(&mut self, other: &SampleSums) {
        debug_assert!(self.rect.contains(&other.rect));
        let r = other.rect;
        for y in r.y0..r.y1 {
            for x in r.x0..r.x1 {
                let (i, j) = (self.rect.index(x, y), r.index(x, y));
                self.sums[i].add(&other.sums[j]);
                if let (Some(s), Some(o)) = (&mut self.spread, &other.spread) {
                    s.late[i].add(&o.late[j]);
                    s.counts[i] = s.counts[i].saturating_add(o.counts[j]);
                }
            }
        }
    }

    /// The mean over `n` samples per pixel, as an image of `rect`'s size;
    /// for sums spread by noise, each pixel's mean over its own count
    /// ([`two_pass_mean`], once every sample of the pixel is in).
    pub fn mean(&self, n: u32) -> Image {
        let pixels = match &self.spread {
            None => self.sums.iter().map(|s| s.mean(n)).collect(),
            Some(s) => self
                .sums
                .iter()
                .zip(&s.late)
                .zip(&s.counts)
                .map(|((sum, late), &count)| {
                    two_pass_mean(sum.mean(s.first), s.first, late, count.saturating_sub(s.first))
                })
                .collect(),
        };
        Image {
            width: self.rect.width(),
            height: self.rect.height(),
            pixels,
        }
    }

    /// Each pixel's mean over the samples summed here (what a piece shows
    /// in a viewer): `n` each, or the pixel's own count when spread by noise.
    pub fn piece_mean(&self, n: u32) -> Image {
        let pixels = match &self.spread {
            None => self.sums.iter().map(|s| s.mean(n)).collect(),
            Some(s) => self
                .sums
                .iter()
                .zip(&s.late)
                .zip(&s.counts)
                .map(|((sum, late), &count)| {
                    let mut all = *sum;
                    all.add(late);
                    all.mean(count)
                })
                .collect(),
        };
        Image {
            width: self.rect.width(),
            height: self.rect.height(),
            pixels,
        }
    }
}
