//! Encoders for the formats [`super::write_image`] writes besides EXR: PNG
//! (display-referred, 8 or 16 bits, through [`Display`]), PFM and Radiance
//! HDR (scene-linear, as rendered). Each writes into the temporary file of
//! an atomic write.

use super::tonemap::Display;
use super::{Image, srgb_encode};
use std::io::Write;

/// The image as display-encoded sRGB bytes, 3 per pixel, row 0 first.
pub fn to_display8(img: &Image, display: &Display) -> Vec<u8> {
    img.pixels
        .iter()
        .flat_map(|&p| display.map(p).to_array().map(super::srgb8))
        .collect()
}

/// The image as display-encoded 16-bit sRGB values, 3 per pixel, row 0 first.
pub fn to_display16(img: &Image, display: &Display) -> Vec<u16> {
    img.pixels
        .iter()
        .flat_map(|&p| {
            display
                .map(p)
                .to_array()
                .map(|x| (srgb_encode(x.clamp(0.0, 1.0)) * 65535.0 + 0.5) as u16)
        })
        .collect()
}

/// PNG through `display`, at its `png_bits` (16, else 8).
pub fn png(img: &Image, display: &Display, w: &mut impl Write) -> Result<(), String> {
    let dynamic = if display.png_bits == 16 {
        image::ImageBuffer::<image::Rgb<u16>, _>::from_raw(img.width, img.height, to_display16(img, display))
            .map(image::DynamicImage::ImageRgb16)
    } else {
        image::RgbImage::from_raw(img.width, img.height, to_display8(img, display))
            .map(image::DynamicImage::ImageRgb8)
    }
    .ok_or("size mismatch")?;
    let mut bytes = std::io::Cursor::new(Vec::new());
    dynamic
        .write_to(&mut bytes, image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    w.write_all(bytes.get_ref()).map_err(|e| e.to_string())
}

/// Portable float map: `PF`, size, `-1.0` (little endian), then rows
/// **bottom first**, as [`super::read::read_pfm`] reads them.
pub fn pfm(img: &Image, w: &mut impl Write) -> Result<(), String> {
    check_size(img)?;
    let mut out = format!("PF\n{} {}\n-1.0\n", img.width, img.height).into_bytes();
    out.reserve(img.pixels.len() * 12);
    for row in img.pixels.chunks_exact(img.width as usize).rev() {
        for p in row {
            for v in p.to_array() {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    w.write_all(&out).map_err(|e| e.to_string())
}

/// Radiance RGBE (`.hdr`): 8-bit mantissas sharing an exponent, about 1%
/// precision; negative values become 0.
pub fn hdr(img: &Image, w: &mut impl Write) -> Result<(), String> {
    check_size(img)?;
    let pixels: Vec<image::Rgb<f32>> = img
        .pixels
        .iter()
        .map(|p| image::Rgb(p.max(crate::math::Rgb::ZERO).to_array()))
        .collect();
    image::codecs::hdr::HdrEncoder::new(w)
        .encode(&pixels, img.width as usize, img.height as usize)
        .map_err(|e| e.to_string())
}

fn check_size(img: &Image) -> Result<(), String> {
    if img.width == 0 || img.pixels.len() != img.width as usize * img.height as usize {
        return Err("size mismatch".into());
    }
    Ok(())
}
