//! The film: its checks (size, sampling, filter, output, layers) and the
//! runtime [`Film`], [`Filter`] and [`Display`] it builds.

use super::validate::{Checker, MAX_EXPOSURE, MAX_FILTER_RADIUS, MAX_RESOLUTION, MAX_SPP, MIN_FILTER_SIGMA};
use crate::aov::Aov;
use crate::desc::{AllocationDesc, AovDesc, FilmDesc, FilterDesc, SamplerDesc, TonemapDesc};
use crate::film::{Adaptive, Filter, FilterKind};
use crate::imageio::{Display, OutputFormat, Tonemap};
use crate::sampler::SamplerKind;
use crate::view::{Allocation, Film};

impl Checker {
    /// The pixel filter's parameters.
    fn filter(&mut self, f: &FilterDesc) {
        let radius = |v: &mut Self, r: f32| {
            if !(r > 0.0 && r <= MAX_FILTER_RADIUS) {
                v.push(
                    "film.filter.radius",
                    format!("filter radius {r} is outside (0, {MAX_FILTER_RADIUS}]"),
                    "it is the half-width in pixels: 1.5 for `Gaussian`, 2 for `Mitchell` are typical",
                );
            }
        };
        match *f {
            FilterDesc::Box => {}
            FilterDesc::Gaussian { radius: r, sigma } => {
                radius(self, r);
                if !(MIN_FILTER_SIGMA..=MAX_FILTER_RADIUS).contains(&sigma) {
                    self.push(
                        "film.filter.sigma",
                        format!("sigma {sigma} is outside [{MIN_FILTER_SIGMA}, {MAX_FILTER_RADIUS}]"),
                        "it is the standard deviation in pixels; 0.5 is typical (pbrt's default)",
                    );
                }
            }
            FilterDesc::Mitchell { radius: r, b, c } => {
                radius(self, r);
                self.range(
                    "film.filter.b",
                    b,
                    0.0,
                    1.0,
                    "B",
                    "B = C = ⅓ is Mitchell and Netravali's recommendation",
                );
                self.range(
                    "film.filter.c",
                    c,
                    0.0,
                    1.0,
                    "C",
                    "B = C = ⅓ is Mitchell and Netravali's recommendation",
                );
            }
        }
    }

    pub(super) fn film(&mut self, f: &FilmDesc) {
        self.filter(&f.filter);
        if !f.exposure.is_finite() || f.exposure.abs() > MAX_EXPOSURE {
            self.push(
                "film.exposure",
                format!(
                    "exposure {} is not a number of stops within ±{MAX_EXPOSURE}",
                    f.exposure
                ),
                "it is in stops: +1 doubles the brightness of PNG outputs, −1 halves it; 0 leaves it",
            );
        }
        if f.png_bits != 8 && f.png_bits != 16 {
            self.push(
                "film.png_bits",
                format!("PNG bit depth {} is neither 8 nor 16", f.png_bits),
                "write 16 for smooth gradients, or leave it out for 8",
            );
        }
        for (name, v) in [("width", f.width), ("height", f.height)] {
            if v == 0 || v > MAX_RESOLUTION {
                self.push(
                    &format!("film.{name}"),
                    format!("{name} {v} is outside 1..={MAX_RESOLUTION}"),
                    format!("images are at most {MAX_RESOLUTION} pixels on a side"),
                );
            }
        }
        if !(0.0..=1.0).contains(&f.noise_threshold) {
            self.push(
                "film.noise_threshold",
                format!(
                    "noise threshold {} is outside [0, 1]",
                    f.noise_threshold
                ),
                "it is the relative standard error at which a pixel stops: 0.01 is typical, 0 turns adaptive sampling off",
            );
        }
        if f.min_spp < 2 || f.min_spp > MAX_SPP {
            self.push(
                "film.min_spp",
                format!("{} minimum samples per pixel is outside 2..={MAX_SPP}", f.min_spp),
                "a pixel needs at least 2 samples to estimate its noise; 16 (the default) or more is safer",
            );
        }
        if f.spp == 0 || f.spp > MAX_SPP {
            self.push(
                "film.spp",
                format!("{} samples per pixel is outside 1..={MAX_SPP}", f.spp),
                "use at least 1; 16–1024 is typical",
            );
        }
        if let Some(out) = &f.output {
            if OutputFormat::of_path(std::path::Path::new(out)).is_none() {
                self.push(
                    "film.output",
                    format!("output `{out}` has no supported extension"),
                    OutputFormat::advice(),
                );
            }
            // A scene from someone else's repository must not write outside
            // its own folder; the command line may (`-o`).
            let p = std::path::Path::new(out);
            if p.is_absolute()
                || p.components()
                    .any(|c| matches!(c, std::path::Component::ParentDir))
            {
                self.push(
                    "film.output",
                    format!("output `{out}` leaves the scene's folder"),
                    "write a path relative to the scene file, without `..`; to write elsewhere, pass `-o PATH` on the command line",
                );
            }
        }
        self.film_layers(f);
    }

    /// `film.aovs` and `film.denoise`: each layer once, layers only into
    /// EXR, and the denoiser only when it was built in.
    fn film_layers(&mut self, f: &FilmDesc) {
        for (i, a) in f.aovs.iter().enumerate() {
            if f.aovs[..i].contains(a) {
                self.push(
                    &format!("film.aovs[{i}]"),
                    format!("`{a:?}` is listed twice"),
                    "list each layer once",
                );
            }
        }
        let layered = |o: &str| {
            OutputFormat::of_path(std::path::Path::new(o)).is_some_and(OutputFormat::carries_layers)
        };
        if let Some(out) = f.output.as_deref().filter(|o| !f.aovs.is_empty() && !layered(o)) {
            self.push(
                "film.aovs",
                format!("AOV layers are written only to EXR, and `film.output` is `{out}`"),
                "end `film.output` in `.exr` (or pass `-o NAME.exr`), or remove `aovs`",
            );
        }
        if f.denoise && !crate::denoise::AVAILABLE {
            self.push(
                "film.denoise",
                crate::denoise::NOT_BUILT,
                crate::denoise::HOW_TO_ENABLE,
            );
        }
    }
}

/// The film of a checked scene.
pub(super) fn build_film(f: &FilmDesc) -> Film {
    Film {
        width: f.width,
        height: f.height,
        spp: f.spp,
        seed: f.seed,
        sampler: match f.sampler {
            SamplerDesc::Independent => SamplerKind::Independent,
            SamplerDesc::Stratified => SamplerKind::Stratified,
            SamplerDesc::Sobol => SamplerKind::Sobol,
        },
        aovs: f.aovs.iter().map(|a| aov_of(*a)).collect(),
        denoise: f.denoise,
        adaptive: (f.noise_threshold > 0.0).then(|| Adaptive {
            threshold: f.noise_threshold,
            min_spp: f.min_spp,
            white: (-f.exposure).exp2(),
        }),
        allocation: match f.allocation {
            AllocationDesc::Even => Allocation::Even,
            AllocationDesc::ByNoise => Allocation::ByNoise,
        },
    }
}

/// The pixel filter of a checked film.
pub(super) fn build_filter(f: &FilmDesc) -> Filter {
    Filter::new(match f.filter {
        FilterDesc::Box => FilterKind::Box,
        FilterDesc::Gaussian { radius, sigma } => FilterKind::Gaussian { radius, sigma },
        FilterDesc::Mitchell { radius, b, c } => FilterKind::Mitchell { radius, b, c },
    })
}

/// Exposure, tone map and bit depth of PNG outputs.
pub(super) fn build_display(f: &FilmDesc) -> Display {
    Display {
        exposure: f.exposure,
        tonemap: match f.tonemap {
            TonemapDesc::Clamp => Tonemap::Clamp,
            TonemapDesc::Reinhard => Tonemap::Reinhard,
            TonemapDesc::Aces => Tonemap::Aces,
            TonemapDesc::AgX => Tonemap::AgX,
        },
        png_bits: f.png_bits,
    }
}

/// The runtime layer of a scene-file layer.
fn aov_of(a: AovDesc) -> Aov {
    match a {
        AovDesc::Albedo => Aov::Albedo,
        AovDesc::Normal => Aov::Normal,
        AovDesc::Depth => Aov::Depth,
        AovDesc::Position => Aov::Position,
        AovDesc::MaterialIndex => Aov::MaterialIndex,
        AovDesc::ObjectIndex => Aov::ObjectIndex,
    }
}
