//! A moving mesh light (an emissive keyed instance) against closed forms at
//! given times: its irradiance is the polygon formula's for the polygon
//! placed at that time, its samples average its placed area, the density
//! it reports for a sample is the one `pdf` gives at the hit a ray along it
//! makes on the moving instance, and the light tree's bounds hold it over
//! the whole shutter.

use super::tests::{irradiance, polygon_irradiance};
use super::tree::light_bounds;
use super::*;
use crate::anim::{Interpolation, TransformTrack, clock};
use crate::geometry::moving::InstanceMotion;
use crate::geometry::{Instance, Mesh};
use crate::math::{Pcg32, Ray};
use glam::{Affine3A, Mat4, Quat, Vec3};
use std::f32::consts::PI;

/// The unit square in the mesh's xz plane, facing down (−y).
const SQUARE: [Vec3A; 4] = [
    Vec3A::new(-0.5, 0.0, -0.5),
    Vec3A::new(0.5, 0.0, -0.5),
    Vec3A::new(0.5, 0.0, 0.5),
    Vec3A::new(-0.5, 0.0, 0.5),
];

fn square_tris() -> Vec<[Vec3A; 3]> {
    let [a, b, c, d] = SQUARE;
    vec![[a, b, c], [a, c, d]]
}

/// From 2 units up at frame 0 to lower, tilted 30° and stretched 2 × 1.5
/// (its area tripled) at frame 1; the shutter open over the frame.
fn rise_and_stretch() -> InstanceMotion {
    let a = Mat4::from_translation(Vec3::new(0.0, 2.0, 0.0));
    let b = Mat4::from_scale_rotation_translation(
        Vec3::new(2.0, 1.0, 1.5),
        Quat::from_rotation_x(30f32.to_radians()),
        Vec3::new(0.5, 1.5, -0.3),
    );
    InstanceMotion::new(
        TransformTrack::new(&[(0.0, a), (1.0, b)], Interpolation::Linear),
        (0.0, 1.0),
    )
}

fn moving_square(radiance: f32, two_sided: bool) -> (MeshLight, InstanceMotion) {
    let m = rise_and_stretch();
    let light = MeshLight::new(square_tris(), Rgb::splat(radiance), two_sided)
        .expect("area")
        .with_motion(m.clone());
    (light, m)
}

#[test]
fn moving_mesh_light_irradiance_matches_the_polygon_formula_at_each_time() {
    let (light, m) = moving_square(2.0, false);
    let light = Light::Mesh(light);
    for t in [0.0, 0.35, 1.0] {
        clock::set(t);
        let placed = SQUARE.map(|v| m.placement_at(t).world_from_object.transform_point3a(v));
        for p in [Vec3A::ZERO, Vec3A::new(0.7, 0.2, 0.4)] {
            let want = polygon_irradiance(p, Vec3A::Y, &placed, 2.0);
            // `irradiance` also checks each sample's pdf against `pdf`.
            let got = irradiance(&light, p, Vec3A::Y, 200_000);
            assert!(
                ((got - want as f64) / want as f64).abs() < 0.01,
                "time {t}, at {p}: {got} vs {want}"
            );
        }
    }
    // Selection weighs the light as placed at the opening: area 1.
    assert!((light.power().x - PI * 2.0).abs() < 1e-4, "{}", light.power().x);
}

#[test]
fn moving_mesh_light_samples_average_the_placed_area_of_every_triangle() {
    // A tetrahedron's faces: four normals, each stretched differently, so
    // each triangle's area grows by its own factor.
    let v = [
        Vec3A::new(0.0, 0.0, 0.0),
        Vec3A::new(1.0, 0.0, 0.0),
        Vec3A::new(0.0, 1.0, 0.0),
        Vec3A::new(0.0, 0.0, 1.0),
    ];
    let tris = vec![
        [v[0], v[2], v[1]],
        [v[0], v[1], v[3]],
        [v[0], v[3], v[2]],
        [v[1], v[2], v[3]],
    ];
    let m = rise_and_stretch();
    let light = MeshLight::new(tris.clone(), Rgb::ONE, true)
        .expect("area")
        .with_motion(m.clone());
    let p = Vec3A::new(3.0, -1.0, 2.0);
    let mut rng = Pcg32::new(5, 1);
    for t in [0.3f32, 0.9] {
        clock::set(t);
        let w = m.placement_at(t).world_from_object;
        let placed_area: f64 = tris
            .iter()
            .map(|[a, b, c]| {
                let [a, b, c] = [a, b, c].map(|q| w.transform_point3a(*q));
                f64::from(0.5 * (b - a).cross(c - a).length())
            })
            .sum();
        // E[d² / (pdf · |cos θl|)] = E[1 / area density] = the placed area.
        let n = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let ls = light.sample(p, rng.next_vec2()).expect("two-sided, outside");
            sum += f64::from(ls.dist * ls.dist / (ls.pdf * ls.wi.dot(ls.n).abs()));
        }
        let got = sum / f64::from(n);
        assert!(
            ((got - placed_area) / placed_area).abs() < 0.005,
            "time {t}: samples average area {got}, placed area {placed_area}"
        );
    }
}

#[test]
fn moving_mesh_light_pdf_at_the_instance_hit_is_the_sample_pdf() {
    let mut mesh = Mesh::default();
    mesh.positions = SQUARE.to_vec();
    mesh.indices = vec![[0, 1, 2], [0, 2, 3]];
    mesh.slot_count = 1;
    mesh.prepare();
    let meshes = vec![mesh];
    let (light, m) = moving_square(1.0, false);
    let opening = Affine3A::from_mat4(m.track.at(0.0));
    let instance = Instance::new(0, opening, Box::new([0])).with_motion(m);
    let mut rng = Pcg32::new(9, 2);
    let p = Vec3A::new(0.2, 0.0, 0.1);
    for s in 0..200 {
        let t = s as f32 / 199.0;
        clock::set(t);
        let ls = light
            .sample(p, rng.next_vec2())
            .expect("the square faces the point");
        let ray = Ray::new(p, ls.wi);
        let h = instance
            .closest(&ray, f32::INFINITY, &meshes)
            .unwrap_or_else(|| panic!("time {t}: the ray toward the sample misses the instance"));
        let hit = instance.hit(&ray, h, &meshes);
        assert!(
            (hit.t - ls.dist).abs() < 1e-4 * ls.dist,
            "time {t}: hit at {}, sample at {}",
            hit.t,
            ls.dist
        );
        let pdf = light.pdf(ls.wi, hit.t, hit.ng);
        assert!(
            (pdf - ls.pdf).abs() < 1e-3 * ls.pdf,
            "time {t}: pdf at the hit {pdf}, sample pdf {}",
            ls.pdf
        );
    }
}

#[test]
fn moving_mesh_light_tree_bounds_hold_it_over_the_shutter() {
    let (light, m) = moving_square(1.0, false);
    let power = crate::math::luminance(light.power());
    let b = light_bounds(&Light::Mesh(light)).expect("a surface");
    assert_eq!(b.cos_theta_o, -1.0, "a turning light's normals go anywhere");
    // Still a flat one-sided panel to a point: weighed by its whole power,
    // not the quarter a sphere of normals would get.
    assert!(
        (b.phi - power).abs() < 1e-3 * power,
        "weight {} of power {power}",
        b.phi
    );
    for s in 0..=400 {
        let t = s as f32 / 400.0;
        let w = m.placement_at(t).world_from_object;
        for v in SQUARE {
            let q = w.transform_point3a(v);
            assert!(
                q.cmpge(b.bounds.min).all() && q.cmple(b.bounds.max).all(),
                "time {t}: corner {q} outside {:?}",
                b.bounds
            );
        }
    }
}
