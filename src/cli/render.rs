//! `ronray render`: load, render the whole frame or a piece of it, write
//! atomically, summarise.
use super::{RenderSettings, USAGE, print_load_error, print_warnings};
use crate::farm::split::{parse_crop, parse_pixels, parse_samples, parse_tile};
use crate::farm::{Existing, PieceSpec, Region, TileIndex, existing_piece, piece_meta, write_piece};
use crate::imageio::PixelRect;
use crate::load::{Loaded, load_with};
use crate::render::{RenderOptions, RenderStats, TileDone, render_image, render_sums};
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
    let Limits { root, max_memory } = *limits;
    if layer_args.denoise && !crate::denoise::AVAILABLE {
        eprintln!(
            "error: --denoise: {}; {}; nothing was written",
            crate::denoise::NOT_BUILT,
            crate::denoise::HOW_TO_ENABLE
        );
        return USAGE.into();
    }
    let json = piece.progress.as_deref() == Some("json");
    let overrides = crate::load::Overrides {
        root: root.map(Path::to_path_buf),
        ..settings.overrides()
    };
    let loaded = match load_with(path, &overrides) {
        Ok(l) => l,
        Err(e) => {
            print_load_error(&e, "; nothing was written");
            return ExitCode::FAILURE;
        }
    };
    // Warnings are printed, not fatal: the scene renders as written.
    print_warnings(&loaded.warnings);
    let f = loaded.view.film;
    let env = |k: &str| std::env::var(k).ok();
    let spec = if piece.is_piece() {
        match crate::farm::resolve(piece.region(), piece.samples, (f.width, f.height, f.spp), &env) {
            Ok(s) => Some(s),
            Err(e) => {
                eprintln!("error: {e}; nothing was written");
                return USAGE.into();
            }
        }
    } else {
        if piece.resume {
            eprintln!(
                "error: --resume skips pieces already written; give --crop, --pixels, --tile or --samples"
            );
            return USAGE.into();
        }
        None
    };
    let mut out = loaded.view.output_path(path, output);
    if let Some((i, _)) = spec.and_then(|s| s.tile) {
        out = PathBuf::from(out.to_string_lossy().replace("{tile}", &i.to_string()));
    }
    let ext = out
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    if spec.is_some() && ext != "exr" {
        eprintln!(
            "error: a piece of a frame is written as EXR, and {} is not .exr: PNG pieces are 8-bit and cannot be merged exactly (assemble the EXR pieces into a PNG instead); nothing was written",
            out.display()
        );
        return USAGE.into();
    }
    if !crate::imageio::WRITTEN_EXTENSIONS.contains(&ext.as_str()) {
        eprintln!(
            "error: output {} must end in .png, .exr, .pfm or .hdr; nothing was written",
            out.display()
        );
        return ExitCode::FAILURE;
    }
    if let Some(input) = loaded.input_at(&out) {
        eprintln!(
            "error: output {} is {}, which the scene reads; nothing was written",
            out.display(),
            input.display()
        );
        return ExitCode::FAILURE;
    }
    let denoise = layer_args.denoise || f.denoise;
    if spec.is_some() && (denoise || !f.aovs.is_empty()) {
        eprintln!(
            "error: AOV layers and denoising need the whole frame (pieces carry only the beauty pass's sums); render without --crop, --pixels, --tile and --samples; nothing was written"
        );
        return USAGE.into();
    }
    if !f.aovs.is_empty() && ext != "exr" {
        eprintln!(
            "error: `film.aovs` adds layers to EXR files, and {} is not .exr; pass `-o NAME.exr` or remove `aovs`; nothing was written",
            out.display()
        );
        return USAGE.into();
    }
    let spec = spec.unwrap_or(PieceSpec {
        rect: PixelRect::full(f.width, f.height),
        samples: (0, f.spp),
        tile: None,
    });
    let is_piece = piece.is_piece();
    // Refused before anything is allocated: a piece keeps exact sums per
    // pixel, like a progressive render.
    let (rw, rh) = (spec.rect.x1 - spec.rect.x0, spec.rect.y1 - spec.rect.y0);
    if let Err(e) = crate::memory::check_film(rw, rh, is_piece, max_memory) {
        eprintln!("error: {e}; nothing was written");
        return ExitCode::FAILURE;
    }
    if is_piece && loaded.view.film.adaptive.is_some() {
        eprintln!(
            "note: film.noise_threshold is ignored for pieces: their exact sums add up across machines only when every pixel takes every sample"
        );
    }
    let meta = match is_piece.then(|| piece_meta(&loaded, &spec)).transpose() {
        Ok(m) => m,
        Err(e) => {
            eprintln!("error: {e}; nothing was written");
            return ExitCode::FAILURE;
        }
    };
    if let (true, Some(m)) = (piece.resume, &meta) {
        match existing_piece(&out, m) {
            Existing::Done => {
                eprintln!(
                    "skipped {}: it already holds this piece of scene {}",
                    out.display(),
                    m.scene
                );
                if json {
                    json_line(json!({"event": "skipped", "output": out, "scene": m.scene}));
                }
                return ExitCode::SUCCESS;
            }
            Existing::Different(why) => eprintln!("re-rendering {}: {why}", out.display()),
            Existing::Absent => {}
        }
    }
    let opts = RenderOptions {
        threads: settings.threads,
        progress: !json && piece.progress.as_deref() != Some("none") && std::io::stderr().is_terminal(),
        sample_range: Some((spec.samples.0, spec.samples.1 - spec.samples.0)),
    };
    if json {
        json_line(json!({
            "event": "start",
            "output": out,
            "scene": meta.as_ref().map(|m| m.scene.clone()),
            "pixels": [spec.rect.x0, spec.rect.y0, spec.rect.x1, spec.rect.y1],
            "samples": [spec.samples.0, spec.samples.1],
            "tile": spec.tile.map(|(i, n)| format!("{i}/{n}")),
        }));
    }
    let report = |t: &TileDone| {
        if json {
            json_line(json!({
                "event": "tile",
                "done": t.done,
                "total": t.total,
                "pixels": [t.rect.x0, t.rect.y0, t.rect.x1, t.rect.y1],
                "elapsed_s": t.elapsed.as_secs_f64(),
            }));
        }
    };
    let cancel = AtomicBool::new(false);
    let mut extra = String::new();
    let (written, stats) = match &meta {
        Some(m) => {
            let (sums, stats) = render_sums(&loaded.scene, &loaded.view, &opts, spec.rect, &cancel, &report);
            (write_piece(&out, m, &sums).map_err(|e| e.to_string()), stats)
        }
        None => {
            let (image, stats) = render_image(&loaded.scene, &loaded.view, &opts, &cancel, &report);
            let written = super::layers::write_frame(
                &loaded,
                image,
                &out,
                opts.threads,
                denoise,
                layer_args.keep_noisy,
            );
            (written.map(|n| extra = n), stats)
        }
    };
    if let Err(e) = written {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    let what = if is_piece {
        format!(
            "piece: pixels {}, samples {}..{} of a {}×{}, {} spp frame",
            spec.rect, spec.samples.0, spec.samples.1, f.width, f.height, f.spp
        )
    } else if loaded.view.film.adaptive.is_some() {
        let pixels = (u64::from(f.width) * u64::from(f.height)).max(1);
        format!(
            "{}×{}, adaptive: {:.1} spp on average, at most {}",
            f.width,
            f.height,
            stats.samples as f64 / pixels as f64,
            f.spp
        )
    } else if crate::render::spread_plan(&loaded.view, &opts).is_some() {
        let pixels = (u64::from(f.width) * u64::from(f.height)).max(1);
        format!(
            "{}×{}, {} spp spread by noise: {:.1} on average",
            f.width,
            f.height,
            f.spp,
            stats.samples as f64 / pixels as f64
        )
    } else {
        format!("{}×{}, {} spp", f.width, f.height, f.spp)
    };
    eprintln!("wrote {} ({what}) in {}{extra}", out.display(), stats.summary());
    if json {
        json_line(json!({
            "event": "done",
            "output": out,
            "elapsed_s": stats.elapsed.as_secs_f64(),
            "samples": stats.samples,
            "rays": stats.rays,
        }));
    }
    if show_stats {
        print_stats(&loaded, &stats);
    }
    ExitCode::SUCCESS
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
            (map.rgb.len() * 4) as f64 / 1048576.0,
            (map.rgb.len() * 4) as f64 / px,
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
