//! Subcommands. No rendering logic here: each command calls the library and
//! turns its results into messages and exit codes.

use crate::imageio::{self, Image, compare, read_image, write_image};
use crate::render::{RenderOptions, render};
use crate::scene::{LoadError, Overrides, load_with};
use clap::{Args, Parser, Subcommand};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser, Debug)]
#[command(
    name = "ronray",
    version,
    about = "A physically based renderer for hand-written RON scenes"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene to PNG (8-bit sRGB) or EXR (linear float).
    Render {
        scene: PathBuf,
        /// Output image; defaults to the scene's `film.output`, else
        /// `<scene name>.png` in the current folder.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        settings: RenderSettings,
        /// Print build and traversal statistics.
        #[arg(long)]
        stats: bool,
    },
    /// Re-render progressively whenever the scene or a file it uses changes.
    Watch {
        scene: PathBuf,
        /// Output image, as for `render`; rewritten after every pass.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[command(flatten)]
        settings: RenderSettings,
        /// Serve a live page (default 127.0.0.1:8765 or the next free port;
        /// `ADDR` is `HOST:PORT` or a port on loopback, 0 for any).
        #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "")]
        serve: Option<String>,
    },
    /// Check scenes without rendering; prints every problem found.
    Validate {
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// `human` (source excerpts) or `json` (one JSON object per line:
        /// file, line, column, path, severity, message, suggestion).
        #[arg(long, default_value = "human", value_parser = ["human", "json"])]
        format: String,
    },
    /// Rewrite scenes in canonical form (stable field order and layout).
    Fmt {
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Only report files that are not canonical (exit 1 if any).
        #[arg(long)]
        check: bool,
        /// Print to standard output instead of rewriting.
        #[arg(long)]
        stdout: bool,
        /// Write JSON (to `<scene>.json`) instead of RON.
        #[arg(long)]
        json: bool,
        /// Format files with comments anyway (ron cannot keep comments).
        #[arg(long)]
        drop_comments: bool,
    },
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Render every scene of the folders given into one folder of PNGs and
    /// print a Markdown gallery (what the README shows).
    Gallery {
        /// Scene files or folders; default `scenes`.
        paths: Vec<PathBuf>,
        /// Output folder.
        #[arg(short, long, default_value = "docs/gallery")]
        out: PathBuf,
        /// Image width (the height keeps each scene's aspect).
        #[arg(long, default_value_t = 320)]
        width: u32,
        #[arg(long)]
        spp: Option<u32>,
    },
    /// Render scenes at their `test` settings and compare with their golden
    /// images (`golden/<name>.png` beside each scene).
    Check {
        /// Scene files or folders (every scene in a folder); default `scenes`.
        paths: Vec<PathBuf>,
        /// Rewrite the goldens that fail or are missing, on purpose.
        #[arg(long)]
        bless: bool,
        #[arg(long)]
        threads: Option<usize>,
    },
    /// Compare two images (PNG, EXR, PFM): RMSE, relative MSE, PSNR, means.
    Diff {
        /// The image under test.
        a: PathBuf,
        /// The reference.
        b: PathBuf,
        /// Write a per-pixel error heat map (PNG).
        #[arg(long)]
        heatmap: Option<PathBuf>,
        /// Exit with status 1 when the RMSE is above this.
        #[arg(long)]
        max_rmse: Option<f64>,
        /// Grey image; pixels ≥ 128 are left out of the error metrics.
        #[arg(long)]
        mask: Option<PathBuf>,
    },
    /// Time BVH build and closest-hit throughput on an OBJ mesh.
    Bench {
        obj: PathBuf,
        /// Threads for the multi-threaded figures (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
    },
}

/// Overrides shared by `render` and `watch`.
#[derive(Args, Debug, Clone, Default)]
pub struct RenderSettings {
    /// Samples per pixel.
    #[arg(long)]
    pub spp: Option<u32>,
    /// Image size, `WIDTHxHEIGHT`.
    #[arg(long, value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads (default: all cores). The image does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Typed override `path=value` (value in RON), e.g.
    /// `--set film.spp=256 --set materials.floor.albedo=(0.2,0.2,0.2)`.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
}

impl RenderSettings {
    pub fn overrides(&self) -> Overrides {
        Overrides {
            spp: self.spp,
            size: self.size,
            seed: self.seed,
            sets: self.sets.clone(),
        }
    }
}

fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT (e.g. 640x480)"))?;
    let p = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{v}` in `{s}` is not a whole number"))
    };
    Ok((p(w)?, p(h)?))
}

pub fn run(cli: Cli) -> ExitCode {
    match cli.command {
        Command::Render {
            scene,
            output,
            settings,
            stats,
        } => cmd_render(&scene, output, &settings, stats),
        Command::Validate { scenes, format } => cmd_validate(&scenes, format == "json"),
        Command::Fmt {
            scenes,
            check,
            stdout,
            json,
            drop_comments,
        } => cmd_fmt(&scenes, check, stdout, json, drop_comments),
        Command::Gallery {
            paths,
            out,
            width,
            spp,
        } => cmd_gallery(paths, &out, width, spp),
        Command::Schema => {
            print_out(&crate::schema::schema_json());
            ExitCode::SUCCESS
        }
        Command::Check {
            paths,
            bless,
            threads,
        } => cmd_check(paths, bless, threads),
        Command::Watch {
            scene,
            output,
            settings,
            serve,
        } => crate::watch::run(crate::watch::WatchArgs {
            scene,
            output,
            settings,
            serve,
        }),
        Command::Diff {
            a,
            b,
            heatmap,
            max_rmse,
            mask,
        } => cmd_diff(&a, &b, heatmap.as_deref(), max_rmse, mask.as_deref()),
        Command::Bench { obj, threads } => crate::bench::run(&obj, threads).map_or_else(
            |e| {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            },
            |()| ExitCode::SUCCESS,
        ),
    }
}

/// Prints a load failure with full context.
pub fn print_load_error(e: &LoadError) {
    match e.report() {
        Some(r) => eprint!("{}", r.render(std::io::stderr().is_terminal())),
        None => eprintln!("error: {e}"),
    }
}

/// Where a render goes: `-o`, else the scene's `film.output`, else
/// `<scene stem>.png` in the current folder.
pub fn output_path(scene_path: &Path, cli: Option<PathBuf>, from_scene: &Path) -> PathBuf {
    cli.or_else(|| (!from_scene.as_os_str().is_empty()).then(|| from_scene.to_path_buf()))
        .unwrap_or_else(|| {
            PathBuf::from(format!(
                "{}.png",
                scene_path
                    .file_stem()
                    .and_then(|s| s.to_str())
                    .unwrap_or("render")
            ))
        })
}

fn cmd_render(path: &Path, output: Option<PathBuf>, settings: &RenderSettings, show_stats: bool) -> ExitCode {
    let loaded = match load_with(path, &settings.overrides()) {
        Ok(l) => l,
        Err(e) => {
            print_load_error(&e);
            eprintln!("error: {e}; nothing was written");
            return ExitCode::FAILURE;
        }
    };
    let out = output_path(path, output, &loaded.scene.output);
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if ext != "png" && ext != "exr" {
        eprintln!(
            "error: output {} must end in .png or .exr; nothing was written",
            out.display()
        );
        return ExitCode::FAILURE;
    }
    let f = loaded.scene.film;
    let opts = RenderOptions {
        threads: settings.threads,
        progress: std::io::stderr().is_terminal(),
        sample_range: None,
    };
    let (image, stats) = render(&loaded.scene, &opts);
    if let Err(e) = write_image(&image, &out) {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    eprintln!(
        "wrote {} ({}×{}, {} spp) in {}",
        out.display(),
        f.width,
        f.height,
        f.spp,
        stats.summary()
    );
    if show_stats {
        let b = loaded.stats;
        let bs = loaded.scene.bvh.stats();
        eprintln!(
            "scene: {} shapes, {} triangles placed; load {:.1} ms (OBJ parse + mesh BVHs); top-level BVH build {:.1} ms, {} nodes, {} leaves, depth {}, SAH cost {:.2}, {:.1} KiB",
            loaded.scene.shapes.len(),
            b.triangles,
            b.load_time.as_secs_f64() * 1e3,
            b.bvh_time.as_secs_f64() * 1e3,
            bs.nodes,
            bs.leaves,
            bs.max_depth,
            bs.sah_cost,
            bs.bytes as f64 / 1024.0
        );
        let geo = &loaded.scene.geometry;
        let unique: usize = geo.meshes.iter().map(|m| m.triangle_count()).sum();
        eprintln!(
            "meshes: {} in memory ({} triangles), {} instances; mesh BVHs + triangles {:.1} MiB ({:.1} B/triangle), all mesh data {:.1} MiB",
            b.meshes,
            unique,
            b.instances,
            b.mesh_accel_bytes as f64 / 1048576.0,
            b.mesh_accel_bytes as f64 / unique.max(1) as f64,
            geo.meshes.iter().map(|m| m.total_bytes()).sum::<usize>() as f64 / 1048576.0
        );
        for (i, m) in geo.meshes.iter().enumerate().take(8) {
            if let Some(s) = m.blas().map(|b| b.stats()) {
                eprintln!(
                    "  mesh {i}: {} triangles, {} 4-wide nodes, {} leaves, depth {} (binary), SAH cost {:.2}",
                    m.triangle_count(),
                    s.nodes,
                    s.leaves,
                    s.max_depth,
                    s.sah_cost
                );
            }
        }
        let secs = stats.elapsed.as_secs_f64().max(1e-9);
        eprintln!(
            "rays: {} traced, {:.2} M rays/s",
            stats.rays,
            stats.rays as f64 / secs / 1e6
        );
        let sdf = crate::geometry::sdf_object::take_stats();
        if sdf.traces > 0 {
            eprintln!(
                "sdf: {} marches, {:.1} steps per march; steps histogram {}",
                sdf.traces,
                sdf.steps_per_trace(),
                sdf.histogram_text()
            );
        }
    }
    ExitCode::SUCCESS
}

/// Prints to stdout, ignoring a closed pipe (`ronray diff … | head`).
fn print_out(text: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}

fn cmd_validate(paths: &[PathBuf], json: bool) -> ExitCode {
    let mut failed = 0;
    for p in paths {
        match load_with(p, &Overrides::default()) {
            Ok(_) if json => {}
            Ok(_) => print_out(&format!("{}: ok\n", p.display())),
            Err(e) => {
                failed += 1;
                if json {
                    print_out(&json_lines(p, &e));
                } else {
                    print_load_error(&e);
                    eprintln!("error: {e}");
                }
            }
        }
    }
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}

/// One JSON object per diagnostic, for editors and CI.
pub fn json_lines(scene: &Path, e: &LoadError) -> String {
    let items: Vec<serde_json::Value> = match e.report() {
        Some(r) => r
            .diagnostics
            .iter()
            .map(|d| {
                serde_json::json!({
                    "file": d.file.display().to_string(),
                    "line": d.line,
                    "column": d.column,
                    "path": d.path,
                    "severity": "error",
                    "message": d.message,
                    "suggestion": d.help,
                })
            })
            .collect(),
        None => vec![serde_json::json!({
            "file": scene.display().to_string(), "line": 0, "column": 0, "path": null,
            "severity": "error", "message": e.to_string(), "suggestion": null,
        })],
    };
    items.iter().map(|v| format!("{v}\n")).collect()
}

fn cmd_fmt(paths: &[PathBuf], check: bool, stdout: bool, json: bool, drop_comments: bool) -> ExitCode {
    use crate::scene::format::{has_comments, to_json, to_ron};
    let mut failed = false;
    for p in paths {
        let text = match std::fs::read_to_string(p) {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: cannot read {}: {e}", p.display());
                failed = true;
                continue;
            }
        };
        let desc = match crate::scene::load::parse(p, &text) {
            Ok(d) => d,
            Err(r) => {
                eprint!("{}", r.render(std::io::stderr().is_terminal()));
                failed = true;
                continue;
            }
        };
        let (out_text, target) = if json {
            (to_json(&desc), p.with_extension("json"))
        } else {
            (to_ron(&desc), p.clone())
        };
        let out_text = match out_text {
            Ok(t) => t,
            Err(e) => {
                eprintln!("error: {}: {e}", p.display());
                failed = true;
                continue;
            }
        };
        if check {
            if out_text != text {
                println!("{}: not in canonical form", p.display());
                failed = true;
            }
            continue;
        }
        if stdout {
            print_out(&out_text);
            continue;
        }
        if has_comments(&text) && !json && !drop_comments {
            eprintln!(
                "error: {} has comments, which ron cannot keep through formatting; nothing was changed \
                 (pass --drop-comments to format it anyway, or --stdout to see the result)",
                p.display()
            );
            failed = true;
            continue;
        }
        let tmp = target.with_extension("fmt.tmp");
        if let Err(e) = std::fs::write(&tmp, &out_text).and_then(|_| std::fs::rename(&tmp, &target)) {
            eprintln!("error: cannot write {}: {e}", target.display());
            failed = true;
            continue;
        }
        eprintln!("formatted {}", target.display());
    }
    if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    }
}

fn cmd_diff(
    a: &Path,
    b: &Path,
    heatmap: Option<&Path>,
    max_rmse: Option<f64>,
    mask: Option<&Path>,
) -> ExitCode {
    let load = |p: &Path| read_image(p).map_err(|e| eprintln!("error: {e}"));
    let (Ok(ia), Ok(ib)) = (load(a), load(b)) else {
        return ExitCode::FAILURE;
    };
    let skip: Option<Vec<bool>> = match mask.map(load) {
        Some(Ok(m)) if (m.width, m.height) == (ia.width, ia.height) => {
            Some(m.pixels.iter().map(|p| p.x >= 0.2).collect())
        }
        Some(Ok(m)) => {
            eprintln!(
                "error: mask is {}×{}, images are {}×{}",
                m.width, m.height, ia.width, ia.height
            );
            return ExitCode::FAILURE;
        }
        Some(Err(())) => return ExitCode::FAILURE,
        None => None,
    };
    let c = match compare(&ia, &ib, skip.as_deref()) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    println!("rmse     {:.6}", c.rmse);
    println!("rel_mse  {:.6}", c.rel_mse);
    println!("psnr     {:.2} dB", c.psnr);
    println!(
        "mean a   {:.6} {:.6} {:.6}",
        c.mean_a[0], c.mean_a[1], c.mean_a[2]
    );
    println!(
        "mean b   {:.6} {:.6} {:.6}",
        c.mean_b[0], c.mean_b[1], c.mean_b[2]
    );
    println!("pixels   {}", c.pixels);
    if let Some(h) = heatmap {
        let img: Image = imageio::metrics::heatmap(&ia, &ib, (4.0 * c.rmse as f32).max(1e-6));
        if let Err(e) = write_image(&img, h) {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    match max_rmse {
        Some(t) if c.rmse > t => {
            eprintln!("rmse {:.6} is above the threshold {t}", c.rmse);
            ExitCode::FAILURE
        }
        _ => ExitCode::SUCCESS,
    }
}

fn cmd_check(paths: Vec<PathBuf>, bless: bool, threads: Option<usize>) -> ExitCode {
    use crate::check::{Outcome, check_scene, collect, summary};
    let paths = if paths.is_empty() {
        vec![PathBuf::from("scenes")]
    } else {
        paths
    };
    let scenes = match collect(&paths) {
        Ok(s) if !s.is_empty() => s,
        Ok(_) => {
            eprintln!(
                "error: no scenes found in {}",
                paths
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            return ExitCode::FAILURE;
        }
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut results = Vec::new();
    for scene in &scenes {
        let r = check_scene(scene, bless, threads);
        match &r.outcome {
            Outcome::Invalid(e) => print_load_error(e),
            Outcome::Fail { new, heatmap, .. } => {
                eprintln!(
                    "{}: regression; new render {}, heat map {}",
                    scene.display(),
                    new.display(),
                    heatmap.display()
                )
            }
            Outcome::Missing { new } => eprintln!(
                "{}: no golden image; new render written to {} (run `ronray check --bless` to accept it)",
                scene.display(),
                new.display()
            ),
            _ => {}
        }
        results.push(r);
    }
    print_out(&summary(&results));
    let failed = results.iter().filter(|r| r.failed()).count();
    if failed == 0 {
        println!("{} scenes checked, all match their goldens", results.len());
        ExitCode::SUCCESS
    } else {
        println!("{failed} of {} scenes failed", results.len());
        ExitCode::FAILURE
    }
}

fn cmd_gallery(paths: Vec<PathBuf>, out: &Path, width: u32, spp: Option<u32>) -> ExitCode {
    let paths = if paths.is_empty() {
        vec![PathBuf::from("scenes")]
    } else {
        paths
    };
    let Ok(scenes) = crate::check::collect(&paths) else {
        eprintln!(
            "error: cannot list {}",
            paths
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        );
        return ExitCode::FAILURE;
    };
    let mut md = String::from("| scene | image |\n|---|---|\n");
    let mut failed = false;
    for scene in &scenes {
        let full = match load_with(scene, &Overrides::default()) {
            Ok(l) => l,
            Err(e) => {
                print_load_error(&e);
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
            ..Default::default()
        };
        let Ok(loaded) = load_with(scene, &o) else {
            continue;
        };
        let stem = scene.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
        let target = out.join(format!("{stem}.png"));
        let (img, stats) = render(
            &loaded.scene,
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
