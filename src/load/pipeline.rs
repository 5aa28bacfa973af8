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
    /// Every file the scene depends on (itself, meshes…), for watch mode.
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
    #[error("{} in {}", plural(.0.diagnostics.len()), files(.0))]
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
    /// `--root DIR`: every file the scene reads (the scene itself, includes,
    /// OBJ and MTL files, textures, environment maps) must resolve, symlinks
    /// followed, inside this folder; for rendering untrusted scenes. It also
    /// widens where includes may come from (by default, the scene's folder).
    pub root: Option<PathBuf>,
}

impl Overrides {
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
    let (desc, composition) = check(path, text, overrides).map_err(|r| LoadError::Invalid(r.sorted()))?;
    let base = path.parent().unwrap_or(Path::new("."));
    let mut warnings = super::warnings::located(&composition, &super::warnings::warnings(&desc));
    // Under --root the MTL files an OBJ names are fenced too, which only the
    // plain OBJ reader knows how to do (watch mode's cache is skipped).
    let fenced = |p: &Path| crate::geometry::obj::load_obj_data_in(p, root);
    let load_mesh: &dyn Fn(&Path) -> Result<crate::geometry::obj::ObjData, String> =
        if root.is_some() { &fenced } else { load_mesh };
    let (scene, view, stats) = build_in(&desc, base, load_mesh, root)
        .map_err(|p| LoadError::Invalid(composition.locate(&p).sorted()))?;
    // What the build repaired or defaulted (OBJ fixes, a grey default) is
    // reported beside the warnings, as notes.
    warnings
        .diagnostics
        .extend(stats.notes.iter().map(|n| crate::diagnostic::Diagnostic {
            severity: crate::diagnostic::Severity::Note,
            ..crate::diagnostic::Diagnostic::new(path, "", None, n.clone())
        }));
    let mut files: Vec<PathBuf> = composition.sources.iter().map(|(p, _)| p.clone()).collect();
    files.extend(stats.texture_files.iter().cloned());
    for o in &desc.objects {
        if let crate::desc::ObjectDesc::Mesh { file, .. } = o {
            files.push(base.join(file));
        }
    }
    files.extend(desc.meshes.values().map(|m| base.join(&m.file)));
    Ok(Loaded {
        scene,
        view,
        desc,
        stats,
        files,
        warnings,
    })
}

/// Every check before building: parse (as far as each entry allows),
/// compose includes, apply overrides, validate. All mistakes found, of every
/// kind and in every file, fail together; a scene with any is never built.
fn check(path: &Path, text: &str, overrides: &Overrides) -> Result<(SceneDesc, Composition), Report> {
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
    let bad_sets = super::set::apply_sets(&mut desc, &overrides.sets)
        .err()
        .unwrap_or_default();
    found.extend(command_line(&bad_sets).diagnostics);
    overrides.apply(&mut desc);
    let base = path.parent().unwrap_or(Path::new("."));
    let mut report = composition.locate(&super::validate::validate_in(&desc, base, root));
    report.diagnostics.append(&mut found);
    if report.diagnostics.is_empty() {
        return Ok((desc, composition));
    }
    report.sources = composition.sources;
    Err(report)
}
