//! Binary bounding volume hierarchy over primitive bounds: the build stage
//! of the 8-wide [`super::WideBvh`] every ray traverses.
//!
//! Built once from one box per primitive ([`Bvh::build`], binned SAH, see
//! `build.rs`). Its own closure-based traversal (`traverse.rs`) is no longer
//! on the render path; it stays as the simple reference the builder's tests
//! (brute force, degenerate inputs, depth budget) check the tree through.
//! The BVH never sees shapes, so triangles, analytic shapes and SDF bounds
//! all share it.
//!
//! Inputs must be NaN-free. Boxes may be flat (zero thickness on an axis, as
//! for axis-aligned triangles) or huge; empty boxes ([`Aabb::EMPTY`]) are
//! dropped because no ray can hit them, so their primitives are never offered
//! to the closure.

mod build;
mod node;
mod traverse;

#[cfg(test)]
pub(crate) mod tests;

use super::Aabb;
pub(crate) use node::Node;

/// Deepest leaf the build produces; also the traversal stack size, which is
/// therefore fixed, on the stack, and never overflows.
pub(crate) const MAX_DEPTH: u32 = 64;

/// A binary BVH over primitive bounds, built by binned SAH. It stores only boxes and
/// the caller's primitive indices, so any kind of primitive can share it; the wide
/// BVH is built from it.
pub struct Bvh {
    /// Depth-first; empty iff no primitive has non-empty bounds.
    nodes: Vec<Node>,
    /// Caller's primitive indices in leaf order.
    indices: Vec<u32>,
    /// Number of primitives given to `build`.
    len: usize,
}

/// Size and quality of a built tree.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BvhStats {
    /// Number of nodes, inner and leaf.
    pub nodes: usize,
    /// Number of leaf nodes.
    pub leaves: usize,
    /// Root has depth 0.
    pub max_depth: u32,
    /// Expected cost of a random ray that hits the root (traversal step and
    /// primitive test both cost 1), areas normalised by the root's; lower is
    /// better, and comparable across scenes of the same primitive count.
    pub sah_cost: f32,
    /// Heap bytes held by the nodes and the index array.
    pub bytes: usize,
}

impl Bvh {
    /// Builds over `bounds[i]` for primitive `i`.
    pub fn build(bounds: &[Aabb]) -> Self {
        let (nodes, indices) = build::build(bounds);
        Self {
            nodes,
            indices,
            len: bounds.len(),
        }
    }

    /// Number of primitives the tree was built over (including any dropped
    /// for empty bounds).
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if built over no primitive at all.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Bounds of every primitive, grown by a few ulps ([`Aabb::padded`]);
    /// [`Aabb::EMPTY`] if there are none.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, Node::bounds)
    }

    /// Size and SAH quality of the tree (see [`BvhStats`]).
    pub fn stats(&self) -> BvhStats {
        stats_of(&self.nodes, self.indices.len())
    }
}

/// Binary nodes and leaf-order primitive ids, for trees built on this one
/// (the wide [`crate::accel::wide::WideBvh`]): SAH leaves of at most
/// `max_leaf`, and every node of at most `whole` primitives left unsplit.
pub(crate) fn build_nodes(bounds: &[Aabb], max_leaf: usize, whole: usize) -> (Vec<Node>, Vec<u32>) {
    build::build_for_wide(bounds, max_leaf, whole)
}

/// Stats of depth-first binary `nodes` over `indices` leaf slots.
pub(crate) fn stats_of(nodes: &[Node], indices: usize) -> BvhStats {
    let mut s = BvhStats {
        nodes: nodes.len(),
        leaves: 0,
        max_depth: 0,
        sah_cost: 0.0,
        bytes: size_of_val(nodes) + indices * size_of::<u32>(),
    };
    if nodes.is_empty() {
        return s;
    }
    // A zero-area root (every primitive a single point) makes all areas
    // equal; count each node as area 1 then.
    let root_area = nodes[0].bounds().surface_area();
    let rel = |n: &Node| {
        if root_area > 0.0 {
            n.bounds().surface_area() / root_area
        } else {
            1.0
        }
    };
    let mut stack = vec![(0usize, 0u32)];
    while let Some((i, depth)) = stack.pop() {
        let n = &nodes[i];
        s.max_depth = s.max_depth.max(depth);
        if n.is_leaf() {
            s.leaves += 1;
            s.sah_cost += rel(n) * n.count as f32;
        } else {
            s.sah_cost += build::TRAVERSAL_COST * rel(n);
            stack.push((i + 1, depth + 1));
            stack.push((n.offset as usize, depth + 1));
        }
    }
    s
}
