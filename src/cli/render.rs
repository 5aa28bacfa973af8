//! `ronray render`: arguments in; load, plan, check the output, render,
//! write (all library calls: `crate::frame`); the summary out.
use super::{RenderSettings, USAGE, print_load_error, print_warnings};
use crate::farm::frames::FrameArg;
use crate::farm::split::{parse_crop, parse_pixels, parse_samples, parse_tile};
use crate::farm::{Existing, PieceMeta, Region, TileIndex, existing_piece, piece_meta};
use crate::frame::{Output, Plan, RenderOptions, RenderStats, Request, Sampling, TileDone, WriteOptions};
use crate::imageio::PixelRect;
use crate::load::{Loaded, load_with};
use clap::Args;
use serde_json::json;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

/// Which part of the frame to render, and how to report (`render` only).
#[derive(Args, Debug, Clone, Default)]
pub struct PieceArgs {
    /// Render only a crop window: fractions `x0,x1,y0,y1` of the image
    /// (pbrt's order). Writes a piece (EXR) for `ronray assemble`.
    #[arg(long, value_parser = parse_crop, value_name = "X0,X1,Y0,Y1", conflicts_with_all = ["pixels", "tile"])]
    pub crop: Option<[f64; 4]>,
    /// Render only pixels `x0..x1` × `y0..y1` (ends excluded). Writes a piece.
    #[arg(long, value_parser = parse_pixels, value_name = "X0,Y0,X1,Y1", conflicts_with = "tile")]
    pub pixels: Option<PixelRect>,
    /// Render tile I of an N-tile split into bands of rows. `auto/N` takes I
    /// from SLURM_ARRAY_TASK_ID, JOB_COMPLETION_INDEX or PARALLEL_SEQ − 1;
    /// `{tile}` in the output path becomes I. Writes a piece.
    #[arg(long, value_parser = parse_tile, value_name = "I/N")]
    pub tile: Option<(TileIndex, u32)>,
    /// Render frames A to B of an animated scene, both included, one after
    /// another; the output name needs `{frame}` or `{frame:04}`.
    #[arg(long, value_parser = crate::farm::frames::parse_frames, value_name = "A..B", conflicts_with = "frame", allow_hyphen_values = true)]
    pub frames: Option<(i32, i32)>,
    /// Render samples A to B−1 of every pixel (of the scene's spp), so
    /// several machines can add samples to one frame. Writes a piece.
    #[arg(long, value_parser = parse_samples, value_name = "A..B")]
    pub samples: Option<(u32, u32)>,
    /// `bar` (a progress bar on a terminal, the default), `json` (one JSON
    /// line per finished tile on standard output, for scheduler logs) or
    /// `none`.
    #[arg(long, value_parser = ["bar", "json", "none"])]
    pub progress: Option<String>,
    /// Skip the render when the output already holds this piece of this
    /// scene (same scene hash, version, pixels and samples).
    #[arg(long)]
    pub resume: bool,
}

impl PieceArgs {
    fn region(&self) -> Region {
        match (self.crop, self.pixels, self.tile) {
            (Some(c), _, _) => Region::Crop(c),
            (_, Some(p), _) => Region::Pixels(p),
            (_, _, Some((index, count))) => Region::Tile { index, count },
            _ => Region::Whole,
        }
    }

    fn is_piece(&self) -> bool {
        self.region() != Region::Whole || self.samples.is_some()
    }
}

/// Prints one JSON line on standard output (`--progress json`).
fn json_line(v: serde_json::Value) {
    super::print_out(&format!("{v}\n"));
}

/// The global flags that fence what a render may read and allocate.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Limits<'a> {
    /// `--root DIR`: inputs outside it are refused.
    pub root: Option<&'a Path>,
    /// `--max-memory GIB`, in bytes; `None` uses what the machine has.
    pub max_memory: Option<u64>,
}

pub(super) fn cmd_render(
    path: &Path,
    output: Option<PathBuf>,
    settings: &RenderSettings,
    piece: &PieceArgs,
    layer_args: &super::layers::DenoiseArgs,
    show_stats: bool,
    limits: &Limits,
) -> ExitCode {
    // `--frames` stays in `piece`: each frame checks the range and the
    // output name against it.
    let one = |settings: &RenderSettings, piece: &PieceArgs| {
        render_frame(
            path,
            output.clone(),
            settings,
            piece,
            layer_args,
            show_stats,
            limits,
        )
    };
    let done = match (piece.frames, settings.frame) {
        (Some((a, b)), _) => (a..=b).try_for_each(|f| {
            let s = RenderSettings {
                frame: Some(FrameArg::Given(f)),
                ..settings.clone()
            };
            one(&s, piece)
        }),
        (None, Some(FrameArg::Auto)) => match auto_frame(path, settings, piece, limits) {
            Ok((s, p)) => one(&s, &p),
            Err(message) => {
                eprintln!("error: {message}; nothing was written");
                Err(USAGE.into())
            }
        },
        (None, _) => one(settings, piece),
    };
    match done {
        Ok(()) => ExitCode::SUCCESS,
        Err(code) => code,
    }
}

/// `--frame auto`: the scene's first frame plus the job index. With `--tile
/// auto/N` too, job `k` draws tile `k mod N` of frame `first + ⌊k / N⌋`, so
/// one job array covers every tile of every frame.
fn auto_frame(
    path: &Path,
    settings: &RenderSettings,
    piece: &PieceArgs,
    limits: &Limits,
) -> Result<(RenderSettings, PieceArgs), String> {
    let env = |k: &str| std::env::var(k).ok();
    let (index, _) = crate::farm::split::auto_index(&env)?;
    let still = RenderSettings {
        frame: None,
        ..settings.clone()
    };
    let overrides = crate::load::Overrides {
        root: limits.root.map(Path::to_path_buf),
        ..still.overrides()
    };
    let first = match load_with(path, &overrides) {
        Ok(l) => l.desc.animation.map(|a| a.frames.0),
        Err(e) => {
            print_load_error(&e, "");
            return Err("the scene did not load".into());
        }
    };
    let first = first.ok_or("--frame auto needs an `animation` section in the scene")?;
    let mut piece = piece.clone();
    let per_frame = match piece.tile {
        Some((TileIndex::Auto, n)) => {
            piece.tile = Some((TileIndex::Given(index % n.max(1)), n));
            n.max(1)
        }
        _ => 1,
    };
    let frame = i32::try_from(index / per_frame)
        .ok()
        .and_then(|k| first.checked_add(k))
        .ok_or("the job index is past any frame")?;
    let settings = RenderSettings {
        frame: Some(FrameArg::Given(frame)),
        ..settings.clone()
    };
    Ok((settings, piece))
}

fn render_frame(
    path: &Path,
    output: Option<PathBuf>,
    settings: &RenderSettings,
    piece: &PieceArgs,
    layer_args: &super::layers::DenoiseArgs,
    show_stats: bool,
    limits: &Limits,
) -> Result<(), ExitCode> {
    let json = piece.progress.as_deref() == Some("json");
    let overrides = crate::load::Overrides {
        root: limits.root.map(Path::to_path_buf),
        ..settings.overrides()
    };
    let loaded = match load_with(path, &overrides) {
        Ok(l) => l,
        Err(e) => {
            print_load_error(&e, "; nothing was written");
            return Err(ExitCode::FAILURE);
        }
    };
    // Warnings are printed, not fatal: the scene renders as written.
    print_warnings(&loaded.warnings);
    let (plan, out, meta) = match prepare(path, output, &loaded, piece, layer_args.denoise, limits) {
        Ok(Some(job)) => job,
        Ok(None) => return Ok(()),
        Err((message, code)) => {
            eprintln!("error: {message}; nothing was written");
            return Err(code);
        }
    };
    let (scene, view) = (&loaded.scene, &loaded.view);
    let opts = RenderOptions {
        threads: settings.threads,
        progress: !json && piece.progress.as_deref() != Some("none") && std::io::stderr().is_terminal(),
    };
    let r = plan.rect;
    json.then(|| {
        json_line(
            json!({"event": "start", "output": out.path, "scene": meta.as_ref().map(|m| m.scene.clone()),
        "pixels": [r.x0, r.y0, r.x1, r.y1], "samples": [plan.samples.0, plan.samples.1],
        "tile": meta.as_ref().and_then(|m| m.tile).map(|(i, n)| format!("{i}/{n}"))}),
        )
    });
    let report = |t: &TileDone| {
        json.then(|| {
            json_line(json!({"event": "tile", "done": t.done, "total": t.total,
            "pixels": [t.rect.x0, t.rect.y0, t.rect.x1, t.rect.y1], "elapsed_s": t.elapsed.as_secs_f64()}))
        });
    };
    let (pixels, stats) = crate::frame::render(scene, view, &plan, &opts, &AtomicBool::new(false), &report);
    let write = WriteOptions {
        threads: settings.threads,
        keep_noisy: layer_args.keep_noisy,
        piece: meta.as_ref(),
    };
    let extra = match crate::frame::write(scene, view, &plan, &out, &pixels, &write) {
        Ok(extra) => extra,
        Err(e) => {
            eprintln!("error: {e}");
            return Err(ExitCode::FAILURE);
        }
    };
    let what = plan.describe(view, stats.samples);
    eprintln!(
        "wrote {} ({what}) in {}{extra}",
        out.path.display(),
        stats.summary()
    );
    json.then(|| {
        json_line(
            json!({"event": "done", "output": out.path, "elapsed_s": stats.elapsed.as_secs_f64(),
        "samples": stats.samples, "rays": stats.rays}),
        )
    });
    if show_stats {
        print_stats(&loaded, &stats);
    }
    Ok(())
}

/// A refusal to render: the message and the exit code.
type Refusal = (String, ExitCode);

/// The plan, the checked output and, for a piece, its metadata; `None` when
/// `--resume` finds the piece already written.
fn prepare(
    path: &Path,
    output: Option<PathBuf>,
    loaded: &Loaded,
    piece: &PieceArgs,
    denoise: bool,
    limits: &Limits,
) -> Result<Option<(Plan, Output, Option<PieceMeta>)>, Refusal> {
    let usage = |e: &dyn std::fmt::Display| (e.to_string(), USAGE.into());
    let failure = |e: &dyn std::fmt::Display| (e.to_string(), ExitCode::FAILURE);
    let f = loaded.view.film;
    let env = |k: &str| std::env::var(k).ok();
    let spec = match piece.is_piece() {
        true => Some(
            crate::farm::resolve(piece.region(), piece.samples, (f.width, f.height, f.spp), &env)
                .map_err(|e| usage(&e))?,
        ),
        false if piece.resume => {
            return Err(usage(
                &"--resume skips pieces already written; give --crop, --pixels, --tile or --samples",
            ));
        }
        false => None,
    };
    let request = spec.map_or(Request::Whole, |s| Request::Piece {
        rect: s.rect,
        samples: s.samples,
    });
    let plan = Plan::new(&loaded.scene, &loaded.view, request, denoise).map_err(|e| usage(&e))?;
    let tile = spec.and_then(|s| s.tile).map(|(i, _)| i);
    let cli_given = output.is_some();
    let out = frame_name(
        Output::path(&loaded.view, path, output, tile),
        loaded,
        piece.frames,
    )
    .map_err(|e| usage(&e))?;
    let out = Output::new(out, &plan, &loaded.files, limits.max_memory)
        .map_err(|e| if e.is_usage() { usage(&e) } else { failure(&e) })?
        .confine_scene_output(&loaded.view, path, cli_given, limits.root)
        .map_err(|e| failure(&e))?;
    for note in plan.piece_notes(&loaded.view) {
        eprintln!("note: {note}");
    }
    let spread = match plan.sampling {
        Sampling::Spread(s) => Some(s.first),
        Sampling::Even { .. } | Sampling::Adaptive(_) => None,
    };
    let meta = spec
        .map(|s| piece_meta(loaded, &s, spread))
        .transpose()
        .map_err(|e| failure(&e))?;
    if let (true, Some(m)) = (piece.resume, &meta) {
        match existing_piece(&out.path, m) {
            Existing::Done => {
                eprintln!(
                    "skipped {}: it already holds this piece of scene {}",
                    out.path.display(),
                    m.scene
                );
                if piece.progress.as_deref() == Some("json") {
                    json_line(json!({"event": "skipped", "output": out.path, "scene": m.scene}));
                }
                return Ok(None);
            }
            Existing::Different(why) => eprintln!("re-rendering {}: {why}", out.path.display()),
            Existing::Absent => {}
        }
    }
    Ok(Some((plan, out, meta)))
}

/// `--stats`: build, traversal and SDF statistics.
fn print_stats(loaded: &Loaded, stats: &RenderStats) {
    let b = &loaded.stats;
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
    if loaded.scene.lanes.is_some() {
        eprintln!(
            "shapes: a few spheres and quads, tested together in SIMD lanes (the BVH is not traversed)"
        );
    }
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
    if let Some((env, map)) = loaded
        .scene
        .environment()
        .and_then(|(_, e)| e.map().map(|m| (e, m)))
    {
        let px = (map.width as usize * map.height as usize) as f64;
        eprintln!(
            "environment: {}×{} map read in {:.1} ms, {:.1} MiB ({:.1} B/pixel); sampling tables built in {:.1} ms, {:.1} MiB ({:.2} B/pixel)",
            map.width,
            map.height,
            b.env_read_time.as_secs_f64() * 1e3,
            size_of_val(map.texels.as_slice()) as f64 / 1048576.0,
            size_of_val(map.texels.as_slice()) as f64 / px,
            b.env_table_time.as_secs_f64() * 1e3,
            env.table_bytes() as f64 / 1048576.0,
            env.table_bytes() as f64 / px
        );
    }
    for (i, m) in geo.meshes.iter().enumerate().take(8) {
        if let Some(s) = m.blas().map(|b| b.stats()) {
            eprintln!(
                "  mesh {i}: {} triangles, {} {}-wide nodes, {} leaves, depth {}, SAH cost {:.2}",
                m.triangle_count(),
                s.nodes,
                crate::accel::wide::WIDTH,
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

/// The output name of the frame drawn: `{frame}` fields filled in; a name
/// without one is refused when `--frames` writes several, which would all
/// land on it. `--frames` past the scene's last frame is refused before
/// the first is drawn.
fn frame_name(out: PathBuf, loaded: &Loaded, frames: Option<(i32, i32)>) -> Result<PathBuf, String> {
    let Some(a) = &loaded.desc.animation else {
        return Ok(out);
    };
    let name = out.to_string_lossy();
    if let Some((first, last)) = frames {
        let (lo, hi) = a.frames;
        if first < lo || last > hi {
            return Err(format!(
                "--frames {first}..{last} reaches outside the scene's frames {lo}..={hi}"
            ));
        }
        if first < last && !crate::farm::frames::has_field(&name) {
            return Err(format!(
                "--frames {first}..{last} writes {} images, and the output name `{name}` has no `{{frame}}`: each would overwrite the last",
                i64::from(last) - i64::from(first) + 1
            ));
        }
    }
    Ok(PathBuf::from(crate::farm::frames::fill(&name, a.current())))
}
