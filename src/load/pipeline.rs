//! Reading a scene file through every stage: parse ([`super::source`]),
//! compose includes, apply overrides, validate, build. Each stage's problems
//! become located diagnostics, all reported together.

use super::build::{BuildStats, build_in};
use super::include::Composition;
pub use super::source::{command_line, located, parse, read};
use crate::desc::SceneDesc;
use crate::diagnostic::Report;
use crate::scene::Scene;
use crate::view::View;
use std::path::{Path, PathBuf};

/// A scene ready to render, with what produced it.
pub struct Loaded {
    /// What rays query.
    pub scene: Scene,
    /// Camera, film, integrator and output.
    pub view: View,
    /// The checked description the scene was built from (includes composed,
    /// overrides applied).
    pub desc: SceneDesc,
    /// What building cost, and its notes.
    pub stats: BuildStats,
    /// Every file the scene depends on (itself first, its includes, OBJ
    /// files, the MTL files they name and those files' textures, textures,
    /// environment maps, glTF assets with their buffers and images, `.vol`
    /// grids), for watch mode, `validate -v` and the farm's scene hash.
    pub files: Vec<PathBuf>,
    /// Located [`Severity::Warning`](crate::diagnostic::Severity) diagnostics
    /// for a scene that loads but will surprise (`load::warnings`), with the
    /// sources they point into, so commands render them like errors; empty
    /// when there is nothing to say. The library never prints them.
    pub warnings: Report,
}

/// Why a scene did not load.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The scene file itself could not be read.
    #[error("cannot read scene file {}: {source}", path.display())]
    Io {
        /// The file, as given.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// The scene has mistakes: every one found, located.
    #[error("{} in {}", plural(.0.count(crate::diagnostic::Severity::Error)), files(.0))]
    Invalid(Report),
}

/// The files (or `--set` arguments) a report's diagnostics are in, in order.
fn files(r: &Report) -> String {
    let mut names: Vec<String> = Vec::new();
    for d in &r.diagnostics {
        let name = d.file.display().to_string();
        if !names.contains(&name) {
            names.push(name);
        }
    }
    names.join(", ")
}

fn plural(n: usize) -> String {
    if n == 1 {
        "1 error".into()
    } else {
        format!("{n} errors")
    }
}

impl LoadError {
    /// The located diagnostics, for an invalid scene.
    pub fn report(&self) -> Option<&Report> {
        match self {
            LoadError::Invalid(r) => Some(r),
            LoadError::Io { .. } => None,
        }
    }
}

/// Command-line settings that replace the scene file's, checked by the
/// same validation.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// `--spp`: samples per pixel.
    pub spp: Option<u32>,
    /// `--size`: width and height in pixels.
    pub size: Option<(u32, u32)>,
    /// `--seed`.
    pub seed: Option<u64>,
    /// `path=value` typed overrides (`--set`), applied before the others.
    pub sets: Vec<String>,
    /// The entries of `sets` that came from a flag of their own, with the
    /// flag as written (`("film.png_bits=12", "--png-bits 12")`), so a
    /// diagnostic names what the user typed.
    pub flags: Vec<(String, String)>,
    /// `--root DIR`: every file the scene reads (the scene itself, includes,
    /// OBJ and MTL files, textures, environment maps) must resolve, symlinks
    /// followed, inside this folder; for rendering untrusted scenes. It also
    /// widens where includes may come from (by default, the scene's folder).
    pub root: Option<PathBuf>,
    /// `--frame N`: the animation frame drawn (`animation.frame`). A scene
    /// without `animation` has the one frame 0.
    pub frame: Option<i32>,
}

impl Overrides {
    /// The command-line argument that set the scene field `path` (or a
    /// field around it), as the user wrote it: `--spp 0`, `--set
    /// film.spp=0`, `--png-bits 12`.
    pub fn argument_for(&self, path: &str) -> Option<String> {
        let under = |p: &str| {
            path.strip_prefix(p)
                .is_some_and(|r| r.is_empty() || r.starts_with(['.', '[']))
        };
        let flag = match path {
            "film.spp" => self.spp.map(|n| format!("--spp {n}")),
            "film.width" | "film.height" => self.size.map(|(w, h)| format!("--size {w}x{h}")),
            "film.seed" => self.seed.map(|n| format!("--seed {n}")),
            "animation.frame" => self.frame.map(|n| format!("--frame {n}")),
            _ => None,
        };
        // The flags are applied after the sets: they win.
        flag.or_else(|| {
            let set = self
                .sets
                .iter()
                .rev()
                .find(|s| s.split_once('=').is_some_and(|(p, _)| under(p.trim())))?;
            Some(match self.flags.iter().find(|(s, _)| s == set) {
                Some((_, written)) => written.clone(),
                None => format!("--set {set}"),
            })
        })
    }

    /// Writes `--spp`, `--size` and `--seed` into the description (`--set`
    /// is applied earlier, by `set.rs`).
    pub fn apply(&self, desc: &mut SceneDesc) {
        if let Some(spp) = self.spp {
            desc.film.spp = spp;
        }
        if let Some((w, h)) = self.size {
            desc.film.width = w;
            desc.film.height = h;
        }
        if let Some(seed) = self.seed {
            desc.film.seed = seed;
        }
        if let Some(frame) = self.frame {
            let a = desc.animation.get_or_insert(crate::desc::AnimationDesc {
                frames: (0, 0),
                fps: 24.0,
                frame: None,
            });
            a.frame = Some(frame);
        }
    }
}

/// Reads, parses, validates and builds `path`.
pub fn load(path: &Path) -> Result<Loaded, LoadError> {
    load_with(path, &Overrides::default())
}

/// As [`load`], with command-line overrides.
pub fn load_with(path: &Path, overrides: &Overrides) -> Result<Loaded, LoadError> {
    let text = super::source::read_text(path).map_err(|source| LoadError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    load_str(path, &text, overrides)
}

/// As [`load_with`], with the file's text already read (tests, watch mode).
pub fn load_str(path: &Path, text: &str, overrides: &Overrides) -> Result<Loaded, LoadError> {
    load_str_with_meshes(path, text, overrides, &crate::geometry::obj::load_obj_data)
}

/// As [`load_str`], reading OBJ files through `load_mesh` (watch mode's
/// cache of unchanged meshes).
pub fn load_str_with_meshes(
    path: &Path,
    text: &str,
    overrides: &Overrides,
    load_mesh: &dyn Fn(&Path) -> Result<crate::geometry::obj::ObjData, String>,
) -> Result<Loaded, LoadError> {
    let root = overrides.root.as_deref();
    if let Some(why) = root.and_then(|r| crate::files::outside_root(r, path)) {
        let mut d = crate::diagnostic::Diagnostic::new(path, "", None, format!("scene file {why}"));
        d.help = Some("render only scenes inside the --root folder, or name a wider --root".into());
        return Err(LoadError::Invalid(Report {
            diagnostics: vec![d],
            sources: Vec::new(),
        }));
    }
    let Checked {
        desc,
        composition,
        mut report,
        missing_files,
    } = check(path, text, overrides).map_err(|r| LoadError::Invalid(r.sorted()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    // Under --root the MTL files an OBJ names are fenced too, which only the
    // plain OBJ reader knows how to do (watch mode's cache is skipped).
    let fenced = |p: &Path| crate::geometry::obj::load_obj_data_in(p, root);
    let load_mesh: &dyn Fn(&Path) -> Result<crate::geometry::obj::ObjData, String> =
        if root.is_some() { &fenced } else { load_mesh };
    if report.count(crate::diagnostic::Severity::Error) > 0 {
        // Missing files alone do not hide the checks that need no content
        // of theirs: the build's, of every other object.
        let only_missing = report.diagnostics.iter().all(|d| {
            d.severity != crate::diagnostic::Severity::Error
                || d.path.as_ref().is_some_and(|p| missing_files.contains(p))
        });
        let more = if only_missing {
            build_in(&desc, base, load_mesh, root).err().unwrap_or_default()
        } else {
            // What the build would find in the OBJ files that are there.
            super::mesh_keys::content_problems(&desc, base, load_mesh)
        };
        let more: Vec<_> = more
            .into_iter()
            .filter(|p| !missing_files.contains(&p.path))
            .collect();
        report.diagnostics.extend(composition.locate(&more).diagnostics);
        return Err(LoadError::Invalid(report.sorted()));
    }
    let (scene, view, stats) = build_in(&desc, base, load_mesh, root)
        .map_err(|p| LoadError::Invalid(composition.locate(&p).sorted()))?;
    // Warnings once built: meshes, instances and SDFs have bounds then.
    let extents = super::warnings::object_extents(&scene, desc.objects.len());
    // What the files held is known now: an MTL's `Ke`, a glTF's emission
    // or punctual lights.
    let lit = scene.lights.iter().any(|l| l.power().max_element() > 0.0);
    // Judged with the camera as drawn (a glTF asset's, when it is taken).
    let drawn = stats.camera.as_ref().map(|c| SceneDesc {
        camera: c.clone(),
        ..desc.clone()
    });
    let mut warnings = super::warnings::located(
        &composition,
        &super::warnings::warnings_built(drawn.as_ref().unwrap_or(&desc), &extents, Some(lit)),
    );
    // What the build repaired or defaulted (OBJ fixes, a grey default) is
    // reported beside the warnings, as notes.
    warnings
        .diagnostics
        .extend(stats.notes.iter().map(|n| crate::diagnostic::Diagnostic {
            severity: crate::diagnostic::Severity::Note,
            ..crate::diagnostic::Diagnostic::new(path, "", None, n.clone())
        }));
    warnings.diagnostics.extend(
        composition
            .locate(&stats.located_notes)
            .with_severity(crate::diagnostic::Severity::Note)
            .diagnostics,
    );
    let mut files: Vec<PathBuf> = composition.sources.iter().map(|(p, _)| p.clone()).collect();
    files.extend(stats.texture_files.iter().cloned());
    for o in &desc.objects {
        if let crate::desc::ObjectDesc::Mesh { file, .. } = o {
            files.push(base.join(file));
        }
    }
    files.extend(desc.meshes.values().map(|m| base.join(&m.file)));
    files.extend(stats.mesh_inputs.iter().cloned());
    // Density grids: read by the build like the rest, missing from this
    // list until farm pieces were found merged across two grids.
    files.extend(desc.media.values().filter_map(|m| match m {
        crate::desc::MediumDesc::Grid { file, .. } => Some(base.join(file)),
        crate::desc::MediumDesc::Homogeneous { .. } => None,
    }));
    Ok(Loaded {
        scene,
        view,
        desc,
        stats,
        files,
        warnings,
    })
}

/// What the checks before building found.
struct Checked {
    desc: SceneDesc,
    composition: Composition,
    /// Every mistake, with the warnings they cannot have caused; empty
    /// when the scene may be built.
    report: Report,
    /// Paths of the mistakes that are only a missing file.
    missing_files: Vec<String>,
}

/// Every check before building: parse (as far as each entry allows),
/// compose includes, apply overrides, validate. All mistakes found, of every
/// kind and in every file, fail together; a scene with any is never built.
/// `Err` when the description could not be read far enough to check.
fn check(path: &Path, text: &str, overrides: &Overrides) -> Result<Checked, Report> {
    let parsed = read::<SceneDesc>(path, text)?;
    let mut desc = parsed.desc;
    let mut found = parsed.diagnostics;
    let root = overrides.root.as_deref();
    let composition =
        super::include::compose(path, text, parsed.gaps, &mut desc, root).map_err(|mut r| {
            r.diagnostics.append(&mut found);
            r
        })?;
    found.extend(composition.diagnostics.iter().cloned());
    let mut bad_sets = super::set::apply_sets(&mut desc, &overrides.sets)
        .err()
        .unwrap_or_default();
    // What the command line really set: a `--set` that did not apply set
    // nothing, and the file's value is judged where the file wrote it.
    let applied = Overrides {
        sets: overrides
            .sets
            .iter()
            .filter(|s| !bad_sets.iter().any(|b| b.arg == **s))
            .cloned()
            .collect(),
        ..overrides.clone()
    };
    for b in &mut bad_sets {
        if let Some((_, written)) = overrides.flags.iter().find(|(s, _)| *s == b.arg) {
            b.arg = written.clone();
        }
    }
    found.extend(command_line(&bad_sets).diagnostics);
    overrides.apply(&mut desc);
    let base = path.parent().unwrap_or(Path::new("."));
    let validated = super::validate::validate_files_apart(&desc, base, root);
    // A value the command line set is blamed on its argument, not the file.
    let (on_args, in_files): (Vec<_>, Vec<_>) = validated
        .problems
        .into_iter()
        .partition(|p| applied.argument_for(&p.path).is_some());
    let mut report = composition.locate(&in_files);
    report.diagnostics.extend(on_args.iter().map(|p| {
        let arg = applied.argument_for(&p.path).unwrap_or_default();
        let mut d = crate::diagnostic::Diagnostic::new(Path::new(&arg), "", None, p.message.clone());
        d.path = Some(p.path.clone());
        d.help = p.help.clone();
        d
    }));
    // The sections with a parse mistake (which may have lost an entry; one
    // with only mistakes of value, or whose entries were read with a field
    // repaired, has not).
    let broken: Vec<String> = found
        .iter()
        .filter(|d| {
            !d.path
                .as_deref()
                .is_some_and(|p| !p.is_empty() && composition.is_repaired(&d.file, p))
        })
        .map(|d| section_of(d.path.as_deref().unwrap_or("")))
        .collect();
    report.diagnostics.append(&mut found);
    if !report.diagnostics.is_empty() {
        // The warnings the mistakes cannot have caused come with them.
        let beside =
            super::warnings::warnings_beside(&desc, &|s| broken.iter().any(|b| b.is_empty() || b == s));
        let mut warned = super::warnings::located(&composition, &beside);
        report.diagnostics.append(&mut warned.diagnostics);
        report.sources = composition.sources.clone();
    }
    Ok(Checked {
        desc,
        composition,
        report,
        missing_files: validated.missing_files,
    })
}

/// The top-level section a diagnostic path is in (`objects` for
/// `objects[2].radius`); empty for none.
fn section_of(path: &str) -> String {
    path.split(['.', '[']).next().unwrap_or("").to_string()
}
