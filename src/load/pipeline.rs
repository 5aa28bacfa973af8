//! Reading a scene file through every stage, turning each stage's problems
//! into located diagnostics.

use super::build::{BuildStats, build_with};
use super::spans::Spans;
use super::validate::validate;
use crate::desc::SceneDesc;
use crate::diagnostic::{Diagnostic, Report, offset_of};
use crate::diagnostic::{Problem, suggest};
use crate::scene::Scene;
use crate::view::View;
use std::path::{Path, PathBuf};

/// A scene ready to render, with what produced it.
pub struct Loaded {
    pub scene: Scene,
    pub view: View,
    pub desc: SceneDesc,
    pub stats: BuildStats,
    /// Every file the scene depends on (itself, meshes…), for watch mode.
    pub files: Vec<PathBuf>,
    /// Located [`Severity::Warning`](crate::diagnostic::Severity) diagnostics
    /// for a scene that loads but will surprise (`load::warnings`), with the
    /// sources they point into, so commands render them like errors; empty
    /// when there is nothing to say. The library never prints them.
    pub warnings: Report,
}

#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    #[error("cannot read scene file {}: {source}", path.display())]
    Io { path: PathBuf, source: std::io::Error },
    #[error("{} in {}", plural(.0.diagnostics.len()), .0.diagnostics.first().map(|d| d.file.display().to_string()).unwrap_or_default())]
    Invalid(Report),
}

fn plural(n: usize) -> String {
    if n == 1 {
        "1 error".into()
    } else {
        format!("{n} errors")
    }
}

impl LoadError {
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
    pub spp: Option<u32>,
    pub size: Option<(u32, u32)>,
    pub seed: Option<u64>,
    /// `path=value` typed overrides (`--set`), applied before the others.
    pub sets: Vec<String>,
}

impl Overrides {
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
    let text = std::fs::read_to_string(path).map_err(|source| LoadError::Io {
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
    let mut desc = parse(path, text).map_err(LoadError::Invalid)?;
    let composition = super::include::compose(path, text, &mut desc).map_err(LoadError::Invalid)?;
    if let Err(problems) = super::set::apply_sets(&mut desc, &overrides.sets) {
        return Err(LoadError::Invalid(command_line(&problems)));
    }
    overrides.apply(&mut desc);
    let base = path.parent().unwrap_or(Path::new("."));
    let problems = validate(&desc, base);
    if !problems.is_empty() {
        return Err(LoadError::Invalid(composition.locate(&problems)));
    }
    let mut warnings = super::warnings::located(&composition, &super::warnings::warnings(&desc));
    let (scene, view, stats) =
        build_with(&desc, base, load_mesh).map_err(|p| LoadError::Invalid(composition.locate(&p)))?;
    // What the build repaired or defaulted (OBJ fixes, a grey default) is
    // reported beside the warnings, as notes.
    warnings
        .diagnostics
        .extend(stats.notes.iter().map(|n| Diagnostic {
            severity: crate::diagnostic::Severity::Note,
            ..Diagnostic::new(path, "", None, n.clone())
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

/// RON text → [`SceneDesc`]; a syntax or type error becomes one diagnostic at
/// the position ron reports, with a suggestion for misspelled names.
pub fn parse(path: &Path, text: &str) -> Result<SceneDesc, Report> {
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("json")) {
        return parse_json(path, text);
    }
    // `implicit_some` lets optional fields be written bare (`focus_distance: 3.5`).
    let opts = ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    opts.from_str::<SceneDesc>(text).map_err(|e| {
        let start = offset_of(text, e.span.start.line, e.span.start.col);
        let mut end = offset_of(text, e.span.end.line, e.span.end.col).max(start);
        if end == start {
            end = (start + 1).min(text.len());
        }
        let (message, help) = describe(&e.code);
        let mut d = Diagnostic::new(path, text, Some(start..end), message);
        d.help = help;
        Report {
            diagnostics: vec![d],
            sources: vec![(path.to_path_buf(), text.to_string())],
        }
    })
}

/// JSON text → [`SceneDesc`], with the same kind of located diagnostic.
fn parse_json(path: &Path, text: &str) -> Result<SceneDesc, Report> {
    serde_json::from_str::<SceneDesc>(text).map_err(|e| {
        let start = offset_of(text, e.line(), e.column().max(1));
        let full = e.to_string();
        let message = full
            .rsplit_once(" at line ")
            .map_or(full.as_str(), |(m, _)| m)
            .to_string();
        // serde's wording: "unknown field `x`, expected one of `a`, `b`".
        let quoted: Vec<&str> = message.split('`').skip(1).step_by(2).collect();
        let help = match quoted.split_first() {
            Some((found, expected)) if message.starts_with("unknown") && !expected.is_empty() => {
                Some(match suggest(found, expected.iter().copied()) {
                    Some(s) => format!("did you mean `{s}`?"),
                    None => format!("expected one of {}", expected.join(", ")),
                })
            }
            _ => None,
        };
        let mut d = Diagnostic::new(path, text, Some(start.saturating_sub(1)..start), message);
        d.help = help;
        Report {
            diagnostics: vec![d],
            sources: vec![(path.to_path_buf(), text.to_string())],
        }
    })
}

/// Semantic problems → diagnostics located through the RON text.
pub fn located(path: &Path, text: &str, problems: &[Problem]) -> Report {
    let spans = Spans::scan(text);
    let diagnostics = problems
        .iter()
        .map(|p| {
            let mut d = Diagnostic::new(path, text, spans.find(&p.path), p.message.clone());
            d.path = Some(p.path.clone());
            d.help = p.help.clone();
            d
        })
        .collect();
    Report {
        diagnostics,
        sources: vec![(path.to_path_buf(), text.to_string())],
    }
}

fn describe(e: &ron::Error) -> (String, Option<String>) {
    use ron::Error as E;
    let list = |xs: &[&str]| xs.iter().map(|x| format!("`{x}`")).collect::<Vec<_>>().join(", ");
    match e {
        E::NoSuchStructField {
            expected,
            found,
            outer,
        } => {
            let within = outer.as_ref().map(|o| format!(" in `{o}`")).unwrap_or_default();
            let help = match suggest(found, expected.iter().copied()) {
                Some(s) => format!("did you mean `{s}`? (expected one of {})", list(expected)),
                None => format!("expected one of {}", list(expected)),
            };
            (format!("unknown field `{found}`{within}"), Some(help))
        }
        E::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => {
            let within = outer.as_ref().map(|o| format!(" for `{o}`")).unwrap_or_default();
            let help = match suggest(found, expected.iter().copied()) {
                Some(s) => format!("did you mean `{s}`? (expected one of {})", list(expected)),
                None => format!("expected one of {}", list(expected)),
            };
            (format!("unknown variant `{found}`{within}"), Some(help))
        }
        E::MissingStructField { field, outer } => {
            let within = outer.as_ref().map(|o| format!(" in `{o}`")).unwrap_or_default();
            (
                format!("missing field `{field}`{within}"),
                Some(format!("add `{field}: ...`")),
            )
        }
        E::DuplicateStructField { field, .. } => (
            format!("field `{field}` is given twice"),
            Some("keep one of them".into()),
        ),
        E::ExpectedComma => (
            "expected `,`".into(),
            Some("separate fields and elements with commas".into()),
        ),
        E::Eof => (
            "unexpected end of file".into(),
            Some("a bracket or parenthesis is probably not closed".into()),
        ),
        E::ExpectedDifferentLength { expected, found } => (
            format!("expected {expected}, found {found} elements"),
            Some("vectors and colours are written `(x, y, z)`".into()),
        ),
        other => (other.to_string(), None),
    }
}

/// Problems in command-line overrides: located by `--set`, not by file.
fn command_line(problems: &[Problem]) -> Report {
    let diagnostics = problems
        .iter()
        .map(|p| {
            let mut d = Diagnostic::new(Path::new("--set"), "", None, p.message.clone());
            d.path = Some(p.path.clone());
            d.help = p.help.clone();
            d
        })
        .collect();
    Report {
        diagnostics,
        sources: Vec::new(),
    }
}
