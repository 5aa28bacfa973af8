//! Vertex colours: an OBJ's `v x y z r g b` and the scene's
//! `VertexColor(…)` texture and `times_vertex_color` images. Each answer is
//! known in closed form: a flat floor under a uniform sky of radiance 1
//! reflects exactly its albedo, so a ray straight down reads the colour
//! interpolated at the point it meets (glTF's `COLOR_0` is in
//! `tests/gltf/vertex_colors.rs`).

use crate::common;

use glam::Vec3A;
use ronray::load::{Loaded, Overrides, load_str};
use ronray::math::Ray;

/// sRGB-encoded value `x` decoded to linear (IEC 61966-2-1).
fn decode(x: f32) -> f32 {
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// A 2 × 2 floor at y = 0, corners (−1, 1), (1, 1), (1, −1), (−1, −1) in
/// (x, z), with the vertex colours `colors` (sRGB, as written) and the
/// MTL text `mtl` (none when empty), under a sky of radiance 1; the floor
/// has `material` when it is not empty.
fn floor(colors: [[f32; 3]; 4], mtl: &str, material: &str, extra_materials: &str) -> Loaded {
    let dir = tempfile::tempdir().expect("temp dir");
    let corners = [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)];
    let mut obj = String::new();
    if !mtl.is_empty() {
        obj.push_str("mtllib m.mtl\nusemtl paint\n");
        std::fs::write(dir.path().join("m.mtl"), mtl).expect("mtl");
    }
    for ((x, z), c) in corners.iter().zip(colors) {
        obj.push_str(&format!("v {x} 0 {z} {} {} {}\n", c[0], c[1], c[2]));
    }
    obj.push_str("f 1 2 3\nf 1 3 4\n");
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    let material = if material.is_empty() {
        String::new()
    } else {
        format!(", material: \"{material}\"")
    };
    let scene = format!(
        "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), \
         integrator: Path(max_depth: 2), \
         materials: {{ \"grey\": Lambert(albedo: 0.5), {extra_materials} }}, \
         lights: [Environment(radiance: (1, 1, 1))], \
         objects: [Mesh(file: \"m.obj\"{material})])"
    );
    common::load_in(dir.path(), &scene, &Overrides::default())
}

/// The radiance a ray straight down meets at (x, z).
fn seen(l: &Loaded, x: f32, z: f32) -> Vec3A {
    let ray = Ray::new(Vec3A::new(x, 1.0, z), Vec3A::new(0.0, -1.0, 0.0));
    common::mean_li(l, ray, 400)
}

/// The linear colour the floor's vertex colours give at (x, z): the
/// barycentric mix over the triangle holding the point.
fn interpolated(colors: [[f32; 3]; 4], x: f32, z: f32) -> Vec3A {
    let lin: Vec<Vec3A> = colors
        .iter()
        .map(|c| Vec3A::new(decode(c[0]), decode(c[1]), decode(c[2])))
        .collect();
    let p = glam::Vec2::new(x, z);
    let corner = |i: usize| {
        let c = [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)][i];
        glam::Vec2::new(c.0, c.1)
    };
    for tri in [[0, 1, 2], [0, 2, 3]] {
        let (a, b, c) = (corner(tri[0]), corner(tri[1]), corner(tri[2]));
        let d = (b - a).perp_dot(c - a);
        let wb = (p - a).perp_dot(c - a) / d;
        let wc = (b - a).perp_dot(p - a) / d;
        let wa = 1.0 - wb - wc;
        if wa >= -1e-6 && wb >= -1e-6 && wc >= -1e-6 {
            return lin[tri[0]] * wa + lin[tri[1]] * wb + lin[tri[2]] * wc;
        }
    }
    panic!("({x}, {z}) is off the floor")
}

fn assert_close(got: Vec3A, want: Vec3A, what: &str) {
    let err = (got - want).abs().max_element();
    assert!(
        err <= 0.01 + 0.01 * want.max_element(),
        "{what}: {got} against {want}"
    );
}

const PAINT: [[f32; 3]; 4] = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.9, 0.7, 0.2]];

const POINTS: [(f32, f32); 6] = [
    (0.0, 0.0),
    (0.5, 0.5),
    (-0.6, -0.3),
    (0.8, -0.7),
    (-0.9, 0.9),
    (0.2, -0.95),
];

#[test]
fn an_obj_with_vertex_colours_and_no_material_shows_them_interpolated() {
    let l = floor(PAINT, "", "", "");
    for (x, z) in POINTS {
        assert_close(
            seen(&l, x, z),
            interpolated(PAINT, x, z),
            &format!("at ({x}, {z})"),
        );
    }
    assert!(
        !common::notes_text(&l).contains("grey Lambert"),
        "a painted mesh is not grey: {}",
        common::notes_text(&l)
    );
}

#[test]
fn mtl_diffuse_colours_are_multiplied_by_the_vertex_colours() {
    let l = floor(PAINT, "newmtl paint\nKd 0.5 0.25 1\n", "", "");
    for (x, z) in POINTS {
        let want = interpolated(PAINT, x, z) * Vec3A::new(0.5, 0.25, 1.0);
        assert_close(seen(&l, x, z), want, &format!("at ({x}, {z})"));
    }
}

#[test]
fn vertex_color_textures_read_colours_channels_and_scale_images() {
    // A scene material reading them, with a factor.
    let l = floor(
        PAINT,
        "",
        "painted",
        "\"painted\": Lambert(albedo: VertexColor(factor: (0.5, 1, 0.8)))",
    );
    for (x, z) in POINTS {
        let want = interpolated(PAINT, x, z) * Vec3A::new(0.5, 1.0, 0.8);
        assert_close(seen(&l, x, z), want, &format!("factor, at ({x}, {z})"));
    }
    // A number reading one channel: the albedo is a grey of the blend's
    // weight, which reads the green channel.
    let l = floor(
        PAINT,
        "",
        "mix",
        "\"mix\": Blend(weight: VertexColor(factor: 1, channel: G), \
         a: Lambert(albedo: 0), b: Lambert(albedo: 1))",
    );
    for (x, z) in POINTS {
        // The blend picks per hit: the mean over many rays, jittered so
        // that their hashes differ (`docs/materials.md`).
        let ray = |k: u32| {
            let j = 1e-4 * (k as f32 / 997.0 - 0.5);
            Ray::new(Vec3A::new(x + j, 1.0, z - j), Vec3A::new(0.0, -1.0, 0.0))
        };
        let n = 4000;
        let mean = (0..n).map(|k| common::mean_li(&l, ray(k), 1)).sum::<Vec3A>() / n as f32;
        let g = interpolated(PAINT, x, z).y;
        assert!(
            (mean.x - g).abs() < 0.03,
            "blend by green at ({x}, {z}): {mean} against {g}"
        );
    }
    // A plain floor has no colours: `VertexColor` is white there.
    let l = common::load_text(
        "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), \
         materials: { \"painted\": Lambert(albedo: VertexColor(factor: (0.5, 0.25, 1))) }, \
         lights: [Environment(radiance: (1, 1, 1))], \
         objects: [Rect(center: (0, 0, 0), half_u: (1, 0, 0), half_v: (0, 0, -1), material: \"painted\")])",
    );
    assert_close(seen(&l, 0.1, 0.2), Vec3A::new(0.5, 0.25, 1.0), "no colours");
}

#[test]
fn an_image_times_vertex_colours_is_their_product() {
    let dir = tempfile::tempdir().expect("temp dir");
    image::RgbImage::from_pixel(2, 2, image::Rgb([255, 128, 64]))
        .save(dir.path().join("t.png"))
        .expect("png");
    let mut obj = String::new();
    for ((x, z), c) in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
        .iter()
        .zip(PAINT)
    {
        obj.push_str(&format!("v {x} 0 {z} {} {} {}\nvt 0 0\n", c[0], c[1], c[2]));
    }
    obj.push_str("f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    let scene = "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), \
         materials: { \"m\": Lambert(albedo: Image(file: \"t.png\", times_vertex_color: true)) }, \
         lights: [Environment(radiance: (1, 1, 1))], \
         objects: [Mesh(file: \"m.obj\", material: \"m\")])";
    let l = common::load_in(dir.path(), scene, &Overrides::default());
    let texel = Vec3A::new(1.0, decode(128.0 / 255.0), decode(64.0 / 255.0));
    for (x, z) in POINTS {
        let want = interpolated(PAINT, x, z) * texel;
        assert_close(seen(&l, x, z), want, &format!("at ({x}, {z})"));
    }
}

#[test]
fn vertex_colours_survive_cut_outs_and_meshes_without_them() {
    // Two meshes with one material, the first painted and the second not:
    // the second is white, and a ray that passes through a cut-out in
    // front takes the colour of the floor behind, not the cut-out's.
    let dir = tempfile::tempdir().expect("temp dir");
    let mut obj = String::new();
    for ((x, z), c) in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)]
        .iter()
        .zip(PAINT)
    {
        obj.push_str(&format!("v {x} 0 {z} {} {} {}\n", c[0], c[1], c[2]));
    }
    obj.push_str("f 1 2 3\nf 1 3 4\n");
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    let plain = "v 2 0 1\nv 4 0 1\nv 4 0 -1\nv 2 0 -1\nf 1 2 3\nf 1 3 4\n";
    std::fs::write(dir.path().join("p.obj"), plain).expect("obj");
    let scene = "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), \
         materials: { \"p\": Lambert(albedo: VertexColor(factor: (1, 1, 1))), \
                      \"veil\": Cutout(opacity: VertexColor(factor: 0, channel: R), \
                          material: Lambert(albedo: VertexColor(factor: (1, 1, 1)))) }, \
         lights: [Environment(radiance: (1, 1, 1))], \
         objects: [Mesh(file: \"m.obj\", material: \"p\"), Mesh(file: \"p.obj\", material: \"p\"), \
                   Rect(center: (0, 0.5, 0), half_u: (5, 0, 0), half_v: (0, 0, -5), material: \"veil\")])";
    let l = common::load_in(dir.path(), scene, &Overrides::default());
    assert_close(seen(&l, 3.0, 0.0), Vec3A::ONE, "the unpainted object");
    for (x, z) in POINTS {
        assert_close(
            seen(&l, x, z),
            interpolated(PAINT, x, z),
            &format!("through the veil at ({x}, {z})"),
        );
    }
    // One file with painted and plain vertices is refused, saying why.
    let mixed = "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 1 0 1\nf 1 2 3\n";
    std::fs::write(dir.path().join("mixed.obj"), mixed).expect("obj");
    let e = load_str(
        &dir.path().join("t.ron"),
        "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40), \
         lights: [Environment(radiance: (1, 1, 1))], objects: [Mesh(file: \"mixed.obj\")])",
        &Overrides::default(),
    )
    .map(|_| ())
    .expect_err("mixed colours");
    let e = common::message(&e);
    assert!(e.contains("some vertices have a colour"), "{e}");
}

fn error_of(scene: &str) -> String {
    match load_str(&common::root().join("t.ron"), scene, &Overrides::default()) {
        Ok(_) => panic!("must not load: {scene}"),
        Err(e) => common::message(&e),
    }
}

#[test]
fn wrong_vertex_color_textures_are_located_errors() {
    let scene = |m: &str| {
        format!(
            "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40),\n\
             materials: {{ \"m\": {m} }},\n\
             lights: [Environment(radiance: (1, 1, 1))],\n\
             objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\")])"
        )
    };
    for (m, want) in [
        (
            "MetalPlastic(base_color: 0.5, roughness: VertexColor(factor: 1), metalness: 0)",
            "a number reads one channel of the vertex colours",
        ),
        (
            "Lambert(albedo: VertexColor(factor: (1, 1, 1), channel: A))",
            "vertex colours have no alpha channel",
        ),
        (
            "Lambert(albedo: VertexColor(factor: (1, 1, 1), scale: 2))",
            "`VertexColor` takes `factor` and `channel` only, not `scale`",
        ),
        (
            "Lambert(albedo: Image(file: \"x.png\", factor: (2, 2, 2)))",
            "`factor` belongs to `VertexColor(factor: …)`",
        ),
        (
            "Lambert(albedo: Checker(a: (0, 0, 0), b: (1, 1, 1), times_vertex_color: true))",
            "`times_vertex_color` belongs to an image texture",
        ),
        ("Lambert(albedo: VertexColor(factor: (-1, 1, 1)))", "factor"),
    ] {
        let e = error_of(&scene(m));
        assert!(e.contains(want), "{m}: expected `{want}` in:\n{e}");
        assert!(e.contains("t.ron:"), "{m}: not located:\n{e}");
    }
    let e = error_of(
        "Scene(camera: (eye: (0, 3, 3), target: (0, 0, 0), fov_y_degrees: 40),\n\
         materials: { \"m\": Lambert(albedo: 0.5) },\n\
         objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m\",\n\
                   emission: (radiance: VertexColor(factor: (1, 1, 1))))])",
    );
    assert!(e.contains("emission does not read vertex colours"), "{e}");
}

#[test]
fn hostile_obj_vertex_colours_are_clamped_with_a_warning() {
    let bad = [
        [2.0, -1.0, 0.5],
        [f32::NAN, 0.0, 0.0],
        [0.0, f32::INFINITY, 0.0],
        [0.5, 0.5, 0.5],
    ];
    let l = floor(bad, "", "", "");
    assert!(
        common::notes_text(&l).contains("vertex colours outside [0, 1] or not finite"),
        "{}",
        common::notes_text(&l)
    );
    let img = common::render_loaded(&l);
    assert!(img.pixels.iter().all(|p| p.is_finite() && p.min_element() >= 0.0));
    // The first corner reads (1, 0, 0.5) once clamped.
    let near = seen(&l, -0.98, 0.98);
    assert!(near.x > 0.9 && near.y < 0.1, "clamped corner: {near}");
}

/// Every number of the fuzz seed `fuzz/corpus/scene/vertex_colors.ron`
/// replaced in turn by a hostile one: each variant loads or is refused, and
/// each that loads renders finite pixels.
#[test]
fn hostile_numbers_in_vertex_colours_never_panic_and_render_finite() {
    let seed = std::fs::read_to_string(common::root().join("fuzz/corpus/scene/vertex_colors.ron"))
        .expect("the fuzz seed");
    let dir = common::root().join("tests/fixtures/hardening");
    let l = common::load_in(&dir, &seed, &Overrides::default());
    assert!(
        l.scene.geometry.meshes.iter().any(|m| !m.colors.is_empty()),
        "the seed's mesh is painted"
    );
    let (numbers, loaded, refused) = common::hostile_number_sweep(&seed, &dir);
    assert!(numbers > 40, "{numbers} numbers");
    assert!(loaded > 0 && refused > 0, "{loaded} loaded, {refused} refused");
}
