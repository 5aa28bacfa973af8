//! Writes the benchmark's large mesh: a closed, watertight cube-sphere of
//! 6·N²·2 triangles (N = 289: 1,002,252 triangles), each vertex pushed
//! radially by a sum of 48 sine waves in random directions (amplitude ~1/f),
//! so the surface is bumpy at many scales. Deterministic for a seed.
//!
//! ```sh
//! cargo run --release --example gen_big_mesh -- /tmp/big.obj [N] [SEED]
//! ```

use ronray::math::Pcg32;
use std::collections::HashMap;
use std::io::{BufWriter, Write};

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let out = args.get(1).map_or("big.obj", String::as_str);
    let n: i64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(289);
    let seed: u64 = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(1234);

    // Cube surface lattice points 0..=n per axis, shared along seams.
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut lattice: Vec<[i64; 3]> = Vec::new();
    let mut id = |p: [i64; 3]| {
        *index.entry(p).or_insert_with(|| {
            lattice.push(p);
            lattice.len() as u32 - 1
        })
    };
    let mut tris: Vec<[u32; 3]> = Vec::new();
    for axis in 0..3 {
        for high in [true, false] {
            // (u, v) axes chosen so u × v points out of the cube.
            let (mut u, mut v) = [(1, 2), (2, 0), (0, 1)][axis];
            if !high {
                std::mem::swap(&mut u, &mut v);
            }
            let point = |a: i64, b: i64| {
                let mut p = [0; 3];
                p[axis] = if high { n } else { 0 };
                p[u] = a;
                p[v] = b;
                p
            };
            for i in 0..n {
                for j in 0..n {
                    let v00 = id(point(i, j));
                    let v10 = id(point(i + 1, j));
                    let v01 = id(point(i, j + 1));
                    let v11 = id(point(i + 1, j + 1));
                    tris.push([v00, v10, v11]);
                    tris.push([v00, v11, v01]);
                }
            }
        }
    }

    // Radial displacement: sum of sines along random directions.
    let mut rng = Pcg32::new(seed, 7);
    let waves: Vec<([f64; 3], f64, f64)> = (0..48)
        .map(|k| {
            let z = 2.0 * rng.next_f32() as f64 - 1.0;
            let phi = std::f64::consts::TAU * rng.next_f32() as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let dir = [r * phi.cos(), r * phi.sin(), z];
            let freq = 2.0 * 1.12f64.powi(k);
            (dir, freq, std::f64::consts::TAU * rng.next_f32() as f64)
        })
        .collect();
    let mut w = BufWriter::new(std::fs::File::create(out)?);
    writeln!(w, "# noise-displaced cube-sphere, N={n}, seed={seed}")?;
    writeln!(
        w,
        "# {} vertices, {} triangles, by examples/gen_big_mesh.rs",
        lattice.len(),
        tris.len()
    )?;
    for p in &lattice {
        let c = p.map(|x| x as f64 * 2.0 / n as f64 - 1.0);
        let len = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt();
        let d = c.map(|x| x / len);
        let r = 1.0
            + waves
                .iter()
                .map(|(dir, f, phase)| {
                    0.08 * (2.0 / f) * (f * (d[0] * dir[0] + d[1] * dir[1] + d[2] * dir[2]) + phase).sin()
                })
                .sum::<f64>();
        writeln!(w, "v {:.6} {:.6} {:.6}", d[0] * r, d[1] * r, d[2] * r)?;
    }
    for t in &tris {
        writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1)?;
    }
    w.flush()?;
    eprintln!(
        "wrote {out}: {} vertices, {} triangles",
        lattice.len(),
        tris.len()
    );
    Ok(())
}
