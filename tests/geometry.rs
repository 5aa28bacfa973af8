//! Meshes through their own BVH: watertight on a closed mesh, equal to brute
//! force on the bunny, instances equal to baked copies, smooth normals.

use glam::{Affine3A, Quat, Vec3, Vec3A};
use ronray::geometry::obj::load_obj;
use ronray::geometry::{Instance, Mesh};
use ronray::math::{Pcg32, Ray, sampling};
use std::path::Path;

/// A closed icosphere: an icosahedron with each face split `levels` times,
/// vertices pushed onto the unit sphere; shared vertices are shared indices.
fn icosphere(levels: u32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut p: Vec<Vec3A> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|v| Vec3A::from_array(*v).normalize())
    .collect();
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut m = |a: u32, b: u32, p: &mut Vec<Vec3A>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                p.push((p[a as usize] + p[b as usize]).normalize());
                p.len() as u32 - 1
            })
        };
        f = f
            .iter()
            .flat_map(|&[a, b, c]| {
                let (ab, bc, ca) = (m(a, b, &mut p), m(b, c, &mut p), m(c, a, &mut p));
                [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
            })
            .collect();
    }
    let mut mesh = Mesh::default();
    mesh.positions = p;
    mesh.indices = f;
    mesh.slot_count = 1;
    mesh
}

#[test]
fn mesh_is_watertight_at_edges_and_vertices() {
    let mut mesh = icosphere(3);
    mesh.prepare();
    let mut rng = Pcg32::new(5, 5);
    let mut rays = 0;
    for &[a, b, c] in &mesh.indices.clone() {
        let [a, b, c] = [a, b, c].map(|i| mesh.positions[i as usize]);
        // Vertices and points exactly on edges (in f32, as a user computes them).
        let s = rng.next_f32();
        for target in [
            a,
            b,
            c,
            a + s * (b - a),
            b + 0.5 * (c - b),
            c + (1.0 - s) * (a - c),
        ] {
            let inside = 0.5 * sampling::uniform_sphere(rng.next_vec2()) * rng.next_f32();
            // From inside a closed mesh every ray must hit (from outside a
            // ray at a silhouette vertex may graze past, legitimately).
            for o in [inside, Vec3A::ZERO] {
                let ray = Ray::new(o, (target - o).normalize());
                let hit = mesh.closest(&ray, f32::INFINITY);
                rays += 1;
                assert!(
                    hit.is_some(),
                    "ray from {o} at {target} slipped through the closed mesh"
                );
                assert!(
                    mesh.occluded(&ray, f32::INFINITY),
                    "occlusion ray from {o} at {target} slipped through"
                );
            }
        }
    }
    assert!(rays > 10_000, "only {rays} rays");
}

#[test]
fn mesh_bvh_matches_brute_force_on_bunny() {
    let mut mesh = load_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/bunny.obj")).expect("bunny");
    mesh.prepare();
    let rays = ronray::geometry::ray_sets::incoherent_rays(&mesh, 5000, 3);
    let mut hits = 0;
    for (i, ray) in rays.iter().enumerate() {
        let got = mesh.closest(ray, f32::INFINITY);
        let mut want: Option<(u32, f32)> = None;
        for t in 0..mesh.triangle_count() as u32 {
            if let Some((d, _)) = mesh.intersect(t, ray, want.map_or(f32::INFINITY, |w| w.1)) {
                want = Some((t, d));
            }
        }
        match (got, want) {
            (None, None) => {}
            (Some(g), Some((wt, wd))) => {
                hits += 1;
                assert!(g.t == wd, "ray {i}: t {} vs brute force {wd}", g.t);
                assert!(g.tri == wt || mesh.intersect(g.tri, ray, f32::INFINITY).map(|h| h.0) == Some(wd));
            }
            _ => panic!("ray {i}: BVH {got:?} vs brute force {want:?}"),
        }
        assert_eq!(
            mesh.occluded(ray, f32::INFINITY),
            want.is_some(),
            "ray {i}: occlusion"
        );
    }
    assert!(hits > 1000, "{hits} hits");
}

#[test]
fn instance_matches_baked_mesh() {
    let mut object = icosphere(2);
    object.prepare();
    let m = Affine3A::from_scale_rotation_translation(
        Vec3::new(2.0, 0.5, 1.0),
        Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.0).normalize(), 0.7),
        Vec3::new(3.0, -1.0, 2.0),
    );
    let mut baked = icosphere(2);
    baked
        .positions
        .iter_mut()
        .for_each(|p| *p = m.transform_point3a(*p));
    baked.prepare();
    let meshes = [object];
    let inst = Instance::new(0, m, vec![7].into_boxed_slice());
    let b = inst.bounds(&meshes);
    assert!(
        b.contains(&baked.bounds()),
        "instance bounds {b:?} miss the baked mesh"
    );
    let rays = ronray::geometry::ray_sets::incoherent_rays(&baked, 4000, 9);
    for (i, ray) in rays.iter().enumerate() {
        let (got, want) = (
            inst.closest(ray, f32::INFINITY, &meshes),
            baked.closest(ray, f32::INFINITY),
        );
        match (got, want) {
            (None, None) => {}
            (Some(g), Some(w)) => {
                assert!(
                    (g.t - w.t).abs() <= 1e-4 * w.t.max(1.0),
                    "ray {i}: {} vs {}",
                    g.t,
                    w.t
                );
                let h = inst.hit(ray, g, &meshes);
                let hb = baked.hit(w.tri, w.t, w.bc);
                assert!((h.p - hb.p).length() < 1e-3, "ray {i}: p {} vs {}", h.p, hb.p);
                assert!(h.ng.dot(hb.ng) > 0.999, "ray {i}: ng {} vs {}", h.ng, hb.ng);
                assert_eq!(h.material, 7);
            }
            // Grazing rays may differ between the two roundings.
            _ => assert!(
                got.or(want)
                    .is_some_and(|h| h.bc.min_element() < 1e-3 || h.bc.element_sum() > 0.999)
            ),
        }
    }
}

#[test]
fn mesh_smooth_normals_are_area_weighted() {
    let mut mesh = icosphere(3);
    mesh.compute_smooth_normals();
    for (p, n) in mesh.positions.iter().zip(&mesh.normals) {
        assert!(n.dot(*p) > 0.999, "normal {n} at {p} should point outward");
    }
}

/// A scene with the tall Cornell block, written as a baked `Mesh` object
/// (`object`) or as an identity `Instance` of a shared mesh.
fn block_scene(object: &str) -> ronray::scene::Scene {
    use ronray::load::{Overrides, load_str};
    let text = format!(
        r#"Scene(
            camera: (eye: (0, 0, 3.9), target: (0, 0, 0), up: (0, 1, 0), fov_y_degrees: 37.5),
            film: (width: 8, height: 8, spp: 1),
            materials: {{"white": Lambert(albedo: (0.8, 0.8, 0.8))}},
            meshes: {{"block": (file: "tall_block.obj")}},
            lights: [Point(position: (0, 0.9, 0), intensity: (1, 1, 1))],
            objects: [{object}],
        )"#
    );
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/flatten.ron");
    match load_str(&path, &text, &Overrides::default()) {
        Ok(l) => l.scene,
        Err(e) => panic!("block scene: {e}"),
    }
}

/// A closed mesh seen from inside does not leak, flattened into the scene
/// BVH or as an instance: rays from inside the reference Cornell box's tall
/// block, aimed exactly at points of its triangles' edges (the faces' edges
/// and the diagonals each pair shares: the worst case for a test that is
/// not watertight), all hit it and are all occluded. A parallelogram test
/// of the block's pairs (tried for speed, nineteenth session) let 2.6% of
/// such rays through a closed box.
#[test]
fn closed_meshes_do_not_leak_at_their_edges() {
    let block =
        load_obj(&Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/tall_block.obj")).expect("block");
    assert_eq!(block.triangle_count(), 12, "six faces of two triangles");
    let centre = block.positions.iter().copied().sum::<Vec3A>() / block.positions.len() as f32;
    for object in [
        r#"Mesh(file: "tall_block.obj", material: "white")"#,
        r#"Instance(mesh: "block", material: "white")"#,
    ] {
        let scene = block_scene(object);
        let mut rng = Pcg32::new(8, 3);
        for i in 0..20_000 {
            let (p0, p1, p2) = block.corners((i % 12) as u32);
            let (a, b) = [(p0, p1), (p1, p2), (p2, p0)][(i / 12) % 3];
            let target = a + (b - a) * rng.next_f32();
            let o = centre + (Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5) * 0.2;
            let ray = Ray::new(o, (target - o).normalize());
            assert!(
                scene.intersect(&ray, f32::INFINITY).is_some(),
                "{object}: ray {i} left the block through an edge"
            );
            assert!(
                scene.occluded(&ray, f32::INFINITY),
                "{object}: ray {i} not occluded"
            );
        }
    }
}

#[test]
fn small_baked_mesh_in_the_scene_bvh_matches_its_instance() {
    use ronray::geometry::Shape;
    let flat = block_scene(r#"Mesh(file: "tall_block.obj", material: "white")"#);
    let inst = block_scene(r#"Instance(mesh: "block", material: "white")"#);
    // Each face's two triangles go in as one pair.
    let triangles = |s: &ronray::scene::Scene| {
        s.shapes
            .iter()
            .map(|s| match s {
                Shape::Triangle(_) => 1,
                Shape::MeshQuad(_) => 2,
                _ => 0,
            })
            .sum::<usize>()
    };
    let pairs = flat
        .shapes
        .iter()
        .filter(|s| matches!(s, Shape::MeshQuad(_)))
        .count();
    assert_eq!(triangles(&flat), 12, "the 12-triangle block is flattened");
    assert_eq!(pairs, 6, "its six faces are pairs");
    assert_eq!(triangles(&inst), 0, "a shared mesh stays an instance");
    let mut rng = Pcg32::new(5, 2);
    let mut hits = 0;
    for i in 0..5000 {
        let o = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 2.0 - 1.0;
        let ray = Ray::new(o, sampling::uniform_sphere(rng.next_vec2()));
        let (a, b) = (
            flat.intersect(&ray, f32::INFINITY),
            inst.intersect(&ray, f32::INFINITY),
        );
        assert_eq!(a.is_some(), b.is_some(), "ray {i}");
        if let (Some(a), Some(b)) = (a, b) {
            // Same world-space vertices and the same watertight
            // arithmetic, but a pair may take a triangle's corners in
            // another rotation: the sums in another order.
            assert!((a.t - b.t).abs() <= 1e-5 * a.t, "ray {i}: t {} {}", a.t, b.t);
            assert!((a.p - b.p).length() < 1e-6 && a.ng == b.ng && a.material == b.material);
            assert_eq!(flat.occluded(&ray, a.t * 1.001), inst.occluded(&ray, a.t * 1.001));
            hits += 1;
        }
    }
    assert!(hits > 500, "the rays reach the block: {hits}");
}

/// A few spheres and quads (and an unbounded plane) go into SIMD lanes, and
/// the scene answers every query as through its BVH: the same hit records
/// bit for bit and the same shadow answers.
#[test]
fn shape_lanes_answer_as_the_bvh() {
    use ronray::load::{Overrides, load_str};
    let scene = |extra: &str| {
        let text = format!(
            r#"Scene(
                camera: (eye: (0, 1, 5), target: (0, 0.5, 0), up: (0, 1, 0), fov_y_degrees: 40),
                film: (width: 8, height: 8, spp: 1),
                materials: {{"a": Lambert(albedo: (0.8, 0.8, 0.8)), "b": Lambert(albedo: (0.2, 0.5, 0.8))}},
                lights: [Rect(center: (0, 3, 0), half_u: (0.5, 0, 0), half_v: (0, 0, 0.5), radiance: (5, 5, 5))],
                objects: [
                    Rect(center: (0, 0, 0), half_u: (3, 0, 0), half_v: (0, 0, -3), material: "a"),
                    Rect(center: (0, 1, -2), half_u: (1, 0, 0), half_v: (0, 1, 0), material: "b"),
                    Sphere(center: (-1, 0.5, 0), radius: 0.5, material: "b"),
                    Sphere(center: (0.2, 0.4, 0.3), radius: 0.4, material: "a"),
                    Sphere(center: (1.1, 0.7, -0.5), radius: 0.7, material: "b"),
                    Plane(point: (0, -1, 0), normal: (0, 1, 0), material: "a"),
                    {extra}
                ],
            )"#
        );
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lanes.ron");
        match load_str(&path, &text, &Overrides::default()) {
            Ok(l) => l.scene,
            Err(e) => panic!("lanes scene: {e}"),
        }
    };
    let lanes = scene("");
    assert!(lanes.lanes.is_some(), "five spheres and quads go into lanes");
    let mut bvh = scene("");
    bvh.lanes = None;
    let many: String = (0..9)
        .map(|i| format!("Sphere(center: ({i}, 5, 0), radius: 0.1, material: \"a\"),"))
        .collect();
    assert!(scene(&many).lanes.is_none(), "more than eight spheres: the BVH");
    let mut rng = Pcg32::new(11, 3);
    let mut hits = 0;
    for i in 0..20000 {
        let o = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 6.0 - 3.0;
        let ray = Ray::new(o, sampling::uniform_sphere(rng.next_vec2()));
        let t_max = if i % 3 == 0 { 2.0 } else { f32::INFINITY };
        let (a, b) = (lanes.intersect(&ray, t_max), bvh.intersect(&ray, t_max));
        let bits = |h: &ronray::geometry::Hit| {
            (
                h.t.to_bits(),
                h.p.to_array().map(f32::to_bits),
                h.ng.to_array().map(f32::to_bits),
            )
        };
        assert_eq!(a.is_some(), b.is_some(), "ray {i}");
        if let (Some(a), Some(b)) = (&a, &b) {
            assert_eq!(bits(a), bits(b), "ray {i}");
            assert_eq!(
                (a.material, a.uv.to_array()),
                (b.material, b.uv.to_array()),
                "ray {i}"
            );
            hits += 1;
        }
        assert_eq!(lanes.occluded(&ray, t_max), bvh.occluded(&ray, t_max), "ray {i}");
    }
    assert!(hits > 8000, "the rays reach the shapes: {hits}");
}

/// A ground plane exported as a grid of triangles: up to 256 triangles
/// (`FLATTEN_MAX`) a baked mesh goes into the scene BVH triangle by triangle
/// (a 10 × 10 grid, 200), beyond it the mesh keeps its instance (a 12 × 12
/// grid, 288); both answer rays as the same grid placed by `Instance`.
#[test]
fn grid_floors_are_flattened_up_to_256_triangles_and_match_their_instance() {
    use ronray::geometry::Shape;
    use ronray::load::{Overrides, load_str};
    let dir = tempfile::tempdir().expect("temp dir");
    for (n, flattened) in [(10usize, true), (12, false)] {
        let mut obj = String::new();
        for j in 0..=n {
            for i in 0..=n {
                obj.push_str(&format!(
                    "v {} {} 0\n",
                    -1.0 + 2.0 * i as f32 / n as f32,
                    -1.0 + 2.0 * j as f32 / n as f32
                ));
            }
        }
        for j in 0..n {
            for i in 0..n {
                let a = 1 + j * (n + 1) + i;
                obj.push_str(&format!(
                    "f {} {} {}\nf {} {} {}\n",
                    a,
                    a + 1,
                    a + n + 2,
                    a,
                    a + n + 2,
                    a + n + 1
                ));
            }
        }
        std::fs::write(dir.path().join("grid.obj"), obj).expect("obj");
        let scene = |object: &str| {
            let text = format!(
                r#"Scene(
                    camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
                    materials: {{"white": Lambert(albedo: (0.8, 0.8, 0.8))}},
                    meshes: {{"grid": (file: "grid.obj")}},
                    lights: [Point(position: (0, 0, 2), intensity: (1, 1, 1))],
                    objects: [{object}],
                )"#
            );
            load_str(&dir.path().join("grid.ron"), &text, &Overrides::default())
                .unwrap_or_else(|e| panic!("grid scene: {e}"))
                .scene
        };
        let flat = scene(r#"Mesh(file: "grid.obj", material: "white")"#);
        let inst = scene(r#"Instance(mesh: "grid", material: "white")"#);
        let in_top = flat
            .shapes
            .iter()
            .filter(|s| matches!(s, Shape::Triangle(_) | Shape::MeshQuad(_)))
            .count();
        assert_eq!(
            in_top > 0,
            flattened,
            "{} triangles: in the scene BVH: {in_top}",
            2 * n * n
        );
        let mut rng = Pcg32::new(9, 1);
        let mut hits = 0;
        for i in 0..3000 {
            let o = Vec3A::new(rng.next_f32() * 2.4 - 1.2, rng.next_f32() * 2.4 - 1.2, 1.0);
            let ray = Ray::new(
                o,
                (Vec3A::new(0.0, 0.0, -1.0) + 0.5 * sampling::uniform_sphere(rng.next_vec2())).normalize(),
            );
            let (a, b) = (
                flat.intersect(&ray, f32::INFINITY),
                inst.intersect(&ray, f32::INFINITY),
            );
            assert_eq!(a.is_some(), b.is_some(), "{n}: ray {i}");
            if let (Some(a), Some(b)) = (a, b) {
                assert!((a.t - b.t).abs() <= 1e-5 * a.t, "{n}: ray {i}: t {} {}", a.t, b.t);
                assert!((a.p - b.p).length() < 1e-6 && a.ng == b.ng && a.material == b.material);
                hits += 1;
            }
        }
        assert!(hits > 1000, "{n}: the rays reach the grid: {hits}");
    }
}
