//! Images in and out: a linear float RGB buffer, read from PNG/EXR/PFM/HDR,
//! written to PNG (sRGB, 8- or 16-bit, exposed and tone mapped), EXR, PFM or
//! HDR (linear float) atomically, and
//! compared by metrics; [`PixelRect`] names a part of one and
//! [`SampleSums`] holds its exact per-pixel sample sums.

pub mod encode;
pub mod format;
pub mod metrics;
pub mod read;
pub mod rect;
pub mod sample_sums;
pub mod tonemap;
pub mod write;

pub use format::OutputFormat;
pub use metrics::{Block, Comparison, blocks, compare};
pub use read::read_image;
pub use rect::PixelRect;
pub use sample_sums::SampleSums;
pub use tonemap::{Display, Tonemap};
pub use write::{write_atomic, write_image, write_image_with};

use crate::math::Rgb;

/// Linear RGB pixels, row 0 at the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major, top row first: pixel `(x, y)` is `pixels[y·width + x]`; linear RGB
    /// radiance, not clamped.
    pub pixels: Vec<Rgb>,
}

impl Image {
    /// A black image of `width × height` pixels.
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            pixels: vec![Rgb::ZERO; (width * height) as usize],
        }
    }

    /// Pixel `(x, y)`, `x` from the left, `y` from the top; panics outside the image.
    #[inline]
    pub fn get(&self, x: u32, y: u32) -> Rgb {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Box-filtered downsampling by an integer factor: with a box pixel
    /// filter this is the same integral as rendering at the lower size.
    pub fn downsample(&self, factor: u32) -> Image {
        let (w, h) = (self.width / factor, self.height / factor);
        let mut out = Image::new(w, h);
        let norm = 1.0 / (factor * factor) as f32;
        for y in 0..h {
            for x in 0..w {
                let mut s = Rgb::ZERO;
                for dy in 0..factor {
                    for dx in 0..factor {
                        s += self.get(x * factor + dx, y * factor + dy);
                    }
                }
                out.pixels[(y * w + x) as usize] = s * norm;
            }
        }
        out
    }
}

/// sRGB transfer function (IEC 61966-2-1), linear → encoded.
#[inline]
pub fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// Linear → 8-bit sRGB, clamped: what a PNG output stores.
#[inline]
pub fn srgb8(x: f32) -> u8 {
    (srgb_encode(x.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
}

/// The image as 8-bit sRGB RGB bytes, row 0 first (PNG outputs, the watch
/// page).
pub fn to_srgb8(img: &Image) -> Vec<u8> {
    img.pixels.iter().flat_map(|p| p.to_array().map(srgb8)).collect()
}

/// sRGB transfer function, encoded → linear.
#[inline]
pub fn srgb_decode(x: f32) -> f32 {
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// Why an image could not be read or written; the message names the file.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// The file could not be opened or decoded.
    #[error("cannot read image {path}: {reason}")]
    Read {
        /// The image file.
        path: std::path::PathBuf,
        /// What the decoder or the file system said.
        reason: String,
    },
    /// The file could not be encoded or written (the previous file, if any, is left
    /// untouched).
    #[error("cannot write image {path}: {reason}")]
    Write {
        /// The image file.
        path: std::path::PathBuf,
        /// What the encoder or the file system said.
        reason: String,
    },
    /// The file name's extension is not an image format ronray handles.
    #[error("unsupported image extension for {} (use {})", path.display(), OutputFormat::choices())]
    Extension {
        /// The image file.
        path: std::path::PathBuf,
        /// True when reading, false when writing.
        reading: bool,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_and_hits_known_points() {
        assert_eq!(srgb_encode(0.0), 0.0);
        assert!((srgb_encode(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_decode(0.5) - 0.214).abs() < 1e-3);
        for i in 0..=100 {
            let x = i as f32 / 100.0;
            assert!((srgb_decode(srgb_encode(x)) - x).abs() < 1e-5);
        }
    }
}
