//! The [`View`] of a checked scene (what `crate::frame` needs beside the
//! scene): the camera (`camera.rs`), film (`film.rs`) and integrator
//! (`integrator.rs`) put together, with `film.output` resolved.

use super::camera::build_camera;
use super::film::{build_display, build_film, build_filter};
use super::integrator::build_integrator;
use crate::desc::SceneDesc;
use crate::view::{Shutter, View};
use std::path::Path;

/// The view of a checked scene; `base` resolves `film.output`.
pub(super) fn build_view(desc: &SceneDesc, base: &Path) -> View {
    let f = &desc.film;
    // Built at the shutter's opening; what moves while it is open goes to
    // the renderer with its keys.
    let (open, close) = super::animation::shutter(desc);
    let camera = build_camera(&super::animation::camera_at(&desc.camera, open), f.height);
    let shutter = super::animation::moves(desc).then(|| Shutter {
        open,
        close,
        camera: super::animation::camera_motion(&desc.camera, camera)
            .filter(|m| super::animation::camera_moves(m, open, close))
            .map(Box::new),
    });
    View {
        camera,
        shutter,
        film: build_film(f),
        filter: build_filter(f),
        display: build_display(f),
        integrator: build_integrator(&desc.integrator),
        output: f.output.as_ref().map(|o| base.join(o)).unwrap_or_default(),
    }
}
