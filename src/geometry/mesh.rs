//! Triangle meshes with their own 8-wide BVH (the bottom level of the
//! two-level scheme; [`super::Instance`] places a mesh in the world).
//!
//! [`Mesh::prepare`] builds the tree and reorders the triangles into leaf
//! order, then copies each leaf's vertices into SoA blocks of up to four
//! triangles (36 bytes each), so a leaf is one or two four-lane SIMD tests:
//! no index indirection and no `Shape` match per triangle. Inline triangles
//! and a wide tree took closest hit on the 1M-triangle mesh from 0.4 to
//! several Mrays/s; the SIMD blocks took the bunny's incoherent rays from
//! 3.4 to 4.3 Mrays/s on one thread.

use super::triangle::{self, FLOATS, Tri4, WatertightRay4};
use super::{Hit, NO_LIGHT};
use crate::accel::{Aabb, WideBvh};
use crate::math::Ray;
use crate::math::float_error::{error_along, gamma_offset};
use glam::{Vec2, Vec3A, Vec4};
use rayon::prelude::*;

/// A triangle mesh in its own (object) space, with its bottom-level BVH once
/// [`Mesh::prepare`] has run.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Vertex positions, in object space.
    pub positions: Vec<Vec3A>,
    /// Vertex indices of each triangle; counter-clockwise seen from outside, so the
    /// geometric normal `(b − a) × (c − a)` points out.
    pub indices: Vec<[u32; 3]>,
    /// Per-vertex shading normals (same indexing as `positions`), or empty.
    pub normals: Vec<Vec3A>,
    /// Per-vertex texture coordinates, or empty.
    pub uvs: Vec<Vec2>,
    /// Per-vertex tangents (same indexing as `positions`): `xyz` along +u
    /// in the surface, `w` = ±1 the handedness, bitangent `w·(n × t)` (the
    /// glTF `TANGENT` convention). Stored by the asset or made by
    /// [`super::tangents::generate`] (MikkTSpace); empty when neither.
    pub tangents: Vec<Vec4>,
    /// Per-vertex colours (linear RGB, same indexing as `positions`), or
    /// empty: OBJ `v x y z r g b`, glTF `COLOR_0`.
    pub colors: Vec<Vec3A>,
    /// Per-triangle material slot (an OBJ object/group), or empty for one
    /// slot. An instance maps slots to scene materials.
    pub slots: Vec<u32>,
    /// Number of slots (≥ 1).
    pub slot_count: u32,
    /// Vertices of each triangle in leaf order, as [`Tri4`] SoA blocks of up
    /// to four (one or two per BVH leaf), plus 3 spare floats; filled by
    /// `prepare`.
    tris: Vec<f32>,
    blas: Option<WideBvh>,
}

/// A vertex colour as a mesh file writes it (a display colour, sRGB-encoded:
/// OBJ's `v x y z r g b`, PLY's `red green blue`) in linear RGB, and whether
/// it was usable as written: a channel outside [0, 1] is clamped, a
/// non-finite one read as white.
pub fn decode_vertex_colour(c: [f32; 3]) -> (Vec3A, bool) {
    let ok = c.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x));
    let linear = c.map(|x| crate::imageio::srgb_decode(if x.is_finite() { x.clamp(0.0, 1.0) } else { 1.0 }));
    (Vec3A::from_array(linear), ok)
}

/// Where a normal map's tangent frame comes from on a mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TangentFrame {
    /// The mesh's per-vertex tangents, interpolated: the asset's own, else
    /// MikkTSpace (glTF's and Blender's convention).
    #[default]
    Vertex,
    /// Each triangle's own ∂p/∂u (Mitsuba 3's frame), for reference twins.
    Triangle,
}

/// Where a ray meets a mesh, in the mesh's own space.
#[derive(Clone, Copy, Debug)]
pub struct MeshHit {
    /// Ray parameter of the hit (the same in object and world space).
    pub t: f32,
    /// Index of the triangle hit, in leaf order after `prepare`.
    pub tri: u32,
    /// Barycentrics of the triangle's second and third vertices.
    pub bc: Vec2,
}

impl Mesh {
    /// The three corners of triangle `tri`.
    #[inline]
    pub fn corners(&self, tri: u32) -> (Vec3A, Vec3A, Vec3A) {
        let [a, b, c] = self.indices[tri as usize];
        (
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        )
    }

    /// Builds the BVH and reorders `indices`/`slots` into its leaf order.
    /// Triangles whose bounds are empty (none, for finite vertices) drop out.
    pub fn prepare(&mut self) {
        // Every pass but the leaf walk runs on all cores: on a 1M-triangle
        // mesh the serial version of this function was a fifth of the build.
        let bounds: Vec<Aabb> = (0..self.indices.len() as u32)
            .into_par_iter()
            .map(|t| self.tri_bounds(t))
            .collect();
        let blas = WideBvh::build(&bounds);
        let order = blas.order();
        self.indices = order.par_iter().map(|&i| self.indices[i as usize]).collect();
        if !self.slots.is_empty() {
            self.slots = order.par_iter().map(|&i| self.slots[i as usize]).collect();
        }
        // A leaf of up to eight is one or two blocks of up to four; cut the
        // array into each block's slice, then fill the blocks in parallel.
        let mut starts: Vec<(u32, u32)> = blas.leaves().flat_map(|(f, c)| blocks(f, c)).collect();
        starts.par_sort_unstable();
        let mut tris = vec![0.0; FLOATS * self.indices.len() + 3];
        // Zeroed lazily (fresh pages), so advised before any is written:
        // every ray reads these at random (see `huge_pages`).
        crate::huge_pages::advise(&tris);
        let mut rest = tris.as_mut_slice();
        let mut jobs = Vec::with_capacity(starts.len());
        let mut next = 0;
        for &(first, count) in &starts {
            // The leaves tile the slots, so the blocks tile the array.
            debug_assert_eq!(first, next, "leaf blocks leave a gap");
            let (block, tail) = rest.split_at_mut(FLOATS * count as usize);
            jobs.push((block, first, count));
            rest = tail;
            next = first + count;
        }
        jobs.into_par_iter().for_each(|(block, first, count)| {
            let mut corners = [[Vec3A::ZERO; 3]; 4];
            for (i, c) in corners.iter_mut().take(count as usize).enumerate() {
                let (a, b, v) = self.corners(first + i as u32);
                *c = [a, b, v];
            }
            Tri4::pack(block, &corners[..count as usize]);
        });
        self.tris = tris;
        self.blas = Some(blas);
    }

    /// Closest hit in `(0, t_max)` through the mesh's BVH ([`Mesh::prepare`]
    /// must have run; an unprepared mesh is never hit).
    #[inline]
    pub fn closest(&self, ray: &Ray, t_max: f32) -> Option<MeshHit> {
        let blas = self.blas.as_ref()?;
        let wt = WatertightRay4::new(ray);
        let mut best = None;
        let tris = self.tris.as_ptr();
        let leaf_data = |first: u32| tris.wrapping_add(FLOATS * first as usize).cast::<u8>();
        blas.intersect_prefetching(ray, t_max, leaf_data, |first, count, t_best| {
            let h = self.leaf_closest(&wt, first, count, t_best)?;
            best = Some(h);
            Some(h.t)
        })?;
        best
    }

    /// Whether anything is hit in `(0, t_max)`.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let Some(blas) = self.blas.as_ref() else {
            return false;
        };
        let wt = WatertightRay4::new(ray);
        blas.occluded(ray, t_max, |first, count, t_max| {
            self.leaf_occluded(&wt, first, count, t_max)
        })
    }

    /// Nearest hit among leaf slots `first..first + count` (a BVH leaf).
    #[inline(always)]
    pub fn leaf_closest(&self, wt: &WatertightRay4, first: u32, count: u32, t_max: f32) -> Option<MeshHit> {
        let mut best = None;
        let mut t_best = t_max;
        for (first, count) in blocks(first, count) {
            if let Some((t, lane, bc)) = wt.closest(&self.block(first, count), t_best) {
                t_best = t;
                best = Some(MeshHit {
                    t,
                    tri: first + lane,
                    bc,
                });
            }
        }
        best
    }

    /// Whether any of leaf slots `first..first + count` is hit.
    #[inline(always)]
    pub fn leaf_occluded(&self, wt: &WatertightRay4, first: u32, count: u32, t_max: f32) -> bool {
        blocks(first, count).any(|(first, count)| wt.any(&self.block(first, count), t_max))
    }

    /// The triangles `first..first + count` (≤ 4) of one block.
    #[inline(always)]
    fn block(&self, first: u32, count: u32) -> Tri4<'_> {
        Tri4 {
            soa: &self.tris[FLOATS * first as usize..],
            count,
        }
    }

    /// Triangle `tri` alone (brute-force references in tests).
    #[inline]
    pub fn intersect(&self, tri: u32, ray: &Ray, t_max: f32) -> Option<(f32, Vec2)> {
        let (a, b, c) = self.corners(tri);
        triangle::intersect(a, b, c, ray, t_max)
    }

    /// Shading record in the mesh's space for a hit of triangle `tri` at
    /// `p` with barycentrics `bc`; `material` is left 0 for the caller.
    ///
    /// The point is the barycentric sum of the corners, so its error is
    /// pbrt-v4's γ(7)·Σ|bᵢ·pᵢ| (the barycentrics' own rounding included),
    /// not that of `o + t·d` ([`Mesh::point_error`]); `p_error` is that
    /// bound along `ng`, in the mesh's space.
    #[inline]
    pub fn hit(&self, tri: u32, t: f32, bc: Vec2) -> Hit {
        let (a, b, c) = self.corners(tri);
        let w = Vec3A::new(1.0 - bc.x - bc.y, bc.x, bc.y);
        let (pa, pb, pc) = (a * w.x, b * w.y, c * w.z);
        let p_err = gamma_offset(7) * (pa.abs() + pb.abs() + pc.abs());
        // Counter-clockwise winding faces outward.
        let ng = (b - a).cross(c - a).normalize_or(Vec3A::Z);
        let [ia, ib, ic] = self.indices[tri as usize].map(|i| i as usize);
        let mut ns = ng;
        if !self.normals.is_empty() {
            let n = self.normals[ia] * w.x + self.normals[ib] * w.y + self.normals[ic] * w.z;
            if n.length_squared() > 0.0 && n.is_finite() {
                // Keep the shading normal on the geometric normal's side.
                ns = n.normalize();
                if ns.dot(ng) < 0.0 {
                    ns = -ns;
                }
            }
        }
        let uv = if self.uvs.is_empty() {
            bc
        } else {
            self.uvs[ia] * w.x + self.uvs[ib] * w.y + self.uvs[ic] * w.z
        };
        Hit {
            t,
            p: pa + pb + pc,
            p_error: error_along(ng, p_err),
            ng,
            ns,
            uv,
            material: 0,
            light: NO_LIGHT,
            color: glam::Vec3A::ONE,
        }
    }

    /// The tangent at a hit of triangle `tri` with barycentrics `bc`, in
    /// the mesh's space: `xyz` along +u (not normalised), `w` the
    /// handedness of (t, b, n). `Vertex` interpolates the per-vertex
    /// tangents (MikkTSpace's convention: the bitangent's sign comes from the
    /// vertex); `Triangle` is the triangle's own ∂p/∂u from its positions
    /// and UVs (pbrt-v4's `Triangle::InteractionFromIntersection`, what
    /// Mitsuba 3 builds its normal-map frame from), with `w = 1` as Mitsuba
    /// ignores the handedness. `None` where the mesh has no UVs (or no
    /// tangents, for `Vertex`) or the UVs are degenerate.
    pub fn tangent(&self, tri: u32, bc: Vec2, frame: TangentFrame) -> Option<Vec4> {
        let [ia, ib, ic] = self.indices.get(tri as usize)?.map(|i| i as usize);
        match frame {
            TangentFrame::Vertex => {
                let (a, b, c) = (
                    self.tangents.get(ia)?,
                    self.tangents.get(ib)?,
                    self.tangents.get(ic)?,
                );
                let w = 1.0 - bc.x - bc.y;
                let t = a.truncate() * w + b.truncate() * bc.x + c.truncate() * bc.y;
                let sign = if a.w < 0.0 { -1.0 } else { 1.0 };
                (t.is_finite() && t.length_squared() > 0.0).then(|| t.extend(sign))
            }
            TangentFrame::Triangle => {
                let (uva, uvb, uvc) = (self.uvs.get(ia)?, self.uvs.get(ib)?, self.uvs.get(ic)?);
                let (pa, pb, pc) = self.corners(tri);
                // Solve [dp02 dp12] = [duv02 duv12] · [∂p/∂u ∂p/∂v] (pbrt-v4).
                let (duv02, duv12) = (*uva - *uvc, *uvb - *uvc);
                let (dp02, dp12) = (pa - pc, pb - pc);
                let det = duv02.x * duv12.y - duv02.y * duv12.x;
                if det.abs() < 1e-9 {
                    return None;
                }
                let dpdu = (duv12.y * dp02 - duv02.y * dp12) / det;
                (dpdu.is_finite() && dpdu.length_squared() > 0.0).then(|| glam::Vec3::from(dpdu).extend(1.0))
            }
        }
    }

    /// The vertex colour at barycentrics `bc` of triangle `tri`; `None`
    /// on a mesh without colours.
    pub fn color(&self, tri: u32, bc: Vec2) -> Option<Vec3A> {
        let [ia, ib, ic] = self.indices.get(tri as usize)?.map(|i| i as usize);
        let (a, b, c) = (self.colors.get(ia)?, self.colors.get(ib)?, self.colors.get(ic)?);
        Some(*a * (1.0 - bc.x - bc.y) + *b * bc.x + *c * bc.y)
    }

    /// Per-axis error bound of the point [`Mesh::hit`] reports, for an
    /// instance to carry through its transform.
    pub fn point_error(&self, tri: u32, bc: Vec2) -> Vec3A {
        let (a, b, c) = self.corners(tri);
        let w = Vec3A::new(1.0 - bc.x - bc.y, bc.x, bc.y);
        gamma_offset(7) * ((a * w.x).abs() + (b * w.y).abs() + (c * w.z).abs())
    }

    /// Which vertex attributes the mesh carries: normals, UVs, tangents,
    /// colours.
    /// [`Mesh::append`] joins only meshes with the same, so that it invents
    /// none.
    pub fn attributes(&self) -> [bool; 4] {
        [
            !self.normals.is_empty(),
            !self.uvs.is_empty(),
            !self.tangents.is_empty(),
            !self.colors.is_empty(),
        ]
    }

    /// Appends `other`'s vertices and triangles after this mesh's, its
    /// material slots numbered after this mesh's (slot `s` of `other`
    /// becomes `slot_count + s`): two parts placed the same way become one
    /// mesh under one BVH. Each vertex and triangle keeps its attributes, so
    /// every hit shades as before. Both must be unprepared (no BVH yet) and
    /// have the same [`Mesh::attributes`]; the caller keeps the vertex count within
    /// `u32`.
    pub fn append(&mut self, other: Mesh) {
        debug_assert!(
            self.blas.is_none() && other.blas.is_none(),
            "append before `prepare`"
        );
        debug_assert_eq!(self.attributes(), other.attributes());
        let base = self.positions.len() as u32;
        if self.slots.is_empty() {
            self.slots = vec![0; self.indices.len()];
        }
        let first = self.slot_count.max(1);
        if other.slots.is_empty() {
            self.slots.extend(std::iter::repeat_n(first, other.indices.len()));
        } else {
            self.slots.extend(other.slots.iter().map(|s| first + s));
        }
        self.slot_count = first + other.slot_count.max(1);
        self.positions.extend(other.positions);
        self.indices
            .extend(other.indices.iter().map(|t| t.map(|i| base + i)));
        self.normals.extend(other.normals);
        self.uvs.extend(other.uvs);
        self.tangents.extend(other.tangents);
        self.colors.extend(other.colors);
    }

    /// Material slot of triangle `tri`.
    #[inline]
    pub fn slot(&self, tri: u32) -> u32 {
        self.slots.get(tri as usize).copied().unwrap_or(0)
    }

    /// Bounds of triangle `tri`, in object space.
    pub fn tri_bounds(&self, tri: u32) -> Aabb {
        let (a, b, c) = self.corners(tri);
        Aabb::from_points(&[a, b, c])
    }

    /// Bounds of all vertices in use.
    pub fn bounds(&self) -> Aabb {
        match &self.blas {
            Some(b) => b.bounds(),
            None => (0..self.indices.len() as u32).fold(Aabb::EMPTY, |acc, t| acc.union(self.tri_bounds(t))),
        }
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len()
    }

    /// The mesh's own BVH (bottom level), once `prepare` has built it; `None` before.
    /// Exposed for statistics.
    pub fn blas(&self) -> Option<&WideBvh> {
        self.blas.as_ref()
    }

    /// Heap bytes of the BVH nodes and the inline triangle array (what the
    /// ray traverses; excludes shading data).
    pub fn accel_bytes(&self) -> usize {
        self.blas.as_ref().map_or(0, WideBvh::node_bytes) + std::mem::size_of_val(self.tris.as_slice())
    }

    /// Heap bytes of everything the mesh holds.
    pub fn total_bytes(&self) -> usize {
        self.accel_bytes()
            + self.blas.as_ref().map_or(0, |b| b.order().len() * 4)
            + std::mem::size_of_val(self.positions.as_slice())
            + std::mem::size_of_val(self.indices.as_slice())
            + std::mem::size_of_val(self.normals.as_slice())
            + std::mem::size_of_val(self.uvs.as_slice())
            + std::mem::size_of_val(self.tangents.as_slice())
            + std::mem::size_of_val(self.colors.as_slice())
            + std::mem::size_of_val(self.slots.as_slice())
    }

    /// Replaces the normals by area-weighted vertex normals: each face adds
    /// its unnormalised cross product (|cross| = 2 · area) to its corners.
    /// Vertices at the same position share the sum, so splits made for UV
    /// seams do not show as creases.
    pub fn compute_smooth_normals(&mut self) {
        use std::collections::HashMap;
        let key = |p: Vec3A| p.to_array().map(f32::to_bits);
        let mut sum: HashMap<[u32; 3], Vec3A> = HashMap::new();
        for &[a, b, c] in &self.indices {
            let (pa, pb, pc) = (
                self.positions[a as usize],
                self.positions[b as usize],
                self.positions[c as usize],
            );
            let n = (pb - pa).cross(pc - pa);
            if !n.is_finite() {
                continue;
            }
            for p in [pa, pb, pc] {
                *sum.entry(key(p)).or_insert(Vec3A::ZERO) += n;
            }
        }
        self.normals = self
            .positions
            .iter()
            .map(|&p| sum.get(&key(p)).map_or(Vec3A::ZERO, |n| n.normalize_or_zero()))
            .collect();
    }
}

/// A leaf's slots as blocks of at most four: `(first, 4)`, then the rest.
#[inline(always)]
fn blocks(first: u32, count: u32) -> impl Iterator<Item = (u32, u32)> {
    let head = count.min(4);
    std::iter::once((first, head)).chain((count > 4).then(|| (first + 4, count - 4)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::Pcg32 as Rng;

    /// A mesh of `n` random triangles in the unit cube around `c`, with
    /// vertex normals and UVs; triangle `t` in slot `t mod slots` (one
    /// slot: no per-triangle slots, as a single-material mesh has).
    fn random_mesh(rng: &mut Rng, n: usize, c: Vec3A, slots: u32) -> Mesh {
        let mut v = || Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - Vec3A::splat(0.5);
        let mut m = Mesh::default();
        for t in 0..n as u32 {
            for _ in 0..3 {
                m.positions.push(c + v());
                m.normals.push(v().normalize_or(Vec3A::Z));
                m.uvs.push(v().truncate());
            }
            m.indices.push([3 * t, 3 * t + 1, 3 * t + 2]);
        }
        if slots > 1 {
            m.slots = (0..n as u32).map(|t| t % slots).collect();
        }
        m.slot_count = slots;
        m
    }

    /// Two meshes appended and given one BVH answer every ray as the two
    /// did on their own: the nearest distance bit for bit, the same shading
    /// record, and the slot of the part hit (the second part's slots
    /// numbered after the first's).
    #[test]
    fn appended_meshes_hit_and_shade_as_their_parts() {
        let mut rng = Rng::new(11, 3);
        let a = random_mesh(&mut rng, 200, Vec3A::ZERO, 1);
        let b = random_mesh(&mut rng, 150, Vec3A::new(0.3, 0.1, 0.2), 3);
        let mut joined = a.clone();
        joined.append(b.clone());
        assert_eq!((joined.triangle_count(), joined.slot_count), (350, 4));
        let (mut a, mut b) = (a, b);
        a.prepare();
        b.prepare();
        joined.prepare();
        let mut hits = 0;
        for _ in 0..4000 {
            let o = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 - Vec3A::splat(2.0);
            let to = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 0.8 - Vec3A::splat(0.3);
            let ray = Ray::new(o, (to - o).normalize());
            let parts = [(&a, 0u32), (&b, 1)];
            let want = parts
                .iter()
                .filter_map(|(m, k)| m.closest(&ray, f32::INFINITY).map(|h| (h, *m, *k)))
                .min_by(|x, y| x.0.t.total_cmp(&y.0.t));
            let got = joined.closest(&ray, f32::INFINITY);
            assert_eq!(
                got.map(|h| h.t.to_bits()),
                want.map(|w| w.0.t.to_bits()),
                "{ray:?}"
            );
            let (Some(g), Some((w, part, k))) = (got, want) else {
                continue;
            };
            hits += 1;
            let (hg, hw) = (joined.hit(g.tri, g.t, g.bc), part.hit(w.tri, w.t, w.bc));
            assert_eq!((hg.p, hg.ns, hg.uv), (hw.p, hw.ns, hw.uv), "{ray:?}");
            let want_slot = if k == 0 {
                part.slot(w.tri)
            } else {
                1 + part.slot(w.tri)
            };
            assert_eq!(joined.slot(g.tri), want_slot, "{ray:?}");
        }
        assert!(hits > 1000, "only {hits} hits");
    }
}
