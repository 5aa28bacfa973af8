//! Binary → 4-wide: each 4-wide node takes a binary node's two children and
//! keeps opening the interior child with the largest surface area until it
//! has four (the greedy rule of Wald et al. 2008 and Embree's BVH4 builder;
//! opening large boxes first removes the traversal steps rays take most).

use super::{Node4, leaf_ref};
use crate::accel::bvh::Node;

/// Collapses depth-first binary `nodes` (leaf ranges index the leaf-order
/// array) into 4-wide nodes, root first.
pub(super) fn collapse(nodes: &[Node]) -> Vec<Node4> {
    let mut out = Vec::with_capacity(nodes.len() / 3 + 1);
    if nodes.is_empty() {
        return out;
    }
    if nodes[0].is_leaf() {
        // A lone leaf still gets a root node, so traversal has one shape.
        let mut root = Node4::EMPTY;
        root.set_child(0, nodes[0].bounds(), leaf_ref(nodes[0].offset, nodes[0].count));
        out.push(root);
        return out;
    }
    emit(nodes, 0, &mut out);
    out
}

/// Children of binary interior node `i`.
#[inline]
fn kids(nodes: &[Node], i: usize) -> [usize; 2] {
    [i + 1, nodes[i].offset as usize]
}

/// Appends the 4-wide node for binary interior node `i` and its subtree;
/// returns its index.
fn emit(nodes: &[Node], i: usize, out: &mut Vec<Node4>) -> u32 {
    let me = out.len();
    out.push(Node4::EMPTY);
    let mut open: Vec<usize> = kids(nodes, i).to_vec();
    while open.len() < 4 {
        let best = open
            .iter()
            .enumerate()
            .filter(|(_, c)| !nodes[**c].is_leaf())
            .max_by(|a, b| {
                let area = |k: usize| nodes[k].bounds().surface_area();
                area(*a.1).total_cmp(&area(*b.1))
            })
            .map(|(slot, _)| slot);
        let Some(slot) = best else { break };
        let c = open.swap_remove(slot);
        open.extend(kids(nodes, c));
    }
    // Keep the binary tree's left-to-right order for determinism.
    open.sort_unstable();
    let mut node = Node4::EMPTY;
    for (lane, &c) in open.iter().enumerate() {
        let n = &nodes[c];
        let r = if n.is_leaf() {
            leaf_ref(n.offset, n.count)
        } else {
            emit(nodes, c, out)
        };
        node.set_child(lane, n.bounds(), r);
    }
    out[me] = node;
    me as u32
}
