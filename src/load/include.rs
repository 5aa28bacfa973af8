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
use crate::desc::{IncludeDesc, MaterialDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::{Diagnostic, LineIndex, Problem, Report};
use crate::syntax::spans::Spans;
use std::collections::{HashMap, HashSet};
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
        // Each file scanned and line-indexed once, and origins found by
        // hashing: per problem, either was a pass over a whole file or over
        // every merged entry (quadratic in the number of mistakes).
        let spans: Vec<Spans> = self.sources.iter().map(|(_, t)| Spans::scan(t)).collect();
        let lines: Vec<LineIndex> = self.sources.iter().map(|(_, t)| LineIndex::new(t)).collect();
        let origins: HashMap<&str, &Origin> = self.origins.iter().map(|o| (o.merged.as_str(), o)).collect();
        let diagnostics = problems
            .iter()
            .filter_map(|p| {
                let (file, path) = origin_of(&origins, &p.path);
                let path = self
                    .gaps
                    .get(file)
                    .map_or(Some(path.clone()), |g| g.original(&path))?;
                let fpath = &self.sources[file].0;
                let p = Problem { path, ..p.clone() };
                Some(source::locate(fpath, &lines[file], &spans[file], &p))
            })
            .collect();
        Report {
            diagnostics,
            sources: self.sources.clone(),
        }
    }

    /// Whether a parse mistake at `path` of `file` (as written) was in a
    /// field its entry was read without: the entry itself is whole.
    pub fn is_repaired(&self, file: &std::path::Path, path: &str) -> bool {
        self.sources
            .iter()
            .position(|(f, _)| f == file)
            .and_then(|i| self.gaps.get(i))
            .is_some_and(|g| g.is_repaired(path))
    }
}

/// The file and the path as written there of `path` in the composed scene:
/// the entry whose merged path is the longest prefix of `path` that ends
/// where a path segment does (`objects[3]` for `objects[3].material`, not
/// for `objects[31]`); file 0 when no entry names it.
fn origin_of(origins: &HashMap<&str, &Origin>, path: &str) -> (usize, String) {
    let ends = path
        .char_indices()
        .filter(|(_, c)| matches!(c, '.' | '['))
        .map(|(i, _)| i)
        .chain([path.len()]);
    let ends: Vec<usize> = ends.collect();
    for &end in ends.iter().rev() {
        if let Some(o) = origins.get(&path[..end]) {
            return (o.file, format!("{}{}", o.original, &path[end..]));
        }
    }
    (0, path.to_string())
}

/// Merges `desc.include` (recursively) into `desc`. Mistakes inside an
/// included file are collected in [`Composition::diagnostics`] and the rest
/// of it is merged; a file that cannot be read, an include cycle or a name
/// defined twice is an `Err`.
///
/// What may be included: `.ron` and `.json` files only, inside the scene's
/// folder (or inside `root` when `--root` names one). A diagnostic shows the
/// line it points at, so an include of `/etc/passwd` or `~/.ssh/id_rsa`
/// would print part of a file that is not a scene; such an include is
/// refused at the include entry without reading the file, and a file that
/// is not UTF-8 text is refused without showing any of it.
pub fn compose(
    path: &Path,
    text: &str,
    gaps: Gaps,
    desc: &mut SceneDesc,
    root: Option<&Path>,
) -> Result<Composition, Report> {
    let c = Composition::single(path, text, gaps);
    if desc.include.is_empty() {
        return Ok(c);
    }
    let mut k = Composer {
        c,
        merged: IncludeDesc::default(),
        defined: HashMap::new(),
        errors: Vec::new(),
        done: HashSet::new(),
        fence: match root {
            Some(r) => (r.to_path_buf(), "the --root folder"),
            None => (
                path.parent().unwrap_or(Path::new(".")).to_path_buf(),
                "the scene's folder",
            ),
        },
    };
    let stack = vec![canonical(path)];
    for (i, inc) in desc.include.clone().iter().enumerate() {
        let at = Site {
            file: 0,
            path: format!("include[{i}]"),
        };
        k.include(&stack, PathBuf::new(), inc, at);
    }
    let Composer {
        mut c,
        mut merged,
        mut errors,
        ..
    } = k;
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
    // One pass: formatting every name against every origin was quadratic.
    let own: HashSet<String> = desc.materials.keys().map(|n| format!("materials.{n}")).collect();
    c.origins.retain(|o| !own.contains(&o.merged));
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

/// Largest include nesting depth. A deeper chain is almost certainly a
/// mistake; raise it here if a real scene needs more.
pub const MAX_INCLUDE_DEPTH: usize = 32;
/// Largest number of distinct files one scene may include (each is read
/// once, however often it is named).
pub const MAX_INCLUDES: usize = 1024;

/// The state of one composition: what was merged so far and where each
/// material was first defined.
struct Composer {
    c: Composition,
    merged: IncludeDesc,
    /// Material name → (file, path) of its first definition.
    defined: HashMap<String, (usize, String)>,
    errors: Vec<Diagnostic>,
    /// Files already included, by canonical path: a file named twice (a
    /// diamond of includes) is read once, so the work stays linear in the
    /// number of distinct files however the includes branch.
    done: HashSet<PathBuf>,
    /// The folder includes must stay in, and how to call it.
    fence: (PathBuf, &'static str),
}

impl Composer {
    /// A problem at the include entry `at`.
    fn error_at(&mut self, at: &Site, msg: String, help: String) {
        let (p, t) = &self.c.sources[at.file];
        let d = source::locate(
            p,
            &LineIndex::new(t),
            &Spans::scan(t),
            &Problem::new(at.path.clone(), msg).help(help),
        );
        self.errors.push(d);
    }

    /// Reads include `inc` (written at `at`, relative to `parent_rel`) and
    /// merges its entries, after its own includes.
    fn include(&mut self, stack: &[PathBuf], parent_rel: PathBuf, inc: &str, at: Site) {
        let rel = parent_rel.join(inc);
        let top_dir = self.c.sources[0]
            .0
            .parent()
            .unwrap_or(Path::new("."))
            .to_path_buf();
        let full = top_dir.join(&rel);
        let key = canonical(&full);
        if self.not_a_fragment(&full, &at) || self.refused(stack, &key, &full, &at) {
            return;
        }
        let Some((file, text, mut inc_desc)) = self.read(&full, &at) else {
            return;
        };
        let here = rel.parent().map(Path::to_path_buf).unwrap_or_default();
        let mut stack = stack.to_vec();
        stack.push(key);
        for (i, nested) in inc_desc.include.clone().iter().enumerate() {
            let site = Site {
                file,
                path: format!("include[{i}]"),
            };
            self.include(&stack, here.clone(), nested, site);
        }
        // Relative asset paths stay relative to the included file.
        let fix = |f: &mut String| {
            if Path::new(f.as_str()).is_relative() {
                *f = here.join(f.as_str()).to_string_lossy().into_owned();
            }
        };
        for (name, mut m) in std::mem::take(&mut inc_desc.materials) {
            m.for_each_file(&mut |f| fix(f));
            self.merge_material(file, &full, &text, name, m);
        }
        for l in &mut inc_desc.lights {
            if let Some(f) = l.file_mut() {
                fix(f);
            }
        }
        for mut o in std::mem::take(&mut inc_desc.objects) {
            if let ObjectDesc::Mesh { file: f, .. } = &mut o {
                fix(f);
            }
            inc_desc.objects.push(o);
        }
        self.merge_lists(file, inc_desc);
    }

    /// Whether `key` may not be included here: a cycle, too deep, too many
    /// files (each reported at `at`), or already included (silently: a
    /// diamond of includes is fine).
    fn refused(&mut self, stack: &[PathBuf], key: &PathBuf, full: &Path, at: &Site) -> bool {
        if let Some(k) = stack.iter().position(|s| s == key) {
            let chain: Vec<String> = stack[k..]
                .iter()
                .chain([key])
                .map(|p| p.display().to_string())
                .collect();
            let first = self
                .c
                .sources
                .iter()
                .position(|(p, _)| canonical(p) == *key)
                .map(|i| location(&self.c, i, ""));
            let help = format!(
                "{} is already being included (from {}); remove one of the includes",
                full.display(),
                first.unwrap_or_default()
            );
            self.error_at(at, format!("include cycle: {}", chain.join(" → ")), help);
            return true;
        }
        if stack.len() > MAX_INCLUDE_DEPTH {
            let msg = format!("includes nest deeper than {MAX_INCLUDE_DEPTH} files");
            self.error_at(at, msg, "flatten the chain of includes".into());
            return true;
        }
        if !self.done.insert(key.clone()) {
            return true;
        }
        if self.done.len() > MAX_INCLUDES {
            let msg = format!("more than {MAX_INCLUDES} included files");
            self.error_at(at, msg, "merge some of the included files".into());
            return true;
        }
        false
    }

    /// Whether `full` may not be included whatever it holds: not a `.ron`
    /// or `.json` file, or outside the fence (symlinks followed). Refused
    /// before reading, so nothing of it is shown.
    fn not_a_fragment(&mut self, full: &Path, at: &Site) -> bool {
        let ext = full
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !matches!(ext.as_deref(), Some("ron" | "json")) {
            let msg = format!("included file {} is not a scene file", full.display());
            let help = "include only .ron or .json scene fragments; the file is not read".to_string();
            self.error_at(at, msg, help);
            return true;
        }
        let (fence, name) = self.fence.clone();
        if let Some(why) = crate::files::outside_root(&fence, full) {
            let why = why.replace("--root", name);
            let msg = format!("included file {why}");
            let help = "keep included files beside the scene or below it, or name a wider folder with --root";
            self.error_at(at, msg, help.into());
            return true;
        }
        false
    }

    /// Reads and parses an included file; `None` (with its diagnostics)
    /// when it cannot be read or does not parse.
    fn read(&mut self, full: &Path, at: &Site) -> Option<(usize, String, IncludeDesc)> {
        let text = match source::read_text(full) {
            Ok(t) => t,
            Err(e) => {
                let msg = format!("cannot read included file {}: {e}", full.display());
                self.error_at(
                    at,
                    msg,
                    "include paths are relative to the including file's folder".into(),
                );
                return None;
            }
        };
        let file = self.c.sources.len();
        self.c.sources.push((full.to_path_buf(), text.clone()));
        self.c.gaps.push(Gaps::default());
        match source::read::<IncludeDesc>(full, &text) {
            Ok(parsed) => {
                self.c.gaps[file] = parsed.gaps;
                self.c.diagnostics.extend(parsed.diagnostics);
                Some((file, text, parsed.desc))
            }
            Err(broken) => {
                self.errors.extend(broken.diagnostics);
                None
            }
        }
    }

    /// Adds material `name` of included file `file`; a name another
    /// included file already defined is a located error.
    fn merge_material(&mut self, file: usize, full: &Path, text: &str, name: String, m: MaterialDesc) {
        if let Some((first_file, first_path)) = self.defined.get(&name) {
            let first = location(&self.c, *first_file, first_path);
            let p = Problem::new(
                format!("materials.{name}"),
                format!("material `{name}` is defined in two included files"),
            )
            .help(format!(
                "it is first defined at {first}; rename one, or define it in the including scene to choose"
            ));
            self.errors.push(source::locate(
                full,
                &LineIndex::new(text),
                &Spans::scan(text),
                &p,
            ));
            return;
        }
        self.defined
            .insert(name.clone(), (file, format!("materials.{name}")));
        self.c.origins.push(Origin {
            merged: format!("materials.{name}"),
            file,
            original: format!("materials.{name}"),
        });
        self.merged.materials.insert(name, m);
    }

    /// Appends the lights and objects of included file `file`.
    fn merge_lists(&mut self, file: usize, inc: IncludeDesc) {
        for (i, l) in inc.lights.into_iter().enumerate() {
            self.c.origins.push(Origin {
                merged: format!("lights[{}]", self.merged.lights.len()),
                file,
                original: format!("lights[{i}]"),
            });
            self.merged.lights.push(l);
        }
        for (i, o) in inc.objects.into_iter().enumerate() {
            self.c.origins.push(Origin {
                merged: format!("objects[{}]", self.merged.objects.len()),
                file,
                original: format!("objects[{i}]"),
            });
            self.merged.objects.push(o);
        }
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
