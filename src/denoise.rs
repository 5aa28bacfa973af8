//! Denoising with Intel Open Image Denoise (the `RT` filter, HDR, with the
//! albedo and normal layers as auxiliary images), behind the cargo feature
//! `denoise`: the default build stays pure Rust and never needs the library.
//! `scripts/fetch-oidn.sh` fetches the official OIDN shared libraries (from
//! the `pyoidn` wheel) and prints the `OIDN_DIR` the `oidn` crate links
//! against.

use crate::aov::AovLayers;
use crate::imageio::Image;

/// Whether this build can denoise.
pub const AVAILABLE: bool = cfg!(feature = "denoise");

/// What is wrong when denoising is asked of a build without it.
pub const NOT_BUILT: &str = "this ronray was built without Open Image Denoise";

/// How to get a build that denoises.
pub const HOW_TO_ENABLE: &str = "fetch the library with `eval \"$(scripts/fetch-oidn.sh)\"`, then build with `cargo build --release --features denoise`; or drop `--denoise` / `film.denoise`";

/// Why a denoise failed.
#[derive(Debug, thiserror::Error)]
pub enum DenoiseError {
    /// The build has no denoiser.
    #[error("{NOT_BUILT}; {HOW_TO_ENABLE}")]
    NotBuilt,
    /// The layers are not the image's size.
    #[error("the AOV layers are {0}×{1} and the image {2}×{3}")]
    SizeMismatch(u32, u32, u32, u32),
    /// Open Image Denoise reported an error.
    #[error("Open Image Denoise: {0}")]
    Oidn(String),
}

/// The image denoised, guided by the first-hit albedo and normal of
/// `layers` (which the caller renders even when `film.aovs` lists neither).
/// The input is HDR linear radiance; so is the output. The emission camera
/// rays see directly (`layers.emission`) is taken out before and added back
/// after: it has no Monte Carlo noise, and Open Image Denoise would shift a
/// bright light's colour (by 0.7–1.6% on the Cornell light).
pub fn denoise(image: &Image, layers: &AovLayers) -> Result<Image, DenoiseError> {
    if (layers.width, layers.height) != (image.width, image.height) {
        return Err(DenoiseError::SizeMismatch(
            layers.width,
            layers.height,
            image.width,
            image.height,
        ));
    }
    run(image, layers)
}

#[cfg(not(feature = "denoise"))]
fn run(_: &Image, _: &AovLayers) -> Result<Image, DenoiseError> {
    Err(DenoiseError::NotBuilt)
}

#[cfg(feature = "denoise")]
fn run(image: &Image, layers: &AovLayers) -> Result<Image, DenoiseError> {
    let flat = |v: &[glam::Vec3A]| -> Vec<f32> { v.iter().flat_map(|p| p.to_array()).collect() };
    // Directly seen emitters and sky go around the denoiser (see
    // `AovLayers::emission`).
    let indirect: Vec<glam::Vec3A> = image
        .pixels
        .iter()
        .zip(&layers.emission)
        .map(|(c, e)| (*c - *e).max(glam::Vec3A::ZERO))
        .collect();
    let color = flat(&indirect);
    let albedo = flat(&layers.albedo);
    let normal = flat(&layers.normal);
    let mut out = vec![0.0f32; color.len()];
    let oidn_err = |e: oidn::Error| DenoiseError::Oidn(e.to_string());
    let device = oidn::Device::new().map_err(oidn_err)?;
    oidn::RayTracing::try_new(&device)
        .map_err(oidn_err)?
        .hdr(true)
        .clean_aux(layers.aux_noise_free)
        .albedo_normal(&albedo, &normal)
        .image_dimensions(image.width as usize, image.height as usize)
        .filter(&color, &mut out)
        .map_err(oidn_err)?;
    device.get_error().map_err(oidn_err)?;
    Ok(Image {
        width: image.width,
        height: image.height,
        pixels: out
            .chunks_exact(3)
            .zip(&layers.emission)
            .map(|(c, e)| glam::Vec3A::new(c[0], c[1], c[2]) + *e)
            .collect(),
    })
}

#[cfg(all(test, not(feature = "denoise")))]
mod tests {
    use super::*;
    use crate::aov::AovSet;

    /// Without the feature the error says how to get it.
    #[test]
    fn a_build_without_the_feature_says_how_to_enable_it() {
        let img = Image::new(2, 2);
        let layers = AovLayers {
            width: 2,
            height: 2,
            written: AovSet::EMPTY,
            albedo: vec![Default::default(); 4],
            normal: vec![Default::default(); 4],
            depth: vec![0.0; 4],
            position: vec![Default::default(); 4],
            material_id: vec![0; 4],
            object_id: vec![0; 4],
            emission: vec![Default::default(); 4],
            aux_noise_free: true,
        };
        let e = denoise(&img, &layers)
            .expect_err("no denoiser in this build")
            .to_string();
        assert!(e.contains("--features denoise"), "{e}");
    }
}
