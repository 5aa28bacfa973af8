//! Degenerate inputs: empty, single, flat, coincident, huge, deep, and rays
//! with zero direction components.

use super::*;

#[test]
fn bvh_empty_has_no_hits() {
    for bounds in [vec![], vec![Aabb::EMPTY; 3]] {
        let bvh = Bvh::build(&bounds);
        check_structure(&bvh, &bounds);
        let ray = Ray::new(Vec3A::ZERO, Vec3A::Z);
        let got = bvh.intersect(&ray, f32::INFINITY, |i, _, _| {
            panic!("closure called for prim {i}")
        });
        assert_eq!(got, None, "{} prims: expected no hit, got {got:?}", bounds.len());
        assert!(
            !bvh.occluded(&ray, f32::INFINITY, |_, _, _| true),
            "expected unoccluded"
        );
        assert_eq!(bvh.bounds(), Aabb::EMPTY);
        assert_eq!(bvh.stats().nodes, 0);
    }
    assert!(Bvh::build(&[]).is_empty());
}

#[test]
fn bvh_single_primitive() {
    let tris = soup(3, 1, 1.0, Vec3A::ZERO, false);
    let bvh = build(&tris);
    let (got, want) = (bvh.bounds(), tris[0].bounds());
    assert!(
        got == want.padded(),
        "bounds: expected {want:?} (padded), got {got:?}"
    );
    let s = bvh.stats();
    assert!(
        s.nodes == 1 && s.leaves == 1 && s.sah_cost == 1.0,
        "expected one leaf of cost 1, got {s:?}"
    );
    assert_matches_brute_force("one triangle", &tris, &rays(3, 2000, &tris), false);
}

#[test]
fn bvh_coplanar_triangles() {
    let tris = soup(4, 2000, 1.0, Vec3A::ZERO, true);
    let mut rs = rays(4, 2000, &tris);
    rs.iter_mut()
        .for_each(|r| r.o.z = if r.o.z.abs() < 0.1 { 1.0 } else { r.o.z });
    assert_matches_brute_force("flat in z", &tris, &rs, true);
    assert_occluded_matches_brute_force("flat in z", &tris, &rs);
}

#[test]
fn bvh_identical_centroids() {
    // Triangles (v, -v, 0) and duplicates: every centroid at the origin.
    let mut rng = Pcg32::new(5, 5);
    let mut tris: Vec<Tri> = (0..500)
        .map(|_| {
            let (a, b) = (2.0 * rand3(&mut rng) - 1.0, 2.0 * rand3(&mut rng) - 1.0);
            Tri([a, b, -a - b])
        })
        .collect();
    tris.extend_from_within(..100);
    assert_matches_brute_force("identical centroids", &tris, &rays(5, 2000, &tris), true);
    assert_occluded_matches_brute_force("identical centroids", &tris, &rays(5, 500, &tris));
}

#[test]
fn bvh_huge_coordinates() {
    let tris = soup(6, 3000, 1000.0, Vec3A::splat(1e6), false);
    assert_matches_brute_force("offset 1e6", &tris, &rays(6, 3000, &tris), false);
    assert_occluded_matches_brute_force("offset 1e6", &tris, &rays(6, 500, &tris));
}

#[test]
fn bvh_depth_is_bounded() {
    // Exponentially spaced boxes: SAH peels a few off per level and goes
    // ~32 deep; a budget of 12 (ceil(log2 300) = 9, plus slack) must hold.
    const LIMIT: u32 = 12;
    let tris: Vec<Tri> = (0..300)
        .map(|i| {
            let x = 1.3f32.powi(i);
            Tri([
                Vec3A::new(x, 0.0, 0.0),
                Vec3A::new(x * 1.01, 1.0, 0.0),
                Vec3A::new(x, 0.0, 1.0),
            ])
        })
        .collect();
    let natural = build(&tris).stats();
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let (nodes, indices) = super::super::build::build_with_max_depth(&bounds, LIMIT);
    let bvh = Bvh {
        nodes,
        indices,
        len: bounds.len(),
    };
    check_structure(&bvh, &bounds);
    let s = bvh.stats();
    assert!(
        natural.max_depth > LIMIT && s.max_depth <= LIMIT,
        "expected unlimited depth > {LIMIT} and limited ≤ {LIMIT}, got {natural:?} and {s:?}"
    );
    let rs: Vec<Ray> = tris
        .iter()
        .map(|t| Ray::new(t.0[0] + Vec3A::new(0.0, 0.2, 0.2) - Vec3A::Z * 5.0, Vec3A::Z))
        .collect();
    assert_matches_brute_force("exponential spacing", &tris, &rs, false);
    for (k, ray) in rs.iter().enumerate() {
        let want = brute(&tris, ray, f32::INFINITY);
        let got = bvh.intersect(ray, f32::INFINITY, |i, r, t| tris[i as usize].hit(r, t));
        assert_eq!(
            got, want,
            "depth-limited tree, ray {k}: expected {want:?}, got {got:?}"
        );
    }
}

#[test]
fn bvh_axis_parallel_rays() {
    let mut tris = soup(8, 1000, 1.0, Vec3A::ZERO, false);
    tris.extend(soup(9, 1000, 1.0, Vec3A::new(0.0, 0.0, 0.5), true));
    let dirs = [
        [1.0, 0.0, 0.0],
        [-1.0, -0.0, 0.0],
        [0.0, 1.0, -0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [-0.0, 0.0, -1.0],
        [1.0, 1.0, 0.0],
        [0.0, -1.0, 1.0],
    ];
    let mut rng = Pcg32::new(8, 8);
    let mut rs = Vec::new();
    for d in dirs {
        let d = Vec3A::from_array(d).normalize();
        for k in 0..400 {
            let mut o = 2.4 * rand3(&mut rng) - 1.2;
            if k % 2 == 0 {
                // Origin on the slab planes of a random primitive's box, on
                // the axes the ray does not move along.
                let b = tris[rng.next_u32() as usize % tris.len()].bounds();
                let corner = if k % 4 == 0 { b.min } else { b.max };
                o = Vec3A::select(d.cmpeq(Vec3A::ZERO), corner, o);
            }
            rs.push(Ray::new(o, d));
        }
    }
    assert_matches_brute_force("axis-parallel", &tris, &rs, true);
    assert_occluded_matches_brute_force("axis-parallel", &tris, &rs);
}

/// Boxes that are no boxes (a NaN or an infinite vertex) are left out of
/// the tree: one NaN among the centroid bounds once put a centroid below
/// its node's minimum and a bin index past the end (the `gltf` fuzz target,
/// a NaN vertex in a 12-triangle cube). The finite ones are found as before.
#[test]
fn bvh_leaves_out_bounds_that_are_not_finite() {
    let good = soup(7, 300, 1.0, Vec3A::ZERO, false);
    let mut bounds: Vec<Aabb> = good.iter().map(Tri::bounds).collect();
    let bad = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY];
    for (k, &x) in bad.iter().cycle().take(30).enumerate() {
        let mut b = bounds[k * 7];
        // A NaN at the min on one axis, as `min` of a NaN vertex gives.
        b.min[k % 3] = x;
        bounds.insert(k * 11, b);
    }
    let bvh = Bvh::build(&bounds);
    let ids: Vec<usize> = {
        let mut g = 0;
        let mut map = Vec::new();
        for b in &bounds {
            let finite = b.min.is_finite() && b.max.is_finite();
            map.push(if finite {
                g += 1;
                g - 1
            } else {
                usize::MAX
            });
        }
        map
    };
    for ray in rays(7, 1000, &good) {
        let want = brute(&good, &ray, f32::INFINITY);
        let got = bvh.intersect(&ray, f32::INFINITY, |i, r, t| {
            let g = ids[i as usize];
            assert_ne!(g, usize::MAX, "primitive {i} has bounds that are not finite");
            good[g].hit(r, t)
        });
        assert_eq!(got.map(|(_, t)| t), want.map(|(_, t)| t), "{ray:?}");
    }
}
