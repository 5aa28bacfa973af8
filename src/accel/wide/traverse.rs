//! Stack-based traversal of the wide tree, nearest child first.
//!
//! One SIMD slab test per node gives eight entry distances; the children hit
//! are pushed farthest first and the nearest is visited next, and entries
//! beyond the best hit found since are skipped when popped. A node with a
//! single child hit (most of them below the top levels) is left for that
//! child without touching the stack (−6% instructions on the bunny
//! benchmark). The stack is a
//! fixed array: the binary tree is at most `MAX_DEPTH` deep and each wide
//! level pushes at most `WIDTH - 1` entries beyond the one it pops, so
//! `(WIDTH - 1) · MAX_DEPTH + 1` never overflows.
//! It is left uninitialised: zeroing the 1.5 KB stack of the 4-wide tree per
//! ray was 4–6% of the time of a render or a benchmark, and only the entries
//! below `sp` are ever read.

use super::{EMPTY, LEAF, WIDTH, WideBvh, WideNode, leaf_range};
use crate::accel::aabb::{FAR_SCALE, safe_inv_dir};
use crate::accel::bvh::MAX_DEPTH;
use crate::math::Ray;
use glam::Vec3A;
use std::mem::MaybeUninit;
use wide::f32x8;

const STACK: usize = (WIDTH - 1) * MAX_DEPTH as usize + 1;

/// Nodes of a tree small enough to stay in the first-level cache (64 ×
/// 256 bytes = 16 KiB of the 32 KiB), whose traversal prefetches nothing:
/// a room of 18 quads as one OBJ (3 nodes) spent 0.6% of its render's
/// instructions on the address arithmetic (callgrind).
const SMALL_TREE: usize = 64;

/// The per-ray slab setup: the origin and the inverse direction, splatted.
struct SlabRay {
    o: [f32x8; 3],
    inv: [f32x8; 3],
}

impl SlabRay {
    #[inline(always)]
    fn new(ray: &Ray) -> Self {
        // The origin and direction are read as the two 16-byte values the
        // caller stored, each once: left to itself the compiler splatted
        // the origin's lanes from one 32-byte load across both, or an
        // 8-byte load across two of the caller's stores, which store
        // forwarding cannot serve (a stall on 14% of the traversal's and
        // 13% of the shadow traversal's samples on the Cornell box, perf).
        // SAFETY: both are fields of a live `&Ray`: valid, aligned, initialised.
        let (o, d) = unsafe { (std::ptr::read_volatile(&ray.o), std::ptr::read_volatile(&ray.d)) };
        // Written out rather than with `array::map`, which the compiler
        // left as out-of-line calls (5% of a Cornell render).
        let inv_d: Vec3A = safe_inv_dir(d);
        Self {
            o: [f32x8::splat(o.x), f32x8::splat(o.y), f32x8::splat(o.z)],
            inv: [
                f32x8::splat(inv_d.x),
                f32x8::splat(inv_d.y),
                f32x8::splat(inv_d.z),
            ],
        }
    }

    /// Entry distances of the children and the mask of those hit before
    /// `t_max`. Empty slots (`+inf` boxes) never hit. `fast_max`/`fast_min`
    /// are the bare SIMD instructions (no NaN fix-up): `safe_inv_dir` keeps
    /// every plane distance a number or an infinity.
    ///
    /// Both planes of each axis are intersected and ordered by a min and a
    /// max, rather than the near and far rows being picked once per ray from
    /// the direction's signs: the picking cost ~30 instructions of setup
    /// per ray and kept six row offsets live (spilled, reloaded at every
    /// node), where the min and max cost six instructions per node. The
    /// entry and exit distances are the same numbers either way (the min of
    /// the two planes is the one the sign would pick), so traversal visits
    /// the same nodes in the same order.
    #[inline(always)]
    fn test(&self, n: &WideNode, t_max: f32) -> ([f32; WIDTH], u32) {
        let plane = |row: usize, a: usize| (f32x8::from(n.b[row]) - self.o[a]) * self.inv[a];
        let (x0, x1) = (plane(0, 0), plane(3, 0));
        let (y0, y1) = (plane(1, 1), plane(4, 1));
        let (z0, z1) = (plane(2, 2), plane(5, 2));
        let t_near = x0
            .fast_min(x1)
            .fast_max(y0.fast_min(y1))
            .fast_max(z0.fast_min(z1))
            .fast_max(f32x8::ZERO);
        let t_far = (x0
            .fast_max(x1)
            .fast_min(y0.fast_max(y1))
            .fast_min(z0.fast_max(z1))
            * f32x8::splat(FAR_SCALE))
        .fast_min(f32x8::splat(t_max));
        (t_near.to_array(), t_near.simd_le(t_far).to_bitmask())
    }
}

/// Asks for a node's cache lines (or as many of a leaf's data) ahead of its
/// visit, so the misses of a node's children overlap instead of following
/// one another. `p` need not be a valid address: a prefetch never faults.
#[inline(always)]
fn prefetch_at(p: *const u8) {
    for line in 0..size_of::<WideNode>() / 64 {
        crate::cpu::prefetch_line(p.wrapping_add(64 * line));
    }
}

impl WideBvh {
    /// Closest hit. `leaf(first, count, t_max)` intersects leaf slots
    /// `first..first + count` (in [`WideBvh::order`]) and returns the nearest
    /// distance below `t_max`, having recorded whatever else it needs.
    /// Returns the best distance.
    #[inline]
    pub fn intersect(
        &self,
        ray: &Ray,
        t_max: f32,
        leaf: impl FnMut(u32, u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        let root = self.nodes.as_ptr().cast::<u8>();
        self.intersect_prefetching(ray, t_max, |_| root, leaf)
    }

    /// [`WideBvh::intersect`], prefetching a leaf's primitives when the leaf
    /// is pushed: `leaf_data(first)` is where the data of leaf slot `first`
    /// starts (it may be computed with `wrapping_add` and is never
    /// dereferenced). A mesh much larger than the caches waits on each
    /// leaf's triangles as on each node.
    #[inline]
    pub fn intersect_prefetching(
        &self,
        ray: &Ray,
        t_max: f32,
        leaf_data: impl Fn(u32) -> *const u8,
        mut leaf: impl FnMut(u32, u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        if self.nodes.is_empty() {
            return None;
        }
        let sr = SlabRay::new(ray);
        // A tree that sits in the first-level cache has nothing to fetch
        // ahead: its pushes skip the prefetches' address arithmetic.
        let prefetch = self.nodes.len() > SMALL_TREE;
        // A finite bound keeps `inf` (empty) slots from passing `near <= far`.
        let mut t_best = t_max.min(f32::MAX);
        let mut found = false;
        let mut stack = [const { MaybeUninit::<(u32, f32)>::uninit() }; STACK];
        let mut sp = 0;
        // The entry being visited; its entry distance is at most `t_best`.
        let mut cur = 0u32;
        loop {
            if cur & LEAF != 0 {
                let (first, count) = leaf_range(cur);
                if let Some(t) = leaf(first, count, t_best)
                    && t < t_best
                {
                    t_best = t;
                    found = true;
                }
            } else {
                let node = &self.nodes[cur as usize];
                let (t_near, mut mask) = sr.test(node, t_best);
                // One child hit (the common case below the top levels): go
                // straight into it, no stack traffic.
                if mask != 0 && mask & (mask - 1) == 0 {
                    let child = node.child[mask.trailing_zeros() as usize];
                    // See below: never follow an empty lane.
                    if child != EMPTY {
                        cur = child;
                        continue;
                    }
                    mask = 0;
                }
                // Push the hit children, then sort the new entries so the
                // nearest is on top (at most eight: insertion sort).
                let base = sp;
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    // An empty lane has inverted bounds and never passes the slab
                    // test with a finite ray; a ray made of huge or non-finite
                    // numbers can still let one through, so it is skipped here
                    // rather than read as a leaf (it would index past the end).
                    if node.child[lane] == EMPTY {
                        continue;
                    }
                    let e = (node.child[lane], t_near[lane]);
                    // A node or a leaf's data, by a select: a branch on the
                    // entry's kind was mispredicted on one push in three
                    // (callgrind's model). Both addresses are computed
                    // wrapping, and a prefetch never faults.
                    if prefetch {
                        let node_at = self.nodes.as_ptr().wrapping_add(e.0 as usize).cast::<u8>();
                        let leaf_at = leaf_data(leaf_range(e.0).0);
                        prefetch_at(if e.0 & LEAF == 0 { node_at } else { leaf_at });
                    }
                    let mut j = sp;
                    // SAFETY: `base..sp` holds this node's entries, all written.
                    while j > base && unsafe { stack[j - 1].assume_init() }.1 < e.1 {
                        stack[j] = stack[j - 1];
                        j -= 1;
                    }
                    stack[j].write(e);
                    sp += 1;
                }
                // The nearest child just pushed passed the test below
                // `t_best`: visit it without the check of a pop.
                if sp > base {
                    sp -= 1;
                    // SAFETY: written just above.
                    cur = unsafe { stack[sp].assume_init() }.0;
                    continue;
                }
            }
            // Next entry not beyond the best hit found since it was pushed.
            loop {
                if sp == 0 {
                    return found.then_some(t_best);
                }
                sp -= 1;
                // SAFETY: entries `..sp` have been written (see the pushes).
                let (r, t_enter) = unsafe { stack[sp].assume_init() };
                if t_enter <= t_best {
                    cur = r;
                    break;
                }
            }
        }
    }

    /// Any hit below `t_max`: `leaf(first, count, t_max)` returns whether a
    /// primitive of the leaf is hit; stops at the first that is.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32, mut leaf: impl FnMut(u32, u32, f32) -> bool) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let sr = SlabRay::new(ray);
        let t_max = t_max.min(f32::MAX);
        let mut stack = [const { MaybeUninit::<u32>::uninit() }; STACK];
        let mut sp = 0;
        let mut cur = 0u32;
        loop {
            if cur & LEAF != 0 {
                let (first, count) = leaf_range(cur);
                if leaf(first, count, t_max) {
                    return true;
                }
            } else {
                let node = &self.nodes[cur as usize];
                let (_, mut mask) = sr.test(node, t_max);
                // See `intersect`: never follow an empty lane; go straight
                // into the last child hit, push the others.
                let mut next = None;
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    if node.child[lane] == EMPTY {
                        continue;
                    }
                    if let Some(r) = next.replace(node.child[lane]) {
                        stack[sp].write(r);
                        sp += 1;
                    }
                }
                if let Some(r) = next {
                    cur = r;
                    continue;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            // SAFETY: entries `..sp` have been written.
            cur = unsafe { stack[sp].assume_init() };
        }
    }
}
