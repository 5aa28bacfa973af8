//! A sphere-traced torus against a finely tessellated one: grazing rays
//! (silhouettes, shadow terminators) make no holes and no acne.

use super::{render_seed, scene_in};
use glam::{Vec2, Vec3A};
use ronray::imageio::{Image, compare};
use ronray::load::Loaded;
use ronray::load::Overrides;
use std::fmt::Write as _;

/// A torus of major radius 1 and minor 0.35 as an OBJ, `n_u × n_v` quads,
/// with vertex normals; vertices lie on the surface, facets within 2e-4.
fn torus_obj(n_u: usize, n_v: usize) -> String {
    let mut s = String::new();
    let tau = std::f32::consts::TAU;
    for i in 0..n_u {
        let (su, cu) = (tau * i as f32 / n_u as f32).sin_cos();
        for j in 0..n_v {
            let (sv, cv) = (tau * j as f32 / n_v as f32).sin_cos();
            let ring = 1.0 + 0.35 * cv;
            writeln!(s, "v {} {} {}", ring * cu, 0.35 * sv, ring * su).unwrap();
            writeln!(s, "vn {} {} {}", cv * cu, sv, cv * su).unwrap();
        }
    }
    let id = |i: usize, j: usize| (i % n_u) * n_v + (j % n_v) + 1;
    for i in 0..n_u {
        for j in 0..n_v {
            let [a, b, c, d] = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            // Wound so the normal points out of the tube.
            writeln!(s, "f {a}//{a} {d}//{d} {c}//{c} {b}//{b}").unwrap();
        }
    }
    s
}

/// Distance to the torus of `torus_scene`, computed analytically.
fn true_torus(p: Vec3A) -> f32 {
    let q = glam::Quat::from_rotation_x(-25f32.to_radians()) * glam::Vec3::from(p);
    glam::Vec2::new(glam::Vec2::new(q.x, q.z).length() - 1.0, q.y).length() - 0.35
}

fn torus_scene(dir: &std::path::Path, object: &str) -> Loaded {
    let text = format!(
        r#"Scene(
        camera: (eye: (0, 2.2, 3.2), target: (0, 0, 0), fov_y_degrees: 40),
        film: (width: 64, height: 64, spp: 4),
        integrator: Direct(light_samples: 1),
        materials: {{ "m": Lambert(albedo: (0.8, 0.8, 0.8)) }},
        lights: [Point(position: (-3, 0.6, 1), intensity: (8, 8, 8))],
        objects: [{object} material: "m", transform: [Rotate(axis: (1, 0, 0), degrees: 25)])],
    )"#
    );
    scene_in(dir, &text, &Overrides::default())
}

#[test]
fn sdf_torus_grazing_rays_match_a_fine_mesh() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("torus.obj"), torus_obj(400, 100)).unwrap();
    // The scene completes either object's fields.
    let mut sdf = torus_scene(dir.path(), "Sdf(shape: Torus(major: 1, minor: 0.35),");
    let mut mesh = torus_scene(dir.path(), "Mesh(file: \"torus.obj\",");
    let cam = sdf.view.camera;
    // Rays on a 256² grid: every disagreement must be a grazing ray, or a
    // crack between the mesh's triangles with the SDF hit on the true torus.
    let (n, mut both, mut grazing, mut cracks) = (256, 0, 0, 0);
    for y in 0..n {
        for x in 0..n {
            let film = (Vec2::new(x as f32, y as f32) + 0.5) / n as f32;
            let ray = cam.ray(film, 1.0, Vec2::ZERO);
            let (s, m) = (
                sdf.scene.intersect(&ray, f32::INFINITY),
                mesh.scene.intersect(&ray, f32::INFINITY),
            );
            // Surfaces 2e-4 apart along the normal: hits about that far apart
            // along it, whatever the angle.
            let agree = match (&s, &m) {
                (Some(s), Some(m)) => (s.t - m.t).abs() * m.ng.dot(ray.d).abs() < 1e-3,
                (None, None) => true,
                _ => false,
            };
            both += u32::from(s.is_some() && m.is_some());
            if agree {
                continue;
            }
            let near = match (&s, &m) {
                (Some(s), Some(m)) => {
                    if s.t < m.t {
                        s
                    } else {
                        m
                    }
                }
                (Some(h), None) | (None, Some(h)) => h,
                (None, None) => unreachable!("agreeing misses were skipped"),
            };
            if near.ng.dot(ray.d).abs() < 0.1 {
                grazing += 1;
            } else if s
                .as_ref()
                .is_some_and(|s| s.t <= near.t && true_torus(s.p).abs() < 1e-4)
            {
                cracks += 1;
            } else {
                panic!("ray {ray:?}: hole or false hit: SDF {s:?}, mesh {m:?}");
            }
        }
    }
    println!("{both} rays hit both; {grazing} grazing and {cracks} mesh-crack disagreements");
    assert!(
        both > 10_000 && grazing < both / 200 && cracks < 5,
        "{grazing}, {cracks} of {both}"
    );
    // Renders: acne would darken lit pixels, holes would show black.
    let (a, b) = (render_seed(&mut sdf, 3), render_seed(&mut mesh, 3));
    let (mask, edges) = silhouette(&b);
    let c = compare(&a, &b, Some(&mask)).unwrap();
    let all = compare(&a, &b, None).unwrap();
    println!(
        "silhouette pixels {edges}: RMSE {:.5}; whole image {:.5}",
        c.rmse, all.rmse
    );
    assert!(edges > 100, "{edges} silhouette pixels");
    assert!(
        c.rmse < 0.01,
        "silhouette RMSE {} (whole image {})",
        c.rmse,
        all.rmse
    );
    assert!(all.rmse < 0.005, "whole-image RMSE {}", all.rmse);
}

/// `skip` mask for [`compare`] keeping pixels whose 3×3 neighbourhood is
/// partly black (background or shadow) and partly lit: silhouettes and
/// shadow boundaries, where grazing rays decide; and how many there are.
fn silhouette(img: &Image) -> (Vec<bool>, usize) {
    let (w, h) = (img.width as i32, img.height as i32);
    let covered = |x: i32, y: i32| {
        img.get(x.clamp(0, w - 1) as u32, y.clamp(0, h - 1) as u32)
            .max_element()
            > 0.0
    };
    let mut skip = vec![true; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let n = (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy)));
            let c = n.filter(|&(dx, dy)| covered(x + dx, y + dy)).count();
            skip[(y * w + x) as usize] = c == 0 || c == 9;
        }
    }
    let edges = skip.iter().filter(|s| !**s).count();
    (skip, edges)
}
