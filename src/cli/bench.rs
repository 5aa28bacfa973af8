//! `ronray bench OBJ`: BVH build time and closest-hit throughput on one
//! mesh, with the ray sets of `perf-anchors.md` so the numbers sit beside
//! Embree's:
//! - **primary**: a 512×512 pinhole camera, 40° vertical fov, looking at the
//!   bounding-box centre from the distance where the bounding sphere just
//!   fills the view;
//! - **incoherent**: 2^20 rays, origins uniform in the bounding box,
//!   directions uniform on the sphere.
//!
//! Always closest hit, t in (0, ∞), through the mesh's own BVH (the path
//! every mesh ray of a render takes). Each figure is measured on 1 thread
//! and on `threads` (default: all cores); the machine load is printed too,
//! since shared machines make absolute numbers noisy. Beside each rate, the
//! rate per CPU-second of this process (Linux `/proc/self/stat`) says what
//! the code does when it gets the cores it asked for.

use crate::camera::Camera;
use crate::geometry::obj::load_obj_data_in;
use crate::geometry::ray_sets::incoherent_rays;
use crate::math::Ray;
use glam::{Vec2, Vec3A};
use rayon::prelude::*;
use std::path::Path;
use std::time::Instant;

/// `println!` that ignores a closed pipe (`ronray bench … | head`).
macro_rules! out {
    ($($arg:tt)*) => {
        super::print_out(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// Runs the benchmark and prints a table; the error names the file.
pub fn run(path: &Path, threads: Option<usize>, root: Option<&Path>) -> Result<(), String> {
    if let Some(why) = root.and_then(|r| crate::files::outside_root(r, path)) {
        return Err(format!("OBJ file {why}"));
    }
    let n = threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let pool = |t: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(t)
            .build()
            .map_err(|e| format!("cannot start {t} threads: {e}"))
    };
    let (p1, pn) = (pool(1)?, pool(n)?);
    let t0 = Instant::now();
    let raw = load_obj_data_in(path, root)?.mesh;
    out!(
        "{}: {} triangles, parsed in {:.0} ms; load {}; ronray {}",
        path.display(),
        raw.triangle_count(),
        t0.elapsed().as_secs_f64() * 1e3,
        load_average(),
        super::VERSION
    );
    // Build: best of 3 on each pool (the first run also warms the allocator).
    let build = |p: &rayon::ThreadPool| {
        let (mut best, mut best_cpu) = (f64::INFINITY, f64::INFINITY);
        let mut mesh = raw.clone();
        for _ in 0..3 {
            mesh = raw.clone();
            let (t, c) = (Instant::now(), cpu_seconds());
            p.install(|| mesh.prepare());
            best = best.min(t.elapsed().as_secs_f64());
            best_cpu = best_cpu.min(cpu_seconds() - c);
        }
        (mesh, best, best_cpu)
    };
    let (_, build1, cpu1) = build(&p1);
    let (mesh, build_n, cpu_n) = build(&pn);
    let s = mesh.blas().map(|b| b.stats()).unwrap_or_default();
    out!(
        "build: {:.1} ms on 1 thread ({:.0} ms CPU), {:.1} ms on {n} ({:.0} ms CPU); {} {}-wide nodes, depth {}, SAH cost {:.2} (8-wide); {:.1} bytes/triangle (nodes + inline triangles)",
        build1 * 1e3,
        cpu1 * 1e3,
        build_n * 1e3,
        cpu_n * 1e3,
        s.nodes,
        crate::accel::wide::WIDTH,
        s.max_depth,
        s.sah_cost,
        mesh.accel_bytes() as f64 / mesh.triangle_count().max(1) as f64
    );
    let b = mesh.bounds();
    let (c, radius) = (b.centroid(), 0.5 * b.extent().length());
    let fov: f32 = 40.0;
    let eye = c + Vec3A::new(0.0, 0.0, radius / (0.5 * fov.to_radians()).sin());
    let cam = Camera::look_at(eye, c, Vec3A::Y, fov);
    let primary: Vec<Ray> = (0..512 * 512)
        .map(|i| {
            let px = Vec2::new((i % 512) as f32 + 0.5, (i / 512) as f32 + 0.5) / 512.0;
            cam.ray(px, 1.0, Vec2::ZERO)
        })
        .collect();
    let incoherent = incoherent_rays(&mesh, 1 << 20, 2024);
    out!("| rays | hit % | 1 thread Mrays/s | per CPU s | {n} threads Mrays/s | per CPU s |");
    out!("|---|---|---|---|---|---|");
    for (name, rays) in [("primary", &primary), ("incoherent", &incoherent)] {
        let trace = |p: &rayon::ThreadPool| {
            let (t, c) = (Instant::now(), cpu_seconds());
            let hits: usize = p.install(|| {
                rays.par_chunks(4096)
                    .map(|c| {
                        c.iter()
                            .filter(|r| mesh.closest(r, f32::INFINITY).is_some())
                            .count()
                    })
                    .sum()
            });
            let m = rays.len() as f64 / 1e6;
            (
                m / t.elapsed().as_secs_f64(),
                m / (cpu_seconds() - c).max(0.01),
                hits,
            )
        };
        let (r1, c1, hits) = trace(&p1);
        let (rn, cn, _) = trace(&pn);
        out!(
            "| {name} | {:.1} | {r1:.2} | {c1:.2} | {rn:.2} | {cn:.2} |",
            100.0 * hits as f64 / rays.len() as f64
        );
    }
    out!("load after: {}", load_average());
    Ok(())
}

/// User + system CPU time of this process (all threads), 10 ms ticks; NaN
/// where `/proc` is missing.
pub(super) fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let f: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
    f.get(11..13).map_or(f64::NAN, |t| {
        t.iter().map(|x| x.parse::<f64>().unwrap_or(0.0)).sum::<f64>() / 100.0
    })
}

/// `/proc/loadavg`'s first three fields, or "unknown".
pub(super) fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|| "unknown".into())
}
