//! Reading PNG (8- or 16-bit, sRGB-decoded to linear), EXR, PFM and
//! Radiance HDR (linear).

use super::{Image, ImageError, srgb_decode};
use crate::math::Rgb;
use std::path::Path;

/// Largest image file read for comparison (`diff`, `check`): 4 GiB, room
/// for a 16384² float EXR. Raise it here.
pub const MAX_IMAGE_FILE_BYTES: u64 = 4 << 30;

/// Reads `path` into linear RGB, choosing the format by extension: `.png`
/// (sRGB-decoded), `.exr`, `.hdr` or `.pfm` (linear as stored). Regular
/// files only, sizes checked before decoding.
pub fn read_image(path: &Path) -> Result<Image, ImageError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let err = |reason: String| ImageError::Read {
        path: path.to_path_buf(),
        reason,
    };
    if super::OutputFormat::from_extension(&ext).is_none() {
        return Err(ImageError::Extension {
            path: path.to_path_buf(),
            reading: true,
        });
    }
    let bytes = crate::files::read_regular(path, MAX_IMAGE_FILE_BYTES).map_err(|e| err(e.to_string()))?;
    decode_image(&bytes, &ext).map_err(err)
}

/// Decodes an image held in memory as `ext` (`png`, `exr`, `hdr` or
/// `pfm`) into linear RGB, its size checked against [`MAX_IMAGE_SIDE`]
/// before pixels are allocated. What [`read_image`] and the fuzz target
/// call.
pub fn decode_image(bytes: &[u8], ext: &str) -> Result<Image, String> {
    let Some(format) = super::OutputFormat::from_extension(ext) else {
        return Err(format!("unsupported image format `{ext}`"));
    };
    let format = match format {
        super::OutputFormat::Pfm => {
            let img = read_pfm(bytes)?;
            if img.width.max(img.height) > MAX_IMAGE_SIDE {
                return Err(format!(
                    "{}×{} is above the limit of {MAX_IMAGE_SIDE} pixels a side",
                    img.width, img.height
                ));
            }
            return Ok(img);
        }
        super::OutputFormat::Png => image::ImageFormat::Png,
        super::OutputFormat::Exr => image::ImageFormat::OpenExr,
        super::OutputFormat::Hdr => image::ImageFormat::Hdr,
    };
    let img = decode_limited(bytes, Some(format), u64::from(MAX_IMAGE_SIDE).pow(2))?;
    let (width, height) = (img.width(), img.height());
    if format == image::ImageFormat::Png
        && img.color().bits_per_pixel() / u16::from(img.color().channel_count()) == 16
    {
        return Ok(decode_png16(&img.to_rgb16()));
    }
    let pixels = if format == image::ImageFormat::Png {
        img.to_rgb8()
            .pixels()
            .map(|p| {
                Rgb::new(
                    srgb_decode(p[0] as f32 / 255.0),
                    srgb_decode(p[1] as f32 / 255.0),
                    srgb_decode(p[2] as f32 / 255.0),
                )
            })
            .collect()
    } else {
        img.to_rgb32f()
            .pixels()
            .map(|p| Rgb::new(p[0], p[1], p[2]))
            .collect()
    };
    Ok(Image {
        width,
        height,
        pixels,
    })
}

/// Decodes `bytes` (format guessed when `None`) refusing, from the header
/// and before decoding, more than `max_pixels` pixels or a side above
/// [`MAX_IMAGE_SIDE`]; the decoder's own allocations are capped too.
fn decode_limited(
    bytes: &[u8],
    format: Option<image::ImageFormat>,
    max_pixels: u64,
) -> Result<image::DynamicImage, String> {
    let open = || {
        let cursor = std::io::Cursor::new(bytes);
        match format {
            Some(f) => Ok(image::ImageReader::with_format(cursor, f)),
            None => image::ImageReader::new(cursor)
                .with_guessed_format()
                .map_err(|e| e.to_string()),
        }
    };
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    // Room for the decoded pixels at 32-bit float RGBA, and no more.
    limits.max_alloc = Some(max_pixels * 16);
    let mut header = open()?;
    header.limits(limits.clone());
    let (w, h) = header.into_dimensions().map_err(|e| e.to_string())?;
    if u64::from(w) * u64::from(h) > max_pixels || w.max(h) > MAX_IMAGE_SIDE {
        return Err(format!("{w}×{h} is above the limit of {max_pixels} pixels"));
    }
    let mut reader = open()?;
    reader.limits(limits);
    // The decoders are not ours: a panic on input nobody foresaw becomes an
    // error rather than taking the renderer down.
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(move || reader.decode()))
        .map_err(|_| "the image decoder gave up".to_string())?
        .map_err(|e| e.to_string())
}

/// A 16-bit PNG's pixels, sRGB-decoded.
fn decode_png16(img: &image::ImageBuffer<image::Rgb<u16>, Vec<u16>>) -> Image {
    let d = |v: u16| srgb_decode(f32::from(v) / 65535.0);
    Image {
        width: img.width(),
        height: img.height(),
        pixels: img
            .pixels()
            .map(|p| Rgb::new(d(p[0]), d(p[1]), d(p[2])))
            .collect(),
    }
}

/// Portable float map: `PF` (RGB) or `Pf` (grey), size, scale (negative =
/// little endian), then rows **bottom first**.
pub fn read_pfm(bytes: &[u8]) -> Result<Image, String> {
    let mut fields = Vec::new();
    let mut i = 0;
    while fields.len() < 4 {
        while i < bytes.len() && bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        let start = i;
        while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if start == i {
            return Err("truncated PFM header".into());
        }
        fields.push(String::from_utf8_lossy(&bytes[start..i]).to_string());
    }
    i += 1; // the single whitespace byte ending the header
    let channels = match fields[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        other => return Err(format!("not a PFM file (magic `{other}`)")),
    };
    let dim = |x: f64| {
        if x.fract() == 0.0 && (1.0..=f64::from(u32::MAX)).contains(&x) {
            Ok(x as u32)
        } else {
            Err(format!("bad PFM size {x}"))
        }
    };
    let parse = |s: &str| {
        s.parse::<f64>()
            .map_err(|_| format!("bad PFM header field `{s}`"))
    };
    let (w, h, scale) = (
        dim(parse(&fields[1])?)?,
        dim(parse(&fields[2])?)?,
        parse(&fields[3])?,
    );
    // Checked: a header may claim any size; the data must be there before
    // anything is allocated or indexed.
    let n = (w as usize)
        .checked_mul(h as usize)
        .and_then(|p| p.checked_mul(channels))
        .filter(|&n| n > 0)
        .ok_or_else(|| format!("PFM size {w}×{h} is empty or too large"))?;
    let end = n
        .checked_mul(4)
        .and_then(|b| b.checked_add(i))
        .ok_or("PFM size too large")?;
    let data = bytes.get(i..end).ok_or("truncated PFM data")?;
    let mut img = Image::new(w, h);
    let value = |k: usize| {
        let b = [data[4 * k], data[4 * k + 1], data[4 * k + 2], data[4 * k + 3]];
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let (w, h) = (w as usize, h as usize);
    for px in 0..w * h {
        let (x, row) = (px % w, px / w);
        let k = px * channels;
        let v = if channels == 3 {
            Rgb::new(value(k), value(k + 1), value(k + 2))
        } else {
            Rgb::splat(value(k))
        };
        img.pixels[(h - 1 - row) * w + x] = v;
    }
    Ok(img)
}

/// Largest side of an image ronray decodes (textures, images to compare).
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// Largest number of pixels of a decoded texture: 8192 × 8192. A PNG of
/// 11000 × 11000 is 375 KB on disk and 2.6 GB decoded, so the size is read
/// from the header and refused before decoding. Raise it here.
pub const MAX_TEXTURE_PIXELS: u64 = 8192 * 8192;

/// Largest texture file read: 1 GiB.
pub const MAX_TEXTURE_FILE_BYTES: u64 = 1 << 30;

/// Decodes an image file for use as a texture: regular files only, its size
/// checked from the header against [`MAX_TEXTURE_PIXELS`] before anything is
/// decoded, and the decoder's own allocation capped.
pub fn decode_texture(path: &Path) -> Result<image::DynamicImage, String> {
    let bytes = crate::files::read_regular(path, MAX_TEXTURE_FILE_BYTES)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    decode_texture_bytes(&bytes).map_err(|e| match e.contains("above the limit") {
        true => format!(
            "{}: {e} (the texture limit is 8192×8192); scale it down",
            path.display()
        ),
        false => format!("cannot decode {}: {e}", path.display()),
    })
}

/// Decodes a texture held in memory (format guessed from its first bytes)
/// within [`MAX_TEXTURE_PIXELS`]. What [`decode_texture`] and the fuzz
/// target call.
pub fn decode_texture_bytes(bytes: &[u8]) -> Result<image::DynamicImage, String> {
    decode_limited(bytes, None, MAX_TEXTURE_PIXELS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pfm_reads_bottom_row_first() {
        let mut bytes = b"PF\n1 2\n-1.0\n".to_vec();
        for v in [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let img = read_pfm(&bytes).expect("valid pfm");
        assert_eq!(
            img.get(0, 1),
            Rgb::new(1.0, 2.0, 3.0),
            "first stored row is the bottom"
        );
        assert_eq!(img.get(0, 0), Rgb::new(4.0, 5.0, 6.0));
        assert!(
            read_pfm(b"PF\n1 2\n-1.0\n\x00").is_err(),
            "truncated data is an error"
        );
    }
}
