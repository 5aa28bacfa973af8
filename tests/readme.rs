//! The README and the guide pages of `docs/` tell the truth: every RON
//! example loads (a whole scene as a file in `scenes/`, scene fields beside
//! a camera, a lone object inside a minimal scene), the annotated scene is
//! the shipped file it says it is, the shell examples name files of the
//! clone only, every relative link and its anchor lead somewhere, every
//! page of `docs/` is linked from the README, the change checklists of
//! `docs/design.md` name every file a new variant touches, and every test
//! `docs/claims.md` cites as a claim's backing exists.

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

/// The README and every Markdown page of `docs/`, as (name relative to the
/// clone, text), README first.
fn pages() -> Vec<(String, String)> {
    let mut names: Vec<String> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".md"))
        .map(|n| format!("docs/{n}"))
        .collect();
    names.sort();
    names.insert(0, "README.md".to_string());
    names
        .into_iter()
        .map(|n| {
            let text = std::fs::read_to_string(root().join(&n)).expect("page");
            (n, text)
        })
        .collect()
}

/// Pages whose RON blocks are fragments that cannot load alone: the
/// material entries of `docs/textures.md` name image files the reader
/// brings (`"albedo.png"`, `"window.exr"`).
const FRAGMENT_PAGES: [&str; 1] = ["docs/textures.md"];

#[test]
fn readme_ron_examples_load() {
    let mut count = 0;
    for (page, text) in pages() {
        if FRAGMENT_PAGES.contains(&page.as_str()) {
            continue;
        }
        let ron = blocks(&text, "ron");
        count += ron.len();
        ron_examples_load(&page, &ron);
    }
    assert!(count >= 6, "{count} RON examples in the README and docs/");
}

/// Each RON block of `page` loads as a scene written in `scenes/`.
fn ron_examples_load(page: &str, ron: &[(usize, String)]) {
    for (line, text) in ron {
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
                "{page}:{line}: the example does not load:\n{}",
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

/// Folders of the clone whose files the shell examples may name.
const CLONE_FOLDERS: [&str; 8] = [
    "scenes/",
    "assets/",
    "examples/",
    "tools/",
    "scripts/",
    ".ci/",
    "tests/",
    "schema/",
];

/// Options after which a shell example names a file it writes.
const OUTPUT_OPTIONS: [&str; 5] = ["-o", "--out", ">", "--heatmap", "--keep-noisy"];

/// Paths in the shell examples of the README and of `docs/` exist in the
/// clone (or are written by the example itself), and nothing reaches
/// outside it.
#[test]
fn readme_commands_need_nothing_outside_the_clone() {
    let mut checked = 0;
    for (page, text) in pages() {
        for (line, block) in blocks(&text, "sh") {
            assert!(
                !block.contains("../"),
                "{page}:{line}: reaches outside the clone:\n{block}"
            );
            for command in block.lines() {
                let command = command.split(" #").next().unwrap_or("");
                let words: Vec<&str> = command.split_whitespace().collect();
                for (i, raw) in words.iter().enumerate() {
                    let word = raw.trim_matches(|c| "\"'$()`;,".contains(c));
                    let in_clone = CLONE_FOLDERS.iter().any(|f| word.starts_with(f))
                        && word.rsplit('/').next().is_some_and(|f| f.contains('.'))
                        && !word.contains(['*', '{']);
                    let written = i > 0 && OUTPUT_OPTIONS.contains(&words[i - 1]);
                    if in_clone && !written {
                        checked += 1;
                        assert!(
                            root().join(word).exists(),
                            "{page}:{line}: `{word}` does not exist"
                        );
                    }
                }
            }
            for ex in block.split("--example ").skip(1) {
                let name = ex.split_whitespace().next().unwrap_or("");
                assert!(
                    root().join("examples").join(format!("{name}.rs")).exists(),
                    "{page}:{line}: no example `{name}`"
                );
            }
        }
    }
    assert!(
        checked >= 10,
        "only {checked} file names checked: is the reader broken?"
    );
}

/// The anchor GitHub gives a heading: lower case, punctuation other than
/// `-` and `_` dropped, spaces turned into `-`.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// The anchors of a page's headings (outside code blocks).
fn anchors(text: &str) -> Vec<String> {
    let mut fenced = false;
    let mut out = Vec::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced && line.starts_with('#') {
            out.push(anchor(line.trim_start_matches('#')));
        }
    }
    out
}

/// The relative link targets of a page: `](target)` that is not a URL.
fn links(text: &str) -> Vec<String> {
    text.split("](")
        .skip(1)
        .filter_map(|rest| rest.split(')').next())
        .filter(|t| !t.starts_with("http") && !t.starts_with("mailto:"))
        .map(str::to_string)
        .collect()
}

#[test]
fn anchor_follows_githubs_rule() {
    assert_eq!(
        anchor(" Versions and `ronray migrate`"),
        "versions-and-ronray-migrate"
    );
    assert_eq!(
        anchor(" Side by side after the realism merges (2026-12-05 02:13–02:22 UTC)"),
        "side-by-side-after-the-realism-merges-2026-12-05-02130222-utc"
    );
    assert_eq!(
        links("see [a](docs/a.md#x) and [b](https://x.org)"),
        ["docs/a.md#x"]
    );
}

/// Moved text stays reachable: every relative link of the README and of
/// `docs/` leads to a file of the clone and, with `#anchor`, to a heading
/// of that file.
#[test]
fn guide_links_lead_to_files_and_headings_that_exist() {
    let pages = pages();
    let mut checked = 0;
    for (page, text) in &pages {
        let folder = std::path::Path::new(page)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        for target in links(text) {
            let (file, fragment) = match target.split_once('#') {
                Some((f, a)) => (f, Some(a)),
                None => (target.as_str(), None),
            };
            let path = if file.is_empty() {
                root().join(page)
            } else {
                root().join(folder).join(file)
            };
            assert!(path.exists(), "{page}: the link `{target}` leads nowhere");
            if let Some(fragment) = fragment {
                let linked = std::fs::read_to_string(&path).expect("linked page");
                assert!(
                    anchors(&linked).iter().any(|a| a == fragment),
                    "{page}: the link `{target}` names no heading of {}",
                    path.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 30, "only {checked} links checked");
}

/// No page of `docs/` is an orphan: the README links every one.
#[test]
fn readme_links_every_docs_page() {
    let readme = readme();
    for (page, _) in pages().iter().skip(1) {
        assert!(
            readme.contains(&format!("]({page}")),
            "README.md does not link {page}"
        );
    }
}

/// Every test `docs/claims.md` cites (`file.rs::name`) exists: a `#[test]`
/// function of that name in that file, so the table of claims cannot rot.
#[test]
fn claims_table_cites_tests_that_exist() {
    let claims = std::fs::read_to_string(root().join("docs/claims.md")).expect("docs/claims.md");
    let mut cited = 0;
    for quoted in claims.split('`').skip(1).step_by(2) {
        let Some((file, name)) = quoted.split_once(".rs::") else {
            continue;
        };
        let path = root().join(format!("{file}.rs"));
        let source = std::fs::read_to_string(&path)
            .unwrap_or_else(|_| panic!("docs/claims.md cites `{quoted}`: no file {file}.rs"));
        let is_test = source.match_indices(&format!("fn {name}(")).any(|(i, _)| {
            source[..i]
                .rsplit_once("#[test]")
                .is_some_and(|(_, between)| between.lines().count() <= 4)
        });
        assert!(
            is_test,
            "docs/claims.md cites `{quoted}`: {file}.rs has no #[test] fn {name}"
        );
        cited += 1;
    }
    assert!(cited >= 100, "docs/claims.md cites only {cited} tests");
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

/// The change checklists of `docs/design.md` ("Adding a material touches …") cannot
/// go stale: each names every file that spells out all the variants of the
/// kind's enums (so a new variant must be added there), and every file it
/// names exists (`<model>` stands for any file of that folder).
#[test]
fn readme_change_checklists_name_every_file_a_new_variant_touches() {
    let readme = std::fs::read_to_string(root().join("docs/design.md")).expect("docs/design.md");
    let checklists: [(&str, &[(&str, &str)]); 3] = [
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
        (
            "An output format touches",
            &[("src/imageio/format.rs", "OutputFormat")],
        ),
    ];
    for (opening, enums) in checklists {
        let at = readme
            .find(opening)
            .unwrap_or_else(|| panic!("docs/design.md has no `{opening}`"));
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
