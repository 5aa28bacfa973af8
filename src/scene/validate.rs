//! Semantic checks on a parsed scene. Returns every problem at once, each
//! with its path in the scene, so a user fixes a file in one round trip.

use super::desc::{
    CameraDesc, Color, FilmDesc, IntegratorDesc, LightDesc, MaterialDesc, ObjectDesc, SceneDesc,
    TransformDesc, V3,
};
use super::problem::{Problem, suggest};
use glam::Vec3;

/// Largest accepted image side, in pixels.
pub const MAX_RESOLUTION: u32 = 16_384;
/// Largest accepted samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;
/// Largest accepted shadow rays per area light.
pub const MAX_LIGHT_SAMPLES: u32 = 4096;

pub fn validate(scene: &SceneDesc) -> Vec<Problem> {
    let mut v = Checker { problems: Vec::new() };
    v.camera(&scene.camera);
    v.film(&scene.film);
    v.integrator(&scene.integrator);
    for (name, m) in &scene.materials {
        v.material(&format!("materials.{name}"), m);
    }
    for (i, l) in scene.lights.iter().enumerate() {
        v.light(&format!("lights[{i}]"), l);
    }
    for (i, o) in scene.objects.iter().enumerate() {
        let path = format!("objects[{i}]");
        v.object(&path, o);
        if let Some(name) = o.material() {
            v.name_ref(
                &format!("{path}.material"),
                "material",
                name,
                scene.materials.keys(),
                "materials",
            );
        }
        for (key, name) in o.material_overrides().into_iter().flatten() {
            let at = format!("{path}.materials.{key}");
            v.name_ref(&at, "material", name, scene.materials.keys(), "materials");
        }
        if let ObjectDesc::Instance { mesh, .. } = o {
            v.name_ref(
                &format!("{path}.mesh"),
                "mesh",
                mesh,
                scene.meshes.keys(),
                "meshes",
            );
        }
    }
    for (name, m) in &scene.meshes {
        if m.file.trim().is_empty() {
            v.push(
                &format!("meshes.{name}.file"),
                "empty OBJ path",
                "give the path of a .obj file, relative to the scene file",
            );
        }
    }
    v.problems
}

struct Checker {
    problems: Vec<Problem>,
}

impl Checker {
    /// `name` must be one of `known` (the keys of the scene's `section`).
    fn name_ref<'a>(
        &mut self,
        path: &str,
        what: &str,
        name: &str,
        known: impl Iterator<Item = &'a String> + Clone,
        section: &str,
    ) {
        if known.clone().any(|k| k == name) {
            return;
        }
        let mut p = Problem::new(path, format!("unknown {what} `{name}`"));
        let names: Vec<&str> = known.map(String::as_str).collect();
        p = match suggest(name, names.iter().copied()) {
            Some(s) => p.help(format!("did you mean `{s}`?")),
            None if names.is_empty() => p.help(format!("define it under `{section}: {{ ... }}`")),
            None => p.help(format!(
                "the {section} defined are: {}",
                names
                    .iter()
                    .map(|k| format!("`{k}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        };
        self.problems.push(p);
    }

    fn push(&mut self, path: &str, msg: impl Into<String>, help: impl Into<String>) {
        self.problems.push(Problem::new(path, msg).help(help));
    }

    /// Finite components; false (after reporting) if not.
    fn finite(&mut self, path: &str, v: &[f32]) -> bool {
        if v.iter().all(|x| x.is_finite()) {
            return true;
        }
        self.push(
            path,
            format!("non-finite number in {v:?}"),
            "use finite numbers (no inf or NaN)",
        );
        false
    }

    fn color(&mut self, path: &str, c: &Color, upper: Option<f32>) {
        if !self.finite(path, c) {
            return;
        }
        if c.iter().any(|&x| x < 0.0) {
            self.push(
                path,
                format!("negative colour {c:?}"),
                "colour channels are linear RGB values ≥ 0",
            );
        } else if let Some(max) = upper.filter(|&m| c.iter().any(|&x| x > m)) {
            self.push(
                path,
                format!("colour {c:?} has a channel above {max}"),
                "a reflectance above 1 reflects more light than it receives; use values in [0, 1]",
            );
        }
    }

    fn nonzero(&mut self, path: &str, v: &V3, what: &str) -> bool {
        if !self.finite(path, v) {
            return false;
        }
        if Vec3::from(*v).length_squared() == 0.0 {
            self.push(
                path,
                format!("{what} is the zero vector"),
                format!("give {what} a non-zero length"),
            );
            return false;
        }
        true
    }

    fn camera(&mut self, c: &CameraDesc) {
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

    fn film(&mut self, f: &FilmDesc) {
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
        }
    }

    fn integrator(&mut self, i: &IntegratorDesc) {
        match i {
            IntegratorDesc::Direct { light_samples } => {
                if *light_samples == 0 || *light_samples > MAX_LIGHT_SAMPLES {
                    self.push(
                        "integrator.light_samples",
                        format!("{light_samples} light samples is outside 1..={MAX_LIGHT_SAMPLES}"),
                        "use 1–64 shadow rays per area light",
                    );
                }
            }
        }
    }

    fn material(&mut self, path: &str, m: &MaterialDesc) {
        match m {
            MaterialDesc::Lambert { albedo } => self.color(&format!("{path}.albedo"), albedo, Some(1.0)),
        }
    }

    fn light(&mut self, path: &str, l: &LightDesc) {
        match l {
            LightDesc::Point { position, intensity } => {
                self.finite(&format!("{path}.position"), position);
                self.color(&format!("{path}.intensity"), intensity, None);
            }
            LightDesc::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
            } => {
                self.finite(&format!("{path}.corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
                self.color(&format!("{path}.radiance"), radiance, None);
            }
            LightDesc::Rect {
                center,
                half_u,
                half_v,
                radiance,
            } => {
                self.finite(&format!("{path}.center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
                self.color(&format!("{path}.radiance"), radiance, None);
            }
        }
    }

    fn parallelogram(&mut self, path: &str, un: &str, u: &V3, vn: &str, v: &V3) {
        if self.finite(&format!("{path}.{un}"), u)
            && self.finite(&format!("{path}.{vn}"), v)
            && Vec3::from(*u).cross(Vec3::from(*v)).length() <= 1e-12
        {
            self.push(
                &format!("{path}.{vn}"),
                format!("zero-area quad: `{un}` {u:?} and `{vn}` {v:?} are parallel or zero"),
                "give the two edges non-zero, non-parallel directions",
            );
        }
    }

    fn object(&mut self, path: &str, o: &ObjectDesc) {
        match o {
            ObjectDesc::Sphere { center, radius, .. } => {
                self.finite(&format!("{path}.center"), center);
                if !(*radius > 0.0 && radius.is_finite()) {
                    self.push(
                        &format!("{path}.radius"),
                        format!("sphere radius {radius} must be > 0"),
                        "give a positive radius in scene units",
                    );
                }
            }
            ObjectDesc::Plane { point, normal, .. } => {
                self.finite(&format!("{path}.point"), point);
                self.nonzero(&format!("{path}.normal"), normal, "`normal`");
            }
            ObjectDesc::Quad {
                corner,
                edge_u,
                edge_v,
                ..
            } => {
                self.finite(&format!("{path}.corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
            }
            ObjectDesc::Rect {
                center,
                half_u,
                half_v,
                ..
            } => {
                self.finite(&format!("{path}.center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
            }
            ObjectDesc::Mesh { file, .. } => {
                if file.trim().is_empty() {
                    self.push(
                        &format!("{path}.file"),
                        "empty OBJ path",
                        "give the path of a .obj file, relative to the scene file",
                    );
                }
            }
            ObjectDesc::Instance { .. } => {}
        }
        for (k, t) in o.transform().iter().enumerate() {
            let tp = format!("{path}.transform[{k}]");
            match t {
                TransformDesc::Translate(v) => {
                    self.finite(&tp, v);
                }
                TransformDesc::Rotate { axis, degrees } => {
                    self.nonzero(&format!("{tp}.axis"), axis, "the rotation axis");
                    if !degrees.is_finite() {
                        self.push(
                            &format!("{tp}.degrees"),
                            "non-finite angle",
                            "use a finite angle in degrees",
                        );
                    }
                }
                TransformDesc::Scale(s) => {
                    if self.finite(&tp, s) && s.contains(&0.0) {
                        self.push(
                            &tp,
                            format!("scale {s:?} has a zero factor"),
                            "a zero scale flattens the object; use non-zero factors",
                        );
                    }
                }
                TransformDesc::Matrix(m) => {
                    let flat: Vec<f32> = m.iter().flatten().copied().collect();
                    if self.finite(&tp, &flat) && super::build::matrix(m).determinant().abs() < 1e-12 {
                        self.push(&tp, "matrix is singular", "a transform matrix must be invertible");
                    }
                }
            }
        }
        if let ObjectDesc::Sphere { transform, .. } = o
            && !transform.is_empty()
            && !super::build::is_similarity(&super::build::compose(transform))
        {
            self.push(
                &format!("{path}.transform"),
                "a sphere's transform must keep it round",
                "use equal scale factors on all axes (or a Mesh for an ellipsoid)",
            );
        }
    }
}
