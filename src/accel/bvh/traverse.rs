//! Stack-based traversal, nearer child first.
//!
//! Both children of a node are tested together; the nearer (by entry
//! distance, which beats the split-axis sign for incoherent rays) is visited
//! next and the farther one pushed with its entry distance, so entries that
//! lie beyond a hit found in the meantime are discarded when popped. The
//! stack is a fixed array of `MAX_DEPTH` entries (the build guarantees no
//! deeper leaf), so a ray allocates nothing.

use super::{Bvh, MAX_DEPTH};
use crate::accel::aabb::safe_inv_dir;
use crate::math::Ray;

const STACK: usize = MAX_DEPTH as usize;

impl Bvh {
    /// Closest hit. `hit(prim, ray, t_max)` returns the primitive's hit
    /// distance if it is below `t_max`. Returns the winning primitive and t.
    #[inline]
    pub fn intersect(
        &self,
        ray: &Ray,
        t_max: f32,
        mut hit: impl FnMut(u32, &Ray, f32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let root = self.nodes.first()?;
        let (o, inv_d) = (ray.o, safe_inv_dir(ray.d));
        let mut t_best = t_max;
        let mut best = None;
        if root.hit(o, inv_d, t_best) == f32::INFINITY {
            return None;
        }
        let mut stack = [(0u32, 0.0f32); STACK];
        let mut sp = 0;
        let mut cur = 0usize;
        loop {
            let node = &self.nodes[cur];
            if node.is_leaf() {
                let first = node.offset as usize;
                for &prim in &self.indices[first..first + node.count as usize] {
                    if let Some(t) = hit(prim, ray, t_best)
                        && t < t_best
                    {
                        t_best = t;
                        best = Some((prim, t));
                    }
                }
            } else {
                let (l, r) = (cur + 1, node.offset as usize);
                let tl = self.nodes[l].hit(o, inv_d, t_best);
                let tr = self.nodes[r].hit(o, inv_d, t_best);
                match (tl < f32::INFINITY, tr < f32::INFINITY) {
                    (true, true) => {
                        let (near, far, t_far) = if tl <= tr { (l, r, tr) } else { (r, l, tl) };
                        debug_assert!(sp < STACK, "BVH deeper than MAX_DEPTH");
                        stack[sp] = (far as u32, t_far);
                        sp += 1;
                        cur = near;
                        continue;
                    }
                    (true, false) => {
                        cur = l;
                        continue;
                    }
                    (false, true) => {
                        cur = r;
                        continue;
                    }
                    (false, false) => {}
                }
            }
            // Pop, skipping nodes whose entry is now behind the best hit.
            loop {
                if sp == 0 {
                    return best;
                }
                sp -= 1;
                let (n, t_enter) = stack[sp];
                if t_enter <= t_best {
                    cur = n as usize;
                    break;
                }
            }
        }
    }

    /// Any hit below `t_max` (shadow rays): stops at the first one.
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32, mut hit: impl FnMut(u32, &Ray, f32) -> bool) -> bool {
        let Some(root) = self.nodes.first() else {
            return false;
        };
        let (o, inv_d) = (ray.o, safe_inv_dir(ray.d));
        if root.hit(o, inv_d, t_max) == f32::INFINITY {
            return false;
        }
        let mut stack = [0u32; STACK];
        let mut sp = 0;
        let mut cur = 0usize;
        loop {
            let node = &self.nodes[cur];
            if node.is_leaf() {
                let first = node.offset as usize;
                for &prim in &self.indices[first..first + node.count as usize] {
                    if hit(prim, ray, t_max) {
                        return true;
                    }
                }
            } else {
                let (l, r) = (cur + 1, node.offset as usize);
                let tl = self.nodes[l].hit(o, inv_d, t_max);
                let tr = self.nodes[r].hit(o, inv_d, t_max);
                match (tl < f32::INFINITY, tr < f32::INFINITY) {
                    (true, true) => {
                        let (near, far) = if tl <= tr { (l, r) } else { (r, l) };
                        debug_assert!(sp < STACK, "BVH deeper than MAX_DEPTH");
                        stack[sp] = far as u32;
                        sp += 1;
                        cur = near;
                        continue;
                    }
                    (true, false) => {
                        cur = l;
                        continue;
                    }
                    (false, true) => {
                        cur = r;
                        continue;
                    }
                    (false, false) => {}
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            cur = stack[sp] as usize;
        }
    }
}
