//! A family of open and closed scenes (issue 37): four glossy spheres on a
//! Lambert ground of 4 to 400 units under one to three area lights, with a
//! constant sky of 0 to 1× the lights' irradiance, a sky map with a small
//! bright sun, or inside a room lit through a window. On every one, the
//! default light selection must be no noisier than uniform selection (within
//! 5%) and converge to the same image, block by block.
//!
//! Noise is measured without a reference: the RMS difference of two renders
//! with different seeds, divided by √2.
//!
//! `RONRAY_DUMP_OPEN_SCENES=DIR cargo test --test integration open_scenes::dump` writes
//! every scene as RON (for `ronray render`) and as the renderer-neutral
//! JSON of `../shared/refs` (for Mitsuba 3 through `mitsuba_run.py`), with
//! the sun's sky map, for the side-by-side table in `docs/benchmarks.md`
//! (`tools/open_scenes.sh`).

use crate::common;

use ronray::math::Rgb;
use std::f32::consts::PI;
use std::fmt::Write as _;
use std::path::Path;

/// What lights a generated scene besides its area lights.
#[derive(Clone, Copy, Debug)]
enum Sky {
    /// A constant sky whose irradiance on the ground is this many times the
    /// area lights' at the ground's centre (0: no sky).
    Constant(f32),
    /// The sky map: a gradient sky (0.3× the lights' irradiance) and a 0.5°
    /// sun (2× the lights' irradiance at normal incidence).
    Sun,
    /// A `Directional` sun from the map sun's direction (2× the lights'
    /// irradiance at normal incidence) over a constant sky (0.3×).
    Directional,
}

/// One generated scene.
#[derive(Clone, Copy, Debug)]
struct Spec {
    /// Side of the square ground; 0 for the room.
    ground: f32,
    sky: Sky,
    /// Lights, 1 to 3.
    lights: usize,
    /// What the lights are.
    kind: Kind,
}

/// What a scene's lights are: downward rectangles (most scenes), or at the
/// same places points, emissive spheres or emissive octahedron meshes, so
/// the family also mixes the sky with every other kind of light.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Rect,
    Point,
    Sphere,
    Mesh,
}

impl Spec {
    fn name(&self) -> String {
        let place = if self.ground > 0.0 {
            format!("ground{}", self.ground)
        } else {
            "room".into()
        };
        let sky = match self.sky {
            Sky::Constant(k) => format!("sky{k}"),
            Sky::Sun => "sun".into(),
            Sky::Directional => "directional".into(),
        };
        let kind = match self.kind {
            Kind::Rect => "lights",
            Kind::Point => "points",
            Kind::Sphere => "spheres",
            Kind::Mesh => "meshes",
        };
        format!("{place}_{sky}_{}{kind}", self.lights)
    }
}

/// The family: 24 open scenes under a constant sky (three grounds × four
/// sky levels × one or three lights), 6 under the sun map (three grounds ×
/// one or two lights), 6 rooms lit through a window (three sky levels ×
/// one or three lights), and 6 with two point, sphere or mesh lights under
/// the constant sky or the sun.
fn family() -> Vec<Spec> {
    let mut v = Vec::new();
    for ground in [4.0, 40.0, 400.0] {
        for k in [0.0, 0.05, 0.3, 1.0] {
            for lights in [1, 3] {
                v.push(Spec {
                    ground,
                    sky: Sky::Constant(k),
                    lights,
                    kind: Kind::Rect,
                });
            }
        }
    }
    for ground in [4.0, 40.0, 400.0] {
        for lights in [1, 2] {
            v.push(Spec {
                ground,
                sky: Sky::Sun,
                lights,
                kind: Kind::Rect,
            });
        }
    }
    for k in [0.0, 0.3, 1.0] {
        for lights in [1, 3] {
            v.push(Spec {
                ground: 0.0,
                sky: Sky::Constant(k),
                lights,
                kind: Kind::Rect,
            });
        }
    }
    for ground in [4.0, 40.0, 400.0] {
        for lights in [1, 2] {
            v.push(Spec {
                ground,
                sky: Sky::Directional,
                lights,
                kind: Kind::Rect,
            });
        }
    }
    for kind in [Kind::Point, Kind::Sphere, Kind::Mesh] {
        for sky in [Sky::Constant(0.3), Sky::Sun, Sky::Directional] {
            v.push(Spec {
                ground: 40.0,
                sky,
                lights: 2,
                kind,
            });
        }
    }
    v
}

/// Radius of the emissive spheres and octahedra that stand for lamps.
const BULB: f32 = 0.3;

impl Lamp {
    /// Area of the rectangle.
    fn area(&self) -> f32 {
        4.0 * self.hx * self.hz
    }
    /// A point light's intensity giving about the rectangle's irradiance
    /// below it (W/sr).
    fn intensity(&self) -> [f32; 3] {
        self.l.map(|c| c * self.area())
    }
    /// A bulb's radiance giving about the rectangle's power downward.
    fn bulb_radiance(&self) -> [f32; 3] {
        self.l.map(|c| c * self.area() / (PI * BULB * BULB))
    }
}

/// An octahedron of radius [`BULB`] around `c`, outward counter-clockwise
/// faces, as OBJ text.
fn octahedron(c: [f32; 3]) -> String {
    let r = BULB;
    let v = [
        [c[0] + r, c[1], c[2]],
        [c[0] - r, c[1], c[2]],
        [c[0], c[1] + r, c[2]],
        [c[0], c[1] - r, c[2]],
        [c[0], c[1], c[2] + r],
        [c[0], c[1], c[2] - r],
    ];
    let mut s = String::new();
    for p in v {
        let _ = writeln!(s, "v {} {} {}", p[0], p[1], p[2]);
    }
    // glow_octahedron.obj's faces: the same vertex order.
    s.push_str("f 1 3 5\nf 5 3 2\nf 2 3 6\nf 6 3 1\nf 1 5 4\nf 5 2 4\nf 2 6 4\nf 6 1 4\n");
    s
}

/// A downward rectangle light: centre, half extents along x and z, radiance.
struct Lamp {
    c: [f32; 3],
    hx: f32,
    hz: f32,
    l: [f32; 3],
}

fn lamps(n: usize) -> Vec<Lamp> {
    let all = [
        Lamp {
            c: [0.0, 4.0, 0.0],
            hx: 1.5,
            hz: 0.75,
            l: [10.0, 10.0, 10.0],
        },
        Lamp {
            c: [-3.0, 3.0, -2.0],
            hx: 0.5,
            hz: 0.5,
            l: [20.0, 18.0, 15.0],
        },
        Lamp {
            c: [3.0, 2.5, 1.5],
            hx: 0.4,
            hz: 0.8,
            l: [8.0, 10.0, 16.0],
        },
    ];
    all.into_iter().take(n).collect()
}

/// The lamps' irradiance (luminance) at the origin on an upward surface,
/// each taken as a point: what the sky levels are relative to.
fn lamp_irradiance(lamps: &[Lamp]) -> f32 {
    lamps
        .iter()
        .map(|l| {
            let d2 = l.c[0] * l.c[0] + l.c[1] * l.c[1] + l.c[2] * l.c[2];
            let cos = l.c[1] / d2.sqrt();
            let lum = 0.2126 * l.l[0] + 0.7152 * l.l[1] + 0.0722 * l.l[2];
            lum * 4.0 * l.hx * l.hz * cos * cos / d2
        })
        .sum()
}

/// The sun's direction (toward it), its angular radius and the map's size.
const SUN: [f32; 3] = [0.45, 0.6, 0.66];
const SUN_RADIUS_DEGREES: f32 = 0.25;
const MAP: (u32, u32) = (1440, 720);

/// The sun sky map (linear RGB, rows from the zenith at θ = πj/(H − 1),
/// columns at φ = 2π(i + ½)/W, direction (sin θ sin φ, cos θ, −sin θ cos φ):
/// ronray's and Mitsuba's convention), for lamps of irradiance `e`.
fn sun_map(e: f32) -> Vec<f32> {
    let (w, h) = MAP;
    let s = glam::Vec3::from(SUN).normalize();
    let cos_sun = SUN_RADIUS_DEGREES.to_radians().cos();
    let sun_solid_angle = 2.0 * PI * (1.0 - cos_sun);
    let sun = 2.0 * e / sun_solid_angle;
    // Sky radiance z(1 + 2 cos θ) above the horizon, 0.2 z below: its
    // irradiance on the ground is π z (1 + 4/3) = 0.3 e.
    let z = 0.3 * e / (PI * (1.0 + 4.0 / 3.0));
    let mut rgb = Vec::with_capacity((3 * w * h) as usize);
    for j in 0..h {
        let theta = PI * j as f32 / (h - 1) as f32;
        for i in 0..w {
            let phi = 2.0 * PI * (i as f32 + 0.5) / w as f32;
            let d = glam::Vec3::new(theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos());
            let sky = if d.y > 0.0 { z * (1.0 + 2.0 * d.y) } else { 0.2 * z };
            let l = if d.dot(s) >= cos_sun { sun } else { sky };
            rgb.extend_from_slice(&[0.8 * l, 0.95 * l, 1.25 * l]);
        }
    }
    rgb
}

/// Writes the sun map as `sun.exr` and the lamp octahedra as
/// `lamp<k>.obj` in `dir` (once per folder).
fn write_sun_map(dir: &Path) {
    for (k, l) in lamps(3).iter().enumerate() {
        std::fs::write(dir.join(format!("lamp{k}.obj")), octahedron(l.c)).expect("a lamp mesh");
    }
    let path = dir.join("sun.exr");
    if path.exists() {
        return;
    }
    let e = lamp_irradiance(&lamps(1));
    let img = image::Rgb32FImage::from_raw(MAP.0, MAP.1, sun_map(e)).expect("map size");
    img.save(&path).expect("the sun map is written");
}

/// What the sky adds: ronray's light entry.
fn sky_light(spec: &Spec) -> String {
    let e = lamp_irradiance(&lamps(spec.lights));
    match spec.sky {
        Sky::Constant(k) if k > 0.0 => {
            let l = k * e / PI;
            format!("Environment(radiance: ({l}, {l}, {l})),")
        }
        Sky::Constant(_) => String::new(),
        Sky::Sun => {
            // The map was made for one lamp; scale it to these lamps.
            let strength = e / lamp_irradiance(&lamps(1));
            format!(r#"Environment(map: "sun.exr", strength: {strength}),"#)
        }
        Sky::Directional => {
            let (d, sun, l) = directional(e);
            format!(
                "Directional(direction: {}, irradiance: {}),\nEnvironment(radiance: ({l}, {l}, {l})),",
                v3(d),
                v3(sun)
            )
        }
    }
}

/// A directional sun for lamps of irradiance `e`: the way it travels (from
/// [`SUN`]), its irradiance (2 `e`, the map sun's tint) and the constant
/// sky's radiance beside it (0.3 `e` of irradiance on the ground).
fn directional(e: f32) -> ([f32; 3], [f32; 3], f32) {
    let d = (-glam::Vec3::from(SUN)).normalize().to_array();
    let sun = [0.8, 0.95, 1.25].map(|c| c * 2.0 * e);
    (d, sun, 0.3 * e / PI)
}

/// Rectangles (centre, half_u, half_v, material) the scene holds besides
/// its lamps and spheres: the ground, or the room's floor, ceiling and
/// walls, one of them with a 2 × 1.5 window.
/// A rectangle: centre, half_u, half_v (normal half_u × half_v) and material.
type RectSpec = ([f32; 3], [f32; 3], [f32; 3], &'static str);

fn rects(spec: &Spec) -> Vec<RectSpec> {
    if spec.ground > 0.0 {
        let g = 0.5 * spec.ground;
        return vec![([0.0, 0.0, 0.0], [g, 0.0, 0.0], [0.0, 0.0, -g], "ground")];
    }
    // A 10 × 10 × 5 room; normals (half_u × half_v) face in.
    vec![
        ([0.0, 0.0, 0.0], [5.0, 0.0, 0.0], [0.0, 0.0, -5.0], "ground"),
        ([0.0, 5.0, 0.0], [5.0, 0.0, 0.0], [0.0, 0.0, 5.0], "wall"),
        ([0.0, 2.5, -5.0], [5.0, 0.0, 0.0], [0.0, 2.5, 0.0], "wall"),
        ([0.0, 2.5, 5.0], [-5.0, 0.0, 0.0], [0.0, 2.5, 0.0], "wall"),
        ([5.0, 2.5, 0.0], [0.0, 0.0, 5.0], [0.0, 2.5, 0.0], "wall"),
        // The left wall (x = −5) around a window z ∈ [−1, 1], y ∈ [2, 3.5].
        ([-5.0, 1.0, 0.0], [0.0, 0.0, -5.0], [0.0, 1.0, 0.0], "wall"),
        ([-5.0, 4.25, 0.0], [0.0, 0.0, -5.0], [0.0, 0.75, 0.0], "wall"),
        ([-5.0, 2.75, -3.0], [0.0, 0.0, -2.0], [0.0, 0.75, 0.0], "wall"),
        ([-5.0, 2.75, 3.0], [0.0, 0.0, -2.0], [0.0, 0.75, 0.0], "wall"),
    ]
}

/// Camera eye and target.
fn camera(spec: &Spec) -> ([f32; 3], [f32; 3]) {
    if spec.ground > 0.0 {
        ([0.0, 1.6, 6.0], [0.0, 0.4, 0.0])
    } else {
        ([1.0, 2.2, 4.8], [-1.0, 0.8, 0.0])
    }
}

const SPHERES: [([f32; 3], &str); 4] = [
    ([-1.65, 0.5, 0.0], "gold"),
    ([-0.55, 0.5, 0.0], "plastic"),
    ([0.55, 0.5, 0.0], "copper"),
    ([1.65, 0.5, 0.0], "green"),
];

fn v3(v: [f32; 3]) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
}

/// The scene as ronray RON, `size`², `spp`, `Independent`, `Path(max_depth: 8)`.
fn ron(spec: &Spec, selection: &str, size: u32, spp: u32, seed: u64) -> String {
    let (eye, target) = camera(spec);
    let mut lights = String::new();
    let mut objects = String::new();
    for (k, l) in lamps(spec.lights).iter().enumerate() {
        match spec.kind {
            // Normal half_u × half_v = −y: facing down.
            Kind::Rect => writeln!(
                lights,
                "Rect(center: {}, half_u: ({}, 0, 0), half_v: (0, 0, {}), radiance: {}),",
                v3(l.c),
                l.hx,
                l.hz,
                v3(l.l)
            ),
            Kind::Point => writeln!(
                lights,
                "Point(position: {}, intensity: {}),",
                v3(l.c),
                v3(l.intensity())
            ),
            Kind::Sphere => writeln!(
                objects,
                r#"Sphere(center: {}, radius: {BULB}, material: "black", emission: (radiance: {})),"#,
                v3(l.c),
                v3(l.bulb_radiance())
            ),
            Kind::Mesh => writeln!(
                objects,
                r#"Mesh(file: "lamp{k}.obj", material: "black", emission: (radiance: {})),"#,
                v3(l.bulb_radiance())
            ),
        }
        .expect("writing to a String");
    }
    lights.push_str(&sky_light(spec));
    for (c, u, v, m) in rects(spec) {
        let _ = writeln!(
            objects,
            r#"Rect(center: {}, half_u: {}, half_v: {}, material: "{m}"),"#,
            v3(c),
            v3(u),
            v3(v)
        );
    }
    for (c, m) in SPHERES {
        let _ = writeln!(
            objects,
            r#"Sphere(center: {}, radius: 0.5, material: "{m}"),"#,
            v3(c)
        );
    }
    format!(
        r#"Scene(
    camera: (eye: {}, target: {}, up: (0, 1, 0), fov_y_degrees: 40),
    film: (width: {size}, height: {size}, spp: {spp}, sampler: Independent, seed: {seed}),
    integrator: Path(max_depth: 8, rr_depth: 5, light_selection: {selection}),
    materials: {{
        "ground": Lambert(albedo: (0.5, 0.5, 0.5)),
        "black": Lambert(albedo: (0, 0, 0)),
        "wall": Lambert(albedo: (0.7, 0.7, 0.7)),
        "green": Lambert(albedo: (0.2, 0.6, 0.25)),
        // Mitsuba's GGX α is roughness² here.
        "gold": CookTorrance(distribution: Ggx, roughness: 0.4472136,
            fresnel: Conductor(eta: (0.143036, 0.375307, 1.44205), k: (3.983, 2.38556, 1.60336))),
        "copper": CookTorrance(distribution: Ggx, roughness: 0.5477226,
            fresnel: Conductor(eta: (0.200438, 0.924033, 1.10221), k: (3.91295, 2.45285, 2.14219))),
        "plastic": RoughPlastic(diffuse: (0.1, 0.25, 0.6), roughness: 0.31622777, ior: 1.5),
    }},
    lights: [
{lights}    ],
    objects: [
{objects}    ],
)"#,
        v3(eye),
        v3(target),
    )
}

/// The same scene as the renderer-neutral JSON of `../shared/refs`, for
/// Mitsuba 3 through `mitsuba_run.py`.
fn json(spec: &Spec, size: u32) -> String {
    let (eye, target) = camera(spec);
    let rect = |name: String, c: [f32; 3], u: [f32; 3], v: [f32; 3], mat: &str, emit: Option<[f32; 3]>| {
        let n = glam::Vec3::from(u).cross(glam::Vec3::from(v)).normalize();
        let m = format!(
            "[[{}, {}, {}, {}], [{}, {}, {}, {}], [{}, {}, {}, {}], [0, 0, 0, 1]]",
            u[0], v[0], n.x, c[0], u[1], v[1], n.y, c[1], u[2], v[2], n.z, c[2]
        );
        let emitter = emit.map_or(String::new(), |l| {
            format!(r#", "emitter": {{"radiance": [{}, {}, {}]}}"#, l[0], l[1], l[2])
        });
        format!(
            r#"{{"name": "{name}", "type": "rectangle", "material": "{mat}", "mitsuba_to_world": {m}{emitter}}}"#
        )
    };
    let mut shapes = Vec::new();
    let mut points = Vec::new();
    for (k, l) in lamps(spec.lights).iter().enumerate() {
        let emitter = |c: [f32; 3]| format!(r#""emitter": {{"radiance": [{}, {}, {}]}}"#, c[0], c[1], c[2]);
        match spec.kind {
            Kind::Rect => shapes.push(rect(
                format!("lamp{k}"),
                l.c,
                [l.hx, 0.0, 0.0],
                [0.0, 0.0, l.hz],
                "black",
                Some(l.l),
            )),
            Kind::Point => {
                let i = l.intensity();
                points.push(format!(
                    r#"{{"position": [{}, {}, {}], "intensity": [{}, {}, {}]}}"#,
                    l.c[0], l.c[1], l.c[2], i[0], i[1], i[2]
                ))
            }
            Kind::Sphere => shapes.push(format!(
                r#"{{"name": "lamp{k}", "type": "sphere", "center": [{}, {}, {}], "radius": {BULB}, "material": "black", {}}}"#,
                l.c[0],
                l.c[1],
                l.c[2],
                emitter(l.bulb_radiance())
            )),
            Kind::Mesh => shapes.push(format!(
                r#"{{"name": "lamp{k}", "type": "mesh", "file": "lamp{k}.obj", "material": "black", {}}}"#,
                emitter(l.bulb_radiance())
            )),
        }
    }
    for (k, (c, u, v, m)) in rects(spec).into_iter().enumerate() {
        shapes.push(rect(format!("rect{k}"), c, u, v, m, None));
    }
    for (k, (c, m)) in SPHERES.iter().enumerate() {
        shapes.push(format!(
            r#"{{"name": "sphere{k}", "type": "sphere", "center": [{}, {}, {}], "radius": 0.5, "material": "{m}"}}"#,
            c[0], c[1], c[2]
        ));
    }
    let e = lamp_irradiance(&lamps(spec.lights));
    let env = match spec.sky {
        Sky::Constant(k) if k > 0.0 => {
            let l = k * e / PI;
            format!(r#", "environment": {{"type": "constant", "radiance": [{l}, {l}, {l}]}}"#)
        }
        Sky::Constant(_) => String::new(),
        Sky::Sun => format!(
            r#", "environment": {{"type": "envmap", "filename": "sun.exr", "scale": {}}}"#,
            e / lamp_irradiance(&lamps(1))
        ),
        // `mitsuba_run.py` reads no directional light: tools/open_scenes.py
        // leaves these scenes out of its table.
        Sky::Directional => {
            let (d, sun, l) = directional(e);
            format!(
                r#", "environment": {{"type": "constant", "radiance": [{l}, {l}, {l}]}}, "directional_lights": [{{"direction": [{}, {}, {}], "irradiance": [{}, {}, {}]}}]"#,
                d[0], d[1], d[2], sun[0], sun[1], sun[2]
            )
        }
    };
    let conductor = |alpha: f32, eta: [f32; 3], k: [f32; 3]| {
        format!(
            r#"{{"type": "rough_conductor", "distribution": "ggx", "alpha": {alpha}, "eta": [{}, {}, {}], "k": [{}, {}, {}], "specular_reflectance": [1, 1, 1]}}"#,
            eta[0], eta[1], eta[2], k[0], k[1], k[2]
        )
    };
    format!(
        r#"{{"scene": "{name}",
 "film": {{"width": {size}, "height": {size}}},
 "camera": {{"type": "perspective", "origin": [{}, {}, {}], "target": [{}, {}, {}], "up": [0, 1, 0], "fov_deg": 40, "fov_axis": "y", "near_clip": 0.01}},
 "integrator": {{"type": "path", "max_depth": 8, "rr_depth": 5}},
 "materials": {{
  "black": {{"type": "lambert", "reflectance": [0, 0, 0]}},
  "ground": {{"type": "lambert", "reflectance": [0.5, 0.5, 0.5]}},
  "wall": {{"type": "lambert", "reflectance": [0.7, 0.7, 0.7]}},
  "green": {{"type": "lambert", "reflectance": [0.2, 0.6, 0.25]}},
  "gold": {},
  "copper": {},
  "plastic": {{"type": "rough_plastic", "distribution": "ggx", "alpha": 0.1, "int_ior": 1.5, "ext_ior": 1.0, "diffuse_reflectance": [0.1, 0.25, 0.6], "specular_reflectance": [1, 1, 1], "nonlinear": false}}
 }},
 "shapes": [
  {}
 ],
 "point_lights": [{}]{env}
}}
"#,
        eye[0],
        eye[1],
        eye[2],
        target[0],
        target[1],
        target[2],
        conductor(0.2, [0.143036, 0.375307, 1.44205], [3.983, 2.38556, 1.60336]),
        conductor(0.3, [0.200438, 0.924033, 1.10221], [3.91295, 2.45285, 2.14219]),
        shapes.join(",\n  "),
        points.join(", "),
        name = spec.name(),
    )
}

const SIZE: u32 = 64;
const SPP: u32 = 64;

fn render(dir: &Path, spec: &Spec, selection: &str, seed: u64) -> Vec<Rgb> {
    let text = ron(spec, selection, SIZE, SPP, seed);
    let loaded = common::load_in(dir, &text, &Default::default());
    common::render_loaded(&loaded).pixels
}

/// RMS difference of two renders over pixels and channels, ÷ √2: one
/// render's noise.
fn noise(a: &[Rgb], b: &[Rgb]) -> f64 {
    let s: f64 = a
        .iter()
        .zip(b)
        .map(|(p, q)| {
            let d = *p - *q;
            f64::from(d.x * d.x + d.y * d.y + d.z * d.z)
        })
        .sum();
    (s / (6.0 * a.len() as f64)).sqrt()
}

/// Per-pixel squared noise of the mean of the two renders `a`, `b`
/// (channel sums), from their difference.
fn pixel_var(a: &[Rgb], b: &[Rgb]) -> Vec<f64> {
    a.iter()
        .zip(b)
        .map(|(p, q)| {
            let d = common::sum(p) - common::sum(q);
            d * d / 4.0
        })
        .collect()
}

#[test]
fn default_selection_is_never_noisier_than_uniform_and_agrees_block_by_block() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    write_sun_map(dir.path());
    let mut failures = Vec::new();
    common::report("scene                          uniform    default   ratio");
    for spec in family() {
        let (t1, t2) = (
            render(dir.path(), &spec, "Tree", 1),
            render(dir.path(), &spec, "Tree", 2),
        );
        let (u1, u2) = (
            render(dir.path(), &spec, "Uniform", 1),
            render(dir.path(), &spec, "Uniform", 2),
        );
        let (nt, nu) = (noise(&t1, &t2), noise(&u1, &u2));
        common::report(&format!("{:30} {nu:.5}  {nt:.5}  {:.3}", spec.name(), nt / nu));
        if nt > 1.05 * nu {
            failures.push(format!(
                "{}: default noise {nt:.5} > 1.05 × uniform {nu:.5}",
                spec.name()
            ));
        }
        // Same image: each 8 × 8 block's mean agrees within 5σ of the two
        // estimates' combined noise (plus a relative 2% for the blocks
        // where both are nearly noiseless).
        let q = 8usize;
        let w = SIZE as usize;
        let mean = |a: &[Rgb], b: &[Rgb]| -> Vec<f64> {
            let ab: Vec<Rgb> = a.iter().zip(b).map(|(p, q)| (*p + *q) * 0.5).collect();
            common::blocks(&ab, w, q)
        };
        let (mt, mu) = (mean(&t1, &t2), mean(&u1, &u2));
        let var = |a: &[Rgb], b: &[Rgb]| -> Vec<f64> {
            let v = pixel_var(a, b);
            let mut out = vec![0.0; (w / q) * (w / q)];
            for (i, x) in v.iter().enumerate() {
                out[(i / w / q) * (w / q) + (i % w) / q] += x / ((q * q) as f64 * (q * q) as f64);
            }
            out
        };
        let (vt, vu) = (var(&t1, &t2), var(&u1, &u2));
        for k in 0..mt.len() {
            let tol = 5.0 * (vt[k] + vu[k]).sqrt() + 0.02 * mu[k].abs() + 1e-4;
            if (mt[k] - mu[k]).abs() > tol {
                failures.push(format!(
                    "{}: block {k} mean {:.5} (default) vs {:.5} (uniform), tolerance {tol:.5}",
                    spec.name(),
                    mt[k],
                    mu[k]
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Writes the family for the side-by-side table when
/// `RONRAY_DUMP_OPEN_SCENES` names a folder; does nothing otherwise.
#[test]
fn dump_the_family_for_mitsuba_when_asked() {
    let Ok(dir) = std::env::var("RONRAY_DUMP_OPEN_SCENES") else {
        return;
    };
    let dir = Path::new(&dir);
    std::fs::create_dir_all(dir).expect("the dump folder");
    write_sun_map(dir);
    let size: u32 = std::env::var("RONRAY_DUMP_SIZE")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(256);
    for spec in family() {
        for (selection, suffix) in [("Tree", ""), ("Uniform", ".uniform")] {
            let path = dir.join(format!("{}{suffix}.ron", spec.name()));
            std::fs::write(path, ron(&spec, selection, size, 64, 0)).expect("a scene file");
        }
        std::fs::write(dir.join(format!("{}.json", spec.name())), json(&spec, size)).expect("a JSON file");
    }
}

#[test]
fn the_family_has_at_least_24_scenes_with_distinct_names_that_load() {
    let specs = family();
    assert!(specs.len() >= 24, "{} scenes", specs.len());
    for kind in [Kind::Rect, Kind::Point, Kind::Sphere, Kind::Mesh] {
        assert!(specs.iter().any(|s| s.kind == kind), "no {kind:?} lights");
    }
    let mut names: Vec<String> = specs.iter().map(Spec::name).collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), specs.len());
    let dir = tempfile::tempdir().expect("a temporary folder");
    write_sun_map(dir.path());
    for spec in specs {
        let text = ron(&spec, "Tree", 16, 1, 0);
        common::load_in(dir.path(), &text, &Default::default());
        let j: serde_json::Value = serde_json::from_str(&json(&spec, 16)).expect("valid JSON");
        assert!(j["shapes"].as_array().is_some_and(|s| s.len() >= 5));
    }
}

/// The sky's measured visibility (light selection's weight for it) follows
/// what hides it: nearly all of it over an open ground, a little through a
/// window, the floor of 1/256 in a closed room.
#[test]
fn sky_visibility_follows_what_the_walls_hide() {
    use ronray::integrators::sky_visibility::sky_visibility;
    let dir = tempfile::tempdir().expect("a temporary folder");
    let v = |text: &str| {
        let l = common::load_in(dir.path(), text, &Default::default());
        let aspect = l.view.film.width as f32 / l.view.film.height as f32;
        sky_visibility(&l.scene, &l.view.camera, aspect)
    };
    let open = Spec {
        ground: 40.0,
        sky: Sky::Constant(1.0),
        lights: 1,
        kind: Kind::Rect,
    };
    let room = Spec { ground: 0.0, ..open };
    let windowed = ron(&room, "Tree", 16, 1, 0);
    // The same room with its window walled up.
    let closed = windowed.replace(
        "    ],\n)",
        "Rect(center: (-5, 2.75, 0), half_u: (0, 0, -1), half_v: (0, 0.75, 0), material: \"wall\"),\n    ],\n)",
    );
    let (vo, vw, vc) = (v(&ron(&open, "Tree", 16, 1, 0)), v(&windowed), v(&closed));
    // Not 1: the spheres' sides see the ground below their horizon.
    assert!(vo > 0.6, "open ground sees {vo} of the sky");
    assert!(vw > 1.0 / 256.0 && vw < 0.3, "the windowed room sees {vw}");
    assert_eq!(vc, 1.0 / 256.0, "the closed room sees {vc}");
}
