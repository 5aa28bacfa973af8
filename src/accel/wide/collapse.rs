//! Binary → wide: each wide node takes a binary node's two children and
//! keeps opening the interior child with the largest surface area until it
//! has [`WIDTH`] (the greedy rule of Wald et al. 2008 and Embree's builder;
//! opening large boxes first removes the traversal steps rays take most).
//! A binary subtree of at most `MAX_LEAF` primitives becomes one leaf: its
//! primitives are contiguous in leaf order, and one leaf test is cheaper
//! than a node visit plus two leaf tests (it also cut node memory from 37
//! to about 22 bytes per triangle). That merge suits triangles, whose boxes
//! are small and cheap to test; [`Leaves::Single`] keeps the binary tree's
//! one-primitive leaves instead, for scene-level shapes such as the walls of
//! a room, whose union box every ray enters.

use rayon::prelude::*;

use super::{EMPTY, LEAF, Leaves, MAX_LEAF, WIDTH, WideNode, leaf_ref};
use crate::accel::bvh::Node;

/// Subtrees over at least this many primitives are collapsed in parallel
/// (the top three wide levels of the 1M-triangle mesh).
const PARALLEL_MIN: u32 = 1 << 14;

/// Collapses depth-first binary `nodes` (leaf ranges index the leaf-order
/// array) into wide nodes, root first.
pub(super) fn collapse(nodes: &[Node], leaves: Leaves) -> Vec<WideNode> {
    let mut out = Vec::with_capacity(nodes.len() / 3 + 1);
    // Read at random by every ray: huge pages (see `huge_pages`).
    crate::huge_pages::advise(&out);
    if nodes.is_empty() {
        return out;
    }
    if nodes[0].is_leaf() {
        // A lone leaf still gets a root node, so traversal has one shape.
        let mut root = WideNode::EMPTY;
        root.set_child(0, nodes[0].bounds(), leaf_ref(nodes[0].offset, nodes[0].count));
        out.push(root);
        return out;
    }
    // Leaf range of every binary subtree, bottom-up (children come after
    // their parent in depth-first order).
    let mut range = vec![(0u32, 0u32); nodes.len()];
    for i in (0..nodes.len()).rev() {
        let n = &nodes[i];
        range[i] = if n.is_leaf() {
            (n.offset, n.count)
        } else {
            let [l, r] = kids(nodes, i);
            (range[l].0, range[l].1 + range[r].1)
        };
    }
    let c = Collapser {
        nodes,
        range: &range,
        leaves,
    };
    c.emit(0, &mut out);
    out
}

struct Collapser<'a> {
    nodes: &'a [Node],
    range: &'a [(u32, u32)],
    leaves: Leaves,
}

/// Children of binary interior node `i`.
#[inline]
fn kids(nodes: &[Node], i: usize) -> [usize; 2] {
    [i + 1, nodes[i].offset as usize]
}

impl Collapser<'_> {
    /// Whether binary node `i` becomes a wide-tree leaf.
    fn is_leaf(&self, i: usize) -> bool {
        match self.leaves {
            Leaves::Merged => self.range[i].1 <= MAX_LEAF,
            Leaves::Single => self.nodes[i].is_leaf(),
        }
    }

    /// Appends the wide node for binary interior node `i` and its subtree;
    /// returns its index.
    fn emit(&self, i: usize, out: &mut Vec<WideNode>) -> u32 {
        let nodes = self.nodes;
        let me = out.len();
        out.push(WideNode::EMPTY);
        let [l, r] = kids(nodes, i);
        let mut open = [l, r, 0, 0, 0, 0, 0, 0];
        let mut len = 2;
        while len < WIDTH {
            let best = open[..len]
                .iter()
                .enumerate()
                .filter(|(_, c)| !self.is_leaf(**c))
                .max_by(|a, b| {
                    let area = |k: usize| nodes[k].bounds().surface_area();
                    area(*a.1).total_cmp(&area(*b.1))
                })
                .map(|(slot, _)| slot);
            let Some(slot) = best else { break };
            let [a, b] = kids(nodes, open[slot]);
            (open[slot], open[len]) = (a, b);
            len += 1;
        }
        // Keep the binary tree's left-to-right order for determinism.
        let open = &mut open[..len];
        open.sort_unstable();
        let mut node = WideNode::EMPTY;
        if self.range[i].1 >= PARALLEL_MIN {
            // Big subtrees: each interior child into its own vector on its
            // own task, appended in lane order with its node indices shifted,
            // which is exactly what the serial recursion writes.
            let subtrees: Vec<Option<Vec<WideNode>>> = open
                .par_iter()
                .map(|&c| {
                    (!self.is_leaf(c)).then(|| {
                        let mut sub = Vec::new();
                        self.emit(c, &mut sub);
                        sub
                    })
                })
                .collect();
            for (lane, (&c, sub)) in open.iter().zip(subtrees).enumerate() {
                let r = match sub {
                    None => leaf_ref(self.range[c].0, self.range[c].1),
                    Some(sub) => {
                        let shift = out.len() as u32;
                        out.extend(sub.into_iter().map(|mut n| {
                            for r in &mut n.child {
                                if *r != EMPTY && *r & LEAF == 0 {
                                    *r += shift;
                                }
                            }
                            n
                        }));
                        shift
                    }
                };
                node.set_child(lane, nodes[c].bounds(), r);
            }
        } else {
            for (lane, &c) in open.iter().enumerate() {
                let r = if self.is_leaf(c) {
                    leaf_ref(self.range[c].0, self.range[c].1)
                } else {
                    self.emit(c, out)
                };
                node.set_child(lane, nodes[c].bounds(), r);
            }
        }
        out[me] = node;
        me as u32
    }
}
