//! Light-traced caustics on generated scenes, not the few written for them
//! (`tests/caustics.rs`): open floors and closed rooms; glass and mirror
//! balls, tilted rectangles, bunnies and rotated rounded boxes (a distance
//! field); rectangle lights, sphere lights, a rotated and scaled sky map, a
//! constant sky and point lights, one or two at a time. The light tracer
//! must leave each scene's expected image as the path tracer alone draws it,
//! region by region.
//!
//! The path tracer alone cannot draw a point light's caustics (no BSDF
//! sample reaches a point), so a scene with a point light is compared with
//! its twin lit by a sphere of radius 0.003 and radiance I/πr² at the same
//! place (the same intensity toward every direction), whose caustics both
//! estimators draw. The pixels that see that sphere, directly or in a
//! mirror (the point is invisible), are masked out: those where the two
//! images differ by more than half their sum plus 0.3, one or two per
//! scene.
//!
//! The comparison is statistical: eight seeds of each render (24 × 24
//! pixels; the truth at 256 samples, the split at 64) give each region's
//! mean and standard error — the whole image, its quadrants and its sixteen
//! 6 × 6 blocks — and a region fails when the two means differ by six
//! standard errors and by 1% of the whole image's mean (a dark block's
//! rare bright caustic paths make its error estimate unreliable, so a
//! difference too small to see there is not a failure). What it catches,
//! checked: the light paths of the rectangle and sphere lights, of the sky
//! or of point lights left out (each fails a scene by 8–12 standard
//! errors), or every light path's flux 30% low; not 10% low (these scenes'
//! caustics are a few percent of any region, and the path tracer's own
//! noise on them is the limit).

use crate::common;

use common::{blocks, load_text, report};
use ronray::frame::{Plan, RenderOptions, render_whole};
use ronray::math::Rgb;

/// A small linear congruential generator: the scenes are the same on every
/// machine and every run.
struct Lcg(u64);

impl Lcg {
    fn new(k: u64) -> Self {
        let mut g = Lcg(k.wrapping_mul(7919).wrapping_add(17));
        for _ in 0..4 {
            g.unit();
        }
        g
    }
    fn unit(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 40) as f32) / (1u64 << 24) as f32
    }
    fn range(&mut self, a: f32, b: f32) -> f32 {
        a + (b - a) * self.unit()
    }
    fn pick(&mut self, n: usize) -> usize {
        ((self.unit() * n as f32) as usize).min(n - 1)
    }
}

/// One generated scene: its lights and objects (RON), and a point light
/// (position, intensity) added at render time as a point or as its tiny
/// sphere twin.
struct Family {
    closed: bool,
    lights: Vec<String>,
    objects: Vec<String>,
    point: Option<(String, f32)>,
    eye: (f32, f32),
    ior: f32,
    what: String,
}

/// Scene `k` of the family; with `point`, its first light is a point light.
fn family(k: u64, point: bool) -> Family {
    let mut g = Lcg::new(k);
    let closed = g.unit() < 0.5;
    let mut objects = vec![
        r#"Rect(center: (0, 0, 0), half_u: (4, 0, 0), half_v: (0, 0, -4), material: "floor")"#.to_string(),
    ];
    if closed {
        objects.extend([
            r#"Rect(center: (0, 3, 0), half_u: (4, 0, 0), half_v: (0, 0, 4), material: "floor")"#.to_string(),
            r#"Rect(center: (0, 1.5, -4), half_u: (4, 0, 0), half_v: (0, 1.5, 0), material: "red")"#
                .to_string(),
            r#"Rect(center: (-4, 1.5, 0), half_u: (0, 1.5, 0), half_v: (0, 0, 4), material: "floor")"#
                .to_string(),
        ]);
    }
    let mut what = format!("scene {k}{}:", if closed { " closed" } else { " open" });
    for _ in 0..1 + g.pick(3) {
        let (x, z, r) = (g.range(-1.5, 1.5), g.range(-1.5, 1.0), g.range(0.2, 0.7));
        let mat = if g.unit() < 0.6 { "glass" } else { "mirror" };
        let (kind, object) = match g.pick(6) {
            0..=2 => (
                "ball",
                format!(r#"Sphere(center: ({x}, {r}, {z}), radius: {r}, material: "{mat}")"#),
            ),
            3 => (
                "rect",
                format!(
                    r#"Rect(center: ({x}, {}, {z}), half_u: ({r}, 0, 0), half_v: (0, {}, {}), material: "{mat}")"#,
                    g.range(0.5, 1.5),
                    g.range(-0.5, 0.5),
                    g.range(0.2, 0.6)
                ),
            ),
            4 => (
                "bunny",
                format!(
                    r#"Mesh(file: "assets/bunny.obj", material: "{mat}", transform: [Scale(({s}, {s}, {s})), Translate(({x}, 0, {z}))])"#,
                    s = g.range(0.04, 0.1)
                ),
            ),
            _ => (
                "rounded box",
                format!(
                    r#"Sdf(shape: RoundBox(half_extents: ({r}, {}, {r}), radius: {}), material: "{mat}", transform: [Rotate(axis: (1, 1, 0), degrees: {}), Translate(({x}, {}, {z}))])"#,
                    0.7 * r,
                    0.2 * r,
                    g.range(0.0, 90.0),
                    r + 0.3
                ),
            ),
        };
        what += &format!(" {mat} {kind},");
        objects.push(object);
    }
    let mut lights = Vec::new();
    let mut point_light = None;
    let mut sky = false;
    for n in 0..1 + g.pick(2) {
        let kind = if point && n == 0 { 4 } else { g.pick(4) };
        let (x, y, z) = (g.range(-2.0, 2.0), g.range(1.5, 2.9), g.range(-2.0, 1.0));
        let e = g.range(5.0, 30.0);
        match kind {
            0 => {
                what += " rect light,";
                lights.push(format!(
                    "Rect(center: ({x}, {y}, {z}), half_u: ({}, 0, 0), half_v: (0, {}, {}), radiance: ({e}, {e}, {e}))",
                    g.range(0.1, 0.5),
                    g.range(-0.2, 0.2),
                    g.range(0.1, 0.5)
                ))
            }
            1 => {
                what += " sphere light,";
                objects.push(format!(
                    r#"Sphere(center: ({x}, {y}, {z}), radius: {}, material: "lamp", emission: (radiance: ({e}, {}, {})))"#,
                    g.range(0.05, 0.25),
                    0.7 * e,
                    0.4 * e
                ))
            }
            2 | 3 if sky => {}
            2 => {
                sky = true;
                what += " sky map,";
                lights.push(format!(
                    r#"Environment(map: "assets/sky_sun.exr", strength: {}, rotation_degrees: {})"#,
                    g.range(0.3, 1.5),
                    g.range(0.0, 360.0)
                ))
            }
            3 => {
                sky = true;
                what += " constant sky,";
                lights.push("Environment(radiance: (0.3, 0.35, 0.4))".to_string())
            }
            _ => {
                what += " point light,";
                point_light = Some((format!("({x}, {y}, {z})"), g.range(1.0, 6.0)));
            }
        }
    }
    Family {
        closed,
        lights,
        objects,
        point: point_light,
        eye: (g.range(-2.0, 2.0), g.range(1.0, 2.5)),
        ior: g.range(1.3, 1.9),
        what,
    }
}

impl Family {
    /// The scene's text with `film` and `integrator` settings; a point light
    /// as itself or (`tiny`) as its sphere twin.
    fn text(&self, film: &str, integrator: &str, tiny: bool) -> String {
        let (mut lights, mut objects) = (self.lights.clone(), self.objects.clone());
        if let Some((at, i)) = &self.point {
            if tiny {
                let r = 0.003f32;
                let l = i / (std::f32::consts::PI * r * r);
                objects.push(format!(
                    r#"Sphere(center: {at}, radius: {r}, material: "lamp", emission: (radiance: ({l}, {l}, {l})))"#
                ));
            } else {
                lights.push(format!("Point(position: {at}, intensity: ({i}, {i}, {i}))"));
            }
        }
        format!(
            r#"Scene(
                camera: (eye: ({}, {}, 5.5), target: (0, 0.5, 0), fov_y_degrees: 40),
                film: ({film}),
                integrator: Path(max_depth: 8, {integrator}),
                materials: {{
                    "floor": Lambert(albedo: (0.6, 0.6, 0.6)),
                    "red": Lambert(albedo: (0.6, 0.2, 0.2)),
                    "glass": Glass(ior: {}),
                    "mirror": Mirror(),
                    "lamp": Lambert(albedo: (0, 0, 0)),
                }},
                lights: [{}],
                objects: [{}],
            )"#,
            self.eye.0,
            self.eye.1,
            self.ior,
            lights.join(", "),
            objects.join(",\n")
        )
    }
}

const W: usize = 24;
const SEEDS: u32 = 8;

/// [`SEEDS`] renders (seeds from `first`) at `spp`; whether the plan
/// light-traces.
fn renders(f: &Family, spp: u32, first: u32, integrator: &str, tiny: bool) -> (Vec<Vec<Rgb>>, bool) {
    let opts = RenderOptions {
        threads: Some(2),
        ..Default::default()
    };
    let mut traced = false;
    let imgs = (first..first + SEEDS)
        .map(|seed| {
            let film = format!("width: {W}, height: {W}, spp: {spp}, seed: {seed}, allocation: Even");
            let l = load_text(&f.text(&film, integrator, tiny));
            traced |= Plan::whole(&l.scene, &l.view).light_trace.is_some();
            let img = render_whole(&l.scene, &l.view, &opts).0.pixels;
            assert!(img.iter().all(|p| p.is_finite()), "{}: non-finite pixels", f.what);
            img
        })
        .collect();
    (imgs, traced)
}

/// Per region (the whole image, its four quadrants, its sixteen blocks):
/// mean and standard error of the mean over the renders, pixels in `mask`
/// left out (as 0).
fn regions(imgs: &[Vec<Rgb>], mask: &[bool]) -> Vec<(f64, f64)> {
    let per: Vec<Vec<f64>> = imgs
        .iter()
        .map(|img| {
            let kept: Vec<Rgb> = img
                .iter()
                .zip(mask)
                .map(|(p, m)| if *m { Rgb::ZERO } else { *p })
                .collect();
            let mut v = blocks(&kept, W, W);
            v.extend(blocks(&kept, W, W / 2));
            v.extend(blocks(&kept, W, W / 4));
            v
        })
        .collect();
    let n = per.len() as f64;
    (0..per[0].len())
        .map(|r| {
            let mean = per.iter().map(|v| v[r]).sum::<f64>() / n;
            let var = per.iter().map(|v| (v[r] - mean).powi(2)).sum::<f64>() / (n - 1.0);
            (mean, (var / n).sqrt())
        })
        .collect()
}

/// Scene `k` (with a point light when `point`): the truth (the path tracer
/// alone, or the tiny sphere twin) against the light-traced split, region by
/// region (module docs). Returns whether the split traced.
fn check(k: u64, point: bool) -> bool {
    let f = family(k, point);
    let tiny = f.point.is_some();
    let (truth, _) = if tiny {
        renders(&f, 256, 10, "", true)
    } else {
        renders(&f, 256, 10, "caustics: PathOnly", false)
    };
    let (split, traced) = renders(&f, 64, 30, "", false);
    // The tiny sphere seen (directly, in a mirror, through glass) is far
    // brighter than anything the point light's image shows there.
    let mean = |v: &[Vec<Rgb>], i: usize| v.iter().map(|p| common::sum(&p[i])).sum::<f64>() / v.len() as f64;
    let mask: Vec<bool> = (0..W * W)
        .map(|i| {
            let (a, b) = (mean(&truth, i), mean(&split, i));
            tiny && (a - b).abs() > 0.5 * (a + b) + 0.3
        })
        .collect();
    let (a, b) = (regions(&truth, &mask), regions(&split, &mask));
    let mut line = format!(
        "{} light-traced {traced}, {} pixels masked:",
        f.what,
        mask.iter().filter(|m| **m).count()
    );
    for (r, (x, y)) in a.iter().zip(&b).enumerate() {
        let se = (x.1 * x.1 + y.1 * y.1).sqrt();
        let z = if se > 0.0 { (y.0 - x.0) / se } else { 0.0 };
        if r < 5 || z.abs() > 3.0 {
            line += &format!(" [{r}: {:.4} vs {:.4}, {z:+.1} se]", x.0, y.0);
        }
        let off = (y.0 - x.0).abs() / a[0].0.max(1e-9);
        assert!(
            z.abs() < 6.0 || off < 0.01,
            "{} (closed {}): region {r} {:.5} light-traced vs {:.5}, {z:.1} standard errors",
            f.what,
            f.closed,
            y.0,
            x.0
        );
    }
    report(&line);
    traced
}

#[test]
fn generated_scenes_keep_the_image_region_by_region() {
    let traced = (0..12).filter(|&k| check(k, false)).count();
    // The generator must reach the light tracer, or the test tests nothing.
    assert!(traced >= 8, "only {traced} of 12 scenes light-traced");
}

#[test]
fn generated_scenes_with_a_point_light_match_their_tiny_sphere_twins() {
    for k in 100..108 {
        assert!(check(k, true), "scene {k} with a point light is not light-traced");
    }
}
