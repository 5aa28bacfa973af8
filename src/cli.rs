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
    /// Check scenes without rendering; prints every problem found.
    Validate {
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
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
}

impl RenderSettings {
    pub fn overrides(&self) -> Overrides {
        Overrides {
            spp: self.spp,
            size: self.size,
            seed: self.seed,
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
        Command::Validate { scenes } => cmd_validate(&scenes),
        Command::Diff {
            a,
            b,
            heatmap,
            max_rmse,
            mask,
        } => cmd_diff(&a, &b, heatmap.as_deref(), max_rmse, mask.as_deref()),
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
            "scene: {} shapes, {} triangles; load {:.1} ms; BVH build {:.1} ms, {} nodes, {} leaves, depth {}, SAH cost {:.2}, {:.1} KiB",
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

fn cmd_validate(paths: &[PathBuf]) -> ExitCode {
    let mut failed = 0;
    for p in paths {
        match load_with(p, &Overrides::default()) {
            Ok(_) => println!("{}: ok", p.display()),
            Err(e) => {
                failed += 1;
                print_load_error(&e);
                eprintln!("error: {e}");
            }
        }
    }
    if failed == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
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
