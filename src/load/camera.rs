//! The camera: its checks and the runtime [`Camera`] it builds.

use super::validate::{Checker, MAX_COORD};
use crate::camera::{Camera, Projection};
use crate::desc::{CameraDesc, ProjectionDesc};
use glam::Vec3;

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
}

/// The camera of a checked scene; a spherical camera's rows are the film's.
pub(super) fn build_camera(c: &CameraDesc, rows: u32) -> Camera {
    let projection = match c.projection {
        ProjectionDesc::Perspective => Projection::Perspective,
        ProjectionDesc::Orthographic { view_height } => Projection::Orthographic { view_height },
        ProjectionDesc::Spherical => Projection::Spherical { rows },
    };
    let fov = c.fov_y_degrees.unwrap_or(40.0);
    let mut camera =
        Camera::look_at(c.eye.into(), c.target.into(), c.up.into(), fov).with_projection(projection);
    camera.aperture_radius = c.aperture_radius;
    if let Some(f) = c.focus_distance {
        camera.focus_distance = f;
    }
    camera
}
