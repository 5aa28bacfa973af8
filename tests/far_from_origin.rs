//! One set-up rendered at 0 to 10,000 units from the origin (issue 44):
//! two spheres resting on a large floor (contact shadows), a plank hovering
//! 0.02 above the floor and a thin gap between the spheres, under a quad
//! light and a point light that grazes the floor at about 7°. Camera,
//! lights and objects move together along `(1, 0.5, 1)`, so no coordinate
//! stays small.
//!
//! The ray offset used to grow like `1e-4·(1 + |p|)`: at 1,000 units, 0.1,
//! more than the gap under a sphere near its contact point, and bright
//! rings lit the contact shadows. Each moved render is compared with a
//! reference made at the origin from independent seeds: its RMSE must stay
//! within 1.25× the unmoved render's, and no pixel may be more than 5σ off,
//! σ the pixel's noise estimated from the reference renders.

use crate::common;

use common::{load_in, report, root};
use glam::DVec3;
use ronray::frame::render_whole;
use ronray::imageio::Image;
use ronray::load::Overrides;

const SIZE: u32 = 64;
const SPP: u32 = 64;
/// Independent reference renders at the origin.
const REFERENCES: u64 = 4;

fn v(p: DVec3) -> String {
    format!("({}, {}, {})", p.x, p.y, p.z)
}

/// The scene's text with everything moved by `b`.
fn scene(b: DVec3) -> String {
    let at = |x: f64, y: f64, z: f64| v(b + DVec3::new(x, y, z));
    format!(
        r#"Scene(
    camera: (eye: {eye}, target: {target}, fov_y_degrees: 35),
    integrator: Path(max_depth: 3),
    materials: {{
        "floor": Lambert(albedo: (0.6, 0.6, 0.6)),
        "red": Lambert(albedo: (0.7, 0.2, 0.2)),
        "blue": Lambert(albedo: (0.2, 0.3, 0.7)),
    }},
    lights: [
        Rect(center: {light}, half_u: (0.8, 0, 0), half_v: (0, 0, 0.8), radiance: (6, 6, 6)),
        Point(position: {point}, intensity: (30, 30, 30)),
    ],
    objects: [
        Rect(center: {floor}, half_u: (30, 0, 0), half_v: (0, 0, -30), material: "floor"),
        Sphere(center: {a}, radius: 0.6, material: "red"),
        Sphere(center: {c}, radius: 0.45, material: "blue"),
        Rect(center: {plank}, half_u: (0.7, 0, 0), half_v: (0, 0, -0.15), material: "floor"),
    ],
)"#,
        eye = at(0.5, 2.2, 4.5),
        target = at(0.0, 0.3, 0.0),
        light = at(0.0, 4.0, 0.0),
        point = at(5.0, 0.6, -1.5),
        floor = at(0.0, 0.0, 0.0),
        a = at(-0.8, 0.6, 0.0),
        // 0.016 from the red sphere at the closest.
        c = at(0.255, 0.45, 0.0),
        plank = at(0.3, 0.02, 1.3),
    )
}

fn render_at(offset: f64, seed: u64) -> Image {
    let b = DVec3::new(1.0, 0.5, 1.0) / 1.5 * offset;
    let o = Overrides {
        spp: Some(SPP),
        size: Some((SIZE, SIZE)),
        seed: Some(seed),
        ..Default::default()
    };
    let l = load_in(&root(), &scene(b), &o);
    let img = render_whole(&l.scene, &l.view, &Default::default()).0;
    assert!(
        img.pixels.iter().all(|p| p.is_finite()),
        "non-finite pixels at {offset}"
    );
    img
}

/// Per pixel and channel: the mean of the reference renders and the noise
/// σ of one render, from their spread pooled over the pixel's 3 × 3
/// neighbourhood (the largest estimate in it, so a pixel on a shadow's
/// edge is not judged by its dark neighbour's noise).
struct Reference {
    mean: Vec<[f64; 3]>,
    sigma: Vec<[f64; 3]>,
}

fn reference() -> Reference {
    let renders: Vec<Image> = (0..REFERENCES).map(|k| render_at(0.0, 100 + k)).collect();
    let n = (SIZE * SIZE) as usize;
    let k = REFERENCES as f64;
    let mut mean = vec![[0.0; 3]; n];
    let mut var = vec![[0.0; 3]; n];
    for i in 0..n {
        for c in 0..3 {
            let xs: Vec<f64> = renders.iter().map(|r| f64::from(r.pixels[i][c])).collect();
            let m = xs.iter().sum::<f64>() / k;
            mean[i][c] = m;
            var[i][c] = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (k - 1.0);
        }
    }
    let s = SIZE as i64;
    let sigma = (0..n)
        .map(|i| {
            let (x, y) = (i as i64 % s, i as i64 / s);
            let mut out = [0.0f64; 3];
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (nx, ny) = (x + dx, y + dy);
                    if (0..s).contains(&nx) && (0..s).contains(&ny) {
                        let j = (ny * s + nx) as usize;
                        for c in 0..3 {
                            out[c] = out[c].max(var[j][c]);
                        }
                    }
                }
            }
            out.map(f64::sqrt)
        })
        .collect();
    Reference { mean, sigma }
}

/// What a moved render does against the reference.
struct Figures {
    rmse: f64,
    worst_abs: f64,
    worst_z: f64,
    beyond_5_sigma: usize,
    off_by_0_1: usize,
}

fn figures(img: &Image, r: &Reference) -> Figures {
    let mut f = Figures {
        rmse: 0.0,
        worst_abs: 0.0,
        worst_z: 0.0,
        beyond_5_sigma: 0,
        off_by_0_1: 0,
    };
    let mut se = 0.0;
    for (i, p) in img.pixels.iter().enumerate() {
        let mut z_max = 0.0f64;
        let mut abs_max = 0.0f64;
        for c in 0..3 {
            let e = f64::from(p[c]) - r.mean[i][c];
            se += e * e;
            // σ of the difference: this render's noise and the reference
            // mean's; a floor for pixels no sample varies in (flat,
            // deterministic regions), far below anything visible.
            let sigma = r.sigma[i][c] * (1.0 + 1.0 / REFERENCES as f64).sqrt() + 2e-3;
            z_max = z_max.max(e.abs() / sigma);
            abs_max = abs_max.max(e.abs());
        }
        f.worst_z = f.worst_z.max(z_max);
        f.worst_abs = f.worst_abs.max(abs_max);
        f.beyond_5_sigma += usize::from(z_max > 5.0);
        f.off_by_0_1 += usize::from(abs_max > 0.1);
    }
    f.rmse = (se / (3 * img.pixels.len()) as f64).sqrt();
    f
}

#[test]
fn contact_shadows_and_thin_gaps_render_the_same_far_from_the_origin() {
    let r = reference();
    let base = figures(&render_at(0.0, 1), &r);
    report(&format!(
        "far_from_origin: offset 0: RMSE {:.5}, worst pixel {:.3} ({:.1}σ), {} beyond 5σ, {} off by > 0.1",
        base.rmse, base.worst_abs, base.worst_z, base.beyond_5_sigma, base.off_by_0_1
    ));
    let mut failures = Vec::new();
    for offset in [10.0, 100.0, 1000.0, 10_000.0] {
        let f = figures(&render_at(offset, 1), &r);
        let ratio = f.rmse / base.rmse;
        report(&format!(
            "far_from_origin: offset {offset}: RMSE {:.5} ({ratio:.3}× unmoved), worst pixel {:.3} ({:.1}σ), {} beyond 5σ, {} off by > 0.1",
            f.rmse, f.worst_abs, f.worst_z, f.beyond_5_sigma, f.off_by_0_1
        ));
        // 10,000 is reported, not judged: see the issue's closing note.
        if offset <= 1000.0 && (ratio > 1.25 || f.beyond_5_sigma > 0) {
            failures.push(format!(
                "offset {offset}: RMSE {:.5} is {ratio:.3}× the unmoved {:.5} (≤ 1.25 expected), {} pixels beyond 5σ (worst {:.1}σ, {:.3} off)",
                f.rmse, base.rmse, f.beyond_5_sigma, f.worst_z, f.worst_abs
            ));
        }
    }
    assert!(
        base.beyond_5_sigma == 0,
        "the unmoved render itself has pixels beyond 5σ: the σ estimate is too tight"
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
