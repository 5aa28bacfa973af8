//! Two triangles of a small baked mesh that share an edge, as one entry of
//! the scene BVH: an OBJ quad, split in two by the loader.
//!
//! The two halves of a planar quad usually have the same box (always for a
//! rectangle along the axes: each half holds a diagonal), so as separate
//! entries a ray that meets the box tests both, each with its own setup,
//! and the tree has twice the leaves. As one entry the four corners are
//! moved and sheared once and both edge-function sets come out of one
//! vector product ([`WatertightRay4::pair`]), bit for bit what the two
//! triangle tests give. On the reference Cornell box as one OBJ (36
//! triangles, `bench/cornell_mesh`) the flattened triangles became 18
//! pairs; the instruction counts are in `docs/benchmarks.md`.
//!
//! The loader pairs triangles that are nearly coplanar, share an edge, are
//! wound alike and whose joint box is no larger in surface area than their
//! two boxes together — the condition under which one entry cannot cost
//! more traversal than two.

use super::flat_shade::FlatShade;
use super::triangle::WatertightRay4;
use super::{Geometry, Hit, MeshHit};
use crate::accel::Aabb;
use crate::math::Ray;
use glam::{Vec2, Vec3A, Vec4};

/// Bits of [`MeshQuad::tris`] that hold the triangle index; the top two
/// hold the rotation between the mesh's corner order and the pair's.
const INDEX: u32 = (1 << 30) - 1;

/// Two triangles `(v0, v1, v2)` and `(v0, v2, v3)` of one placed mesh.
#[derive(Clone, Copy, Debug)]
pub struct MeshQuad {
    /// World-space corners v0…v3, one row per axis: the layout of
    /// [`WatertightRay4::pair`].
    rows: [Vec4; 3],
    /// The instance that shades it.
    pub instance: u32,
    /// The mesh's index of each triangle (low 30 bits) and the rotation
    /// `r` of its corners (top 2 bits): the mesh's corner `(k + r) mod 3`
    /// is the pair's `k`-th corner of that triangle.
    tris: [u32; 2],
    /// Each triangle's whole shading record when the mesh has neither
    /// vertex normals nor UVs (`flat_shade.rs`); `None`: through the
    /// instance.
    flat: Option<[FlatShade; 2]>,
}

impl MeshQuad {
    /// The pair whose first triangle is mesh triangle `tris[0]` with its
    /// corners rotated by `rot[0]` to `(v0, v1, v2)`, the second `tris[1]`
    /// rotated by `rot[1]` to `(v0, v2, v3)`. `None` when an index does not
    /// fit in 30 bits (flattened meshes are small: never in practice).
    pub fn new(v: [Vec3A; 4], instance: u32, tris: [u32; 2], rot: [u32; 2]) -> Option<Self> {
        if tris.iter().any(|&t| t > INDEX) || rot.iter().any(|&r| r > 2) {
            return None;
        }
        Some(Self {
            rows: [0, 1, 2].map(|a| Vec4::new(v[0][a], v[1][a], v[2][a], v[3][a])),
            instance,
            tris: [tris[0] | rot[0] << 30, tris[1] | rot[1] << 30],
            flat: None,
        })
    }

    /// This pair shaded from `flat` alone (triangle `k`'s record
    /// `flat[k]`), which must be what its instance gives (a static,
    /// untransformed mesh without vertex normals or UVs).
    pub fn with_flat(self, flat: [FlatShade; 2]) -> Self {
        Self {
            flat: Some(flat),
            ..self
        }
    }

    /// The corners of triangle `k` (0 or 1) in its mesh's order.
    #[inline]
    pub fn mesh_corners(&self, k: u32) -> [Vec3A; 3] {
        let r = (self.tris[k as usize & 1] >> 30) as usize;
        // Read straight from the rows by a table: transposing all four
        // corners, then rotating three through the stack by `(m − r) mod 3`
        // cost ~20 instructions a hit (2% of the Cornell box as one OBJ,
        // callgrind).
        let [x, y, z]: [&[f32; 4]; 3] = [0, 1, 2].map(|a| self.rows[a].as_ref());
        // `& 3`: within the rows' four lanes, which the compiler can see
        // (the table's entries are, but it checked each of them).
        MESH_CORNERS[k as usize & 1][r.min(2)].map(|i| Vec3A::new(x[i & 3], y[i & 3], z[i & 3]))
    }

    /// World-space corners v0…v3.
    pub fn corners(&self) -> [Vec3A; 4] {
        [0, 1, 2, 3].map(|v| Vec3A::new(self.rows[0][v], self.rows[1][v], self.rows[2][v]))
    }

    /// Mesh index of triangle `k` (0 or 1) of the pair.
    pub fn tri(&self, k: usize) -> u32 {
        self.tris[k] & INDEX
    }

    /// Watertight intersection in `(0, t_max)`: distance, which triangle,
    /// and the barycentrics of its second and third corners in the pair's
    /// order.
    #[inline(always)]
    pub fn intersect(&self, wt: &WatertightRay4, t_max: f32) -> Option<(f32, u32, Vec2)> {
        wt.pair(&self.rows, t_max)
    }

    /// Shading record for a hit of triangle `k` found by
    /// [`MeshQuad::intersect`]: the barycentrics are turned back to the
    /// mesh's corner order, so normals and UVs interpolate as for a
    /// triangle hit on its own.
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, t: f32, k: u32, bc: Vec2, geo: &Geometry) -> Hit {
        let mut out = Hit::default();
        self.hit_into(ray, t, k, bc, geo, &mut out);
        out
    }

    /// [`MeshQuad::hit`] written into `out` (see [`FlatShade::hit_into`]).
    /// Inline: a record returned from a call is copied out of the callee's
    /// stores by wider loads, a store-forwarding stall.
    #[inline(always)]
    pub fn hit_into(&self, ray: &Ray, t: f32, k: u32, bc: Vec2, geo: &Geometry, out: &mut Hit) {
        match &self.flat {
            Some(f) => f[k as usize & 1].hit_into(self.mesh_corners(k), t, self.mesh_hit(t, k, bc).bc, out),
            None => *out = self.hit_through_instance(ray, t, k, bc, geo),
        }
    }

    #[inline(never)]
    fn hit_through_instance(&self, ray: &Ray, t: f32, k: u32, bc: Vec2, geo: &Geometry) -> Hit {
        let h = self.mesh_hit(t, k, bc);
        geo.instances[self.instance as usize].hit(ray, h, &geo.meshes)
    }

    /// The hit of triangle `k` as a hit of the mesh's own triangle, with
    /// barycentrics in the mesh's corner order.
    #[inline]
    pub fn mesh_hit(&self, t: f32, k: u32, bc: Vec2) -> MeshHit {
        let packed = self.tris[k as usize & 1];
        MeshHit {
            t,
            tri: packed & INDEX,
            bc: to_mesh_order(packed >> 30, bc),
        }
    }

    /// World-space bounds of the four corners.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(&self.corners())
    }
}

/// Barycentrics `(b1, b2)` of a triangle's corners `k = 1, 2` in the
/// pair's order, as those of the mesh's corners 1 and 2 when the mesh's
/// corner `(k + r) mod 3` is the pair's `k`-th.
#[inline]
fn to_mesh_order(r: u32, bc: Vec2) -> Vec2 {
    // Mesh corner m is the pair's corner (m − r) mod 3: the weights of
    // corners (1, 2) are the pair's (0, 1) for r = 1, (2, 0) for r = 2.
    // By a table, not a branch: which rotation a hit's triangle has is
    // a coin flip from one hit to the next, and a `match` on it was
    // mispredicted 140 k times in the OBJ room's 65 k samples (callgrind's
    // branch model, 64², 16 spp).
    // Four weights and `& 3`, so neither read needs a bounds check; the
    // table a constant, not rebuilt on the stack at every hit.
    const PICK: [[u8; 2]; 3] = [[1, 2], [0, 1], [2, 0]];
    let b = [1.0 - bc.x - bc.y, bc.x, bc.y, 0.0];
    let [i, j] = PICK[(r as usize).min(2)];
    Vec2::new(b[usize::from(i) & 3], b[usize::from(j) & 3])
}

/// The pair's corner (0 to 3) that is mesh corner `m` of triangle `k`
/// rotated by `r`: `MESH_CORNERS[k][r][m]`. Triangle 0 is the pair's
/// corners (0, 1, 2), triangle 1 its (0, 2, 3); mesh corner m is the
/// triangle's corner (m − r) mod 3.
const MESH_CORNERS: [[[usize; 3]; 3]; 2] = [
    [[0, 1, 2], [2, 0, 1], [1, 2, 0]],
    [[0, 2, 3], [3, 0, 2], [2, 3, 0]],
];

/// How to pair triangles `a` and `b` (corners in the mesh's order) as
/// `(v0, v1, v2)` and `(v0, v2, v3)`: the four corners and each
/// triangle's rotation, when they are nearly coplanar, share an edge wound
/// in opposite directions (so their fronts agree) and their joint box is
/// no larger in surface area than their two boxes together.
pub fn pairing(a: [Vec3A; 3], b: [Vec3A; 3]) -> Option<([Vec3A; 4], [u32; 2])> {
    // Nearly coplanar (within ~8°): halves of one face, not a fold of two
    // faces, whose joint box would hold the space between them.
    let normal = |t: &[Vec3A; 3]| (t[1] - t[0]).cross(t[2] - t[0]).normalize_or_zero();
    // (NaN normals of degenerate triangles fail the test too.)
    if normal(&a).dot(normal(&b)).partial_cmp(&0.99) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let area = |t: &[Vec3A]| Aabb::from_points(t).surface_area();
    let joint = [a[0], a[1], a[2], b[0], b[1], b[2]];
    if area(&joint).partial_cmp(&(area(&a) + area(&b))) == Some(std::cmp::Ordering::Greater)
        || !area(&joint).is_finite()
    {
        return None;
    }
    // Rotate `a` so that its edge v2 → v0 is the shared one; `b` must
    // run it v0 → v2.
    for ra in 0..3u32 {
        let v = |k: u32| a[((k + ra) % 3) as usize];
        let (v0, v1, v2) = (v(0), v(1), v(2));
        for rb in 0..3u32 {
            let w = |k: u32| b[((k + rb) % 3) as usize];
            if w(0) == v0 && w(1) == v2 && w(2) != v1 {
                return Some(([v0, v1, v2, w(2)], [ra, rb]));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::flat_shade::FlatShade;
    use crate::geometry::mesh_triangle::MeshTriangle;
    use crate::geometry::{Geometry, Instance, Mesh, NO_LIGHT};
    use crate::math::rng::Pcg32;
    use glam::Affine3A;

    /// Every field of two hit records, bit for bit.
    fn same(a: &Hit, b: &Hit) -> bool {
        let bits = |v: Vec3A| v.to_array().map(f32::to_bits);
        a.t.to_bits() == b.t.to_bits()
            && bits(a.p) == bits(b.p)
            && a.p_error.to_bits() == b.p_error.to_bits()
            && bits(a.ng) == bits(b.ng)
            && bits(a.ns) == bits(b.ns)
            && a.uv.to_array().map(f32::to_bits) == b.uv.to_array().map(f32::to_bits)
            && (a.material, a.light) == (b.material, b.light)
    }

    /// A skewed, non-planar quad far from the origin as two triangles in
    /// two slots (the second emitting), each corner order rotated as an
    /// OBJ file may write it: the flat records give exactly the hits the
    /// instance gives, for the pair and for each triangle on its own.
    #[test]
    fn flat_records_are_the_instances_bit_for_bit() {
        let o = Vec3A::new(123.4, -56.7, 8.9);
        let q = [
            o,
            o + Vec3A::new(1.3, 0.1, -0.02),
            o + Vec3A::new(1.1, 0.9, 0.005),
            o + Vec3A::new(-0.1, 1.2, 0.01),
        ];
        let mut rng = Pcg32::new(7, 3);
        for (ra, rb) in [(0, 0), (1, 2), (2, 1)] {
            let rot = |t: [usize; 3], r: usize| [t[r % 3], t[(r + 1) % 3], t[(r + 2) % 3]];
            let (ta, tb) = (rot([0, 1, 2], ra), rot([0, 2, 3], rb));
            let mut mesh = Mesh::default();
            mesh.positions = q.to_vec();
            mesh.indices = vec![ta.map(|i| i as u32), tb.map(|i| i as u32)];
            mesh.slots = vec![0, 1];
            mesh.slot_count = 2;
            let mut instance = Instance::new(0, Affine3A::IDENTITY, vec![3, 5].into_boxed_slice());
            instance.lights = vec![NO_LIGHT, 7].into_boxed_slice();
            let geo = Geometry {
                meshes: vec![mesh],
                instances: vec![instance],
                sdfs: Vec::new(),
            };
            let corners = |t: [usize; 3]| t.map(|i| q[i]);
            let flat =
                |tri: usize, t: [usize; 3]| FlatShade::new(corners(t), [3, 5][tri], [NO_LIGHT, 7][tri]);
            let (v, rots) = pairing(corners(ta), corners(tb)).expect("the two halves pair");
            let pair = MeshQuad::new(v, 0, [0, 1], rots).expect("small indices");
            let flat_pair = pair.with_flat([flat(0, ta), flat(1, tb)]);
            let singles = [(0, ta), (1, tb)].map(|(tri, t)| {
                let s = MeshTriangle::new(corners(t), 0, tri as u32);
                (s, s.with_flat(flat(tri, t)))
            });
            let ray = Ray::new(o + Vec3A::new(0.5, 0.5, 3.0), Vec3A::NEG_Z);
            for _ in 0..200 {
                let bc = Vec2::new(rng.next_f32(), rng.next_f32()) * 0.5;
                let t = 1.0 + rng.next_f32();
                for k in 0..2 {
                    let (a, b) = (
                        pair.hit(&ray, t, k, bc, &geo),
                        flat_pair.hit(&ray, t, k, bc, &geo),
                    );
                    assert!(
                        same(&a, &b),
                        "pair, rotations ({ra}, {rb}), triangle {k}: {a:?} != {b:?}"
                    );
                    let (s, f) = &singles[k as usize];
                    let (a, b) = (s.hit(&ray, t, bc, &geo), f.hit(&ray, t, bc, &geo));
                    assert!(same(&a, &b), "single triangle {k}: {a:?} != {b:?}");
                }
            }
        }
    }

    #[test]
    fn barycentrics_return_to_the_meshs_corner_order() {
        let m = [Vec3A::ZERO, Vec3A::X, Vec3A::Y];
        let p = |bc: Vec2, t: [Vec3A; 3]| t[0] * (1.0 - bc.x - bc.y) + t[1] * bc.x + t[2] * bc.y;
        for r in 0..3u32 {
            // The pair's corner k is the mesh's (k + r) mod 3.
            let pair_order = [0, 1, 2].map(|k| m[((k + r) % 3) as usize]);
            let bc = Vec2::new(0.2, 0.3);
            let at = p(bc, pair_order);
            let back = to_mesh_order(r, bc);
            assert!((p(back, m) - at).length() < 1e-6, "rotation {r}");
        }
    }

    #[test]
    fn a_fanned_quad_pairs_and_a_fold_or_a_flip_does_not() {
        let q = [Vec3A::ZERO, Vec3A::X, Vec3A::new(1.0, 1.0, 0.0), Vec3A::Y];
        // The fan (0, 1, 2), (0, 2, 3) as an OBJ loader writes it, rotated.
        let a = [q[1], q[2], q[0]];
        let b = [q[2], q[3], q[0]];
        let (v, [ra, rb]) = pairing(a, b).expect("a quad");
        assert_eq!((v[0], v[2]), (q[0], q[2]));
        let corner = |t: [Vec3A; 3], r: u32, k: u32| t[((k + r) % 3) as usize];
        assert_eq!(
            [corner(a, ra, 0), corner(a, ra, 1), corner(a, ra, 2)],
            [v[0], v[1], v[2]]
        );
        assert_eq!(
            [corner(b, rb, 0), corner(b, rb, 1), corner(b, rb, 2)],
            [v[0], v[2], v[3]]
        );
        // The second triangle wound the other way: their fronts disagree.
        assert!(pairing(a, [q[0], q[3], q[2]]).is_none());
        // Folded along the shared edge: two faces of a box.
        assert!(pairing(a, [q[2], Vec3A::new(0.0, 1.0, 1.0), q[0]]).is_none());
        // No shared edge.
        assert!(pairing(a, [q[3], Vec3A::new(5.0, 5.0, 0.0), Vec3A::new(0.0, 5.0, 0.0)]).is_none());
        // A long sliver beside a small triangle: the joint box is larger.
        let far = [q[0], q[2], Vec3A::new(-9.0, 9.0, 9.0)];
        assert!(pairing(a, far).is_none());
    }
}
