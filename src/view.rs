//! What [`crate::render::render`] needs beside the [`crate::scene::Scene`]:
//! the camera, the film, the integrator and where the image goes. Kept apart
//! from the scene so that integrators, geometry and lights see only what rays
//! query, and one scene can be rendered through several views.

use crate::aov::AovSet;
use crate::camera::Camera;
use crate::integrators::Integrator;
use crate::sampler::SamplerKind;
use std::path::{Path, PathBuf};

/// Image size and sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Seed of every random stream: same seed, same image.
    pub seed: u64,
    /// How sample positions are drawn.
    pub sampler: SamplerKind,
    /// Layers written beside the beauty pass (`film.aovs`); EXR only.
    pub aovs: AovSet,
    /// Run the denoiser on the image before writing it (`film.denoise`).
    pub denoise: bool,
}

/// Camera, film, integrator and output of one render.
#[derive(Clone, Debug)]
pub struct View {
    /// The perspective camera, in world space.
    pub camera: Camera,
    /// Image size and sampling.
    pub film: Film,
    /// The light-transport estimator.
    pub integrator: Integrator,
    /// The scene's `film.output`, resolved against the scene file's folder;
    /// empty when the scene names none.
    pub output: PathBuf,
}

impl View {
    /// Where a render of the scene at `scene_path` goes: `cli` (`-o`), else
    /// the scene's `film.output`, else `<scene stem>.png` in the current
    /// folder.
    pub fn output_path(&self, scene_path: &Path, cli: Option<PathBuf>) -> PathBuf {
        cli.or_else(|| (!self.output.as_os_str().is_empty()).then(|| self.output.clone()))
            .unwrap_or_else(|| {
                PathBuf::from(format!(
                    "{}.png",
                    scene_path
                        .file_stem()
                        .and_then(|s| s.to_str())
                        .unwrap_or("render")
                ))
            })
    }
}
