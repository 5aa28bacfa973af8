//! Writing images atomically: encode into a temporary file in the target's
//! folder, then rename over the target, so a viewer never sees half an image
//! and a failed write leaves the previous file untouched.

use super::tonemap::Display;
use super::{Image, ImageError, OutputFormat, encode};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Writes `img` to `path` atomically, choosing the format by extension: `.png`
/// (clamped, 8-bit sRGB), `.exr`, `.pfm` or `.hdr` (linear).
pub fn write_image(img: &Image, path: &Path) -> Result<(), ImageError> {
    write_image_with(img, path, &Display::default())
}

/// As [`write_image`], with `display` (exposure, tone map, bit depth)
/// applied to PNG outputs; EXR, PFM and HDR outputs stay linear.
pub fn write_image_with(img: &Image, path: &Path, display: &Display) -> Result<(), ImageError> {
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let Some(format) = OutputFormat::of_path(path) else {
        return Err(ImageError::Extension {
            path: path.to_path_buf(),
            reading: false,
        });
    };
    match format {
        OutputFormat::Png => write_atomic(path, |w| encode::png(img, display, w)),
        OutputFormat::Pfm => write_atomic(path, |w| encode::pfm(img, w)),
        OutputFormat::Hdr => write_atomic(path, |w| encode::hdr(img, w)),
        OutputFormat::Exr => {
            if img.pixels.len() != img.width as usize * img.height as usize {
                return Err(err("size mismatch".into()));
            }
            write_atomic(path, |w| write_exr(img, w))
        }
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

/// Temporary files being written now, so that an interrupted command
/// (Ctrl-C) can remove them before it exits: see [`remove_pending`].
static PENDING: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

/// Removes every temporary file a write in progress holds. The command
/// line's Ctrl-C handler calls it before exiting (the process ends without
/// running destructors, which would otherwise leave `.ronray-*.tmp` files
/// behind); the write that owned them then fails, which no one sees.
pub fn remove_pending() {
    let pending = PENDING.lock().unwrap_or_else(|p| p.into_inner());
    for p in pending.iter() {
        let _ = std::fs::remove_file(p);
    }
}

fn pending(tmp: &Path, add: bool) {
    let mut pending = PENDING.lock().unwrap_or_else(|p| p.into_inner());
    if add {
        pending.push(tmp.to_path_buf());
    } else {
        pending.retain(|p| p != tmp);
    }
}

/// Writes `path` atomically: `encode` writes into a temporary file in the
/// target's folder, which is then renamed over the target (piece files use
/// it too). An existing target keeps its permissions; a new one is 0644.
/// A symlink is written through to its target.
pub fn write_atomic(
    path: &Path,
    encode: impl FnOnce(&mut BufWriter<&std::fs::File>) -> Result<(), String>,
) -> Result<(), ImageError> {
    let err = |reason: String| ImageError::Write {
        path: path.to_path_buf(),
        reason,
    };
    let target = crate::files::follow_links(path);
    let ext = target.extension().and_then(|e| e.to_str()).unwrap_or("");
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    std::fs::create_dir_all(dir).map_err(|e| err(e.to_string()))?;
    let tmp = tempfile::Builder::new()
        .prefix(".ronray-")
        .suffix(&format!(".{ext}.tmp"))
        .tempfile_in(dir)
        .map_err(|e| err(e.to_string()))?;
    pending(tmp.path(), true);
    let written = (|| {
        {
            let mut w = BufWriter::new(tmp.as_file());
            encode(&mut w).map_err(err)?;
            w.flush().map_err(|e| err(e.to_string()))?;
        }
        // tempfile creates 0600 files; an image is a normal, readable file,
        // and one written over keeps the mode it had.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&target).map_or(0o644, |m| m.permissions().mode() & 0o7777);
            let _ = tmp
                .as_file()
                .set_permissions(std::fs::Permissions::from_mode(mode));
        }
        Ok(())
    })();
    let tmp_path = tmp.path().to_path_buf();
    let result = written.and_then(|()| {
        tmp.persist(&target)
            .map(drop)
            .map_err(|e| err(e.error.to_string()))
    });
    pending(&tmp_path, false);
    result
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

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .expect("list")
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .filter(|n| n.starts_with(".ronray-"))
            .collect()
    }

    /// Ctrl-C while an image is being written: the handler removes the
    /// temporary file (the process then exits without destructors).
    #[test]
    fn an_interrupted_write_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("out.png");
        let r = write_atomic(&out, |w| {
            w.write_all(b"half an image").map_err(|e| e.to_string())?;
            w.flush().map_err(|e| e.to_string())?;
            assert_eq!(leftovers(dir.path()).len(), 1, "the temporary file is there");
            remove_pending(); // what the Ctrl-C handler does
            Ok(())
        });
        assert!(r.is_err(), "the interrupted write fails");
        assert!(leftovers(dir.path()).is_empty(), "{:?}", leftovers(dir.path()));
        assert!(!out.exists());
    }

    /// Overwriting keeps the file's mode (a 0600 private render stays
    /// private, a 0664 shared one stays shared).
    #[test]
    fn an_overwritten_output_keeps_its_mode() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().expect("temp dir");
        let out = dir.path().join("out.png");
        for mode in [0o600, 0o664] {
            write_image(&Image::new(2, 2), &out).expect("write");
            std::fs::set_permissions(&out, std::fs::Permissions::from_mode(mode)).expect("chmod");
            write_image(&Image::new(2, 2), &out).expect("overwrite");
            let got = std::fs::metadata(&out).expect("meta").permissions().mode() & 0o7777;
            assert_eq!(got, mode, "mode {mode:o} became {got:o}");
        }
    }

    /// An output that is a symlink: the link stays, its target is replaced.
    #[test]
    fn an_output_symlink_is_written_through_not_replaced() {
        let dir = tempfile::tempdir().expect("temp dir");
        let real_dir = dir.path().join("real");
        std::fs::create_dir(&real_dir).expect("mkdir");
        let real = real_dir.join("image.png");
        std::fs::write(&real, b"old").expect("write");
        let link = dir.path().join("link.png");
        std::os::unix::fs::symlink("real/image.png", &link).expect("symlink");
        write_image(&Image::new(2, 2), &link).expect("write through the link");
        assert!(
            std::fs::symlink_metadata(&link)
                .expect("meta")
                .file_type()
                .is_symlink()
        );
        assert_ne!(
            std::fs::read(&real).expect("read"),
            b"old",
            "the target was written"
        );
        assert!(leftovers(dir.path()).is_empty() && leftovers(&real_dir).is_empty());
    }
}
