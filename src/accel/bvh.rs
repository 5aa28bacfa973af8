//! Bounding volume hierarchy over primitive bounds.
//!
//! PLACEHOLDER CONTRACT: brute force until the SAH build lands. The public
//! API below is the contract the renderer codes against.

use super::Aabb;
use crate::math::Ray;

pub struct Bvh {
    bounds: Vec<Aabb>,
}

impl Bvh {
    /// Builds over `bounds[i]` for primitive `i`.
    pub fn build(bounds: &[Aabb]) -> Self {
        Self {
            bounds: bounds.to_vec(),
        }
    }

    /// Closest hit. `hit(prim, ray, t_max)` returns the primitive's hit
    /// distance if it is below `t_max`. Returns the winning primitive and t.
    pub fn intersect(
        &self,
        ray: &Ray,
        t_max: f32,
        mut hit: impl FnMut(u32, &Ray, f32) -> Option<f32>,
    ) -> Option<(u32, f32)> {
        let mut best = None;
        let mut t_best = t_max;
        for i in 0..self.bounds.len() as u32 {
            if let Some(t) = hit(i, ray, t_best).filter(|&t| t < t_best) {
                t_best = t;
                best = Some((i, t));
            }
        }
        best
    }

    /// Any hit below `t_max` (shadow rays): stops at the first one.
    pub fn occluded(&self, ray: &Ray, t_max: f32, mut hit: impl FnMut(u32, &Ray, f32) -> bool) -> bool {
        (0..self.bounds.len() as u32).any(|i| hit(i, ray, t_max))
    }
}

/// Placeholder statistics (replaced with the SAH build).
#[derive(Clone, Copy, Debug, Default)]
pub struct BvhStats {
    pub nodes: usize,
    pub leaves: usize,
    pub max_depth: usize,
    pub sah_cost: f32,
    pub bytes: usize,
}

impl Bvh {
    pub fn stats(&self) -> BvhStats {
        BvhStats::default()
    }
}
