//! Camera, film and integrator: their checks, and the [`View`] they build
//! (what `render()` needs beside the scene).

use super::validate::{
    Checker, MAX_COORD, MAX_DEPTH, MAX_EXPOSURE, MAX_FILTER_RADIUS, MAX_LIGHT_SAMPLES, MAX_RESOLUTION,
    MAX_RR_DEPTH, MAX_SPLITS, MAX_SPP, MIN_FILTER_SIGMA,
};
use crate::aov::Aov;
use crate::camera::{Camera, Projection};
use crate::desc::{
    AllocationDesc, AovDesc, CameraDesc, CausticsDesc, FilmDesc, FilterDesc, IntegratorDesc, ProjectionDesc,
    SamplerDesc, SceneDesc, TonemapDesc,
};
use crate::film::{Adaptive, Filter, FilterKind};
use crate::imageio::{Display, Tonemap};
use crate::integrators::{Direct, Integrator, Path as PathTracer, Whitted};
use crate::sampler::SamplerKind;
use crate::view::{Allocation, Film, View};
use glam::Vec3;
use std::path::Path;

impl Checker {
    pub(super) fn camera(&mut self, c: &CameraDesc) {
        let ok = self.finite("camera.eye", &c.eye)
            & self.finite("camera.target", &c.target)
            & self.nonzero("camera.up", &c.up, "`up`");
        if ok {
            let view = Vec3::from(c.target) - Vec3::from(c.eye);
            if view.length_squared() == 0.0 {
                self.push(
                    "camera.target",
                    "`target` equals `eye`: the camera has no view direction",
                    "move `target` away from `eye`",
                );
            } else if view.normalize().cross(Vec3::from(c.up).normalize()).length() < 1e-4 {
                self.push(
                    "camera.up",
                    format!(
                        "`up` {:?} is parallel to the view direction {:?}",
                        c.up,
                        view.to_array()
                    ),
                    "choose an `up` that is not along `target − eye`, e.g. (0, 1, 0) or (0, 0, 1)",
                );
            }
        }
        self.projection(c);
        if !(c.aperture_radius >= 0.0 && c.aperture_radius.is_finite()) {
            self.push(
                "camera.aperture_radius",
                format!("aperture radius {} must be ≥ 0", c.aperture_radius),
                "use 0 for a pinhole camera",
            );
        }
        if let Some(f) = c.focus_distance.filter(|f| !(*f > 0.0 && f.is_finite())) {
            self.push(
                "camera.focus_distance",
                format!("focus distance {f} must be > 0"),
                "it is the distance from `eye` to the sharp plane",
            );
        }
    }

    /// The projection and the fields that belong to it: a perspective camera
    /// needs `fov_y_degrees`; the others take none of the lens fields.
    fn projection(&mut self, c: &CameraDesc) {
        match c.projection {
            ProjectionDesc::Perspective => match c.fov_y_degrees {
                None => self.push(
                    "camera",
                    "the camera has no `fov_y_degrees`",
                    "a perspective camera needs its full vertical field of view in degrees, e.g. `fov_y_degrees: 40`; or choose `projection: Orthographic(view_height: ..)` or `Spherical`",
                ),
                Some(f) if !(f > 0.0 && f < 180.0) => self.push(
                    "camera.fov_y_degrees",
                    format!("field of view {f} is outside (0, 180)"),
                    "it is the full vertical angle in degrees; typical values are 30–90",
                ),
                Some(_) => {}
            },
            ProjectionDesc::Orthographic { view_height } => {
                if !(view_height > 0.0 && view_height <= MAX_COORD) {
                    self.push(
                        "camera.projection.view_height",
                        format!("view height {view_height} is not a positive size"),
                        "it is the height of the rectangle the image shows, in scene units, e.g. 2",
                    );
                }
            }
            ProjectionDesc::Spherical => {}
        }
        if c.projection != ProjectionDesc::Perspective {
            let name = match c.projection {
                ProjectionDesc::Spherical => "a spherical",
                _ => "an orthographic",
            };
            let lens = [
                ("fov_y_degrees", c.fov_y_degrees.is_some()),
                ("aperture_radius", c.aperture_radius != 0.0),
                ("focus_distance", c.focus_distance.is_some()),
            ];
            for (field, set) in lens {
                if set {
                    self.push(
                        &format!("camera.{field}"),
                        format!("`{field}` does nothing for {name} camera"),
                        "remove it; field of view and depth of field belong to `Perspective`",
                    );
                }
            }
        }
    }

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
            let ext = std::path::Path::new(out)
                .extension()
                .and_then(|e| e.to_str())
                .unwrap_or("")
                .to_ascii_lowercase();
            if !crate::imageio::WRITTEN_EXTENSIONS.contains(&ext.as_str()) {
                self.push(
                    "film.output",
                    format!("output `{out}` has no supported extension"),
                    "end it in `.png` (sRGB, tone mapped), or `.exr`, `.pfm` or `.hdr` (linear float)",
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
        let exr = |o: &str| o.to_ascii_lowercase().ends_with(".exr");
        if let Some(out) = f.output.as_deref().filter(|o| !f.aovs.is_empty() && !exr(o)) {
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

    pub(super) fn integrator(&mut self, i: &IntegratorDesc) {
        let samples = |v: &mut Self, n: u32| {
            if n == 0 || n > MAX_LIGHT_SAMPLES {
                v.push(
                    "integrator.light_samples",
                    format!("{n} light samples is outside 1..={MAX_LIGHT_SAMPLES}"),
                    "use 1–64 shadow rays per area light",
                );
            }
        };
        match i {
            IntegratorDesc::Direct { light_samples } => samples(self, *light_samples),
            IntegratorDesc::Whitted {
                max_depth,
                light_samples,
            } => {
                samples(self, *light_samples);
                if *max_depth > MAX_DEPTH {
                    self.push(
                        "integrator.max_depth",
                        format!("max_depth {max_depth} is above {MAX_DEPTH}"),
                        "a handful of specular bounces is enough; 5 is typical",
                    );
                }
            }
            IntegratorDesc::Path {
                max_depth,
                rr_depth,
                splits,
                ..
            } => {
                if *splits == 0 || *splits > MAX_SPLITS {
                    self.push(
                        "integrator.splits",
                        format!("{splits} paths per camera sample is outside 1..={MAX_SPLITS}"),
                        "1 (the default) traces one path per camera sample; 2 suits rooms lit mostly indirectly",
                    );
                }
                if *max_depth == 0 || *max_depth < -1 {
                    self.push(
                        "integrator.max_depth",
                        format!("max_depth {max_depth} is neither −1 nor ≥ 1"),
                        "it counts path segments: 1 = emitters only, 2 = direct lighting, 8 is typical, −1 = unlimited",
                    );
                }
                if *rr_depth > MAX_RR_DEPTH {
                    self.push(
                        "integrator.rr_depth",
                        format!("rr_depth {rr_depth} is above {MAX_RR_DEPTH}"),
                        "Russian roulette is what ends long paths cheaply; 5 is typical",
                    );
                }
            }
        }
    }
}

/// The view of a checked scene; `base` resolves `film.output`.
pub(super) fn build_view(desc: &SceneDesc, base: &Path) -> View {
    let c = &desc.camera;
    let f = &desc.film;
    let projection = match c.projection {
        ProjectionDesc::Perspective => Projection::Perspective,
        ProjectionDesc::Orthographic { view_height } => Projection::Orthographic { view_height },
        ProjectionDesc::Spherical => Projection::Spherical { rows: f.height },
    };
    let fov = c.fov_y_degrees.unwrap_or(40.0);
    let mut camera =
        Camera::look_at(c.eye.into(), c.target.into(), c.up.into(), fov).with_projection(projection);
    camera.aperture_radius = c.aperture_radius;
    if let Some(f) = c.focus_distance {
        camera.focus_distance = f;
    }
    let integrator = match desc.integrator {
        IntegratorDesc::Direct { light_samples } => Integrator::Direct(Direct { light_samples }),
        IntegratorDesc::Whitted {
            max_depth,
            light_samples,
        } => Integrator::Whitted(Whitted {
            max_depth,
            light_samples,
        }),
        IntegratorDesc::Path {
            max_depth,
            rr_depth,
            caustics,
            splits,
            ..
        } => Integrator::Path(PathTracer {
            max_depth: u32::try_from(max_depth).unwrap_or(u32::MAX),
            rr_depth,
            light_trace_caustics: caustics == CausticsDesc::LightTracing,
            split_caustics: false,
            splits: splits.clamp(1, MAX_SPLITS),
        }),
    };
    let filter = Filter::new(match f.filter {
        FilterDesc::Box => FilterKind::Box,
        FilterDesc::Gaussian { radius, sigma } => FilterKind::Gaussian { radius, sigma },
        FilterDesc::Mitchell { radius, b, c } => FilterKind::Mitchell { radius, b, c },
    });
    let display = Display {
        exposure: f.exposure,
        tonemap: match f.tonemap {
            TonemapDesc::Clamp => Tonemap::Clamp,
            TonemapDesc::Reinhard => Tonemap::Reinhard,
            TonemapDesc::Aces => Tonemap::Aces,
            TonemapDesc::AgX => Tonemap::AgX,
        },
        png_bits: f.png_bits,
    };
    View {
        camera,
        film: Film {
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
        },
        filter,
        display,
        integrator,
        output: f.output.as_ref().map(|o| base.join(o)).unwrap_or_default(),
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
