//! Cameras beside the perspective one: the orthographic camera keeps sizes
//! whatever the distance, the spherical camera sees an environment map as
//! the map itself.

use crate::common;

use common::{load_in, render_loaded, report};
use ronray::imageio::{Image, compare, write_image};
use ronray::load::Overrides;
use ronray::math::Rgb;

/// A black sphere of radius `r` at the origin against a white sky, seen by
/// an orthographic camera on +z at `distance`.
fn orthographic_disc(r: f32, view_height: f32, distance: f32, size: (u32, u32)) -> Image {
    let text = format!(
        "Scene(
            camera: (eye: (0, 0, {distance}), target: (0, 0, 0), projection: Orthographic(view_height: {view_height})),
            film: (width: {}, height: {}, spp: 16),
            materials: {{ \"black\": Lambert(albedo: (0, 0, 0)) }},
            lights: [Environment(radiance: (1, 1, 1))],
            objects: [Sphere(center: (0, 0, 0), radius: {r}, material: \"black\")],
        )",
        size.0, size.1
    );
    render_loaded(&load_in(&common::root(), &text, &Overrides::default()))
}

/// Pixels covered (1 − brightness, summed), and the covered run of the
/// centre column and the centre row, in pixels.
fn coverage(img: &Image) -> (f64, f64, f64) {
    let cover = |p: Rgb| f64::from(1.0 - p.x);
    let area = img.pixels.iter().map(|&p| cover(p)).sum();
    let column = (0..img.height).map(|y| cover(img.get(img.width / 2, y))).sum();
    let row = (0..img.width).map(|x| cover(img.get(x, img.height / 2))).sum();
    (area, column, row)
}

#[test]
fn orthographic_camera_sees_a_sphere_as_a_disc_2r_over_view_height_tall() {
    // r = 0.5, view height 2: the disc is 0.5 of the image tall, 32 of 64 rows.
    let img = orthographic_disc(0.5, 2.0, 5.0, (96, 64));
    let (area, column, row) = coverage(&img);
    let diameter = 2.0 * 0.5 / 2.0 * 64.0;
    report(&format!(
        "orthographic disc: column {column:.2} px, row {row:.2} px tall/wide (expected {diameter}), area {area:.1} px² (expected {:.1})",
        std::f64::consts::PI * (diameter / 2.0) * (diameter / 2.0)
    ));
    assert!(
        (column - diameter).abs() < 0.5,
        "disc is {column} px tall, expected {diameter}"
    );
    assert!(
        (row - diameter).abs() < 0.5,
        "disc is {row} px wide on a 3:2 image, expected {diameter} (round)"
    );
    let disc = std::f64::consts::PI * (diameter / 2.0).powi(2);
    assert!(
        (area - disc).abs() < 0.01 * disc,
        "disc area {area}, expected {disc}"
    );
}

#[test]
fn orthographic_disc_does_not_shrink_with_distance() {
    let near = orthographic_disc(0.3, 1.5, 2.0, (48, 48));
    let far = orthographic_disc(0.3, 1.5, 40.0, (48, 48));
    let (a, b) = (coverage(&near).0, coverage(&far).0);
    assert!((a - b).abs() < 1e-3 * a, "area at distance 2: {a}, at 40: {b}");
}

/// An environment map written to a temporary folder, and the spherical
/// camera's render of an empty scene lit by it, at the map's size.
fn spherical_round_trip(map: &Image) -> Image {
    let dir = tempfile::tempdir().expect("temp dir");
    write_image(map, &dir.path().join("env.exr")).expect("map written");
    let text = format!(
        "Scene(
            camera: (eye: (0, 0, 0), target: (0, 0, 1), projection: Spherical),
            film: (width: {}, height: {}, spp: 64),
            lights: [Environment(map: \"env.exr\")],
        )",
        map.width, map.height
    );
    render_loaded(&load_in(dir.path(), &text, &Overrides::default()))
}

fn smooth_map(w: u32, h: u32) -> Image {
    let mut map = Image::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let (u, v) = ((x as f32 + 0.5) / w as f32, y as f32 / (h - 1) as f32);
            // A real map: each pole row is one direction, so one colour.
            let (t, pole) = (std::f32::consts::TAU * u, (std::f32::consts::PI * v).sin());
            map.pixels[(y * w + x) as usize] = Rgb::new(
                1.0 + 0.5 * t.cos() * pole,
                0.2 + v,
                1.0 + 0.3 * (2.0 * t).sin() * pole,
            );
        }
    }
    map
}

#[test]
fn spherical_camera_renders_an_environment_map_back() {
    let map = smooth_map(64, 32);
    let img = spherical_round_trip(&map);
    let c = compare(&img, &map, None).expect("same size");
    report(&format!(
        "spherical camera, 64×32 smooth map at 64 spp: RMSE {:.2e} (map mean {:.3})",
        c.rmse,
        map.pixels.iter().map(|p| p.x).sum::<f32>() / map.pixels.len() as f32
    ));
    // What remains is the pixel box averaging the bilinear map over ±½ texel.
    assert!(c.rmse < 3e-3, "RMSE {} against the map", c.rmse);
}

/// A map of independent texels: the render matches the map far better than
/// the map moved by one texel or one row, so the mapping is not off by one.
#[test]
fn spherical_camera_is_aligned_texel_for_texel() {
    let (w, h) = (32u32, 16u32);
    let mut map = Image::new(w, h);
    let mut rng = ronray::math::Pcg32::new(7, 1);
    for p in &mut map.pixels {
        *p = Rgb::splat(rng.next_f32());
    }
    // Each pole row is one direction: one value.
    for y in [0, h - 1] {
        let v = map.get(0, y);
        map.pixels[(y * w) as usize..((y + 1) * w) as usize].fill(v);
    }
    let img = spherical_round_trip(&map);
    let shifted = |dx: u32, dy: u32| {
        let mut s = Image::new(w, h);
        for y in 0..h {
            for x in 0..w {
                s.pixels[(y * w + x) as usize] = map.get((x + dx) % w, (y + dy).min(h - 1));
            }
        }
        s
    };
    let exact = compare(&img, &map, None).expect("size").rmse;
    let by_column = compare(&img, &shifted(1, 0), None).expect("size").rmse;
    let by_row = compare(&img, &shifted(0, 1), None).expect("size").rmse;
    report(&format!(
        "spherical camera, 32×16 white-noise map at 64 spp: RMSE {exact:.3} (one column off {by_column:.3}, one row off {by_row:.3})"
    ));
    assert!(
        exact < 0.5 * by_column && exact < 0.5 * by_row,
        "RMSE {exact} vs shifted {by_column}, {by_row}"
    );
}
