//! `ronray render`'s switches for the optional finishing steps of a whole
//! frame: the denoiser (`--denoise`, `film.denoise`) and keeping the noisy
//! image. The plan decides and the writer does them (`crate::frame`).

use clap::Args;

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
