//! Writing images atomically: encode into a temporary file in the target's
//! folder, then rename over the target, so a viewer never sees half an image
//! and a failed write leaves the previous file untouched.

use super::tonemap::Display;
use super::{Image, ImageError, encode};
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes `img` to `path` atomically, choosing the format by extension: `.png`
/// (clamped, 8-bit sRGB), `.exr`, `.pfm` or `.hdr` (linear).
pub fn write_image(img: &Image, path: &Path) -> Result<(), ImageError> {
    write_image_with(img, path, &Display::default())
}

/// As [`write_image`], with `display` (exposure, tone map, bit depth)
/// applied to PNG outputs; EXR, PFM and HDR outputs stay linear.
pub fn write_image_with(img: &Image, path: &Path, display: &Display) -> Result<(), ImageError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    match ext.as_str() {
        "png" => write_atomic(path, |w| encode::png(img, display, w)),
        "pfm" => write_atomic(path, |w| encode::pfm(img, w)),
        "hdr" => write_atomic(path, |w| encode::hdr(img, w)),
        "exr" => {
            if img.pixels.len() != img.width as usize * img.height as usize {
                return Err(err("size mismatch".into()));
            }
            write_atomic(path, |w| write_exr(img, w))
        }
        _ => Err(ImageError::Extension {
            path: path.to_path_buf(),
            reading: false,
        }),
    }
}

/// Linear float RGB. The `image` crate's EXR encoding (run-length, 64-pixel
/// tiles), but with the tiles stored in increasing order: its own writer
/// stores them as its threads finish, so two writes of one image could
/// differ in bytes, and assembled pieces must equal the whole render in
/// bytes.
fn write_exr(img: &Image, w: &mut BufWriter<&std::fs::File>) -> Result<(), String> {
    use exr::prelude::{Encoding, LineOrder, SpecificChannels, Vec2, WritableImage};
    let width = img.width as usize;
    let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let c = img.pixels[p.y() * width + p.x()];
        (c.x, c.y, c.z)
    });
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    exr::prelude::Image::from_encoded_channels((width, img.height as usize), encoding, channels)
        .write()
        .to_buffered(w)
        .map_err(|e| e.to_string())
}

/// Writes `path` atomically: `encode` writes into a temporary file in the
/// target's folder, which is then renamed over the target (piece files use
/// it too).
pub fn write_atomic(
    path: &Path,
    encode: impl FnOnce(&mut BufWriter<&std::fs::File>) -> Result<(), String>,
) -> Result<(), ImageError> {
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(|e| err(e.to_string()))?;
    let tmp = tempfile::Builder::new()
        .prefix(".ronray-")
        .suffix(&format!(".{ext}.tmp"))
        .tempfile_in(dir)
        .map_err(|e| err(e.to_string()))?;
    {
        let mut w = BufWriter::new(tmp.as_file());
        encode(&mut w).map_err(err)?;
        w.flush().map_err(|e| err(e.to_string()))?;
    }
    // tempfile creates 0600 files; an image is a normal, readable file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let _ = tmp
            .as_file()
            .set_permissions(std::fs::Permissions::from_mode(0o644));
    }
    tmp.persist(path).map_err(|e| err(e.error.to_string()))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    /// Many tiles, written several times: the same bytes every time.
    #[test]
    fn exr_output_is_byte_reproducible() {
        let mut img = Image::new(300, 200);
        for (i, p) in img.pixels.iter_mut().enumerate() {
            *p = Rgb::new(i as f32 * 1e-3, (i % 7) as f32, 1.0 / (1 + i) as f32);
        }
        let dir = tempfile::tempdir().expect("temp dir");
        let bytes: Vec<Vec<u8>> = (0..4)
            .map(|k| {
                let p = dir.path().join(format!("{k}.exr"));
                write_image(&img, &p).expect("write");
                std::fs::read(&p).expect("read")
            })
            .collect();
        assert!(
            bytes.windows(2).all(|w| w[0] == w[1]),
            "EXR bytes differ between writes"
        );
        let back = crate::imageio::read_image(&dir.path().join("0.exr")).expect("reads back");
        assert!(back == img, "EXR did not round-trip");
    }
}
