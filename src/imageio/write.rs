//! Writing images atomically: encode into a temporary file in the target's
//! folder, then rename over the target, so a viewer never sees half an image
//! and a failed write leaves the previous file untouched.

use super::{Image, ImageError};
use std::io::{BufWriter, Write};
use std::path::Path;

pub fn write_image(img: &Image, path: &Path) -> Result<(), ImageError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let format = match ext.as_str() {
        "png" => image::ImageFormat::Png,
        "exr" => image::ImageFormat::OpenExr,
        _ => {
            return Err(ImageError::Extension {
                path: path.to_path_buf(),
                reading: false,
            });
        }
    };
    let dynimg = match format {
        image::ImageFormat::Png => {
            let bytes = super::to_srgb8(img);
            image::DynamicImage::ImageRgb8(
                image::RgbImage::from_raw(img.width, img.height, bytes)
                    .ok_or_else(|| err("size mismatch".into()))?,
            )
        }
        _ => {
            let floats = img.pixels.iter().flat_map(|p| p.to_array()).collect();
            image::DynamicImage::ImageRgb32F(
                image::Rgb32FImage::from_raw(img.width, img.height, floats)
                    .ok_or_else(|| err("size mismatch".into()))?,
            )
        }
    };
    write_atomic(path, |w| dynimg.write_to(w, format).map_err(|e| e.to_string()))
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
