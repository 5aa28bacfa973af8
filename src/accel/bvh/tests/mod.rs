//! BVH against brute force, structure checks and degenerate inputs. The
//! primitives are triangles with a test-only Möller–Trumbore intersector; the
//! BVH itself never sees them.

use glam::{Vec2, Vec3A};

use super::build::MAX_LEAF;
use super::{Bvh, MAX_DEPTH};
use crate::accel::Aabb;
use crate::math::sampling::uniform_sphere;
use crate::math::{Pcg32, Ray};

#[derive(Clone, Copy, Debug)]
pub(crate) struct Tri(pub [Vec3A; 3]);

impl Tri {
    pub(crate) fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.0)
    }

    /// Möller & Trumbore 1997, <https://doi.org/10.1080/10867651.1997.10487468>.
    pub(crate) fn hit(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let [v0, v1, v2] = self.0;
        let (e1, e2) = (v1 - v0, v2 - v0);
        let p = ray.d.cross(e2);
        let det = e1.dot(p);
        if det == 0.0 {
            return None;
        }
        let inv = 1.0 / det;
        let s = ray.o - v0;
        let u = s.dot(p) * inv;
        if !(0.0..=1.0).contains(&u) {
            return None;
        }
        let q = s.cross(e1);
        let v = ray.d.dot(q) * inv;
        if v < 0.0 || u + v > 1.0 {
            return None;
        }
        let t = e2.dot(q) * inv;
        (t > 0.0 && t < t_max).then_some(t)
    }
}

fn rand3(rng: &mut Pcg32) -> Vec3A {
    Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32())
}

/// Triangles with centres in `[-1, 1]³ · scale + offset`, mostly small, some
/// large; `flat` puts every vertex on z = offset.z.
pub(crate) fn soup(seed: u64, n: usize, scale: f32, offset: Vec3A, flat: bool) -> Vec<Tri> {
    let mut rng = Pcg32::new(seed, 1);
    (0..n)
        .map(|i| {
            let c = (2.0 * rand3(&mut rng) - 1.0) * scale;
            let size = if i % 17 == 0 { 0.5 } else { 0.1 } * scale;
            let mut v = [0; 3].map(|_| c + (2.0 * rand3(&mut rng) - 1.0) * size);
            if flat {
                v.iter_mut().for_each(|p| p.z = 0.0);
            }
            Tri(v.map(|p| p + offset))
        })
        .collect()
}

/// Origins in the scene bounds grown by half their size, uniform directions.
pub(crate) fn rays(seed: u64, n: usize, tris: &[Tri]) -> Vec<Ray> {
    let b = tris.iter().fold(Aabb::EMPTY, |b, t| b.union(t.bounds()));
    let (c, e) = (b.centroid(), b.extent().max(Vec3A::splat(1e-3)));
    let mut rng = Pcg32::new(seed, 2);
    (0..n)
        .map(|_| {
            let o = c + (2.0 * rand3(&mut rng) - 1.0) * e;
            Ray::new(o, uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32())))
        })
        .collect()
}

fn build(tris: &[Tri]) -> Bvh {
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let bvh = Bvh::build(&bounds);
    check_structure(&bvh, &bounds);
    bvh
}

pub(crate) fn brute(tris: &[Tri], ray: &Ray, t_max: f32) -> Option<(u32, f32)> {
    let mut best = None;
    let mut t_best = t_max;
    for (i, tri) in tris.iter().enumerate() {
        if let Some(t) = tri.hit(ray, t_best) {
            t_best = t;
            best = Some((i as u32, t));
        }
    }
    best
}

/// Closest hits agree. With `ties`, a different primitive is accepted when it
/// is hit at the same distance (coincident or coplanar primitives).
fn assert_matches_brute_force(what: &str, tris: &[Tri], rays: &[Ray], ties: bool) {
    let bvh = build(tris);
    let mut hits = 0;
    for (k, ray) in rays.iter().enumerate() {
        let want = brute(tris, ray, f32::INFINITY);
        let got = bvh.intersect(ray, f32::INFINITY, |i, r, t| tris[i as usize].hit(r, t));
        let ok = match (want, got) {
            (None, None) => true,
            (Some((wi, wt)), Some((gi, gt))) => {
                (gt - wt).abs() <= 1e-6 * wt.abs().max(gt.abs()) && (wi == gi || ties)
            }
            _ => false,
        };
        assert!(
            ok,
            "{what}, ray {k} {ray:?}: expected (prim, t) = {want:?}, got {got:?}"
        );
        hits += want.is_some() as usize;
    }
    if tris.len() >= 1000 && rays.len() >= 1000 {
        assert!(
            hits > rays.len() / 20,
            "{what}: only {hits} of {} rays hit; the test is vacuous",
            rays.len()
        );
    }
}

fn assert_occluded_matches_brute_force(what: &str, tris: &[Tri], rays: &[Ray]) {
    let bvh = build(tris);
    for (k, ray) in rays.iter().enumerate() {
        for t_max in [f32::INFINITY, 0.3, 1.0] {
            let want = tris.iter().any(|tri| tri.hit(ray, t_max).is_some());
            let got = bvh.occluded(ray, t_max, |i, r, t| tris[i as usize].hit(r, t).is_some());
            assert_eq!(
                got, want,
                "{what}, ray {k} {ray:?}, t_max {t_max}: expected occluded = {want}, got {got}"
            );
        }
    }
}

/// Every non-empty primitive exactly once, parents contain children, leaves
/// contain their primitives, leaves are small, depth is within the stack.
fn check_structure(bvh: &Bvh, bounds: &[Aabb]) {
    assert_eq!(
        bvh.len(),
        bounds.len(),
        "len: expected {}, got {}",
        bounds.len(),
        bvh.len()
    );
    let mut seen = vec![0u32; bounds.len()];
    let mut visited = 0;
    let mut stack = if bvh.nodes.is_empty() {
        vec![]
    } else {
        vec![(0usize, 0u32)]
    };
    while let Some((i, depth)) = stack.pop() {
        visited += 1;
        let n = bvh.nodes[i];
        let nb = n.bounds();
        assert!(
            depth <= MAX_DEPTH,
            "node {i}: depth {depth} exceeds MAX_DEPTH {MAX_DEPTH}"
        );
        if n.is_leaf() {
            assert!(
                n.count as usize <= MAX_LEAF,
                "leaf {i}: expected ≤ {MAX_LEAF} prims, got {}",
                n.count
            );
            for &p in &bvh.indices[n.offset as usize..(n.offset + n.count) as usize] {
                seen[p as usize] += 1;
                let pb = bounds[p as usize];
                assert!(
                    nb.contains(&pb),
                    "leaf {i} {nb:?} does not contain prim {p} {pb:?}"
                );
            }
        } else {
            let (l, r) = (i + 1, n.offset as usize);
            assert!(
                r > l && r < bvh.nodes.len(),
                "node {i}: second child {r} out of order/range"
            );
            for c in [l, r] {
                let cb = bvh.nodes[c].bounds();
                assert!(
                    nb.contains(&cb),
                    "node {i} {nb:?} does not contain child {c} {cb:?}"
                );
                stack.push((c, depth + 1));
            }
        }
    }
    assert_eq!(
        visited,
        bvh.nodes.len(),
        "expected every node reachable once, visited {visited}"
    );
    for (p, (&count, b)) in seen.iter().zip(bounds).enumerate() {
        let want = !b.is_empty() as u32;
        assert_eq!(
            count, want,
            "prim {p} ({b:?}): expected in {want} leaves, found in {count}"
        );
    }
}

#[test]
fn bvh_matches_brute_force() {
    for (seed, n) in [1, 2, 10, 1000, 5000].into_iter().enumerate() {
        let tris = soup(seed as u64, n, 1.0, Vec3A::ZERO, false);
        assert_matches_brute_force(
            &format!("{n} triangles"),
            &tris,
            &rays(seed as u64, 3000, &tris),
            false,
        );
    }
}

#[test]
fn bvh_occluded_matches_brute_force() {
    for (seed, n) in [1, 2, 10, 1000, 5000].into_iter().enumerate() {
        let tris = soup(100 + seed as u64, n, 1.0, Vec3A::ZERO, false);
        assert_occluded_matches_brute_force(
            &format!("{n} triangles"),
            &tris,
            &rays(seed as u64, 2000, &tris),
        );
    }
}

#[test]
fn bvh_structure_is_consistent() {
    for n in [1, 3, 5, 17, 100, 20_000] {
        build(&soup(n as u64, n, 1.0, Vec3A::ZERO, false));
    }
}

/// Builds the BVH over `n` random triangles on 1 and on `threads` threads
/// and checks both trees are the same, node for node.
fn assert_same_tree_on(threads: usize, seed: u64, n: usize) {
    let tris = soup(seed, n, 1.0, Vec3A::ZERO, false);
    let bounds: Vec<Aabb> = tris.iter().map(Tri::bounds).collect();
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| Bvh::build(&bounds))
    };
    let (a, b) = (on(1), on(threads));
    assert!(
        a.nodes == b.nodes && a.indices == b.indices,
        "1 and {threads} threads built different trees: {:?} vs {:?}",
        a.stats(),
        b.stats()
    );
    check_structure(&a, &bounds);
}

#[test]
fn bvh_build_is_deterministic() {
    assert_same_tree_on(3, 7, 50_000);
}

#[test]
fn bvh_top_levels_are_identical_on_1_and_2_threads() {
    // Over 2^16 references, so the root's binning and partition run over
    // parallel chunks; the tree must not depend on how they were scheduled.
    assert_same_tree_on(2, 8, 150_000);
}

#[test]
fn bvh_stats_are_plausible() {
    let tris = soup(10, 10_000, 1.0, Vec3A::ZERO, false);
    let bvh = build(&tris);
    let s = bvh.stats();
    assert_eq!(
        s.nodes,
        2 * s.leaves - 1,
        "binary tree: expected nodes = 2·leaves − 1, got {s:?}"
    );
    assert_eq!(s.bytes, 32 * s.nodes + 4 * tris.len(), "bytes: got {s:?}");
    // Every primitive is tested whenever its leaf is entered, and its leaf is
    // at least as big as it: Σ A(prim) / A(root) bounds the cost from below.
    // Interior nodes add ~n^(1/3) for small primitives in a cube; one big
    // leaf would cost n.
    let lower: f32 =
        tris.iter().map(|t| t.bounds().surface_area()).sum::<f32>() / bvh.bounds().surface_area();
    let upper = 0.02 * tris.len() as f32;
    assert!(
        s.sah_cost >= lower && s.sah_cost < upper,
        "SAH cost: expected in [{lower}, {upper}], got {s:?}"
    );
}

mod degenerate;
mod throughput;
