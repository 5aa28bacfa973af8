//! The module graph, read from the source: no two top-level modules import
//! each other (directly or through others), nor two modules inside one
//! folder (`load/`, `syntax/`, `load/sdf/`…), and the renderer's core —
//! `integrators/`, `geometry/`, `materials/`, `lights/`, `accel/` — knows
//! nothing of the loader (`load/`) or the scene-file types (`desc/`). Scene
//! text has one tokenizer, in `syntax/`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Top-level module → the top-level modules its files name as `crate::x`
/// (in `use` lines and paths alike; comments and doc text are skipped).
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut stack = vec![src.clone()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).expect("read src").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
                continue;
            }
            if p.extension().is_none_or(|x| x != "rs") {
                continue;
            }
            let rel = p.strip_prefix(&src).expect("under src");
            let top = rel.components().next().expect("a component");
            let module = top
                .as_os_str()
                .to_string_lossy()
                .trim_end_matches(".rs")
                .to_string();
            if module == "lib" || module == "main" {
                continue;
            }
            let text = std::fs::read_to_string(&p).expect("read file");
            let deps = g.entry(module.clone()).or_default();
            for line in text.lines() {
                let code = line.split("//").next().unwrap_or("");
                for (i, _) in code.match_indices("crate::") {
                    let name: String = code[i + 7..]
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    if !name.is_empty() && name != module {
                        deps.insert(name);
                    }
                }
            }
        }
    }
    g
}

/// A cycle through `start`, if any, as the list of modules on it.
fn cycle_from(g: &BTreeMap<String, BTreeSet<String>>, start: &str) -> Option<Vec<String>> {
    fn visit(
        g: &BTreeMap<String, BTreeSet<String>>,
        start: &str,
        at: &str,
        path: &mut Vec<String>,
        seen: &mut BTreeSet<String>,
    ) -> bool {
        for next in g.get(at).into_iter().flatten() {
            if next == start {
                return true;
            }
            if seen.insert(next.clone()) {
                path.push(next.clone());
                if visit(g, start, next, path, seen) {
                    return true;
                }
                path.pop();
            }
        }
        false
    }
    let mut path = vec![start.to_string()];
    visit(g, start, start, &mut path, &mut BTreeSet::new()).then_some(path)
}

#[test]
fn no_two_modules_import_each_other() {
    let g = graph();
    assert!(g.len() > 10, "read too few modules: {g:?}");
    let cycles: Vec<String> = g
        .keys()
        .filter_map(|m| cycle_from(&g, m))
        .map(|c| format!("{} → {}", c.join(" → "), c[0]))
        .collect();
    assert!(cycles.is_empty(), "import cycles:\n{}", cycles.join("\n"));
}

#[test]
fn the_renderer_core_does_not_import_the_loader() {
    let g = graph();
    let mut bad = Vec::new();
    for core in ["integrators", "geometry", "materials", "lights", "accel"] {
        let deps = g.get(core).unwrap_or_else(|| panic!("no module {core}"));
        for forbidden in ["load", "desc", "cli", "watch", "check"] {
            if deps.contains(forbidden) {
                bad.push(format!("{core} imports {forbidden}"));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

/// The checker itself: it must see a cycle when there is one.
#[test]
fn the_cycle_finder_finds_a_planted_cycle() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    g.entry("c".into()).or_default().insert("a".into());
    g.entry("d".into()).or_default().insert("a".into());
    assert_eq!(
        cycle_from(&g, "a"),
        Some(vec!["a".into(), "b".into(), "c".into()])
    );
    assert_eq!(cycle_from(&g, "d"), None);
}

/// The loader and the scene-file types never import the frame wing
/// (`frame/`): the plan and the output rule sit above the loader, and the
/// loader reads the format table from `imageio/` (STYLE: "a rule is
/// written once").
#[test]
fn the_loader_does_not_import_the_frame_wing() {
    let g = graph();
    assert!(g.contains_key("frame"), "no module frame: {:?}", g.keys());
    let bad: Vec<&str> = ["load", "desc", "syntax", "diagnostic"]
        .into_iter()
        .filter(|m| g.get(*m).is_some_and(|d| d.contains("frame")))
        .collect();
    assert!(bad.is_empty(), "these import the frame wing: {bad:?}");
}

/// Every `.rs` file under `src/` with its path relative to `src/`, comments
/// (`//` to the end of the line) removed.
fn sources() -> Vec<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut out = Vec::new();
    let mut stack = vec![src.clone()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).expect("read src").flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p
                    .strip_prefix(&src)
                    .expect("under src")
                    .to_string_lossy()
                    .replace('\\', "/");
                let text = std::fs::read_to_string(&p).expect("read file");
                let code: Vec<&str> = text.lines().map(|l| l.split("//").next().unwrap_or("")).collect();
                out.push((rel, code.join("\n")));
            }
        }
    }
    out.sort();
    out
}

/// Sibling modules inside one folder that a file names: `super::x`,
/// `self::x` (from a `mod.rs`) and `crate::<folder>::x`, with `{a, b}`
/// groups opened. The key is the folder (`load`, `load/sdf`), the edge runs
/// from the child module that holds the file to the sibling it names.
fn folder_graphs() -> BTreeMap<String, BTreeMap<String, BTreeSet<String>>> {
    let files = sources();
    // Each folder's child modules: its files (not mod.rs) and subfolders.
    let mut children: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (rel, _) in &files {
        let parts: Vec<&str> = rel.split('/').collect();
        for depth in 1..parts.len() {
            let folder = parts[..depth].join("/");
            let child = parts[depth].trim_end_matches(".rs");
            if child != "mod" {
                children.entry(folder).or_default().insert(child.to_string());
            }
        }
    }
    let mut graphs: BTreeMap<String, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for (rel, code) in &files {
        let parts: Vec<&str> = rel.split('/').collect();
        // The module this file is: `load/source.rs` → load::source.
        let mut module: Vec<&str> = parts.iter().map(|p| p.trim_end_matches(".rs")).collect();
        if module.last() == Some(&"mod") {
            module.pop();
        }
        if module.len() < 2 {
            continue;
        }
        // Each ancestor folder sees this file as part of one child.
        for depth in 1..module.len() {
            let folder = module[..depth].join("/");
            let me = module[depth].to_string();
            let Some(siblings) = children.get(&folder) else {
                continue;
            };
            let mut prefixes = vec![format!("crate::{}::", module[..depth].join("::"))];
            // `super::` from a direct child, `super::super::` from a grandchild…
            prefixes.push("super::".repeat(module.len() - depth));
            for prefix in &prefixes {
                for (i, _) in code.match_indices(prefix.as_str()) {
                    if i > 0 && code[..i].ends_with("super::") {
                        continue;
                    }
                    for name in names_after(&code[i + prefix.len()..]) {
                        if name != me && siblings.contains(&name) {
                            graphs
                                .entry(folder.clone())
                                .or_default()
                                .entry(me.clone())
                                .or_default()
                                .insert(name);
                        }
                    }
                }
            }
        }
    }
    graphs
}

/// The first path segments named at the start of `rest`: `x` for
/// `x::…`, `a` and `b` for `{a, b::c}`.
fn names_after(rest: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let Some(group) = rest.strip_prefix('{') else {
        return vec![ident(rest)];
    };
    let mut depth = 0;
    let mut names = Vec::new();
    let mut start = true;
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => break,
            '}' => depth -= 1,
            ',' if depth == 0 => start = true,
            c if c.is_whitespace() => {}
            _ if start && depth == 0 => {
                names.push(ident(&group[i..]));
                start = false;
            }
            _ => {}
        }
    }
    names
}

/// Circles inside folders that predate this test, by the modules on them.
/// Empty since issue 38 opened the last two (in `load/`); the list can only
/// shrink: a circle not listed fails, and so does a listed one that is gone.
const KNOWN_FOLDER_CYCLES: &[&str] = &[];

/// No module circle inside a folder either (`load/source.rs` naming
/// `load/tokens.rs` naming `load/source.rs`): folders are layered too.
#[test]
fn no_two_modules_in_a_folder_import_each_other() {
    let graphs = folder_graphs();
    for folder in ["load", "syntax", "lsp"] {
        assert!(
            graphs.contains_key(folder),
            "read no imports inside {folder}/: {:?}",
            graphs.keys()
        );
    }
    let mut cycles = BTreeSet::new();
    for (folder, g) in &graphs {
        for m in g.keys() {
            if let Some(mut c) = cycle_from(g, m) {
                // One name per circle, whichever module it is entered from.
                c.sort();
                cycles.insert(format!("{folder}/: {}", c.join(" ↔ ")));
            }
        }
    }
    let known: BTreeSet<String> = KNOWN_FOLDER_CYCLES.iter().map(|c| c.to_string()).collect();
    assert_eq!(
        cycles, known,
        "import cycles inside folders (left) against the known ones (right)"
    );
}

/// The folder-level reader itself: a planted circle between two files of
/// one folder, named both ways (`super::` and `crate::`), is seen.
#[test]
fn the_folder_reader_sees_sibling_imports() {
    assert_eq!(names_after("tokens::Tok;"), vec!["tokens"]);
    assert_eq!(
        names_after("{spans::Span, words, self}"),
        vec!["spans", "words", "self"]
    );
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("source".into()).or_default().insert("tokens".into());
    g.entry("tokens".into()).or_default().insert("source".into());
    assert!(cycle_from(&g, "source").is_some());
}

/// Scene text is tokenized in one place, `syntax/lex.rs` (issue 38: the
/// loader had a second tokenizer whose tokens disagreed with the
/// formatter's): no other file defines a tokenizer or a token type.
#[test]
fn scene_text_has_one_tokenizer() {
    let found: Vec<String> = sources()
        .into_iter()
        .filter(|(rel, _)| rel != "syntax/lex.rs")
        .filter(|(_, code)| {
            [
                "fn tokenize",
                "fn lex(",
                "enum Tok ",
                "enum Tok{",
                "struct Token ",
            ]
            .iter()
            .any(|d| code.contains(d))
        })
        .map(|(rel, _)| rel)
        .collect();
    assert!(
        found.is_empty(),
        "tokenizers outside syntax/lex.rs: {found:?}; read `syntax::lex` tokens or the `syntax::tree` instead"
    );
}

/// `match` arms that are a bare `_` (or `_ if …`) in a match whose other
/// arms name a variant of one of `enums`: (file, line, enum).
fn wildcard_arms(enums: &[&str]) -> Vec<(String, usize, String)> {
    sources()
        .into_iter()
        .flat_map(|(rel, code)| {
            scan_text(&code, enums)
                .into_iter()
                .map(move |(line, e)| (rel.clone(), line, e))
        })
        .collect()
}

/// [`wildcard_arms`] in one file's text: (line, enum).
fn scan_text(code: &str, enums: &[&str]) -> Vec<(usize, String)> {
    let bytes = code.as_bytes();
    let mut found = Vec::new();
    for (at, _) in code.match_indices("match ") {
        if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_') {
            continue;
        }
        let Some(open) = code[at..].find('{').map(|o| at + o) else {
            continue;
        };
        // The arms at the match's own depth, by the line they start on.
        let mut depth = 0i32;
        let mut arms: Vec<(usize, &str)> = Vec::new();
        let mut line_start = false;
        for (i, c) in code[open..].char_indices() {
            let i = open + i;
            if line_start && depth == 1 {
                arms.push((i, code[i..].lines().next().unwrap_or("").trim_start()));
            }
            line_start = c == '\n';
            match c {
                '{' | '(' | '[' => depth += 1,
                '}' | ')' | ']' => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                _ => {}
            }
        }
        for e in enums {
            let variant = format!("{e}::");
            let names_enum = arms.iter().any(|(_, a)| {
                // The pattern, before `=>`: `Light::Sphere(s) if …`, `Some(Light::Quad(q))`.
                let pat = a.split("=>").next().unwrap_or("");
                pat.match_indices(&variant).any(|(j, _)| {
                    j == 0
                        || !(pat.as_bytes()[j - 1].is_ascii_alphanumeric() || pat.as_bytes()[j - 1] == b'_')
                })
            });
            if !names_enum {
                continue;
            }
            for (i, a) in &arms {
                if a.starts_with("_ =>") || a.starts_with("_ if ") {
                    found.push((code[..*i].matches('\n').count() + 1, e.to_string()));
                }
            }
        }
    }
    found
}

/// A `_ =>` arm over a closed enum hides the next variant (STYLE: "enums
/// for closed sets"): none over the output formats.
#[test]
fn no_wildcard_arm_over_output_formats() {
    let found = wildcard_arms(&["OutputFormat"]);
    assert!(found.is_empty(), "`_ =>` over the output formats: {found:?}");
}

/// No `_ =>` arm over the material, BSDF or light enums (issue 38): a new
/// material or light is then a compile error at every match that must decide
/// what it does (the inline-Lambert dispatch in `materials/mod.rs` names the
/// out-of-line variants instead).
#[test]
fn no_wildcard_arm_over_materials_or_lights() {
    let found = wildcard_arms(&["Material", "MaterialDesc", "Bsdf", "Light", "LightDesc"]);
    assert!(
        found.is_empty(),
        "`_ =>` arms over material or light enums: {found:?}; name the variants, so that a new one is a compile error where it needs a decision"
    );
}

/// The wildcard finder itself: it sees a planted `_ =>` and ignores a match
/// over something else.
#[test]
fn the_wildcard_finder_finds_a_planted_arm() {
    let code = "fn f(x: OutputFormat) -> u8 {\n    match x {\n        OutputFormat::Png => 1,\n        _ => 2,\n    }\n}\nfn g(y: u8) -> u8 {\n    match y {\n        0 => 1,\n        _ => 2,\n    }\n}\n";
    assert_eq!(
        scan_text(code, &["OutputFormat"]),
        vec![(4, "OutputFormat".to_string())]
    );
    assert_eq!(scan_text(code, &["Material"]), vec![]);
}

/// The files of `tests/` that no test target builds. With `autotests =
/// false` cargo builds only the `[[test]]` targets of `Cargo.toml`, so every
/// `tests/<name>.rs` (`files`) must be a target's `path` or named by a
/// `mod <name>;` line of a target's root file (`read` gives a root's text).
fn unbuilt_test_files(manifest: &str, files: &[String], read: impl Fn(&str) -> String) -> Vec<String> {
    let mut roots = Vec::new();
    let mut in_test = false;
    for line in manifest.lines().map(str::trim) {
        if line.starts_with('[') {
            in_test = line == "[[test]]";
        } else if in_test && let Some(p) = line.strip_prefix("path") {
            let p = p.trim_start().trim_start_matches('=').trim().trim_matches('"');
            roots.push(p.to_string());
        }
    }
    let mut built: BTreeSet<String> = roots.iter().cloned().collect();
    for root in &roots {
        let dir = root.rsplit_once('/').map_or("", |(d, _)| d);
        for line in read(root).lines() {
            let line = line.trim().trim_start_matches("pub ");
            if let Some(name) = line.strip_prefix("mod ").and_then(|r| r.strip_suffix(';')) {
                built.insert(format!("{dir}/{}.rs", name.trim()));
            }
        }
    }
    files.iter().filter(|f| !built.contains(*f)).cloned().collect()
}

/// No test disappears silently: every `tests/*.rs` file is built, as a test
/// target of its own or as a module of `tests/main.rs`.
#[test]
fn every_test_file_is_in_a_test_target() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).expect("read Cargo.toml");
    let mut files: Vec<String> = std::fs::read_dir(root.join("tests"))
        .expect("read tests")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".rs"))
        .map(|n| format!("tests/{n}"))
        .collect();
    files.sort();
    assert!(files.len() > 40, "read too few test files: {files:?}");
    let read = |p: &str| std::fs::read_to_string(root.join(p)).unwrap_or_else(|e| panic!("{p}: {e}"));
    let unbuilt = unbuilt_test_files(&manifest, &files, read);
    assert!(
        unbuilt.is_empty(),
        "not built by any test target, so their tests never run: {unbuilt:?}; add `mod <name>;` to tests/main.rs (or a [[test]] in Cargo.toml)"
    );
}

/// The test-file check itself: a file that is neither a target nor a
/// module of one is reported; modules and targets are not.
#[test]
fn the_test_file_check_finds_a_planted_orphan() {
    let manifest = "[package]\nname = \"x\"\npath = \"tests/not_a_test.rs\"\n\n[[test]]\nname = \"integration\"\npath = \"tests/main.rs\"\n\n[[test]]\nname = \"alone\"\npath = \"tests/alone.rs\"\n\n[dependencies]\n";
    let files: Vec<String> = ["alone", "kept", "main", "not_a_test", "orphan"]
        .iter()
        .map(|n| format!("tests/{n}.rs"))
        .collect();
    let read = |p: &str| match p {
        "tests/main.rs" => "//! root\nmod common;\n#[cfg(unix)]\nmod kept;\n// mod orphan;\n".to_string(),
        _ => String::new(),
    };
    assert_eq!(
        unbuilt_test_files(manifest, &files, read),
        vec!["tests/not_a_test.rs".to_string(), "tests/orphan.rs".to_string()]
    );
}
