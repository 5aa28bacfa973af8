//! Size and SAH quality of the wide tree itself. It used to report the
//! binary tree's figures, but the binary build now stops at subtrees the
//! collapse merges into one leaf, so only the wide tree holds the structure
//! rays see. Measuring it here also took a walk over the ~1M binary nodes
//! of the 1M-triangle mesh out of the build.

use super::{EMPTY, LEAF, WIDTH, WideNode, leaf_range};
use crate::accel::{Aabb, BvhStats};

/// Stats of `nodes` (root first) over `slots` leaf slots. A wide node visit
/// costs 1 (its eight box tests are one SIMD step), a primitive test 1;
/// areas are relative to the root's box. `max_depth` counts leaves as one
/// level below the node holding them, as in the binary tree.
pub(super) fn stats(nodes: &[WideNode], slots: usize) -> BvhStats {
    let mut s = BvhStats {
        nodes: nodes.len(),
        leaves: 0,
        max_depth: 0,
        sah_cost: 0.0,
        bytes: size_of_val(nodes) + slots * size_of::<u32>(),
    };
    let Some(root) = nodes.first() else {
        return s;
    };
    let root_box = live_lanes(root).fold(Aabb::EMPTY, |acc, i| acc.union(root.child_bounds(i)));
    // A zero-area root (every primitive one point): count every box as 1.
    let root_area = root_box.surface_area();
    let rel = |b: Aabb| {
        if root_area > 0.0 {
            b.surface_area() / root_area
        } else {
            1.0
        }
    };
    let mut stack = vec![(0u32, root_box, 0u32)];
    while let Some((n, b, depth)) = stack.pop() {
        s.sah_cost += rel(b);
        let node = &nodes[n as usize];
        for i in live_lanes(node) {
            let (r, cb) = (node.child[i], node.child_bounds(i));
            if r & LEAF != 0 {
                s.leaves += 1;
                s.max_depth = s.max_depth.max(depth + 1);
                s.sah_cost += rel(cb) * leaf_range(r).1 as f32;
            } else {
                stack.push((r, cb, depth + 1));
            }
        }
    }
    s
}

/// Lanes of `n` that hold a child.
fn live_lanes(n: &WideNode) -> impl Iterator<Item = usize> + '_ {
    (0..WIDTH).filter(move |&i| n.child[i] != EMPTY)
}
