//! A ray leaving a mesh never meets the triangle it leaves. A flat mesh
//! floor under a uniform sky of radiance 1 reflects exactly its albedo; a
//! family of such floors — tilted, shifted, scaled, at the origin's plane
//! (where a triangle's error bound along its normal is zero, so the ray
//! origin is not moved) and far from it — is checked point by point. Before
//! the triangle test rejected hits within its own rounding error of the
//! origin (pbrt-v4's conservative `t`), a grazing ray met the same
//! triangle at t ≈ 10⁻⁸ half the time and the floor at y = 0 reflected
//! 0.434 of a 0.5 albedo.

use crate::common;

use glam::{Mat3, Vec3, Vec3A};
use ronray::load::Overrides;
use ronray::math::{Pcg32, Ray};

#[test]
fn mesh_floors_under_a_sky_reflect_their_albedo_wherever_they_lie() {
    let mut rng = Pcg32::new(2026, 12);
    let mut cases = vec![(Mat3::IDENTITY, Vec3::ZERO, 1.0)];
    for _ in 0..11 {
        let axis = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5).normalize();
        let angle = if rng.next_f32() < 0.3 {
            0.0
        } else {
            rng.next_f32() * 1.2
        };
        let shift = match (rng.next_f32() * 3.0) as u32 {
            0 => Vec3::ZERO,
            1 => Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 3.0,
            _ => Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2000.0,
        };
        let size = 0.01 + rng.next_f32() * 50.0;
        cases.push((Mat3::from_axis_angle(axis, angle), shift, size));
    }
    for (k, (rot, shift, size)) in cases.into_iter().enumerate() {
        let dir = tempfile::tempdir().expect("temp dir");
        let corner = |x: f32, z: f32| rot * Vec3::new(x * size, 0.0, z * size) + shift;
        let mut obj = String::new();
        for (x, z) in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            let p = corner(x, z);
            obj.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
        }
        obj.push_str("f 1 2 3\nf 1 3 4\n");
        std::fs::write(dir.path().join("floor.obj"), obj).expect("obj");
        let up = rot * Vec3::Y;
        let scene = format!(
            "Scene(camera: (eye: ({}, {}, {}), target: ({}, {}, {}), fov_y_degrees: 40), \
             materials: {{ \"m\": Lambert(albedo: (0.5, 0.3, 0.9)) }}, \
             lights: [Environment(radiance: (1, 1, 1))], \
             objects: [Mesh(file: \"floor.obj\", material: \"m\")])",
            shift.x + (up.x + 0.3) * size,
            shift.y + up.y * size,
            shift.z + (up.z + 0.2) * size,
            shift.x,
            shift.y,
            shift.z
        );
        let l = common::load_in(dir.path(), &scene, &Overrides::default());
        for _ in 0..4 {
            let p = corner(rng.next_f32() * 1.8 - 0.9, rng.next_f32() * 1.8 - 0.9);
            let o = Vec3A::from(p + up * (0.5 * size));
            let got = common::mean_li(&l, Ray::new(o, -Vec3A::from(up)), 300);
            let want = Vec3A::new(0.5, 0.3, 0.9);
            assert!(
                (got - want).abs().max_element() < 0.01,
                "floor {k} (rotation {rot:?}, shift {shift}, size {size}) at {p}: {got} against {want}"
            );
        }
    }
}
