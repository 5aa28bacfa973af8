//! `ronray render`'s optional finishing steps for a whole frame: the AOV
//! layers (`film.aovs`) and the denoiser (`--denoise`, `film.denoise`).

use crate::aov::{render_aovs, write_exr_layers};
use crate::imageio::{Image, write_image_with};
use crate::load::Loaded;
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Denoising switches (`render` only).
#[derive(Args, Debug, Clone, Default)]
pub struct DenoiseArgs {
    /// Denoise with Intel Open Image Denoise (as `film.denoise: true`);
    /// needs a build with `--features denoise`.
    #[arg(long)]
    pub denoise: bool,
    /// With denoising, also write the image before denoising, as
    /// `<name>.noisy.<ext>` beside the output.
    #[arg(long)]
    pub keep_noisy: bool,
}

/// Where `--keep-noisy` writes: `out` with `.noisy` before its extension.
pub(super) fn noisy_path(out: &Path) -> PathBuf {
    let stem = out.file_stem().and_then(|s| s.to_str()).unwrap_or("render");
    let ext = out.extension().and_then(|e| e.to_str()).unwrap_or("png");
    out.with_file_name(format!("{stem}.noisy.{ext}"))
}

/// Writes the whole-frame `image` to `out`, first rendering the AOV pass
/// when layers or denoising are asked for, denoising when `denoise`, and
/// adding the layers `film.aovs` lists. Returns what to add to the summary.
pub(super) fn write_frame(
    loaded: &Loaded,
    image: Image,
    out: &Path,
    threads: Option<usize>,
    denoise: bool,
    keep_noisy: bool,
) -> Result<String, String> {
    let film = loaded.view.film;
    if !denoise && film.aovs.is_empty() {
        write_image_with(&image, out, &loaded.view.display).map_err(|e| e.to_string())?;
        return Ok(String::new());
    }
    let t = Instant::now();
    let layers = render_aovs(&loaded.scene, &loaded.view, film.aovs, threads);
    let mut note = format!("; AOV pass {:.2} s", t.elapsed().as_secs_f64());
    let write = |img: &Image, path: &Path| {
        if film.aovs.is_empty() {
            write_image_with(img, path, &loaded.view.display)
        } else {
            write_exr_layers(img, &layers, path)
        }
        .map_err(|e| e.to_string())
    };
    let image = if denoise {
        if keep_noisy {
            let noisy = noisy_path(out);
            write(&image, &noisy)?;
            note += &format!("; noisy image in {}", noisy.display());
        }
        let t = Instant::now();
        let clean = crate::denoise::denoise(&image, &layers).map_err(|e| e.to_string())?;
        note += &format!("; denoised in {:.2} s", t.elapsed().as_secs_f64());
        clean
    } else {
        image
    };
    write(&image, out)?;
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
