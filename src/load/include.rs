//! Scene composition: `include: ["studio.ron", ...]` pulls materials, lights
//! and objects from other files.
//!
//! Precedence: included files are merged in the order listed (depth first),
//! then the including file's own entries; a material the including file
//! defines overrides an included one of the same name. Two *included* files
//! defining the same material name is an error (neither should win
//! silently), and so is an include cycle; both show both locations.
//! Relative paths inside an included file (OBJ files, textures, nested
//! includes) stay relative to that file.
//!
//! Every merged entry remembers where it came from, so a problem found in
//! the composed scene is reported in the file and at the line that wrote it.

use super::document::Gaps;
use super::source;
use super::spans::Spans;
use crate::desc::{ColorDesc, IncludeDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::{Diagnostic, Problem, Report};
use std::path::{Path, PathBuf};

/// Where a path of the composed scene was written.
#[derive(Clone, Debug)]
struct Origin {
    merged: String,
    file: usize,
    original: String,
}

/// The files a composed scene was read from, and where each entry came from.
#[derive(Debug, Default)]
pub struct Composition {
    /// Every file read (the scene first, then its includes) with its text.
    pub sources: Vec<(PathBuf, String)>,
    /// What each source's partial read left out (parallel to `sources`).
    gaps: Vec<Gaps>,
    origins: Vec<Origin>,
    /// Mistakes in included files that did not stop the composition.
    pub diagnostics: Vec<Diagnostic>,
}

impl Composition {
    /// A scene without includes: everything is in file 0.
    pub fn single(path: &Path, text: &str, gaps: Gaps) -> Self {
        Self {
            sources: vec![(path.to_path_buf(), text.to_string())],
            gaps: vec![gaps],
            ..Self::default()
        }
    }

    /// Turns problems of the composed scene into diagnostics in the file and
    /// at the entry that wrote them. Problems inside a stand-in for a broken
    /// entry are dropped: that entry's parse error is already reported.
    pub fn locate(&self, problems: &[Problem]) -> Report {
        let spans: Vec<Spans> = self.sources.iter().map(|(_, t)| Spans::scan(t)).collect();
        let diagnostics = problems
            .iter()
            .filter_map(|p| {
                let (file, path) = self.origin_of(&p.path);
                let path = self
                    .gaps
                    .get(file)
                    .map_or(Some(path.clone()), |g| g.original(&path))?;
                let (fpath, text) = &self.sources[file];
                let p = Problem { path, ..p.clone() };
                Some(source::locate(fpath, text, &spans[file], &p))
            })
            .collect();
        Report {
            diagnostics,
            sources: self.sources.clone(),
        }
    }

    fn origin_of(&self, path: &str) -> (usize, String) {
        let best = self
            .origins
            .iter()
            .filter(|o| {
                path.strip_prefix(o.merged.as_str())
                    .is_some_and(|rest| rest.is_empty() || rest.starts_with(['.', '[']))
            })
            .max_by_key(|o| o.merged.len());
        match best {
            Some(o) => (o.file, format!("{}{}", o.original, &path[o.merged.len()..])),
            None => (0, path.to_string()),
        }
    }
}

/// Merges `desc.include` (recursively) into `desc`. Mistakes inside an
/// included file are collected in [`Composition::diagnostics`] and the rest
/// of it is merged; a file that cannot be read, an include cycle or a name
/// defined twice is an `Err`.
pub fn compose(path: &Path, text: &str, gaps: Gaps, desc: &mut SceneDesc) -> Result<Composition, Report> {
    let mut c = Composition::single(path, text, gaps);
    if desc.include.is_empty() {
        return Ok(c);
    }
    let mut merged = IncludeDesc::default();
    let mut defined: std::collections::HashMap<String, (usize, String)> = Default::default();
    let mut errors = Vec::new();
    let stack = vec![canonical(path)];
    for (i, inc) in desc.include.clone().iter().enumerate() {
        let at = Site {
            file: 0,
            path: format!("include[{i}]"),
        };
        include(
            &mut c,
            &mut merged,
            &mut defined,
            &mut errors,
            &stack,
            PathBuf::new(),
            inc,
            at,
        );
    }
    if !errors.is_empty() {
        errors.append(&mut c.diagnostics);
        return Err(Report {
            diagnostics: errors,
            sources: c.sources,
        });
    }
    // The including file's own entries come after the included ones.
    let (nl, no) = (merged.lights.len(), merged.objects.len());
    for i in 0..desc.lights.len() {
        c.origins.push(Origin {
            merged: format!("lights[{}]", nl + i),
            file: 0,
            original: format!("lights[{i}]"),
        });
    }
    for i in 0..desc.objects.len() {
        c.origins.push(Origin {
            merged: format!("objects[{}]", no + i),
            file: 0,
            original: format!("objects[{i}]"),
        });
    }
    for name in desc.materials.keys() {
        c.origins.retain(|o| o.merged != format!("materials.{name}"));
    }
    merged.lights.append(&mut desc.lights);
    merged.objects.append(&mut desc.objects);
    desc.lights = merged.lights;
    desc.objects = merged.objects;
    for (name, m) in merged.materials {
        desc.materials.entry(name).or_insert(m);
    }
    Ok(c)
}

/// Where an include entry is written.
struct Site {
    file: usize,
    path: String,
}

#[allow(clippy::too_many_arguments)]
fn include(
    c: &mut Composition,
    merged: &mut IncludeDesc,
    defined: &mut std::collections::HashMap<String, (usize, String)>,
    errors: &mut Vec<Diagnostic>,
    stack: &[PathBuf],
    parent_rel: PathBuf,
    inc: &str,
    at: Site,
) {
    let rel = parent_rel.join(inc);
    let top_dir = c.sources[0].0.parent().unwrap_or(Path::new(".")).to_path_buf();
    let full = top_dir.join(&rel);
    let err = |c: &Composition, msg: String, help: String| {
        let (p, t) = &c.sources[at.file];
        source::locate(
            p,
            t,
            &Spans::scan(t),
            &Problem::new(at.path.clone(), msg).help(help),
        )
    };
    let key = canonical(&full);
    if let Some(k) = stack.iter().position(|s| *s == key) {
        let chain: Vec<String> = stack[k..]
            .iter()
            .chain([&key])
            .map(|p| p.display().to_string())
            .collect();
        let first = c
            .sources
            .iter()
            .position(|(p, _)| canonical(p) == key)
            .map(|i| location(c, i, ""));
        errors.push(err(
            c,
            format!("include cycle: {}", chain.join(" → ")),
            format!(
                "{} is already being included (from {}); remove one of the includes",
                full.display(),
                first.unwrap_or_default()
            ),
        ));
        return;
    }
    let text = match std::fs::read_to_string(&full) {
        Ok(t) => t,
        Err(e) => {
            errors.push(err(
                c,
                format!("cannot read included file {}: {e}", full.display()),
                "include paths are relative to the including file's folder".into(),
            ));
            return;
        }
    };
    let file = c.sources.len();
    c.sources.push((full.clone(), text.clone()));
    c.gaps.push(Gaps::default());
    let mut inc_desc = match source::read::<IncludeDesc>(&full, &text) {
        Ok(parsed) => {
            c.gaps[file] = parsed.gaps;
            c.diagnostics.extend(parsed.diagnostics);
            parsed.desc
        }
        Err(broken) => {
            errors.extend(broken.diagnostics);
            return;
        }
    };
    let here = rel.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut stack = stack.to_vec();
    stack.push(key);
    for (i, nested) in inc_desc.include.clone().iter().enumerate() {
        let site = Site {
            file,
            path: format!("include[{i}]"),
        };
        include(c, merged, defined, errors, &stack, here.clone(), nested, site);
    }
    // Relative asset paths stay relative to the included file.
    let fix = |f: &mut String| {
        if Path::new(f.as_str()).is_relative() {
            *f = here.join(f.as_str()).to_string_lossy().into_owned();
        }
    };
    for (name, mut m) in std::mem::take(&mut inc_desc.materials) {
        for c in m.color_params_mut() {
            if let ColorDesc::Image(file) = c {
                fix(file);
            }
        }
        if let Some((first_file, first_path)) = defined.get(&name) {
            let first = location(c, *first_file, first_path);
            let p = Problem::new(
                format!("materials.{name}"),
                format!("material `{name}` is defined in two included files"),
            )
            .help(format!(
                "it is first defined at {first}; rename one, or define it in the including scene to choose"
            ));
            errors.push(source::locate(&full, &text, &Spans::scan(&text), &p));
            continue;
        }
        defined.insert(name.clone(), (file, format!("materials.{name}")));
        c.origins.push(Origin {
            merged: format!("materials.{name}"),
            file,
            original: format!("materials.{name}"),
        });
        merged.materials.insert(name, m);
    }
    for (i, l) in inc_desc.lights.into_iter().enumerate() {
        c.origins.push(Origin {
            merged: format!("lights[{}]", merged.lights.len()),
            file,
            original: format!("lights[{i}]"),
        });
        merged.lights.push(l);
    }
    for (i, mut o) in inc_desc.objects.into_iter().enumerate() {
        if let ObjectDesc::Mesh { file: f, .. } = &mut o {
            fix(f);
        }
        c.origins.push(Origin {
            merged: format!("objects[{}]", merged.objects.len()),
            file,
            original: format!("objects[{i}]"),
        });
        merged.objects.push(o);
    }
}

/// `file:line:col` of `path` in source `file` (the file alone if unknown).
fn location(c: &Composition, file: usize, path: &str) -> String {
    let (p, t) = &c.sources[file];
    match Spans::scan(t).find(path).filter(|_| !path.is_empty()) {
        Some(r) => {
            let (l, col) = crate::diagnostic::line_col(t, r.start);
            format!("{}:{l}:{col}", p.display())
        }
        None => p.display().to_string(),
    }
}

fn canonical(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}
