//! A rectangle of pixels: what a crop window, a tile or a piece of a frame
//! covers.

use std::fmt;

/// Pixels `x0..x1` × `y0..y1` (ends excluded), row 0 at the top.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// One past the last column.
    pub x1: u32,
    /// One past the last row.
    pub y1: u32,
}

impl PixelRect {
    /// Every pixel of a `width` × `height` image.
    pub fn full(width: u32, height: u32) -> Self {
        Self {
            x0: 0,
            y0: 0,
            x1: width,
            y1: height,
        }
    }

    /// Columns covered.
    pub fn width(&self) -> u32 {
        self.x1.saturating_sub(self.x0)
    }

    /// Rows covered.
    pub fn height(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Pixels covered.
    pub fn area(&self) -> u64 {
        self.width() as u64 * self.height() as u64
    }

    /// Whether it covers no pixel.
    pub fn is_empty(&self) -> bool {
        self.area() == 0
    }

    /// Whether `other` lies inside this rectangle.
    pub fn contains(&self, other: &PixelRect) -> bool {
        other.x0 >= self.x0 && other.y0 >= self.y0 && other.x1 <= self.x1 && other.y1 <= self.y1
    }

    /// The pixels both rectangles cover, if any.
    pub fn intersect(&self, other: &PixelRect) -> Option<PixelRect> {
        let r = PixelRect {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        };
        (r.x0 < r.x1 && r.y0 < r.y1).then_some(r)
    }

    /// Index of pixel (x, y), given in image coordinates, in a row-major
    /// buffer of this rectangle.
    #[inline]
    pub fn index(&self, x: u32, y: u32) -> usize {
        debug_assert!(x >= self.x0 && x < self.x1 && y >= self.y0 && y < self.y1);
        ((y - self.y0) as usize) * self.width() as usize + (x - self.x0) as usize
    }
}

/// `x 0..64, y 16..32` (ends excluded), as messages show it.
impl fmt::Display for PixelRect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "x {}..{}, y {}..{}", self.x0, self.x1, self.y0, self.y1)
    }
}
