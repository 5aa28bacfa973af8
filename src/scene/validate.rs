//! Semantic checks on a parsed scene. Returns every problem at once, each
//! with its path in the scene, so a user fixes a file in one round trip.

use super::desc::{
    CameraDesc, Color, ColorDesc, FilmDesc, FresnelDesc, IntegratorDesc, LightDesc, MaterialDesc, ObjectDesc,
    SceneDesc, TransformDesc, V3,
};
use super::problem::{Problem, suggest};
use glam::Vec3;

/// Largest accepted image side, in pixels.
pub const MAX_RESOLUTION: u32 = 16_384;
/// Largest accepted samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;
/// Largest accepted shadow rays per area light.
pub const MAX_LIGHT_SAMPLES: u32 = 4096;
/// Largest accepted Whitted recursion depth.
pub const MAX_DEPTH: u32 = 64;

pub fn validate(scene: &SceneDesc) -> Vec<Problem> {
    let mut v = Checker { problems: Vec::new() };
    v.camera(&scene.camera);
    v.film(&scene.film);
    v.integrator(&scene.integrator);
    if let Some(t) = &scene.test {
        if t.width == 0 || t.width > 4096 || t.height.is_some_and(|h| h == 0 || h > 4096) {
            v.push(
                "test.width",
                "test image size is outside 1..=4096",
                "regression renders are small, e.g. 64 pixels wide",
            );
        }
        if t.spp == 0 || t.spp > MAX_SPP {
            v.push(
                "test.spp",
                format!("{} samples per pixel is outside 1..={MAX_SPP}", t.spp),
                "use 4–64 for regression renders",
            );
        }
        if !(t.tolerance > 0.0 && t.tolerance.is_finite()) {
            v.push(
                "test.tolerance",
                format!("tolerance {} must be > 0", t.tolerance),
                "it is the largest accepted relative MSE, e.g. 0.02",
            );
        }
    }
    for (name, m) in &scene.materials {
        v.material(&format!("materials.{name}"), m);
    }
    let names: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
    for (i, l) in scene.lights.iter().enumerate() {
        v.light(&format!("lights[{i}]"), l, &names);
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
            IntegratorDesc::Path { max_depth, .. } => {
                if *max_depth == 0 || *max_depth < -1 {
                    self.push(
                        "integrator.max_depth",
                        format!("max_depth {max_depth} is neither −1 nor ≥ 1"),
                        "it counts path segments: 1 = emitters only, 2 = direct lighting, 8 is typical, −1 = unlimited",
                    );
                }
            }
        }
    }

    /// A colour parameter: constants are range-checked; textures are
    /// checked when they are loaded (build).
    fn color_param(&mut self, path: &str, c: &ColorDesc, upper: Option<f32>) {
        match c {
            ColorDesc::Rgb(c) => self.color(path, c, upper),
            ColorDesc::Image(f) if f.trim().is_empty() => self.push(
                path,
                "empty texture path",
                "give an image file (PNG, JPEG) relative to the scene file",
            ),
            ColorDesc::Image(_) => {}
            ColorDesc::Checker { a, b, scale } => {
                self.color(&format!("{path}.a"), a, upper);
                self.color(&format!("{path}.b"), b, upper);
                if !(*scale > 0.0 && scale.is_finite()) {
                    self.push(
                        &format!("{path}.scale"),
                        format!("checker scale {scale} must be > 0"),
                        "it is the number of squares per UV unit",
                    );
                }
            }
        }
    }

    fn range(&mut self, path: &str, x: f32, lo: f32, hi: f32, what: &str, help: &str) {
        if !(x >= lo && x <= hi) {
            self.push(path, format!("{what} {x} is outside [{lo}, {hi}]"), help);
        }
    }

    fn material(&mut self, path: &str, m: &MaterialDesc) {
        let p = |f: &str| format!("{path}.{f}");
        match m {
            MaterialDesc::Lambert { albedo } => self.color_param(&p("albedo"), albedo, Some(1.0)),
            MaterialDesc::OrenNayar { albedo, sigma } => {
                self.color_param(&p("albedo"), albedo, Some(1.0));
                self.range(
                    &p("sigma"),
                    *sigma,
                    0.0,
                    2.0,
                    "sigma",
                    "sigma is a unitless roughness: 0 is Lambert, 1 is very rough",
                );
            }
            MaterialDesc::Phong {
                diffuse,
                specular,
                exponent,
            }
            | MaterialDesc::BlinnPhong {
                diffuse,
                specular,
                exponent,
            } => {
                self.color_param(&p("diffuse"), diffuse, Some(1.0));
                self.color_param(&p("specular"), specular, Some(1.0));
                self.range(
                    &p("exponent"),
                    *exponent,
                    0.0,
                    100_000.0,
                    "exponent",
                    "the lobe sharpness: 1 is broad, 1000 is nearly a mirror",
                );
                if let (ColorDesc::Rgb(d), ColorDesc::Rgb(s)) = (diffuse, specular)
                    && d.iter().zip(s).any(|(a, b)| a + b > 1.0 + 1e-6)
                {
                    self.push(&p("specular"), format!("diffuse {d:?} + specular {s:?} exceeds 1 in a channel"), "keep diffuse + specular ≤ 1 per channel so the surface reflects no more light than it receives");
                }
            }
            MaterialDesc::CookTorrance {
                roughness, fresnel, ..
            } => {
                self.range(
                    &p("roughness"),
                    *roughness,
                    0.0,
                    1.0,
                    "roughness",
                    "0 is polished, 1 is very rough (α = roughness²)",
                );
                match fresnel {
                    FresnelDesc::Conductor { eta, k } => {
                        self.color(&p("fresnel.eta"), eta, None);
                        self.color(&p("fresnel.k"), k, None);
                        if eta.contains(&0.0) {
                            self.push(
                                &p("fresnel.eta"),
                                "a conductor's η must be > 0",
                                "use a preset such as `Metal(Gold)`",
                            );
                        }
                    }
                    FresnelDesc::Schlick { f0 } => self.color(&p("fresnel.f0"), f0, Some(1.0)),
                    FresnelDesc::Metal(_) => {}
                }
            }
            MaterialDesc::MetalPlastic {
                base_color,
                roughness,
                metalness,
            } => {
                self.color_param(&p("base_color"), base_color, Some(1.0));
                self.range(
                    &p("roughness"),
                    *roughness,
                    0.0,
                    1.0,
                    "roughness",
                    "0 is polished, 1 is very rough",
                );
                self.range(
                    &p("metalness"),
                    *metalness,
                    0.0,
                    1.0,
                    "metalness",
                    "0 is plastic, 1 is metal",
                );
            }
            MaterialDesc::Mirror { tint } => self.color_param(&p("tint"), tint, Some(1.0)),
            MaterialDesc::Glass { ior, tint, .. } => {
                self.color_param(&p("tint"), tint, Some(1.0));
                if !(*ior > 0.0 && ior.is_finite() && *ior <= 10.0) {
                    self.push(
                        &p("ior"),
                        format!("index of refraction {ior} is outside (0, 10]"),
                        "glass is about 1.5, water 1.33, diamond 2.42",
                    );
                }
            }
        }
    }

    fn light(&mut self, path: &str, l: &LightDesc, materials: &[&str]) {
        let p = |f: &str| format!("{path}.{f}");
        let surface = |v: &mut Self, m: &Option<String>| {
            if let Some(name) = m.as_deref().filter(|n| !materials.contains(n)) {
                let mut pr = Problem::new(p("material"), format!("unknown material `{name}`"));
                if let Some(s) = suggest(name, materials.iter().copied()) {
                    pr = pr.help(format!("did you mean `{s}`?"));
                }
                v.problems.push(pr);
            }
        };
        match l {
            LightDesc::Point { position, intensity } => {
                self.finite(&p("position"), position);
                self.color(&p("intensity"), intensity, None);
            }
            LightDesc::Spot {
                position,
                direction,
                intensity,
                cone_degrees,
                falloff_degrees,
            } => {
                self.finite(&p("position"), position);
                self.nonzero(&p("direction"), direction, "`direction`");
                self.color(&p("intensity"), intensity, None);
                if !(*cone_degrees > 0.0 && *cone_degrees < 180.0) {
                    self.push(
                        &p("cone_degrees"),
                        format!("cone angle {cone_degrees} is outside (0, 180)"),
                        "the full opening angle of the cone, in degrees",
                    );
                }
                if !(*falloff_degrees >= 0.0 && *falloff_degrees <= *cone_degrees) {
                    self.push(
                        &p("falloff_degrees"),
                        format!("falloff {falloff_degrees} is outside [0, cone_degrees = {cone_degrees}]"),
                        "the falloff band is the outer part of the cone",
                    );
                }
            }
            LightDesc::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
                material,
            } => {
                self.finite(&p("corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
                self.color(&p("radiance"), radiance, None);
                surface(self, material);
            }
            LightDesc::Rect {
                center,
                half_u,
                half_v,
                radiance,
                material,
            } => {
                self.finite(&p("center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
                self.color(&p("radiance"), radiance, None);
                surface(self, material);
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
            ObjectDesc::Sdf {
                shape,
                march,
                transform,
                ..
            } => (self.problems).extend(super::validate_sdf::validate_sdf(path, shape, march, transform)),
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
