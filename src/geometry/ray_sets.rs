//! Ray sets for measuring a mesh's BVH, shared by `ronray bench` and the
//! tests that compare traversal with brute force (the sets of
//! `perf-anchors.md`, so figures sit beside Embree's).

use super::Mesh;
use crate::math::{Pcg32, Ray, sampling};
use glam::Vec3A;

/// `n` incoherent rays: origins uniform in the mesh's bounding box,
/// directions uniform on the sphere.
pub fn incoherent_rays(mesh: &Mesh, n: usize, seed: u64) -> Vec<Ray> {
    let b = mesh.bounds();
    let mut rng = Pcg32::new(seed, 1);
    (0..n)
        .map(|_| {
            let u = Vec3A::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            Ray::new(b.min + u * b.extent(), sampling::uniform_sphere(rng.next_vec2()))
        })
        .collect()
}
