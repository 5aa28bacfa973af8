//! An 8-wide BVH: the binned-SAH binary tree of [`super::bvh`] collapsed so
//! each node holds eight child boxes in SoA layout, tested together with one
//! SIMD slab test (`wide::f32x8`: one AVX operation per step on x86-64-v3,
//! two SSE ones elsewhere). It takes a third of the binary tree's levels,
//! and a level is one dependent memory access: on a mesh far larger than
//! the caches, where traversal waits on memory, depth is what costs (Wald,
//! Benthin, Boulos 2008, "Getting Rid of Packets",
//! <https://doi.org/10.1109/RT.2008.4634620>; Embree uses BVH8 on AVX
//! machines). An earlier 4-wide version of this tree traced incoherent rays
//! on the 1M-triangle mesh at 1.04-1.11 Mrays/s on one thread.
//!
//! Like [`super::Bvh`] it knows no shapes: it is built from bounds, and its
//! [`WideBvh::order`] tells the caller how to reorder its primitives so that
//! every leaf is a contiguous range `first..first + count`. Traversal hands
//! the closure whole leaves, so a mesh intersects a run of inline triangles
//! with no index indirection and no per-primitive `enum` dispatch.

mod collapse;
mod stats;
mod traverse;

#[cfg(test)]
mod tests;

use super::Aabb;
use super::bvh::{self, BvhStats};
use glam::Vec3A;

/// Child reference: a node index, or (top bit set) a leaf packing its first
/// primitive (bits 3..31) and `count - 1` (bits 0..3; leaves hold at most
/// [`MAX_LEAF`]).
const LEAF: u32 = 1 << 31;
/// Largest leaf: a merged subtree of up to eight primitives (two four-lane
/// triangle blocks for a mesh).
pub const MAX_LEAF: u32 = 8;
/// An unused child slot; its box is all `+inf`, which no ray enters.
const EMPTY: u32 = u32::MAX;
/// Leaf-first indices must fit 28 bits.
pub const MAX_PRIMS: usize = 1 << 28;

/// Children per node.
pub const WIDTH: usize = 8;

/// Eight child boxes, SoA: `b[row][lane]` for mins (rows 0..3, one per
/// axis) and maxes (3..6). 224 bytes used, padded to four whole cache
/// lines (a 224-byte layout straddling lines measured ~3% slower).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct WideNode {
    pub b: [[f32; WIDTH]; 6],
    pub child: [u32; WIDTH],
}

const _: () = assert!(size_of::<WideNode>() == 256);

/// The 8-wide BVH every ray traverses, over any primitives' bounds: the scene's
/// shapes (top level) and each mesh's triangles (bottom level).
#[derive(Clone, Debug)]
pub struct WideBvh {
    /// Node 0 is the root; empty iff no primitive has non-empty bounds.
    nodes: Vec<WideNode>,
    /// Caller's primitive index for each leaf slot.
    order: Vec<u32>,
    len: usize,
}

#[inline(always)]
fn leaf_ref(first: u32, count: u32) -> u32 {
    debug_assert!((1..=MAX_LEAF).contains(&count) && (first as usize) < MAX_PRIMS);
    LEAF | first << 3 | (count - 1)
}

/// `(first, count)` of a leaf reference.
#[inline(always)]
fn leaf_range(r: u32) -> (u32, u32) {
    ((r & !LEAF) >> 3, (r & 7) + 1)
}

/// How leaves are formed when collapsing the binary tree.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Leaves {
    /// Any binary subtree of at most [`MAX_LEAF`] primitives becomes one
    /// leaf (meshes: fewer, fuller leaves and smaller trees). Without it, a
    /// subtree of 5–8 triangles became a 256-byte node holding two leaves,
    /// and the bunny's tree took 68 bytes per triangle.
    Merged,
    /// One primitive per leaf (scene shapes). The SAH assumes rays come
    /// from outside a box; in a room they start inside it, and it grouped
    /// walls and the light into leaves every ray entered (3.7 quad tests
    /// per ray in the Cornell box). A box test per shape is cheaper than a
    /// quad or sphere test.
    Single,
}

impl WideBvh {
    /// Builds over `bounds[i]` for primitive `i` (binned SAH, parallel, then
    /// collapsed). Panics above [`MAX_PRIMS`] primitives.
    pub fn build(bounds: &[Aabb]) -> Self {
        Self::build_with(bounds, Leaves::Merged)
    }

    /// Builds over `bounds[i]` for primitive `i`, forming leaves as `leaves` says;
    /// [`WideBvh::build`] is this with [`Leaves::Merged`]. Panics above [`MAX_PRIMS`]
    /// primitives.
    pub fn build_with(bounds: &[Aabb], leaves: Leaves) -> Self {
        assert!(bounds.len() < MAX_PRIMS, "WideBvh holds at most 2^28 primitives");
        // `whole`: the collapse makes any subtree of at most that many
        // primitives one leaf, so the binary build need not split it.
        let (max_leaf, whole) = match leaves {
            Leaves::Merged => (4, MAX_LEAF as usize),
            Leaves::Single => (1, 1),
        };
        let (binary, order) = bvh::build_nodes(bounds, max_leaf, whole);
        let nodes = collapse::collapse(&binary, leaves);
        Self {
            nodes,
            order,
            len: bounds.len(),
        }
    }

    /// `order()[slot]` is the caller's primitive in leaf slot `slot`; a
    /// caller stores its primitives in this order. Primitives with empty
    /// bounds are absent.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// Number of primitives the tree was built over (including any dropped for empty
    /// bounds).
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if built over no primitive at all.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Bounds of every primitive (padded); [`Aabb::EMPTY`] if none.
    pub fn bounds(&self) -> Aabb {
        let Some(root) = self.nodes.first() else {
            return Aabb::EMPTY;
        };
        (0..WIDTH)
            .filter(|&i| root.child[i] != EMPTY)
            .fold(Aabb::EMPTY, |acc, i| acc.union(root.child_bounds(i)))
    }

    /// Stats of the wide tree: `nodes` counts wide nodes, `leaves` wide
    /// leaves, `bytes` the wide nodes and the order array; the SAH cost
    /// charges 1 per wide node visit (see `stats.rs`). Walks the tree.
    pub fn stats(&self) -> BvhStats {
        stats::stats(&self.nodes, self.order.len())
    }

    /// Every leaf's `(first, count)` slot range, in no particular order.
    pub fn leaves(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.nodes
            .iter()
            .flat_map(|n| n.child)
            .filter(|&r| r != EMPTY && r & LEAF != 0)
            .map(leaf_range)
    }

    /// Heap bytes of the nodes alone (the order array can be dropped by a
    /// caller that reorders its primitives).
    pub fn node_bytes(&self) -> usize {
        self.nodes.len() * size_of::<WideNode>()
    }
}

impl WideNode {
    pub(crate) const EMPTY: WideNode = WideNode {
        b: [[f32::INFINITY; WIDTH]; 6],
        child: [EMPTY; WIDTH],
    };

    pub(crate) fn child_bounds(&self, i: usize) -> Aabb {
        let b = &self.b;
        Aabb {
            min: Vec3A::new(b[0][i], b[1][i], b[2][i]),
            max: Vec3A::new(b[3][i], b[4][i], b[5][i]),
        }
    }

    pub(crate) fn set_child(&mut self, i: usize, bounds: Aabb, r: u32) {
        for axis in 0..3 {
            self.b[axis][i] = bounds.min[axis];
            self.b[axis + 3][i] = bounds.max[axis];
        }
        self.child[i] = r;
    }
}
