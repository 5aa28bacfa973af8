//! Throughput measurement, ignored by default.

use super::*;

/// Not a check: build time and single-thread closest-hit rate on a bumpy
/// ~1M-triangle sphere with incoherent rays. Run with
/// `cargo test --lib bvh_throughput -- --ignored --nocapture`.
#[test]
#[ignore]
fn bvh_throughput() {
    use std::time::Instant;
    // The machine is shared: CPU time of this process (Linux, 100 Hz ticks)
    // next to wall time.
    let cpu = || -> f64 {
        let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
        let f: Vec<&str> = stat.rsplit(')').next().unwrap_or("").split_whitespace().collect();
        f.get(11..13).map_or(f64::NAN, |t| {
            t.iter().map(|x| x.parse::<f64>().unwrap_or(0.0)).sum::<f64>() / 100.0
        })
    };
    let n = 708;
    let vertex = |i: usize, j: usize| {
        let (theta, phi) = (
            std::f32::consts::PI * i as f32 / n as f32,
            std::f32::consts::TAU * j as f32 / n as f32,
        );
        let r =
            1.0 + 0.05 * (7.0 * theta).sin() * (5.0 * phi).cos() + 0.01 * (41.0 * theta + 37.0 * phi).sin();
        r * Vec3A::new(theta.sin() * phi.cos(), theta.sin() * phi.sin(), theta.cos())
    };
    let mut tris = Vec::with_capacity(2 * n * n);
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            );
            tris.extend([Tri([a, b, c]), Tri([a, c, d])]);
        }
    }
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let (start, cpu0) = (Instant::now(), cpu());
    let bvh = Bvh::build(&bounds);
    let (build_s, build_cpu) = (start.elapsed().as_secs_f64(), cpu() - cpu0);
    let mut rng = Pcg32::new(11, 11);
    let rays: Vec<Ray> = (0..1_000_000)
        .map(|_| {
            let o = 0.8 * uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32())) * rng.next_f32();
            Ray::new(o, uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32())))
        })
        .collect();
    let (start, cpu0) = (Instant::now(), cpu());
    let hits = rays
        .iter()
        .filter(|r| {
            bvh.intersect(r, f32::INFINITY, |i, r, t| tris[i as usize].hit(r, t))
                .is_some()
        })
        .count();
    let (trace_s, trace_cpu) = (start.elapsed().as_secs_f64(), cpu() - cpu0);
    let mut tests = 0usize;
    for r in &rays[..100_000] {
        bvh.intersect(r, f32::INFINITY, |i, r, t| {
            tests += 1;
            tris[i as usize].hit(r, t)
        });
    }
    eprintln!("{:.1} primitive tests per closest-hit ray", tests as f64 / 1e5);
    let start = Instant::now();
    let occluded = rays
        .iter()
        .filter(|r| bvh.occluded(r, 0.5, |i, r, t| tris[i as usize].hit(r, t).is_some()))
        .count();
    let shadow_s = start.elapsed().as_secs_f64();
    eprintln!(
        "{} tris: build {build_s:.3} s wall, {build_cpu:.2} s CPU ({} threads); closest {:.2} Mrays/s wall, {:.2} per CPU s ({hits} hits); occluded {:.2} Mrays/s ({occluded}); {:?}",
        tris.len(),
        rayon::current_num_threads(),
        rays.len() as f64 / trace_s / 1e6,
        rays.len() as f64 / trace_cpu / 1e6,
        rays.len() as f64 / shadow_s / 1e6,
        bvh.stats()
    );
}
