//! The README tells the truth: every RON example loads (a whole scene as a
//! file in `scenes/`, scene fields beside a camera, a lone object inside a
//! minimal scene), the annotated scene is the shipped file it says it is,
//! and the shell examples name files of the clone only.

mod common;

use common::root;
use ronray::load::{Overrides, load_str};

/// The fenced blocks of `lang` in the README, with their first line number.
fn blocks(readme: &str, lang: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (i, line) in readme.lines().enumerate() {
        let fence = line.trim_start();
        match &mut current {
            Some(_) if fence.starts_with("```") => out.extend(current.take()),
            Some((_, text)) => {
                *text += line;
                text.push('\n');
            }
            None if fence == format!("```{lang}") => current = Some((i + 1, String::new())),
            None => {}
        }
    }
    out
}

/// The camera the README's fragments are placed before.
const CAMERA: &str = "camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),";
/// The material names the README's fragments use.
const MATERIALS: &str = "materials: { \"teal\": Lambert(albedo: (0.1, 0.5, 0.5)), \
                         \"clay\": Lambert(albedo: 0.7), \"black\": Lambert(albedo: 0) },";

fn readme() -> String {
    std::fs::read_to_string(root().join("README.md")).expect("README.md")
}

#[test]
fn readme_ron_examples_load() {
    let readme = readme();
    let ron = blocks(&readme, "ron");
    assert!(ron.len() >= 3, "{} RON examples", ron.len());
    for (line, text) in &ron {
        let body: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("//"))
            .collect::<Vec<_>>()
            .join("\n");
        // Examples are written as files in `scenes/`: relative paths resolve
        // from there.
        let path = root().join("scenes").join(format!("readme_line_{line}.ron"));
        let first = body.trim_start();
        let field = first
            .split_once(':')
            .is_some_and(|(k, _)| !k.is_empty() && k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_'));
        let scene = if first.starts_with("Scene(") {
            text.clone()
        } else if field {
            // Fields of a scene (`lights: [...]`): beside a camera and the
            // materials the examples name, unless they bring their own.
            let materials = if body.contains("materials:") {
                ""
            } else {
                MATERIALS
            };
            format!("Scene(\n    {CAMERA}\n    {materials}\n{text})\n")
        } else {
            // A lone object: placed in a minimal scene with the materials it
            // may name.
            format!(
                "Scene(\n    {CAMERA}\n    {MATERIALS}\n    \
                 lights: [Point(position: (0, 3, 3), intensity: (10, 10, 10))],\n    objects: [\n{text}    ],\n)\n"
            )
        };
        if let Err(e) = load_str(&path, &scene, &Overrides::default()) {
            panic!(
                "README.md:{line}: the example does not load:\n{}",
                common::message(&e)
            );
        }
    }
}

#[test]
fn readme_annotated_scene_is_the_shipped_file() {
    let readme = readme();
    let (_, first) = blocks(&readme, "ron").into_iter().next().expect("a RON example");
    let shipped = std::fs::read_to_string(root().join("scenes/bunny.ron")).expect("scenes/bunny.ron");
    assert!(readme.contains("This is `scenes/bunny.ron`"));
    assert_eq!(
        first, shipped,
        "README's annotated scene and scenes/bunny.ron differ"
    );
}

/// Paths in the shell examples exist in the clone (or are written by the
/// example itself), and nothing reaches outside it.
#[test]
fn readme_commands_need_nothing_outside_the_clone() {
    let readme = readme();
    for (line, text) in blocks(&readme, "sh") {
        assert!(
            !text.contains("../"),
            "README.md:{line}: reaches outside the clone:\n{text}"
        );
        for word in text.split_whitespace() {
            let looks_like_file = (word.starts_with("scenes/") || word.starts_with("assets/"))
                && word.rsplit('/').next().is_some_and(|f| f.contains('.'));
            if looks_like_file {
                assert!(
                    root().join(word).exists(),
                    "README.md:{line}: `{word}` does not exist"
                );
            }
        }
        if text.contains("--example") {
            for ex in text.split("--example ").skip(1) {
                let name = ex.split_whitespace().next().unwrap_or("");
                assert!(
                    root().join("examples").join(format!("{name}.rs")).exists(),
                    "README.md:{line}: no example `{name}`"
                );
            }
        }
    }
}

/// The variants of `pub enum name` in `file` (lines of four spaces and a
/// capital inside its braces).
fn variants(file: &str, name: &str) -> Vec<String> {
    let text = std::fs::read_to_string(root().join(file)).expect("enum file");
    let start = text
        .find(&format!("pub enum {name} "))
        .unwrap_or_else(|| panic!("no `pub enum {name}` in {file}"));
    let mut out = Vec::new();
    for line in text[start..].lines().skip(1) {
        if line.starts_with('}') {
            break;
        }
        if let Some(rest) = line.strip_prefix("    ")
            && rest.starts_with(|c: char| c.is_ascii_uppercase())
        {
            out.push(rest.chars().take_while(|c| c.is_alphanumeric()).collect());
        }
    }
    assert!(out.len() > 2, "read too few variants of {name}: {out:?}");
    out
}

/// Every source file (tests aside) that names every variant of `name`:
/// where a new variant has to be added, paths relative to `src/`.
fn every_variant_sites(name: &str, variants: &[String]) -> Vec<String> {
    let src = root().join("src");
    let mut found = Vec::new();
    let mut stack = vec![src.clone()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).expect("read src").flatten() {
            let p = e.path();
            let rel = p
                .strip_prefix(&src)
                .expect("under src")
                .to_string_lossy()
                .replace('\\', "/");
            if p.is_dir() {
                if !rel.ends_with("tests") {
                    stack.push(p);
                }
                continue;
            }
            if !rel.ends_with(".rs") || rel.ends_with("tests.rs") {
                continue;
            }
            let text = std::fs::read_to_string(&p).expect("source");
            let names = |v: &String| {
                let pat = format!("{name}::{v}");
                text.match_indices(&pat).any(|(i, _)| {
                    let before = text[..i].chars().next_back();
                    let after = text[i + pat.len()..].chars().next();
                    !before.is_some_and(|c| c.is_alphanumeric() || c == '_')
                        && !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
                })
            };
            if variants.iter().all(names) {
                found.push(rel);
            }
        }
    }
    found.sort();
    found
}

/// The README's change checklists ("Adding a material touches …") cannot
/// go stale: each names every file that spells out all the variants of the
/// kind's enums (so a new variant must be added there), and every file it
/// names exists (`<model>` stands for any file of that folder).
#[test]
fn readme_change_checklists_name_every_file_a_new_variant_touches() {
    let readme = readme();
    let checklists = [
        (
            "Adding a material touches",
            &[
                ("src/desc/material.rs", "MaterialDesc"),
                ("src/materials/mod.rs", "Material"),
            ],
        ),
        (
            "A light kind touches",
            &[("src/desc/light.rs", "LightDesc"), ("src/lights/mod.rs", "Light")],
        ),
    ];
    for (opening, enums) in checklists {
        let at = readme
            .find(opening)
            .unwrap_or_else(|| panic!("the README has no `{opening}`"));
        let paragraph = readme[at..].split("\n\n").next().unwrap_or("");
        let named: Vec<&str> = paragraph.split('`').skip(1).step_by(2).collect();
        for n in &named {
            let path = root().join("src").join(n.split('<').next().unwrap_or(n));
            assert!(path.exists(), "`{opening}` names `{n}`, which does not exist");
        }
        let covers = |site: &String| {
            named.iter().any(|n| match n.split_once('<') {
                Some((folder, _)) => site.starts_with(folder) && !site[folder.len()..].contains('/'),
                None => site == n,
            })
        };
        for (file, name) in enums {
            for site in every_variant_sites(name, &variants(file, name)) {
                assert!(
                    covers(&site),
                    "`{opening}` leaves out src/{site}, which lists every {name}"
                );
            }
        }
    }
}
