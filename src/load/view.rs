//! Camera, film and integrator: their checks, and the [`View`] they build
//! (what `render()` needs beside the scene).

use super::validate::{Checker, MAX_DEPTH, MAX_LIGHT_SAMPLES, MAX_RESOLUTION, MAX_RR_DEPTH, MAX_SPP};
use crate::aov::Aov;
use crate::camera::Camera;
use crate::desc::{AovDesc, CameraDesc, FilmDesc, IntegratorDesc, SamplerDesc, SceneDesc};
use crate::integrators::{Direct, Integrator, Path as PathTracer, Whitted};
use crate::sampler::SamplerKind;
use crate::view::{Film, View};
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
        if !(c.fov_y_degrees > 0.0 && c.fov_y_degrees < 180.0) {
            self.push(
                "camera.fov_y_degrees",
                format!("field of view {} is outside (0, 180)", c.fov_y_degrees),
                "it is the full vertical angle in degrees; typical values are 30–90",
            );
        }
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

    pub(super) fn film(&mut self, f: &FilmDesc) {
        for (name, v) in [("width", f.width), ("height", f.height)] {
            if v == 0 || v > MAX_RESOLUTION {
                self.push(
                    &format!("film.{name}"),
                    format!("{name} {v} is outside 1..={MAX_RESOLUTION}"),
                    format!("images are at most {MAX_RESOLUTION} pixels on a side"),
                );
            }
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
            if ext != "png" && ext != "exr" {
                self.push(
                    "film.output",
                    format!("output `{out}` has no supported extension"),
                    "end it in `.png` (8-bit sRGB) or `.exr` (linear float)",
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
                max_depth, rr_depth, ..
            } => {
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
    let mut camera = Camera::look_at(c.eye.into(), c.target.into(), c.up.into(), c.fov_y_degrees);
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
            max_depth, rr_depth, ..
        } => Integrator::Path(PathTracer {
            max_depth: u32::try_from(max_depth).unwrap_or(u32::MAX),
            rr_depth,
        }),
    };
    let f = &desc.film;
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
        },
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
    }
}
