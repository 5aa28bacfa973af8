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

/// The same family as analytic shapes and as a mesh placed by an instance's
/// transform (not baked): a tilted rectangle and the top of a large
/// sphere (convex, so it sees the whole sky) reflect their albedo too.
#[test]
fn analytic_floors_spheres_and_instanced_meshes_under_a_sky_reflect_their_albedo() {
    let mut rng = Pcg32::new(7, 44);
    for k in 0..12 {
        let axis = Vec3::new(rng.next_f32() - 0.5, rng.next_f32() - 0.5, rng.next_f32() - 0.5).normalize();
        let rot = Mat3::from_axis_angle(axis, if k % 3 == 0 { 0.0 } else { rng.next_f32() * 1.2 });
        let shift = match k % 3 {
            0 => Vec3::ZERO,
            1 => Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 3.0,
            _ => Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2000.0,
        };
        let size = 0.01 + rng.next_f32() * 50.0;
        let (u, up, v) = (rot * Vec3::X * size, rot * Vec3::Y, rot * Vec3::NEG_Z * size);
        let v3 = |p: Vec3| format!("({}, {}, {})", p.x, p.y, p.z);
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::write(
            dir.path().join("unit.obj"),
            "v -1 0 1\nv 1 0 1\nv 1 0 -1\nv -1 0 -1\nf 1 2 3\nf 1 3 4\n",
        )
        .expect("obj");
        let (ax, angle) = glam::Quat::from_mat3(&rot).to_axis_angle();
        let shapes = [
            format!(
                "Rect(center: {}, half_u: {}, half_v: {}, material: \"m\")",
                v3(shift),
                v3(u),
                v3(v)
            ),
            format!(
                "Sphere(center: {}, radius: {size}, material: \"m\")",
                v3(shift - up * size)
            ),
            format!(
                "Instance(mesh: \"unit\", material: \"m\", transform: [Scale(({size}, {size}, {size})), \
                 Rotate(axis: {}, degrees: {}), Translate({})])",
                v3(if ax.is_finite() { ax } else { Vec3::Y }),
                angle.to_degrees(),
                v3(shift)
            ),
        ];
        for shape in shapes {
            let scene = format!(
                "Scene(camera: (eye: {}, target: {}, fov_y_degrees: 40), \
                 meshes: {{ \"unit\": (file: \"unit.obj\") }}, \
                 materials: {{ \"m\": Lambert(albedo: (0.5, 0.3, 0.9)) }}, \
                 lights: [Environment(radiance: (1, 1, 1))], objects: [{shape}])",
                v3(shift + (up + Vec3::new(0.3, 0.0, 0.2)) * size * 2.0),
                v3(shift)
            );
            let l = common::load_in(dir.path(), &scene, &Overrides::default());
            // The point on top (the sphere's pole), and off-centre ones on
            // the flat shapes.
            let offsets: &[(f32, f32)] = if shape.starts_with("Sphere") {
                &[(0.0, 0.0)]
            } else {
                &[(0.3, -0.5), (-0.7, 0.2), (0.05, 0.85)]
            };
            for &(a, b) in offsets {
                let p = shift + u * a + v * b;
                let o = Vec3A::from(p + up * (0.5 * size));
                let got = common::mean_li(&l, Ray::new(o, -Vec3A::from(up)), 300);
                let want = Vec3A::new(0.5, 0.3, 0.9);
                assert!(
                    (got - want).abs().max_element() < 0.01,
                    "case {k}, {shape} at {p}: {got} against {want}"
                );
            }
        }
    }
}
