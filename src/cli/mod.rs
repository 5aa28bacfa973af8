//! Subcommands. No rendering logic here: each command calls the library and
//! turns its results into messages and exit codes.

mod assemble;
mod bench;
mod bench_scenes;
mod check;
mod diff;
mod fmt;
mod layers;
mod lsp;
mod migrate;
mod new;
mod render;
mod validate;

pub use validate::json_lines;

/// Exit status of a command-line usage error (clap's too): bad arguments,
/// or piece arguments that do not fit the scene.
pub const USAGE: u8 = 2;

use crate::diagnostic::Report;
use crate::load::{LoadError, Overrides};
use assemble::cmd_assemble;
use check::{cmd_check, cmd_gallery};
use clap::{Args, Parser, Subcommand};
use diff::cmd_diff;
use fmt::cmd_fmt;
use render::{PieceArgs, cmd_render};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use validate::cmd_validate;

/// `--version`: the crate's version, or what a build script says of the
/// build (`tools/pgo-build.sh` sets `RONRAY_BUILD` to the version and
/// "profile-guided"), so a benchmark's figures name the binary they timed.
pub(crate) const VERSION: &str = match option_env!("RONRAY_BUILD") {
    Some(v) => v,
    None => env!("CARGO_PKG_VERSION"),
};

/// The command line (clap); `main` parses it and hands it to [`run`].
#[derive(Parser, Debug)]
#[command(
    name = "ronray",
    version = VERSION,
    about = "A physically based renderer for hand-written RON scenes",
    long_about = None
)]
pub struct Cli {
    /// The command to run.
    #[command(subcommand)]
    pub command: Command,
    /// Refuse every input (scene, include, OBJ, MTL, texture, environment
    /// map) that resolves, symlinks followed, outside DIR: for rendering
    /// untrusted scenes in CI. Applies to render, watch, validate, check,
    /// gallery and bench.
    #[arg(long, global = true, value_name = "DIR")]
    pub root: Option<PathBuf>,
    /// Largest estimated memory a render may need, in GiB (default: what
    /// the machine has available, `MemAvailable`); a larger render is
    /// refused before anything is allocated.
    #[arg(long, global = true, value_name = "GIB", value_parser = parse_gib)]
    pub max_memory: Option<u64>,
}

/// The commands; each is one file of `cli/`.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Render a scene to PNG (sRGB, exposed and tone mapped) or EXR, PFM or HDR
    /// (linear float).
    Render {
        /// The scene file (RON, or JSON by its extension).
        scene: PathBuf,
        /// Output image; defaults to the scene's `film.output`, else
        /// `<scene name>.png` in the current folder.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[allow(missing_docs)]
        #[command(flatten)]
        settings: RenderSettings,
        #[allow(missing_docs)]
        #[command(flatten)]
        piece: PieceArgs,
        #[allow(missing_docs)]
        #[command(flatten)]
        denoise: layers::DenoiseArgs,
        /// Print build and traversal statistics.
        #[arg(long)]
        stats: bool,
    },
    /// Put pieces of a frame (EXR files from `render --crop/--pixels/--tile/
    /// --samples`) back together: tiles are placed, sample splits averaged by
    /// sample count. Refuses pieces of different scenes or versions,
    /// overlaps and gaps.
    Assemble {
        /// The piece files (EXR), in any order.
        #[arg(required = true)]
        pieces: Vec<PathBuf>,
        /// Output image, PNG or EXR.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Re-render progressively whenever the scene or a file it uses changes.
    Watch {
        /// The scene file to watch (RON or JSON).
        scene: PathBuf,
        /// Output image, as for `render`; rewritten after every pass.
        #[arg(short, long)]
        output: Option<PathBuf>,
        #[allow(missing_docs)]
        #[command(flatten)]
        settings: RenderSettings,
        /// Serve a live page (default 127.0.0.1:8765 or the next free port;
        /// `ADDR` is `HOST:PORT` or a port on loopback, 0 for any).
        #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = "")]
        serve: Option<String>,
    },
    /// Check scenes without rendering; prints every problem found.
    Validate {
        /// Scene files to check.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Also list every file each scene reads and the image it would
        /// write, resolved (symlinks followed).
        #[arg(short = 'v', long)]
        inputs: bool,
        /// `human` (source excerpts) or `json` (one JSON object per line:
        /// file, line, column, path, severity, message, suggestion).
        #[arg(long, default_value = "human", value_parser = ["human", "json"])]
        format: String,
        /// Count warnings (scenes that load but will surprise) as errors:
        /// exit 1 if any scene has one.
        #[arg(long)]
        deny_warnings: bool,
    },
    /// Lay scene files out again (indentation, spacing, trailing commas, one
    /// entry per line or short vectors on one line), keeping comments,
    /// headers, number spellings and omitted defaults. RON stays RON, JSON
    /// stays JSON.
    Fmt {
        /// Scene files to format.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Change nothing; print a unified diff of what would change (exit 1
        /// if anything would).
        #[arg(long)]
        check: bool,
        /// Print to standard output instead of rewriting.
        #[arg(long)]
        stdout: bool,
        /// Write the canonical JSON twin `<scene>.json` (from the parsed
        /// scene: comments and spellings are not kept).
        #[arg(long)]
        json: bool,
        /// Rewrite from the parsed scene instead: fields in declaration order,
        /// every default written out, comments dropped.
        #[arg(long)]
        canonical: bool,
        /// With `--canonical`, format files with comments anyway.
        #[arg(long)]
        drop_comments: bool,
    },
    /// Bring scene files to the current scene-format version, rewriting them
    /// in place as a text edit: comments, spellings and layout are kept.
    Migrate {
        /// Scene files to migrate.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Change nothing; print a unified diff of what would change (exit 1
        /// if anything would).
        #[arg(long)]
        check: bool,
    },
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Serve the Language Server Protocol on standard input and output:
    /// diagnostics as you type, hover, completion, go to definition.
    Lsp,
    /// Write a commented starter scene `NAME.ron` (camera, a light, a floor,
    /// an object) that validates and renders.
    New {
        /// Scene name or path; `.ron` is added when missing.
        name: PathBuf,
        /// Replace an existing file.
        #[arg(long)]
        force: bool,
    },
    /// Render every scene of the folders given into one folder of PNGs and
    /// print a Markdown gallery (what `docs/gallery.md` shows).
    Gallery {
        /// Scene files or folders; default `scenes`.
        paths: Vec<PathBuf>,
        /// Output folder.
        #[arg(short, long, default_value = "docs/gallery")]
        out: PathBuf,
        /// Image width (the height keeps each scene's aspect), 1..=16384.
        #[arg(long, default_value_t = 320, value_parser = parse_width)]
        width: u32,
        /// Samples per pixel (default: each scene's own).
        #[arg(long)]
        spp: Option<u32>,
    },
    /// Render scenes at their `test` settings and compare with their golden
    /// images (`golden/<name>.png` beside each scene).
    Check {
        /// Scene files or folders (every scene in a folder); default `scenes`.
        paths: Vec<PathBuf>,
        /// Rewrite the goldens that fail or are missing, on purpose, each
        /// with the variance image that measures its noise
        /// (`golden/<name>.var.exr`, from renders with other seeds).
        #[arg(long)]
        bless: bool,
        /// With --bless, also replace goldens that are corrupt or of
        /// another size (without it they are reported and kept).
        #[arg(long, requires = "bless")]
        force: bool,
        /// Worker threads (default: all cores; at most 1024).
        #[arg(long, value_parser = parse_threads)]
        threads: Option<usize>,
        /// Typed override `path=value` (value in RON), applied before the
        /// test settings are read: `--set test.seed=7` re-seeds.
        #[arg(long = "set", value_name = "PATH=VALUE")]
        sets: Vec<String>,
        /// Largest accepted score (the worst 8×8-pixel window's mean squared
        /// z-score against the sampling noise; about 1 for noise alone),
        /// replacing every scene's `test.tolerance`.
        #[arg(long, value_parser = parse_tolerance)]
        tolerance: Option<f64>,
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
        #[arg(long, value_parser = parse_max_rmse)]
        max_rmse: Option<f64>,
        /// Grey image; pixels ≥ 128 are left out of the error metrics.
        #[arg(long)]
        mask: Option<PathBuf>,
    },
    /// Time BVH build and closest-hit throughput on an OBJ mesh, or (with
    /// `--scenes DIR`) render the scenes that have a reference in DIR and
    /// print speed and error against it.
    Bench {
        /// The Wavefront OBJ (or `.ply`) mesh to measure.
        #[arg(required_unless_present = "scenes", conflicts_with = "scenes")]
        obj: Option<PathBuf>,
        /// Threads for the multi-threaded figures (default: all cores; at
        /// most 1024); with `--scenes`, the render's threads.
        #[arg(long, value_parser = parse_threads)]
        threads: Option<usize>,
        /// Folder of references: `<name>_ref.exr` or `<name>_ref.pfm` images
        /// (and optionally `<name>_emitter_mask.png`, 255 where a pixel sees
        /// a light); each one's ronray twin `<name>.ron` is rendered.
        #[arg(long, value_name = "DIR")]
        scenes: Option<PathBuf>,
        /// With `--scenes`: where the ronray twins are looked up after DIR.
        #[arg(long, value_name = "DIR", default_value = "scenes")]
        ronray_scenes: PathBuf,
        /// With `--scenes`: samples per pixel, comma-separated.
        #[arg(long, value_delimiter = ',', value_parser = clap::value_parser!(u32).range(1..), default_value = "16,64,256")]
        spp: Vec<u32>,
        /// With `--scenes`: samplers to compare, comma-separated scene-file
        /// names (`Independent,Sobol`); default each scene's own.
        #[arg(long, value_delimiter = ',')]
        sampler: Vec<String>,
        /// With `--scenes`: seed of the random streams.
        #[arg(long)]
        seed: Option<u64>,
        /// With `--scenes`: typed override `path=value`, as for `render`.
        #[arg(long = "set", value_name = "PATH=VALUE")]
        sets: Vec<String>,
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
    /// Seed of the random streams (same seed, same image).
    #[arg(long)]
    pub seed: Option<u64>,
    /// Worker threads (default: all cores; at most 1024). The image does not
    /// depend on it.
    #[arg(long, value_parser = parse_threads)]
    pub threads: Option<usize>,
    /// Typed override `path=value` (value in RON), e.g.
    /// `--set film.spp=256 --set materials.floor.albedo=(0.2,0.2,0.2)`.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub sets: Vec<String>,
    /// Exposure of PNG outputs in stops (+1 doubles); `--set film.exposure=X`.
    #[arg(long, allow_hyphen_values = true, value_name = "STOPS")]
    pub exposure: Option<f32>,
    /// Tone map of PNG outputs: Clamp, Reinhard, Aces or AgX; `--set
    /// film.tonemap=NAME`.
    #[arg(long, value_name = "NAME")]
    pub tonemap: Option<String>,
    /// Bits per channel of PNG outputs, 8 or 16; `--set film.png_bits=N`.
    #[arg(long, value_name = "BITS")]
    pub png_bits: Option<u8>,
    /// Frame of an animated scene to draw (within its `animation.frames`).
    /// `auto` (render only) is the first frame
    /// plus the job index (SLURM_ARRAY_TASK_ID, …, as `--tile auto`).
    #[arg(long, value_parser = crate::farm::frames::parse_frame, value_name = "N|auto", allow_hyphen_values = true)]
    pub frame: Option<crate::farm::frames::FrameArg>,
}

impl RenderSettings {
    /// The settings the loader applies to the scene. The display flags are
    /// typed overrides, so the loader checks them like the scene's own
    /// fields (an unknown tone map gets a suggestion).
    pub fn overrides(&self) -> Overrides {
        let mut sets = self.sets.clone();
        let mut flags = Vec::new();
        let mut flag = |set: String, written: String| {
            flags.push((set.clone(), written));
            sets.push(set);
        };
        if let Some(e) = self.exposure {
            flag(format!("film.exposure={e:?}"), format!("--exposure {e}"));
        }
        if let Some(t) = &self.tonemap {
            flag(format!("film.tonemap={t}"), format!("--tonemap {t}"));
        }
        if let Some(b) = self.png_bits {
            flag(format!("film.png_bits={b}"), format!("--png-bits {b}"));
        }

        Overrides {
            spp: self.spp,
            size: self.size,
            seed: self.seed,
            sets,
            flags,
            root: None,
            frame: match self.frame {
                Some(crate::farm::frames::FrameArg::Given(f)) => Some(f),
                Some(crate::farm::frames::FrameArg::Auto) | None => None,
            },
        }
    }
}

/// Most worker threads a command starts: beyond the cores, threads only
/// cost memory (100,000 asked for would exhaust it). Raise it here.
pub const MAX_THREADS: usize = 1024;

fn parse_threads(s: &str) -> Result<usize, String> {
    let n: usize = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a whole number"))?;
    if n == 0 || n > MAX_THREADS {
        return Err(format!("{n} threads is outside 1..={MAX_THREADS}"));
    }
    Ok(n)
}

/// `gallery --width`: 0 would render nothing and say nothing.
fn parse_width(s: &str) -> Result<u32, String> {
    let max = crate::load::validate::MAX_RESOLUTION;
    match s.trim().parse::<u32>() {
        Ok(w) if (1..=max).contains(&w) => Ok(w),
        Ok(w) => Err(format!("width {w} is outside 1..={max}")),
        Err(_) => Err(format!("`{s}` is not a whole number")),
    }
}

/// A finite number at least `min` (`exclusive`: above it): a NaN gate would
/// let everything pass, a negative one fail everything.
fn parse_number(s: &str, min: f64, exclusive: bool) -> Result<f64, String> {
    let x: f64 = s.trim().parse().map_err(|_| format!("`{s}` is not a number"))?;
    let ok = x.is_finite() && if exclusive { x > min } else { x >= min };
    if !ok {
        let rel = if exclusive { ">" } else { "≥" };
        return Err(format!("{x} must be a finite number {rel} {min}"));
    }
    Ok(x)
}

/// `--max-memory`: GiB (fractions allowed) → bytes.
fn parse_gib(s: &str) -> Result<u64, String> {
    let gib = parse_number(s, 0.0, true)?;
    Ok((gib * f64::from(1u32 << 30)).min(u64::MAX as f64) as u64)
}

fn parse_tolerance(s: &str) -> Result<f64, String> {
    parse_number(s, 0.0, true)
}

fn parse_max_rmse(s: &str) -> Result<f64, String> {
    parse_number(s, 0.0, false)
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

/// Ctrl-C ends the process without running destructors, which would leave
/// the temporary file of an image being written: remove it, then exit with
/// the usual 130. (Watch mode stops cleanly on its own.)
fn remove_temporaries_on_interrupt() {
    let _ = ctrlc::set_handler(|| {
        crate::imageio::write::remove_pending();
        std::process::exit(130);
    });
}

/// Runs one command; the exit code says whether it succeeded.
pub fn run(cli: Cli) -> ExitCode {
    let root = cli.root;
    if let Some(r) = root.as_ref().filter(|r| !r.is_dir()) {
        eprintln!("error: --root {} is not a folder", r.display());
        return ExitCode::FAILURE;
    }
    let with_root = |mut o: Overrides| {
        o.root = root.clone();
        o
    };
    if !matches!(cli.command, Command::Watch { .. } | Command::Lsp) {
        remove_temporaries_on_interrupt();
    }
    match cli.command {
        Command::Render {
            scene,
            output,
            settings,
            piece,
            denoise,
            stats,
        } => cmd_render(
            &scene,
            output,
            &settings,
            &piece,
            &denoise,
            stats,
            &render::Limits {
                root: root.as_deref(),
                max_memory: cli.max_memory,
            },
        ),
        Command::Assemble { pieces, output } => cmd_assemble(&pieces, &output),
        Command::Validate {
            scenes,
            inputs,
            format,
            deny_warnings,
        } => cmd_validate(&scenes, format == "json", deny_warnings, inputs, root.as_deref()),
        Command::Fmt {
            scenes,
            check,
            stdout,
            json,
            canonical,
            drop_comments,
        } => cmd_fmt(
            &scenes,
            fmt::FmtOptions {
                check,
                stdout,
                json,
                canonical,
                drop_comments,
            },
        ),
        Command::Gallery {
            paths,
            out,
            width,
            spp,
        } => cmd_gallery(paths, &out, width, spp, root.as_deref(), cli.max_memory),
        Command::Lsp => lsp::cmd_lsp(),
        Command::Migrate { scenes, check } => migrate::cmd_migrate(&scenes, check),
        Command::New { name, force } => new::cmd_new(&name, force),
        Command::Schema => {
            print_out(&crate::schema::schema_json());
            ExitCode::SUCCESS
        }
        Command::Check {
            paths,
            bless,
            force,
            threads,
            sets,
            tolerance,
        } => cmd_check(
            paths,
            &crate::check::CheckOptions {
                bless,
                threads,
                sets,
                tolerance,
                force,
                root: root.clone(),
            },
        ),
        Command::Watch {
            scene,
            output,
            settings,
            serve,
        } => crate::watch::run(crate::watch::WatchArgs {
            scene,
            output,
            overrides: with_root(settings.overrides()),
            threads: settings.threads,
            serve,
            max_memory: cli.max_memory,
        }),
        Command::Diff {
            a,
            b,
            heatmap,
            max_rmse,
            mask,
        } => cmd_diff(&a, &b, heatmap.as_deref(), max_rmse, mask.as_deref()),
        Command::Bench {
            obj,
            threads,
            scenes,
            ronray_scenes,
            spp,
            sampler,
            seed,
            sets,
        } => match (obj, scenes) {
            (_, Some(refs)) => bench_scenes::run(&bench_scenes::SceneBench {
                refs: &refs,
                scenes: &ronray_scenes,
                spp: &spp,
                samplers: &sampler,
                settings: &RenderSettings {
                    threads,
                    seed,
                    sets,
                    ..Default::default()
                },
                root: root.as_deref(),
            }),
            (Some(obj), None) => bench::run(&obj, threads, root.as_deref()),
            (None, None) => Err("name an OBJ mesh or `--scenes DIR`".into()),
        }
        .map_or_else(
            |e| {
                eprintln!("error: {e}");
                ExitCode::FAILURE
            },
            |()| ExitCode::SUCCESS,
        ),
    }
}

/// Prints a load failure with full context: every diagnostic, then one
/// summary line ending in `then` (an I/O error is that line alone).
pub fn print_load_error(e: &LoadError, then: &str) {
    if let Some(r) = e.report() {
        eprint!("{}", r.render(std::io::stderr().is_terminal()));
    }
    eprintln!("error: {e}{then}");
}

/// Prints a loaded scene's warnings with context (nothing if it has none).
pub fn print_warnings(warnings: &Report) {
    if !warnings.diagnostics.is_empty() {
        eprint!("{}", warnings.render(std::io::stderr().is_terminal()));
    }
}

/// Prints to stdout, ignoring a closed pipe (`ronray diff … | head`).
pub(crate) fn print_out(text: &str) {
    use std::io::Write;
    let _ = std::io::stdout().lock().write_all(text.as_bytes());
}
