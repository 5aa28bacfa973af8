//! The camera: its checks and the runtime [`Camera`] it builds.

use super::validate::{Checker, MAX_COORD};
use crate::camera::{Camera, Projection};
use crate::desc::{CameraDesc, GltfCameraDesc, ObjectDesc, ProjectionDesc};
use glam::Vec3;

impl Checker {
    pub(super) fn camera(&mut self, c: &CameraDesc, objects: &[ObjectDesc]) {
        if let Some(g) = &c.gltf {
            self.gltf_camera(c, g, objects);
        } else if let Some((eye, target)) = self.eye_and_target(c)
            && self.nonzero("camera.up", &c.up, "`up`")
        {
            let view = Vec3::from(target) - Vec3::from(eye);
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
        if c.gltf.is_none() {
            self.projection(c);
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

    /// `eye` and `target`, both there and finite, or a problem for each
    /// missing one.
    fn eye_and_target(&mut self, c: &CameraDesc) -> Option<([f32; 3], [f32; 3])> {
        let mut check = |field: &str, v: Option<[f32; 3]>, what: &str| match v {
            Some(v) => self.finite(&format!("camera.{field}"), &v).then_some(v),
            None => {
                self.push(
                    "camera",
                    format!("the camera has no `{field}`"),
                    format!(
                        "write `{field}: (x, y, z)`, {what}; or look through a glTF asset's \
                         camera with `gltf: (file: \"…\")`"
                    ),
                );
                None
            }
        };
        let eye = check("eye", c.eye, "the point the camera looks from");
        let target = check("target", c.target, "a point it looks at");
        Some((eye?, target?))
    }

    /// A glTF asset's camera: the file must be one `Gltf` object's, and
    /// the fields the asset's camera gives are not written as well.
    fn gltf_camera(&mut self, c: &CameraDesc, g: &GltfCameraDesc, objects: &[ObjectDesc]) {
        let given = [
            ("eye", c.eye.is_some()),
            ("target", c.target.is_some()),
            ("up", c.up != [0.0, 1.0, 0.0]),
            ("fov_y_degrees", c.fov_y_degrees.is_some()),
            ("projection", c.projection != ProjectionDesc::Perspective),
            ("keys", !c.keys.is_empty()),
        ];
        self.fields_not_wanted(
            &given,
            |field| format!("`{field}` is given by the glTF camera `gltf` takes"),
            "remove it, or remove `gltf` and describe the camera here",
        );
        if c.aperture_radius > 0.0 && c.focus_distance.is_none() {
            self.push(
                "camera.aperture_radius",
                "a glTF camera has no distance in focus: a lens with an aperture needs `focus_distance`",
                "write `focus_distance: d`, the distance from the camera to the sharp plane",
            );
        }
        let matching = objects
            .iter()
            .filter(|o| matches!(o, ObjectDesc::Gltf { file, .. } if *file == g.file))
            .count();
        if matching != 1 {
            let mut files: Vec<&str> = objects
                .iter()
                .filter_map(|o| match o {
                    ObjectDesc::Gltf { file, .. } => Some(file.as_str()),
                    _ => None,
                })
                .collect();
            files.sort_unstable();
            files.dedup();
            let (what, help) = if matching == 0 {
                (
                    format!("no `Gltf` object reads `{}`", g.file),
                    if files.is_empty() {
                        "place the asset with a `Gltf(file: ..)` object; the camera is placed as its meshes are"
                            .to_string()
                    } else {
                        format!("write the `file` of one of: {}", files.join(", "))
                    },
                )
            } else {
                (
                    format!(
                        "{matching} `Gltf` objects read `{}`: which one places the camera is unclear",
                        g.file
                    ),
                    "the camera follows one object's transform: write the file differently in the others \
                     (e.g. `./` in front), or place the asset once"
                        .to_string(),
                )
            };
            self.push("camera.gltf.file", what, help);
        }
    }

    /// A problem at `camera.<field>` for each `(field, written)` written.
    fn fields_not_wanted(&mut self, fields: &[(&str, bool)], why: impl Fn(&str) -> String, help: &str) {
        for &(field, written) in fields {
            if written {
                self.push(&format!("camera.{field}"), why(field), help);
            }
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
            self.fields_not_wanted(
                &lens,
                |field| format!("`{field}` does nothing for {name} camera"),
                "remove it; field of view and depth of field belong to `Perspective`",
            );
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
    let (eye, target) = c.look();
    let mut camera = Camera::look_at(eye.into(), target.into(), c.up.into(), fov).with_projection(projection);
    camera.aperture_radius = c.aperture_radius;
    if let Some(f) = c.focus_distance {
        camera.focus_distance = f;
    }
    camera
}
