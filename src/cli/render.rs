//! `ronray render`: load, render, write atomically, summarise.
use super::{RenderSettings, print_load_error, print_warnings};
use crate::imageio::write_image;
use crate::load::load_with;
use crate::render::{RenderOptions, render};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(super) fn cmd_render(
    path: &Path,
    output: Option<PathBuf>,
    settings: &RenderSettings,
    show_stats: bool,
) -> ExitCode {
    let loaded = match load_with(path, &settings.overrides()) {
        Ok(l) => l,
        Err(e) => {
            print_load_error(&e, "; nothing was written");
            return ExitCode::FAILURE;
        }
    };
    // Warnings are printed, not fatal: the scene renders as written.
    print_warnings(&loaded.warnings);
    let out = loaded.view.output_path(path, output);
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
    if let Some(input) = loaded.input_at(&out) {
        eprintln!(
            "error: output {} is {}, which the scene reads; nothing was written",
            out.display(),
            input.display()
        );
        return ExitCode::FAILURE;
    }
    let f = loaded.view.film;
    let opts = RenderOptions {
        threads: settings.threads,
        progress: std::io::stderr().is_terminal(),
        sample_range: None,
    };
    let (image, stats) = render(&loaded.scene, &loaded.view, &opts);
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
                    "  mesh {i}: {} triangles, {} {}-wide nodes, {} leaves, depth {} (binary), SAH cost {:.2}",
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
    ExitCode::SUCCESS
}
