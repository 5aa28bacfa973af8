//! MTL normal and bump maps: `norm` and a normal-map-looking `map_Bump`
//! tilt the shading normal along the mesh's tangents (MikkTSpace, as a
//! glTF's); a grey `map_Bump` is a height map, scaled by `-bm`, with a
//! note. Before, all three were dropped with a note.

use crate::common;

use glam::Vec3A;
use ronray::load::{Loaded, Overrides};
use ronray::math::Ray;

/// A 2 × 2 floor at y = 0 whose UVs run u along +x and v along −z, with
/// the MTL statement `map` over an image `img` written as `tex.png`.
fn floor_with(map: &str, img: image::RgbImage) -> Loaded {
    let dir = tempfile::tempdir().expect("temp dir");
    img.save(dir.path().join("tex.png")).expect("png");
    let obj = "mtllib m.mtl\n\
               v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\n\
               vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n\
               usemtl floor\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
    std::fs::write(dir.path().join("m.obj"), obj).expect("obj");
    std::fs::write(
        dir.path().join("m.mtl"),
        format!("newmtl floor\nKd 0.5 0.5 0.5\n{map}\n"),
    )
    .expect("mtl");
    let scene = "Scene(camera: (eye: (0, 2, 3), target: (0, 0, 0), fov_y_degrees: 40), \
                 lights: [Point(position: (0, 3, 0), intensity: (10, 10, 10))], \
                 objects: [Mesh(file: \"m.obj\")])";
    common::load_in(dir.path(), scene, &Overrides::default())
}

/// The shading normal where a ray straight down meets the floor at (x, z).
fn shading_normal(l: &Loaded, x: f32, z: f32) -> Vec3A {
    let ray = Ray::new(Vec3A::new(x, 1.0, z), Vec3A::new(0.0, -1.0, 0.0));
    l.scene
        .intersect(&ray, f32::INFINITY)
        .expect("the floor is hit")
        .ns
}

#[test]
fn mtl_normal_maps_tilt_the_shading_normal_along_u() {
    // Texel (0.75, 0.5, 0.933): a normal tilted 30° toward the tangent
    // (+u, here +x), as 8-bit linear values.
    let tilted = image::RgbImage::from_pixel(4, 4, image::Rgb([191, 128, 238]));
    for map in [
        "norm tex.png",
        "map_Bump tex.png",
        "bump tex.png",
        "map_Bump -bm 1 tex.png",
    ] {
        let l = floor_with(map, tilted.clone());
        let n = shading_normal(&l, 0.3, -0.2);
        let want = Vec3A::new(0.5, 0.866, 0.0).normalize();
        assert!(
            (n - want).length() < 0.02,
            "{map}: shading normal {n}, expected {want}"
        );
    }
    // `-bm` is the normal map's strength: 0 leaves the normal as it is.
    let l = floor_with("map_Bump -bm 0 tex.png", tilted);
    let n = shading_normal(&l, 0.3, -0.2);
    assert!((n - Vec3A::Y).length() < 1e-4, "-bm 0: {n}");
}

#[test]
fn a_grey_mtl_bump_map_is_a_height_map_scaled_by_bm() {
    // Heights rising along u (x): a slope of 255 levels over the image.
    let ramp = image::RgbImage::from_fn(64, 4, |x, _| {
        let v = (x * 4) as u8;
        image::Rgb([v, v, v])
    });
    let tilt = |map: &str| {
        let l = floor_with(map, ramp.clone());
        assert!(
            common::notes_text(&l).contains("read as a height map"),
            "{map}: no note: {}",
            common::notes_text(&l)
        );
        let n = shading_normal(&l, 0.1, 0.0);
        assert!(n.y > 0.0 && n.z.abs() < 1e-3, "{map}: {n}");
        // Heights rise toward +x: the normal leans toward −x.
        -n.x / n.y
    };
    let one = tilt("map_Bump tex.png");
    let two = tilt("map_Bump -bm 2 tex.png");
    assert!(one > 0.0, "the normal leans away from the rise: {one}");
    assert!(
        (two / one - 2.0).abs() < 0.02,
        "-bm 2 doubles the slope: {one} and {two}"
    );
    // A flat grey image leaves the normal as it is.
    let flat = floor_with(
        "map_Bump tex.png",
        image::RgbImage::from_pixel(4, 4, image::Rgb([90, 90, 90])),
    );
    assert!((shading_normal(&flat, 0.3, 0.2) - Vec3A::Y).length() < 1e-5);
}
