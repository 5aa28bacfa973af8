//! The one writer: a frame's pixels to its [`Output`], as its [`Plan`]
//! says. A whole frame gets the AOV pass when layers or denoising are
//! asked for, then the denoised beauty (and, on request, the noisy one
//! beside it), with the layers when the plan lists any; a piece gets its
//! exact sums (`crate::farm::piece`); a watch pass its beauty.

use super::output::Output;
use super::plan::Plan;
use super::render::Pixels;
use crate::aov::{render_aovs, write_exr_layers};
use crate::farm::{PieceError, PieceMeta, write_piece};
use crate::imageio::{Image, ImageError, write_image_with};
use crate::scene::Scene;
use crate::view::View;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What the writer needs beside the frame.
#[derive(Clone, Copy, Debug, Default)]
pub struct WriteOptions<'a> {
    /// Threads of the AOV pass; `None` uses every core.
    pub threads: Option<usize>,
    /// With denoising, also write the image before denoising
    /// ([`noisy_path`]).
    pub keep_noisy: bool,
    /// A piece's metadata (`crate::farm::piece_meta`); required for the
    /// sums of a piece, ignored otherwise.
    pub piece: Option<&'a PieceMeta>,
}

/// Why a frame was not written.
#[derive(Debug, thiserror::Error)]
pub enum WriteError {
    /// The image or its layers could not be encoded or written.
    #[error(transparent)]
    Image(#[from] ImageError),
    /// The piece file could not be written.
    #[error(transparent)]
    Piece(#[from] PieceError),
    /// The denoiser failed.
    #[error(transparent)]
    Denoise(#[from] crate::denoise::DenoiseError),
    /// A piece's sums came without its metadata.
    #[error("{}: a piece is written with its metadata", path.display())]
    NoPieceMeta {
        /// The output.
        path: PathBuf,
    },
}

/// Where `--keep-noisy` writes: the output with `.noisy` before its extension.
pub fn noisy_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("render");
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("png");
    out.with_file_name(format!("{stem}.noisy.{ext}"))
}

/// Writes `pixels`, rendered for `plan`, to `output` atomically. Returns
/// what to add to the summary line (the AOV pass's and denoiser's times,
/// where the noisy image went).
pub fn write(
    scene: &Scene,
    view: &View,
    plan: &Plan,
    output: &Output,
    pixels: &Pixels,
    opts: &WriteOptions,
) -> Result<String, WriteError> {
    let path = output.path.as_path();
    let image = match (pixels, opts.piece) {
        (Pixels::Sums(sums), Some(meta)) => {
            write_piece(path, meta, sums)?;
            return Ok(String::new());
        }
        (Pixels::Sums(_), None) if matches!(plan.request, super::Request::Piece { .. }) => {
            return Err(WriteError::NoPieceMeta {
                path: path.to_path_buf(),
            });
        }
        // A watch pass: the sums cover every sample up to its target.
        (Pixels::Sums(sums), None) => &sums.mean(plan.samples.1),
        (Pixels::Means(image), _) => image,
    };
    if !plan.denoise && plan.layers.is_empty() {
        write_image_with(image, path, &view.display)?;
        return Ok(String::new());
    }
    let t = Instant::now();
    let layers = render_aovs(scene, view, plan.layers, opts.threads);
    let mut note = format!("; AOV pass {:.2} s", t.elapsed().as_secs_f64());
    let write = |img: &Image, path: &Path| {
        if plan.layers.is_empty() {
            write_image_with(img, path, &view.display)
        } else {
            write_exr_layers(img, &layers, path)
        }
    };
    if !plan.denoise {
        write(image, path)?;
        return Ok(note);
    }
    if opts.keep_noisy {
        let noisy = noisy_path(path);
        write(image, &noisy)?;
        note += &format!("; noisy image in {}", noisy.display());
    }
    let t = Instant::now();
    let clean = crate::denoise::denoise(image, &layers)?;
    note += &format!("; denoised in {:.2} s", t.elapsed().as_secs_f64());
    write(&clean, path)?;
    Ok(note)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_noisy_image_goes_beside_the_output() {
        assert_eq!(
            noisy_path(Path::new("out/a.exr")),
            PathBuf::from("out/a.noisy.exr")
        );
        assert_eq!(noisy_path(Path::new("b.png")), PathBuf::from("b.noisy.png"));
    }
}
