//! Semantic checks on a parsed scene, before anything is built. Returns
//! every problem at once, each with its path in the scene, so a user fixes a
//! file in one round trip. The limits below are documented in the README;
//! raising one is a one-line change here.

use crate::desc::{Color, SceneDesc, TestDesc, V3};
use crate::diagnostic::{Problem, suggest};
use glam::Vec3;
use std::path::{Path, PathBuf};

/// Largest accepted image side, in pixels.
pub const MAX_RESOLUTION: u32 = 16_384;
/// Largest accepted samples per pixel.
pub const MAX_SPP: u32 = 1 << 20;
/// Largest accepted shadow rays per area light.
pub const MAX_LIGHT_SAMPLES: u32 = 4096;
/// Largest magnitude of any coordinate, size or colour a scene may write,
/// and of any point of a placed object (checked after the build, when
/// meshes are loaded and transformed). Squares of larger values overflow
/// f32 in ray–shape tests.
pub const MAX_COORD: f32 = 1e15;
/// Largest accepted path depth before Russian roulette starts: without
/// roulette a path in a closed white room never ends (u32::MAX took
/// minutes per sample).
pub const MAX_RR_DEPTH: u32 = 1024;
/// Largest accepted number of paths a camera sample splits into: each
/// continuation costs most of a path, and the gain is in the indirect light
/// alone (see `docs/integrators.md`).
pub const MAX_SPLITS: u32 = 16;
/// Largest accepted Whitted recursion depth.
pub const MAX_DEPTH: u32 = 64;
/// Largest pixel-filter radius, in pixels: wider filters only blur, and
/// their samples stray far outside their pixel.
pub const MAX_FILTER_RADIUS: f32 = 8.0;
/// Smallest Gaussian filter deviation, in pixels: narrower ones fall between
/// the sampling table's bins (64 per pixel).
pub const MIN_FILTER_SIGMA: f32 = 0.05;
/// Largest exposure magnitude, in stops (2⁶⁴ is far beyond any scene).
pub const MAX_EXPOSURE: f32 = 64.0;
/// Largest channel of anything that emits, in a scene or an MTL file: a
/// radiance in W/(m²·sr) (area lights, emitting objects, an environment's
/// radiance times its `strength`, an emission texture's scale and offset,
/// MTL `Ke`) or a point or spot light's intensity in W/sr. A hundred
/// thousand times the sun's disc (~2·10⁷), and far enough below `f32::MAX`
/// (3.4·10³⁸) that a light's power (radiance × area × π, summed over its
/// triangles) stays finite: a radiance of 1e38 made the power infinite and
/// the light sampling weights NaN. Above it, a scene is refused with the
/// path of the value and an MTL `Ke` is clamped with a note.
pub const MAX_RADIANCE: f32 = 1e12;
/// The help line of an emitted value above [`MAX_RADIANCE`].
pub(super) const RADIANCE_HELP: &str = "the limit is a hundred thousand times the sun's disc; beyond it a \
     light's power overflows and the image turns NaN (raise MAX_RADIANCE in src/load/validate.rs)";

/// Every problem of `scene`, found before anything is built: values out of
/// range, unknown names, and files that are missing (paths resolve against
/// `base`, the scene file's folder). Each kind of thing checks itself in its
/// own file (`view.rs`, `material.rs`, `light.rs`, `object.rs`, `mesh.rs`,
/// `sdf/`).
pub fn validate(scene: &SceneDesc, base: &Path) -> Vec<Problem> {
    validate_in(scene, base, None)
}

/// As [`validate`], refusing every file the scene names that resolves
/// outside `root` (`--root`).
pub fn validate_in(scene: &SceneDesc, base: &Path, root: Option<&Path>) -> Vec<Problem> {
    validate_files_apart(scene, base, root).problems
}

/// What validation found, with the problems that are only a missing file
/// told apart: checks that do not need the file's content (the build's,
/// of the other objects) can still run.
pub struct Validated {
    /// Every problem found.
    pub problems: Vec<Problem>,
    /// The paths (`objects[2].file`) of the problems that are a missing file.
    pub missing_files: Vec<String>,
}

/// As [`validate_in`], telling missing files apart.
pub fn validate_files_apart(scene: &SceneDesc, base: &Path, root: Option<&Path>) -> Validated {
    let mut v = Checker {
        problems: Vec::new(),
        base: base.to_path_buf(),
        root: root.map(Path::to_path_buf),
        missing_files: Vec::new(),
    };
    if let Some(version) = scene.version
        && !(1..=crate::migrate::CURRENT).contains(&version)
    {
        let current = crate::migrate::CURRENT;
        v.push(
            "version",
            format!("scene-format version {version} is not one this ronray reads (1 to {current})"),
            if version == 0 {
                "versions start at 1; remove `version` or write the current one, `version: 2`".to_string()
            } else {
                format!("the file was written for a newer ronray: update ronray, or write `version: {current}` if the file only uses version {current}'s syntax")
            },
        );
    }
    v.camera(&scene.camera, &scene.objects);
    v.film(&scene.film);
    v.integrator(&scene.integrator);
    if let Some(t) = &scene.test {
        v.test(t);
    }
    for (name, m) in &scene.materials {
        v.material(&format!("materials.{name}"), m);
    }
    let names: Vec<&str> = scene.materials.keys().map(String::as_str).collect();
    for (i, l) in scene.lights.iter().enumerate() {
        v.light(&format!("lights[{i}]"), l, &names);
    }
    v.one_environment(&scene.lights);
    for (i, o) in scene.objects.iter().enumerate() {
        v.object(&format!("objects[{i}]"), o, scene);
        v.object_media(&format!("objects[{i}]"), o, scene);
    }
    v.media(scene);
    for (name, m) in &scene.meshes {
        v.mesh_entry(&format!("meshes.{name}"), m);
    }
    v.animation(scene);
    Validated {
        problems: v.problems,
        missing_files: v.missing_files,
    }
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

/// `written` (which resolves to the missing `full`) with its file name
/// replaced by the closest name in its folder, if one is close.
fn near_name(full: &Path, written: &str) -> Option<String> {
    let name = full.file_name()?.to_str()?;
    let names: Vec<String> = std::fs::read_dir(full.parent()?)
        .ok()?
        .flatten()
        .filter_map(|e| e.file_name().into_string().ok())
        .collect();
    let near = suggest(name, names.iter().map(String::as_str))?;
    let folder = written.len() - written.rsplit(['/', '\\']).next().map_or(0, str::len);
    Some(format!("{}{near}", &written[..folder]))
}

/// Collects problems; each kind adds its own `impl Checker` block in its
/// file, with the shared helpers below.
pub(super) struct Checker {
    pub(super) problems: Vec<Problem>,
    /// The scene file's folder, which relative file names resolve against.
    pub(super) base: PathBuf,
    /// `--root`: no file outside it may be read.
    pub(super) root: Option<PathBuf>,
    /// Paths of the problems that are a missing file.
    pub(super) missing_files: Vec<String>,
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

    /// The regression-test settings (`test`).
    fn test(&mut self, t: &TestDesc) {
        if t.width == 0 || t.width > 4096 || t.height.is_some_and(|h| h == 0 || h > 4096) {
            self.push(
                "test.width",
                "test image size is outside 1..=4096",
                "regression renders are small, e.g. 64 pixels wide",
            );
        }
        if t.spp == 0 || t.spp > MAX_SPP {
            self.push(
                "test.spp",
                format!("{} samples per pixel is outside 1..={MAX_SPP}", t.spp),
                "use 4–64 for regression renders",
            );
        }
        if !(t.tolerance > 0.0 && t.tolerance.is_finite()) {
            self.push(
                "test.tolerance",
                format!("tolerance {} must be > 0", t.tolerance),
                "it is the largest accepted score of `ronray check` (about 1 per window for noise alone), e.g. 8",
            );
        }
    }

    /// `file` (relative to the scene's folder) must be a readable regular
    /// file: a missing OBJ or texture is reported with the other mistakes,
    /// not after them when the build would read it.
    pub(super) fn file(&mut self, path: &str, file: &str, what: &str) {
        if file.trim().is_empty() {
            self.push(
                path,
                format!("empty {what} path"),
                format!("give the path of the {what} file, relative to the scene file"),
            );
            return;
        }
        let full = self.base.join(file);
        if let Some(why) = self
            .root
            .as_deref()
            .and_then(|r| crate::files::outside_root(r, &full))
        {
            self.push(
                path,
                format!("{what} {why}"),
                "an untrusted scene may read only files inside --root; copy the file there or widen --root",
            );
            return;
        }
        match std::fs::metadata(&full) {
            Ok(m) if m.is_file() => {}
            Ok(_) => self.push(
                path,
                format!("{what} `{file}` is not a regular file"),
                format!("{} is a folder, a device or a pipe", full.display()),
            ),
            Err(e) => {
                let help = match near_name(&full, file) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => format!(
                        "the path resolves to {} (paths are relative to the scene file's folder)",
                        full.display()
                    ),
                };
                if e.kind() == std::io::ErrorKind::NotFound {
                    self.missing_files.push(path.to_string());
                }
                self.push(path, format!("cannot read {what} `{file}`: {e}"), help);
            }
        }
    }

    pub(super) fn range(&mut self, path: &str, x: f32, lo: f32, hi: f32, what: &str, help: &str) {
        if !(x >= lo && x <= hi) {
            self.push(path, format!("{what} {x} is outside [{lo}, {hi}]"), help);
        }
    }

    pub(super) fn parallelogram(&mut self, path: &str, un: &str, u: &V3, vn: &str, v: &V3) {
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

    pub(super) fn push(&mut self, path: &str, msg: impl Into<String>, help: impl Into<String>) {
        self.problems.push(Problem::new(path, msg).help(help));
    }

    /// Finite components; false (after reporting) if not.
    /// Finite components within ±[`MAX_COORD`]; false (after reporting)
    /// if not.
    pub(super) fn finite(&mut self, path: &str, v: &[f32]) -> bool {
        if !v.iter().all(|x| x.is_finite()) {
            self.push(
                path,
                format!("non-finite number in {v:?}"),
                "use finite numbers (no inf or NaN)",
            );
            return false;
        }
        if let Some(x) = v.iter().find(|x| x.abs() > MAX_COORD) {
            self.push(
                path,
                format!("{x:e} is beyond ±{MAX_COORD:e}"),
                "scene numbers are 32-bit floats: squared distances of larger ones overflow; scale the scene down",
            );
            return false;
        }
        true
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

    /// An emitted colour (`what`: `radiance` or `intensity`, with its
    /// unit): a colour ([`Checker::color`]) no channel of which is above
    /// [`MAX_RADIANCE`].
    pub(super) fn emitted(&mut self, path: &str, c: &Color, what: &str) {
        // Before `color`, whose ±MAX_COORD bound would call 1e38 a size.
        if c.iter().all(|x| x.is_finite()) && c.iter().any(|&x| x > MAX_RADIANCE) {
            self.push(
                path,
                format!("{what} {c:?} has a channel above the limit of {MAX_RADIANCE:e}"),
                RADIANCE_HELP,
            );
            return;
        }
        self.color(path, c, None);
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
