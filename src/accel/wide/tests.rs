//! The wide tree against brute force and its structure, on the binary
//! tree's test soups and degenerate inputs.

use super::{EMPTY, LEAF, Leaves, MAX_LEAF, WIDTH, WideBvh, leaf_range};
use crate::accel::Aabb;
use crate::accel::bvh::tests::{Tri, brute, rays, soup};
use crate::math::Ray;
use glam::Vec3A;

fn build_with(tris: &[Tri], leaves: Leaves) -> WideBvh {
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let bvh = WideBvh::build_with(&bounds, leaves);
    check_structure(&bvh, &bounds);
    let largest = bvh.leaves().map(|(_, c)| c).max().unwrap_or(0);
    match leaves {
        Leaves::Merged => assert!(largest <= MAX_LEAF, "leaf of {largest}"),
        Leaves::Single => assert!(largest <= 1, "leaf of {largest} in a one-per-leaf tree"),
    }
    bvh
}

/// Every child box contains its subtree; every non-empty primitive is in
/// exactly one leaf slot; empty lanes have no child.
fn check_structure(bvh: &WideBvh, bounds: &[Aabb]) {
    let mut seen = vec![0u32; bvh.order().len()];
    let mut stack = vec![0u32];
    while let Some(n) = stack.pop() {
        let node = &bvh.nodes[n as usize];
        for lane in 0..WIDTH {
            let r = node.child[lane];
            if r == EMPTY {
                continue;
            }
            let b = node.child_bounds(lane);
            if r & LEAF != 0 {
                let (first, count) = leaf_range(r);
                for slot in first..first + count {
                    seen[slot as usize] += 1;
                    let prim = bvh.order()[slot as usize] as usize;
                    assert!(
                        b.contains(&bounds[prim]),
                        "leaf box {b:?} misses primitive {prim}"
                    );
                }
            } else {
                let child = &bvh.nodes[r as usize];
                for l in (0..WIDTH).filter(|&l| child.child[l] != EMPTY) {
                    assert!(
                        b.contains(&child.child_bounds(l)),
                        "node {r} escapes its parent box"
                    );
                }
                stack.push(r);
            }
        }
    }
    assert!(
        seen.iter().all(|&c| c == 1),
        "each leaf slot is used exactly once"
    );
    let live = bounds.iter().filter(|b| !b.is_empty()).count();
    assert_eq!(
        bvh.order().len(),
        live,
        "every non-empty primitive is in the tree"
    );
}

fn closest(bvh: &WideBvh, tris: &[Tri], ray: &Ray) -> Option<(u32, f32)> {
    let mut best = None;
    bvh.intersect(ray, f32::INFINITY, |first, count, t_max| {
        let mut t_best = t_max;
        let mut hit = None;
        for slot in first..first + count {
            let prim = bvh.order()[slot as usize];
            if let Some(t) = tris[prim as usize].hit(ray, t_best) {
                t_best = t;
                hit = Some(t);
                best = Some((prim, t));
            }
        }
        hit
    });
    best
}

fn assert_matches(what: &str, tris: &[Tri], rays: &[Ray]) {
    assert_matches_with(what, tris, rays, Leaves::Merged);
    assert_matches_with(what, tris, rays, Leaves::Single);
}

fn assert_matches_with(what: &str, tris: &[Tri], rays: &[Ray], leaves: Leaves) {
    let bvh = build_with(tris, leaves);
    for (i, ray) in rays.iter().enumerate() {
        let got = closest(&bvh, tris, ray);
        let want = brute(tris, ray, f32::INFINITY);
        match (got, want) {
            (None, None) => {}
            (Some((gp, gt)), Some((wp, wt))) => assert!(
                gt == wt && (gp == wp || tris[gp as usize].hit(ray, f32::INFINITY) == Some(wt)),
                "{what}, ray {i}: WideBvh gave ({gp}, {gt}), brute force ({wp}, {wt})"
            ),
            _ => panic!("{what}, ray {i}: WideBvh gave {got:?}, brute force {want:?}"),
        }
        let occ = bvh.occluded(ray, f32::INFINITY, |first, count, tm| {
            (first..first + count).any(|s| tris[bvh.order()[s as usize] as usize].hit(ray, tm).is_some())
        });
        assert_eq!(occ, want.is_some(), "{what}, ray {i}: occlusion disagrees");
    }
}

#[test]
fn wide_bvh_matches_brute_force() {
    for (seed, n) in [(1, 1), (2, 3), (3, 5), (4, 100), (5, 2000)] {
        let tris = soup(seed, n, 1.0, Vec3A::ZERO, false);
        assert_matches(&format!("soup of {n}"), &tris, &rays(seed, 2000, &tris));
    }
}

#[test]
fn wide_bvh_degenerate_inputs() {
    let empty = WideBvh::build(&[]);
    assert!(
        empty
            .intersect(&Ray::new(Vec3A::ZERO, Vec3A::X), f32::INFINITY, |_, _, _| Some(
                0.0
            ))
            .is_none()
    );
    assert_eq!(empty.bounds(), Aabb::EMPTY);
    let flat = soup(7, 500, 1.0, Vec3A::ZERO, true);
    assert_matches("coplanar", &flat, &rays(7, 2000, &flat));
    let huge = soup(8, 500, 1e18, Vec3A::splat(3e18), false);
    assert_matches("huge", &huge, &rays(8, 2000, &huge));
    let same = vec![Tri([Vec3A::ZERO, Vec3A::X, Vec3A::Y]); 9];
    assert_matches("identical", &same, &rays(9, 500, &same));
    let mut with_empty: Vec<Aabb> = same.iter().map(Tri::bounds).collect();
    with_empty.push(Aabb::EMPTY);
    let bvh = WideBvh::build(&with_empty);
    check_structure(&bvh, &with_empty);
}

/// The binary build leaves subtrees of at most `MAX_LEAF` unsplit, since
/// the collapse merges them anyway: the wide tree must be the one collapsed
/// from the fully split binary tree, node for node, with the same primitives
/// in each leaf (their order inside it may differ). 70,000 triangles cross
/// the chunked-partition threshold.
#[test]
fn unsplit_merged_subtrees_give_the_same_wide_tree() {
    for (seed, n) in [(3, 3_000), (4, 70_000)] {
        let tris = soup(seed, n, 1.0, Vec3A::ZERO, false);
        let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
        let (binary, full_order) = crate::accel::bvh::build_nodes(&bounds, 4, 1);
        let full = super::collapse::collapse(&binary, Leaves::Merged);
        let fast = WideBvh::build(&bounds);
        assert_eq!(full.len(), fast.nodes.len(), "node count, seed {seed}");
        for (i, (a, b)) in full.iter().zip(&fast.nodes).enumerate() {
            assert!(a.b == b.b && a.child == b.child, "node {i} differs, seed {seed}");
        }
        for (first, count) in fast.leaves() {
            let range = first as usize..(first + count) as usize;
            let mut a = full_order[range.clone()].to_vec();
            let mut b = fast.order()[range].to_vec();
            a.sort_unstable();
            b.sort_unstable();
            assert_eq!(a, b, "leaf at slot {first} holds other primitives");
        }
        let s = fast.stats();
        assert!(s.leaves == fast.leaves().count() && s.sah_cost > 0.0, "{s:?}");
    }
}

/// The wide build (unsplit merged subtrees, chunked partition with its
/// scratch array, parallel collapse of subtrees over 2^14 primitives) gives
/// the same tree and leaf order on 1 and 2 threads. 150,000 triangles put
/// the top levels through every parallel path.
#[test]
fn wide_bvh_is_identical_on_1_and_2_threads() {
    let tris = soup(9, 150_000, 1.0, Vec3A::ZERO, false);
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("thread pool");
        pool.install(|| WideBvh::build(&bounds))
    };
    let (a, b) = (on(1), on(2));
    assert_eq!(a.nodes.len(), b.nodes.len(), "node count");
    assert!(
        a.nodes
            .iter()
            .zip(&b.nodes)
            .all(|(x, y)| x.b == y.b && x.child == y.child),
        "1 and 2 threads built different nodes"
    );
    assert_eq!(a.order(), b.order(), "leaf order");
    check_structure(&a, &bounds);
}
