//! `ronray check` (golden-image regressions) and `ronray gallery`.
use super::{print_load_error, print_out};
use crate::check::CheckOptions;
use crate::frame::{RenderOptions, render_whole};
use crate::imageio::write_image;
use crate::load::{Overrides, load_with};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The scenes named or found in the folders named (default `scenes`); an
/// unreadable folder or no scene at all is reported here.
fn scenes_in(paths: Vec<PathBuf>) -> Option<Vec<PathBuf>> {
    let paths = if paths.is_empty() {
        vec![PathBuf::from("scenes")]
    } else {
        paths
    };
    let names = || {
        paths
            .iter()
            .map(|p| p.display().to_string())
            .collect::<Vec<_>>()
            .join(", ")
    };
    match crate::check::collect(&paths) {
        Ok(s) if !s.is_empty() => Some(s),
        Ok(_) => {
            eprintln!("error: no scenes found in {}", names());
            None
        }
        Err(e) => {
            eprintln!("error: cannot list {}: {e}", names());
            None
        }
    }
}

pub(super) fn cmd_check(paths: Vec<PathBuf>, opts: &CheckOptions) -> ExitCode {
    use crate::check::{Outcome, check_scene, report, summary};
    let Some(scenes) = scenes_in(paths) else {
        return ExitCode::FAILURE;
    };
    let mut results = Vec::new();
    for scene in &scenes {
        let r = check_scene(scene, opts);
        match &r.outcome {
            Outcome::Invalid(e) => print_load_error(e, ""),
            Outcome::Fail { new, heatmap, .. } => {
                eprintln!(
                    "{}: regression; new render {}, heat map {} (if the change is meant, accept it with `ronray check {} --bless`)",
                    scene.display(),
                    new.display(),
                    heatmap.display(),
                    scene.display()
                )
            }
            Outcome::BadGolden { reason, new } => eprintln!(
                "{}: {reason}; new render written to {} (delete the golden, or run `ronray check {} --bless --force` to replace it)",
                scene.display(),
                new.display(),
                scene.display()
            ),
            Outcome::Missing { new } => eprintln!(
                "{}: no golden image; new render written to {} (run `ronray check {} --bless` to accept it)",
                scene.display(),
                new.display(),
                scene.display()
            ),
            _ => {}
        }
        results.push(r);
    }
    print_out(&summary(&results));
    let failed = results.iter().filter(|r| r.failed()).count();
    if failed == 0 {
        println!("{} scenes checked, all match their goldens", results.len());
        return ExitCode::SUCCESS;
    }
    println!("{failed} of {} scenes failed", results.len());
    for page in report::write_all(&results) {
        match page {
            Ok(p) => println!("report: {}", p.display()),
            Err(e) => eprintln!("error: cannot write the HTML report: {e}"),
        }
    }
    ExitCode::FAILURE
}

pub(super) fn cmd_gallery(
    paths: Vec<PathBuf>,
    out: &Path,
    width: u32,
    spp: Option<u32>,
    root: Option<&Path>,
    max_memory: Option<u64>,
) -> ExitCode {
    let fenced = Overrides {
        root: root.map(Path::to_path_buf),
        ..Default::default()
    };
    let Some(scenes) = scenes_in(paths) else {
        return ExitCode::FAILURE;
    };
    if let Some(clash) = same_names(&scenes) {
        eprintln!("error: {clash}");
        return ExitCode::FAILURE;
    }
    let mut md = String::from("| scene | image |\n|---|---|\n");
    let mut failed = false;
    for scene in &scenes {
        let full = match load_with(scene, &fenced) {
            Ok(l) => l,
            Err(e) => {
                print_load_error(&e, "");
                failed = true;
                continue;
            }
        };
        let f = &full.desc.film;
        let height = ((width as f32) * f.height as f32 / f.width as f32)
            .round()
            .max(1.0) as u32;
        let o = Overrides {
            size: Some((width, height)),
            spp,
            ..fenced.clone()
        };
        let loaded = match load_with(scene, &o) {
            Ok(l) => l,
            Err(e) => {
                print_load_error(&e, "");
                failed = true;
                continue;
            }
        };
        let film = loaded.view.film;
        if let Err(e) = crate::memory::check_film(film.width, film.height, false, max_memory) {
            eprintln!("error: {}: {e}", scene.display());
            failed = true;
            continue;
        }
        let stem = scene.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
        let target = out.join(format!("{stem}.png"));
        let (img, stats) = render_whole(
            &loaded.scene,
            &loaded.view,
            &RenderOptions {
                progress: std::io::stderr().is_terminal(),
                ..Default::default()
            },
        );
        if let Err(e) = write_image(&img, &target) {
            eprintln!("error: {e}");
            failed = true;
            continue;
        }
        eprintln!("{}: {}", target.display(), stats.summary());
        md += &format!("| `{}` | ![{stem}]({}) |\n", scene.display(), target.display());
    }
    print_out(&md);
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

/// Two scenes whose images would have the same name in the gallery folder
/// (`a/cornell.ron`, `b/cornell.ron`): one would overwrite the other, so the
/// gallery refuses before rendering anything, naming both.
fn same_names(scenes: &[PathBuf]) -> Option<String> {
    let mut seen: std::collections::HashMap<&std::ffi::OsStr, &Path> = std::collections::HashMap::new();
    for s in scenes {
        let stem = s.file_stem().unwrap_or(s.as_os_str());
        if let Some(first) = seen.insert(stem, s) {
            return Some(format!(
                "{} and {} would both be written to {}.png; rename one, or make a gallery of each folder with its own --out",
                first.display(),
                s.display(),
                stem.to_string_lossy()
            ));
        }
    }
    None
}
