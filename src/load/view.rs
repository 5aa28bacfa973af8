//! The [`View`] of a checked scene (what `crate::frame` needs beside the
//! scene): the camera (`camera.rs`), film (`film.rs`) and integrator
//! (`integrator.rs`) put together, with `film.output` resolved.

use super::camera::build_camera;
use super::film::{build_display, build_film, build_filter};
use super::integrator::build_integrator;
use crate::desc::SceneDesc;
use crate::view::View;
use std::path::Path;

/// The view of a checked scene; `base` resolves `film.output`.
pub(super) fn build_view(desc: &SceneDesc, base: &Path) -> View {
    let f = &desc.film;
    View {
        camera: build_camera(&desc.camera, f.height),
        film: build_film(f),
        filter: build_filter(f),
        display: build_display(f),
        integrator: build_integrator(&desc.integrator),
        output: f.output.as_ref().map(|o| base.join(o)).unwrap_or_default(),
    }
}
