//! Semantic checks on a parsed scene. Returns every problem at once, each
//! with its path in the scene, so a user fixes a file in one round trip.

mod camera;
mod material;
mod object;

use crate::desc::{Color, ObjectDesc, SceneDesc, V3};
use crate::diagnostic::{Problem, suggest};
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

/// The help for a reflectance written on a 0–255 scale, as image editors
/// show colours: every channel within [0, 255] and at least one above 1.5
/// (a channel just above 1 is more likely a slip than bytes).
fn byte_scale_help(c: &Color) -> Option<String> {
    let max = c.iter().copied().fold(0.0, f32::max);
    if !(max > 1.5 && max <= 255.0) {
        return None;
    }
    let [r, g, b] = c.map(|x| x / 255.0);
    Some(format!(
        "the channels look like 0–255 values; divide by 255: ({r:.3}, {g:.3}, {b:.3})"
    ))
}

pub(super) struct Checker {
    pub(super) problems: Vec<Problem>,
}

impl Checker {
    /// `name` must be one of `known` (the keys of the scene's `section`).
    pub(super) fn name_ref<'a>(
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

    pub(super) fn push(&mut self, path: &str, msg: impl Into<String>, help: impl Into<String>) {
        self.problems.push(Problem::new(path, msg).help(help));
    }

    /// Finite components; false (after reporting) if not.
    pub(super) fn finite(&mut self, path: &str, v: &[f32]) -> bool {
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

    pub(super) fn color(&mut self, path: &str, c: &Color, upper: Option<f32>) {
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
            let help = byte_scale_help(c).unwrap_or_else(|| {
                "a reflectance above 1 reflects more light than it receives; use values in [0, 1]".into()
            });
            self.push(path, format!("colour {c:?} has a channel above {max}"), help);
        }
    }

    pub(super) fn nonzero(&mut self, path: &str, v: &V3, what: &str) -> bool {
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
}
