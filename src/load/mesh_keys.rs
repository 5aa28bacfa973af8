//! What the `materials: { ... }` keys of a `Mesh` or `Instance` may name
//! (an OBJ group, an MTL material, or with `group:`/`material:` one of the
//! two), and the checks that need an OBJ's content: keys that name nothing
//! or two things, MTL materials defined twice.
//!
//! The build runs them on each OBJ it reads (`mesh.rs`); a scene whose other
//! mistakes stop its build runs them on their own ([`content_problems`]),
//! so they are reported in the same run.

use crate::desc::{ObjectDesc, SceneDesc};
use crate::diagnostic::{Problem, suggest};
use crate::geometry::obj::ObjData;
use std::path::Path;

/// What a `materials` key of a mesh object names: `group:NAME`,
/// `material:NAME`, or a bare name that may be either (an error when it
/// names a group and an MTL material worn by another group, since it would
/// recolour both).
#[derive(Clone, Copy, PartialEq)]
pub(super) enum Key<'a> {
    Group(&'a str),
    Material(&'a str),
    Either(&'a str),
}

impl<'a> Key<'a> {
    pub(super) fn of(key: &'a str) -> Self {
        if let Some(g) = key.strip_prefix("group:") {
            Key::Group(g.trim())
        } else if let Some(m) = key.strip_prefix("material:") {
            Key::Material(m.trim())
        } else {
            Key::Either(key)
        }
    }

    /// Whether it selects the group `group` wearing MTL material `mtl`.
    pub(super) fn selects(self, group: &str, mtl: Option<&str>) -> bool {
        match self {
            Key::Group(n) => n == group,
            Key::Material(n) => mtl == Some(n),
            Key::Either(n) => n == group || mtl == Some(n),
        }
    }

    /// Prefixed keys first: they say what they mean.
    pub(super) fn rank(self) -> u8 {
        match self {
            Key::Group(_) => 0,
            Key::Material(_) => 1,
            Key::Either(_) => 2,
        }
    }
}

/// An MTL material name defined twice (in one MTL file or across the OBJ's
/// MTL files) is a problem: tobj keeps the last, silently.
pub(super) fn twice_defined(data: &ObjData, at: &str) -> Vec<Problem> {
    let mut seen = std::collections::BTreeSet::new();
    let files = data
        .mtl_files
        .iter()
        .map(|f| f.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let mut out = Vec::new();
    for m in &data.materials {
        if !seen.insert(m.name.as_str()) {
            out.push(
                Problem::new(
                    at,
                    format!(
                        "MTL material `{}` is defined twice in {files}: the last definition would win",
                        m.name
                    ),
                )
                .help("rename one of them (`newmtl NAME`) or delete the one not meant"),
            );
        }
    }
    out
}

/// `groups: `a` (material `m`), `b``: an OBJ's groups and the MTL material
/// each wears, for `validate -v`.
pub(super) fn parts_list(data: &ObjData) -> String {
    let groups: Vec<String> = data
        .groups
        .iter()
        .map(|g| match g.material.and_then(|m| data.materials.get(m)) {
            Some(m) => format!("`{}` (material `{}`)", g.name, m.name),
            None => format!("`{}`", g.name),
        })
        .collect();
    format!("groups: {}", groups.join(", "))
}

/// What is wrong with override key `key`, if anything: it names nothing,
/// or, bare, it names a group and an MTL material another group wears.
pub(super) fn key_problem(at: &str, key: &str, parts: &[(&str, Option<&str>)]) -> Option<Problem> {
    let groups: Vec<&str> = parts.iter().map(|(g, _)| *g).collect();
    let mut materials: Vec<&str> = parts.iter().filter_map(|(_, m)| *m).collect();
    materials.sort_unstable();
    materials.dedup();
    let (what, name, known): (&str, &str, Vec<&str>) = match Key::of(key) {
        Key::Group(n) => ("group", n, groups.clone()),
        Key::Material(n) => ("MTL material", n, materials.clone()),
        Key::Either(n) => {
            let group = groups.contains(&n);
            let others: Vec<&str> = parts
                .iter()
                .filter(|(g, m)| *g != n && *m == Some(n))
                .map(|(g, _)| *g)
                .collect();
            if group && !others.is_empty() {
                return Some(
                    Problem::new(
                        at,
                        format!(
                            "`{n}` names both OBJ group `{n}` and MTL material `{n}` (worn by {}): it would recolour both",
                            quoted_strs(&others)
                        ),
                    )
                    .help(format!("write `group:{n}` or `material:{n}` to say which")),
                );
            }
            let mut all = groups.clone();
            all.extend(materials.iter().copied());
            ("group or material", n, all)
        }
    };
    if known.contains(&name) {
        return None;
    }
    let p = Problem::new(at, format!("the OBJ has no {what} `{name}`"));
    Some(match suggest(name, known.iter().copied()) {
        Some(s) => p.help(format!("did you mean `{s}`?")),
        None => p.help(format!(
            "its groups are {}; its MTL materials are {}",
            or_none(&groups),
            or_none(&materials)
        )),
    })
}

fn or_none(names: &[&str]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        quoted_strs(names)
    }
}

fn quoted_strs(names: &[&str]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The checks that need an OBJ's content, for every `Mesh` and `Instance`
/// whose file is there, read through `load_obj`: for a scene whose other
/// mistakes stop the build, so that these come in the same run.
pub(super) fn content_problems(
    desc: &SceneDesc,
    base: &Path,
    load_obj: &dyn Fn(&Path) -> Result<ObjData, String>,
) -> Vec<Problem> {
    let mut out: Vec<Problem> = Vec::new();
    let mut push = |p: Problem| {
        if !out.iter().any(|q| q.path == p.path && q.message == p.message) {
            out.push(p);
        }
    };
    for (i, o) in desc.objects.iter().enumerate() {
        let (file, at) = match o {
            ObjectDesc::Mesh { file, .. } => (file, format!("objects[{i}].file")),
            ObjectDesc::Instance { mesh, .. } => match desc.meshes.get(mesh) {
                Some(m) => (&m.file, format!("meshes.{mesh}.file")),
                None => continue,
            },
            _ => continue,
        };
        let path = base.join(file);
        if !path.is_file() {
            continue; // validation said so
        }
        let data = match load_obj(&path) {
            Ok(d) => d,
            Err(msg) => {
                push(
                    Problem::new(&at, msg)
                        .help("check that the file is a Wavefront OBJ with `v` and `f` lines"),
                );
                continue;
            }
        };
        for p in twice_defined(&data, &at) {
            push(p);
        }
        let parts: Vec<(&str, Option<&str>)> = data
            .groups
            .iter()
            .map(|g| {
                let m = g
                    .material
                    .and_then(|m| data.materials.get(m))
                    .map(|m| m.name.as_str());
                (g.name.as_str(), m)
            })
            .collect();
        for key in o.material_overrides().into_iter().flat_map(|m| m.keys()) {
            if let Some(p) = key_problem(&format!("objects[{i}].materials.{key}"), key, &parts) {
                push(p);
            }
        }
    }
    out
}
