//! Binned SAH construction (Wald 2007, "On fast Construction of SAH-based
//! Bounding Volume Hierarchies", <https://doi.org/10.1109/RT.2007.4342588>):
//! centroids are binned into 16 slots on all three axes at once, the 45
//! candidate planes are scored by the surface area heuristic, and the best one
//! partitions the primitive references in place. O(n log n) overall.
//!
//! Subtrees above `PARALLEL_MIN` primitives are built with `rayon::join`; the
//! right one goes to its own node vector and is appended with its offsets
//! shifted, so the layout is depth-first and identical for any thread count.
//! At the top levels, where `join` has not yet found work for every thread,
//! binning and partitioning are themselves split over fixed-size chunks
//! (as Embree's parallel partition does): the chunks, and so the tree, do not
//! depend on the thread count.

use glam::{Vec3A, Vec4};
use rayon::prelude::*;

use super::MAX_DEPTH;
use super::node::Node;
use crate::accel::Aabb;

const BINS: usize = 16;
/// Leaves never hold more than this many primitives.
pub(crate) const MAX_LEAF: usize = 4;
/// Cost of one traversal step relative to one primitive test.
pub(crate) const TRAVERSAL_COST: f32 = 1.0;
const PARALLEL_MIN: usize = 4096;
/// Above this, the binning and partition passes are split over chunks of
/// `PARALLEL_CHUNK` references (a node this big is one of the top 4 levels
/// of a 1M-triangle mesh).
const PARALLEL_BIN_MIN: usize = 65536;
const PARALLEL_CHUNK: usize = PARALLEL_BIN_MIN / 4;

/// A primitive's bounds and its index in the caller's array, in 32 bytes
/// (two SSE registers; the index rides in the unused fourth lane of the
/// minimum). At 48 bytes, with the index apart, the passes over the
/// references moved 50% more memory.
#[derive(Clone, Copy)]
pub(crate) struct PrimRef {
    /// xyz: the box minimum; w: the index, as bits.
    min_index: Vec4,
    max: Vec3A,
}

impl PrimRef {
    #[inline(always)]
    fn new(b: Aabb, index: u32) -> Self {
        Self {
            min_index: b.min.extend(f32::from_bits(index)),
            max: b.max,
        }
    }

    #[inline(always)]
    fn index(&self) -> u32 {
        self.min_index.w.to_bits()
    }

    #[inline(always)]
    fn min(&self) -> Vec3A {
        Vec3A::from_vec4(self.min_index)
    }

    #[inline(always)]
    fn centroid(&self) -> Vec3A {
        0.5 * (self.min() + self.max)
    }

    #[inline(always)]
    fn aabb(&self) -> Aabb {
        Aabb {
            min: self.min(),
            max: self.max,
        }
    }
}

/// How far the recursion goes.
#[derive(Clone, Copy)]
struct Limits {
    /// Depth budget left.
    budget: u32,
    /// Largest leaf the SAH may choose.
    max_leaf: usize,
    /// Nodes of at most this many references become leaves unsplit.
    whole: usize,
}

/// Output of the build: depth-first nodes and the reordered primitive ids.
pub(crate) fn build(bounds: &[Aabb]) -> (Vec<Node>, Vec<u32>) {
    build_with_limits(
        bounds,
        Limits {
            budget: MAX_DEPTH,
            max_leaf: MAX_LEAF,
            whole: 1,
        },
    )
}

/// With leaves of at most `max_leaf` (1..=[`MAX_LEAF`]) primitives, except
/// that a node of at most `whole` references is a leaf at once: the wide
/// tree turns every such subtree into one leaf whatever its inside, so
/// building that inside was wasted. On the 1M-triangle mesh with `whole` =
/// 8 it was 70% of the binary nodes; the wide tree comes out node for node
/// the same (only the order inside a leaf differs), see the wide tests.
pub(crate) fn build_for_wide(bounds: &[Aabb], max_leaf: usize, whole: usize) -> (Vec<Node>, Vec<u32>) {
    build_with_limits(
        bounds,
        Limits {
            budget: MAX_DEPTH,
            max_leaf: max_leaf.clamp(1, MAX_LEAF),
            whole: whole.max(1),
        },
    )
}

/// Leaves end up no deeper than `max_depth` if it is at least
/// `ceil(log2 n)`; `MAX_DEPTH` = 64 covers any u32 count. Tests lower it to
/// exercise the depth budget.
#[cfg(test)]
pub(crate) fn build_with_max_depth(bounds: &[Aabb], max_depth: u32) -> (Vec<Node>, Vec<u32>) {
    build_with_limits(
        bounds,
        Limits {
            budget: max_depth,
            max_leaf: MAX_LEAF,
            whole: 1,
        },
    )
}

/// Node capacity to reserve for `n` references: measured ~1.1 nodes per
/// reference with leaves of 1–2, ~0.4 with `whole` = 8.
fn node_estimate(n: usize, whole: usize) -> usize {
    (2 * n).div_ceil(whole.clamp(1, 4)) + 16
}

fn build_with_limits(bounds: &[Aabb], limits: Limits) -> (Vec<Node>, Vec<u32>) {
    assert!(
        bounds.len() <= u32::MAX as usize,
        "a BVH indexes primitives with u32"
    );
    // Empty bounds can never be hit: drop them so no node box is empty.
    // Nor can bounds that are not finite (a NaN or infinite vertex): their
    // centroids are no point, and one NaN in the centroid bounds put a
    // centroid below its node's minimum, an index past the bins (found by
    // the `gltf` fuzz target). Padding here makes every node box padded
    // (see `Aabb::padded`). In parallel (rayon's collect keeps the order): a
    // serial pass here was a fixed cost no thread count shortened.
    let mut refs: Vec<PrimRef> = bounds
        .par_iter()
        .enumerate()
        .filter(|(_, b)| !b.is_empty() && b.min.is_finite() && b.max.is_finite())
        .map(|(index, b)| PrimRef::new(b.padded(), index as u32))
        .collect();
    let mut nodes = Vec::new();
    if !refs.is_empty() {
        // Min/max are exact, so the chunked bounds are the serial ones.
        let (b, cb) = refs.par_chunks(PARALLEL_CHUNK).map(bounds_of).reduce(
            || (Aabb::EMPTY, Aabb::EMPTY),
            |(b, cb), (c, d)| (b.union(c), cb.union(d)),
        );
        nodes.reserve(node_estimate(refs.len(), limits.whole));
        // One scratch array for every chunked partition: allocating it per
        // node cost 4 × 32 MB of fresh pages on the 1M-triangle mesh.
        let mut scratch = if refs.len() >= PARALLEL_BIN_MIN {
            refs.par_iter().copied().collect()
        } else {
            Vec::new()
        };
        build_rec(&mut refs, &mut scratch, false, 0, b, cb, limits, &mut nodes);
    }
    (nodes, refs.par_iter().map(PrimRef::index).collect())
}

/// Bounds of the primitives and of their centroids.
fn bounds_of(refs: &[PrimRef]) -> (Aabb, Aabb) {
    refs.iter().fold((Aabb::EMPTY, Aabb::EMPTY), |(b, cb), r| {
        (b.union(r.aabb()), cb.grow_point(r.centroid()))
    })
}

fn ceil_log2(n: usize) -> u32 {
    n.next_power_of_two().trailing_zeros()
}

/// Appends the subtree over `refs` (slots `first..` of the index array) to
/// `out`, root first; offsets are relative to `out`'s start.
///
/// `scratch` is as long as `refs` for nodes the chunked partition may
/// handle, else empty. The chunked partition scatters into `scratch` and
/// the children carry on from there with the two arrays' roles swapped, so
/// `away` says the references sit in the root's scratch array, not in the
/// array the index order is read from. They go back once, when a node is
/// small enough for the serial in-place passes: one copy in all instead of
/// one per chunked level (4 × 32 MB on the 1M-triangle mesh).
#[allow(clippy::too_many_arguments)]
fn build_rec(
    refs: &mut [PrimRef],
    scratch: &mut [PrimRef],
    away: bool,
    first: u32,
    b: Aabb,
    cb: Aabb,
    limits: Limits,
    out: &mut Vec<Node>,
) {
    let n = refs.len();
    let (refs, scratch, away) = if away && n < PARALLEL_BIN_MIN {
        scratch.copy_from_slice(refs);
        (scratch, &mut [][..], false)
    } else {
        (refs, scratch, away)
    };
    debug_assert!(!away || scratch.len() == n, "references away without a way home");
    let me = out.len();
    out.push(Node::leaf(b, first, n as u32));
    if n <= limits.whole {
        return;
    }
    let Limits { budget, max_leaf, .. } = limits;
    // Depth budget: with no slack left, median splits finish the subtree in
    // exactly ceil(log2 n) levels, so no leaf is deeper than max_depth and the
    // traversal stack cannot overflow.
    let sah = if ceil_log2(n) < budget {
        best_split(refs, &cb)
    } else {
        None
    };
    if n <= max_leaf {
        let area = b.surface_area();
        let leaf_cost = area * n as f32;
        if sah.is_none_or(|s| leaf_cost <= TRAVERSAL_COST * area + s.cost) {
            return;
        }
    }
    let chunked = sah.is_some() && n >= PARALLEL_BIN_MIN;
    let (mid, lb, lcb, rb, rcb) = match sah {
        Some(s) if chunked => partition_chunked(refs, scratch, &Binner::new(&cb), s),
        Some(s) => partition(refs, &cb, s),
        None => median_split(refs, &cb),
    };
    // After a chunked partition the references are in `scratch`.
    let (refs, scratch) = if chunked { (scratch, refs) } else { (refs, scratch) };
    let away = away ^ chunked;
    let (left, right) = refs.split_at_mut(mid);
    let second_first = first + mid as u32;
    let limits = Limits {
        budget: budget.saturating_sub(1),
        ..limits
    };
    if n >= PARALLEL_MIN {
        let (ls, rs) = if scratch.is_empty() {
            (&mut [][..], &mut [][..])
        } else {
            scratch.split_at_mut(mid)
        };
        let mut right_nodes = Vec::with_capacity(node_estimate(right.len(), limits.whole));
        rayon::join(
            || build_rec(left, ls, away, first, lb, lcb, limits, out),
            || build_rec(right, rs, away, second_first, rb, rcb, limits, &mut right_nodes),
        );
        let shift = out.len() as u32;
        out[me] = Node::interior(b, shift);
        out.extend(right_nodes.into_iter().map(|mut node| {
            if !node.is_leaf() {
                node.offset += shift;
            }
            node
        }));
    } else {
        debug_assert!(!away, "small nodes are partitioned at home");
        build_rec(left, &mut [], false, first, lb, lcb, limits, out);
        out[me] = Node::interior(b, out.len() as u32);
        build_rec(right, &mut [], false, second_first, rb, rcb, limits, out);
    }
}

#[derive(Clone, Copy)]
struct Split {
    axis: usize,
    /// Bins `< bin` go left.
    bin: usize,
    /// Σ area × count over both sides, not normalised.
    cost: f32,
}

/// Maps a centroid to a bin on each axis; flat axes (zero or denormal extent)
/// get scale 0 and are never split.
#[derive(Clone, Copy)]
struct Binner {
    min: Vec3A,
    scale: Vec3A,
}

impl Binner {
    fn new(cb: &Aabb) -> Self {
        let scale = Vec3A::splat(BINS as f32) / cb.extent();
        let ok = scale.is_finite_mask() & cb.extent().cmpgt(Vec3A::ZERO);
        Self {
            min: cb.min,
            scale: Vec3A::select(ok, scale, Vec3A::ZERO),
        }
    }

    /// Saturating: the maximal centroid lands in the last bin.
    #[inline(always)]
    fn bins(&self, c: Vec3A) -> [usize; 3] {
        truncate(((c - self.min) * self.scale).min(Vec3A::splat((BINS - 1) as f32)))
    }
}

/// Lanes in `[0, BINS - 1]` (centroids never lie below the node's centroid
/// bounds) truncated to bin indices, all three in one SSE2 conversion: the
/// per-lane saturating `as` casts took ~15 instructions per reference and
/// pass. Same results as `as_uvec3` on that range.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn truncate(f: Vec3A) -> [usize; 3] {
    use std::arch::x86_64::{_mm_castsi128_ps, _mm_cvttps_epi32};
    // SAFETY: SSE2 is part of every x86-64 target (no runtime check needed).
    let i = Vec3A::from(unsafe { _mm_castsi128_ps(_mm_cvttps_epi32(f.into())) });
    [
        i.x.to_bits() as usize,
        i.y.to_bits() as usize,
        i.z.to_bits() as usize,
    ]
}

#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn truncate(f: Vec3A) -> [usize; 3] {
    let i = f.as_uvec3();
    [i.x as usize, i.y as usize, i.z as usize]
}

#[derive(Clone, Copy)]
struct Bins {
    bounds: [[Aabb; BINS]; 3],
    counts: [[u32; BINS]; 3],
}

impl Bins {
    const EMPTY: Bins = Bins {
        bounds: [[Aabb::EMPTY; BINS]; 3],
        counts: [[0; BINS]; 3],
    };

    /// In place: `Bins` is 1.7 KB, and passing it by value cost two
    /// `memcpy`s per node, 8% of the build's instructions (callgrind).
    fn fill(&mut self, binner: &Binner, refs: &[PrimRef]) {
        for r in refs {
            let idx = binner.bins(r.centroid());
            for (axis, &i) in idx.iter().enumerate() {
                self.bounds[axis][i] = self.bounds[axis][i].union(r.aabb());
                self.counts[axis][i] += 1;
            }
        }
    }

    /// Exact (min/max and integer sums), so chunked binning is deterministic.
    fn merge(mut self, o: &Bins) -> Self {
        for axis in 0..3 {
            for i in 0..BINS {
                self.bounds[axis][i] = self.bounds[axis][i].union(o.bounds[axis][i]);
                self.counts[axis][i] += o.counts[axis][i];
            }
        }
        self
    }
}

/// The cheapest SAH plane over all axes, or `None` if every centroid is the
/// same point (no plane separates them).
fn best_split(refs: &[PrimRef], cb: &Aabb) -> Option<Split> {
    let binner = Binner::new(cb);
    if binner.scale == Vec3A::ZERO {
        return None;
    }
    let bins = if refs.len() >= PARALLEL_BIN_MIN {
        refs.par_chunks(PARALLEL_CHUNK)
            .map(|c| {
                let mut bins = Bins::EMPTY;
                bins.fill(&binner, c);
                bins
            })
            .reduce(|| Bins::EMPTY, |a, b| a.merge(&b))
    } else {
        let mut bins = Bins::EMPTY;
        bins.fill(&binner, refs);
        bins
    };
    let mut best: Option<Split> = None;
    for axis in (0..3).filter(|&a| binner.scale[a] > 0.0) {
        // Right-to-left sweep: area × count of bins i.. for every i.
        let mut right_cost = [0.0f32; BINS];
        let (mut acc, mut count) = (Aabb::EMPTY, 0u32);
        for i in (1..BINS).rev() {
            acc = acc.union(bins.bounds[axis][i]);
            count += bins.counts[axis][i];
            right_cost[i] = acc.surface_area() * count as f32;
        }
        let (mut acc, mut count) = (Aabb::EMPTY, 0u32);
        for (bin, &right) in right_cost.iter().enumerate().skip(1) {
            acc = acc.union(bins.bounds[axis][bin - 1]);
            count += bins.counts[axis][bin - 1];
            if count == 0 || count as usize == refs.len() {
                continue;
            }
            let cost = acc.surface_area() * count as f32 + right;
            if best.is_none_or(|b| cost < b.cost) {
                best = Some(Split { axis, bin, cost });
            }
        }
    }
    best
}

type Halves = (usize, Aabb, Aabb, Aabb, Aabb);

/// In-place partition by the split's bin; the child bounds are gathered on
/// the way, which saves a pass per level. Large nodes take the parallel
/// [`partition_chunked`] instead.
fn partition(refs: &mut [PrimRef], cb: &Aabb, s: Split) -> Halves {
    let binner = Binner::new(cb);
    let (mut lb, mut lcb, mut rb, mut rcb) = (Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY);
    let (mut i, mut j) = (0, refs.len());
    while i < j {
        let r = refs[i];
        let c = r.centroid();
        if binner.bins(c)[s.axis] < s.bin {
            lb = lb.union(r.aabb());
            lcb = lcb.grow_point(c);
            i += 1;
        } else {
            rb = rb.union(r.aabb());
            rcb = rcb.grow_point(c);
            j -= 1;
            refs.swap(i, j);
        }
    }
    debug_assert!(i > 0 && i < refs.len(), "SAH split left a side empty");
    (i, lb, lcb, rb, rcb)
}

/// Bounds of the left and right side of one chunk, and its left count.
#[derive(Clone, Copy)]
struct Sides {
    left: usize,
    lb: Aabb,
    lcb: Aabb,
    rb: Aabb,
    rcb: Aabb,
}

/// Stable partition over fixed chunks, in two parallel passes: count and
/// bound each chunk's sides; scatter each chunk's references to its slices
/// of `scratch` (offsets by prefix sums in chunk order), where the caller
/// carries on with them. More memory traffic than the serial pass, but it
/// runs on every thread while the tree's top levels leave most of them
/// idle; the result depends only on the chunking, not on the thread count.
fn partition_chunked(refs: &mut [PrimRef], scratch: &mut [PrimRef], binner: &Binner, s: Split) -> Halves {
    let goes_left = |r: &PrimRef| binner.bins(r.centroid())[s.axis] < s.bin;
    let sides: Vec<Sides> = refs
        .par_chunks(PARALLEL_CHUNK)
        .map(|chunk| {
            let (mut left, mut lb, mut lcb, mut rb, mut rcb) =
                (0, Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY);
            for r in chunk {
                let c = r.centroid();
                if goes_left(r) {
                    left += 1;
                    (lb, lcb) = (lb.union(r.aabb()), lcb.grow_point(c));
                } else {
                    (rb, rcb) = (rb.union(r.aabb()), rcb.grow_point(c));
                }
            }
            Sides {
                left,
                lb,
                lcb,
                rb,
                rcb,
            }
        })
        .collect();
    let mid: usize = sides.iter().map(|c| c.left).sum();
    // Each chunk's destination: a slice of the left part and one of the right.
    let (mut lefts, mut rights) = scratch.split_at_mut(mid);
    let mut jobs = Vec::with_capacity(sides.len());
    for (chunk, side) in refs.chunks(PARALLEL_CHUNK).zip(&sides) {
        let (l, lt) = lefts.split_at_mut(side.left);
        let (r, rt) = rights.split_at_mut(chunk.len() - side.left);
        (lefts, rights) = (lt, rt);
        jobs.push((chunk, l, r));
    }
    jobs.into_par_iter().for_each(|(chunk, l, r)| {
        let (mut i, mut j) = (0, 0);
        for x in chunk {
            if goes_left(x) {
                l[i] = *x;
                i += 1;
            } else {
                r[j] = *x;
                j += 1;
            }
        }
    });
    // Min/max are exact: any merge order gives the same boxes.
    let all = sides.iter().fold(
        (Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY, Aabb::EMPTY),
        |(lb, lcb, rb, rcb), c| (lb.union(c.lb), lcb.union(c.lcb), rb.union(c.rb), rcb.union(c.rcb)),
    );
    debug_assert!(mid > 0 && mid < refs.len(), "SAH split left a side empty");
    (mid, all.0, all.1, all.2, all.3)
}

/// Object median on the widest centroid axis; used when centroids coincide
/// or the depth budget is spent. Ties broken by index for determinism.
fn median_split(refs: &mut [PrimRef], cb: &Aabb) -> Halves {
    let e = cb.extent();
    let axis = if e.x >= e.y && e.x >= e.z {
        0
    } else if e.y >= e.z {
        1
    } else {
        2
    };
    let mid = refs.len() / 2;
    refs.select_nth_unstable_by(mid, |a, b| {
        a.centroid()[axis]
            .total_cmp(&b.centroid()[axis])
            .then(a.index().cmp(&b.index()))
    });
    let (l, r) = refs.split_at(mid);
    let ((lb, lcb), (rb, rcb)) = (bounds_of(l), bounds_of(r));
    (mid, lb, lcb, rb, rcb)
}
