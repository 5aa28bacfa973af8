//! The light tree end to end: it must converge to the same image as picking
//! by power (it only changes which light each shadow ray goes to), region by
//! region, and at equal samples it must be closer to that image where the
//! scene has many lights.

use crate::common;

use ronray::math::Rgb;

/// Sixteen small lamps over a floor, half of them facing up (away from it),
/// plus a sphere: most lamps are far from any given floor point. The camera
/// looks down from below the lamps and sees only the floor and the sphere,
/// so the pixel jitter adds little noise and the light choice most of it.
fn scene(selection: &str, spp: u32, seed: u64) -> String {
    let mut lamps = String::new();
    for i in 0..4 {
        for j in 0..4 {
            let (x, z) = (-6.0 + 4.0 * i as f32, -10.0 + 4.0 * j as f32);
            // Facing down (half_u × half_v = −y) or, for odd cells, up.
            let v = if (i + j) % 2 == 0 {
                "(0, 0, 0.3)"
            } else {
                "(0, 0, -0.3)"
            };
            lamps.push_str(&format!(
                "Rect(center: ({x}, 2, {z}), half_u: (0.3, 0, 0), half_v: {v}, radiance: ({}, 20, {})),\n",
                10 + 5 * i,
                10 + 5 * j
            ));
        }
    }
    format!(
        r#"Scene(
    camera: (eye: (0, 1.8, 2), target: (0, 0, -2), fov_y_degrees: 40),
    film: (width: 32, height: 24, spp: {spp}, sampler: Independent, seed: {seed}),
    integrator: Path(max_depth: 3, light_selection: {selection}),
    materials: {{ "floor": Lambert(albedo: (0.6, 0.6, 0.6)) }},
    lights: [{lamps}],
    objects: [
        Rect(center: (0, 0, -4), half_u: (40, 0, 0), half_v: (0, 0, -40), material: "floor"),
        Sphere(center: (0, 0.5, -3), radius: 0.5, material: "floor"),
    ],
)"#
    )
}

fn render(selection: &str, spp: u32, seed: u64) -> Vec<Rgb> {
    common::render_loaded(&common::load_text(&scene(selection, spp, seed))).pixels
}

/// Mean of each 4×4 block of regions (8×6 pixels each) of a 32×24 image.
fn regions(px: &[Rgb]) -> Vec<f64> {
    let mut out = vec![0.0f64; 16];
    for (k, p) in px.iter().enumerate() {
        let (x, y) = (k % 32, k / 32);
        out[(y / 6) * 4 + x / 8] += (p.x + p.y + p.z) as f64 / (3.0 * 48.0);
    }
    out
}

fn rmse(a: &[Rgb], b: &[Rgb]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| ((*p - *q).length_squared() / 3.0) as f64)
        .sum();
    (s / a.len() as f64).sqrt()
}

#[test]
fn the_tree_converges_to_the_power_image_with_less_noise() {
    // One seed for both: the pixel jitter (the far floor's edge against the
    // black sky) is then the same, and only the light choice differs.
    let power_ref = render("Power", 4096, 1);
    let tree_ref = render("Tree", 4096, 1);
    let (rp, rt) = (regions(&power_ref), regions(&tree_ref));
    let worst = rp
        .iter()
        .zip(&rt)
        .map(|(p, t)| (p - t).abs() / p.max(1e-3))
        .fold(0.0, f64::max);
    common::report(&format!(
        "light tree: worst region against power at 4096 spp {:.2}%",
        100.0 * worst
    ));
    for (k, (p, t)) in rp.iter().zip(&rt).enumerate() {
        // Both are 4096-spp estimates of one image: their regions agree to
        // the light choice's noise: 1.53% at most here; 0.27% at 65536 spp,
        // where no region differs beyond noise.
        assert!(
            (p - t).abs() <= 0.04 * p.max(1e-3),
            "region {k}: power {p:.5}, tree {t:.5}"
        );
    }
    assert!(rp.iter().sum::<f64>() > 0.1, "the floor is lit");
    // At 32 spp the tree lands nearer the reference than power does.
    let err_power = rmse(&render("Power", 32, 3), &power_ref);
    let err_tree = rmse(&render("Tree", 32, 3), &power_ref);
    common::report(&format!(
        "light tree: RMSE at 32 spp {err_tree:.5}, by power {err_power:.5}"
    ));
    assert!(
        err_tree < 0.7 * err_power,
        "RMSE at 32 spp: tree {err_tree:.5}, power {err_power:.5}"
    );
}
