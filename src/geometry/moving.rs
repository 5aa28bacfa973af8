//! An instance that moves while the shutter is open: its placement at the
//! time of the camera sample being traced ([`crate::anim::clock`]).
//!
//! The scene BVH holds the box the instance sweeps over the shutter
//! ([`TransformTrack::bounds`]); the mesh's own BVH is untouched, so a
//! moving mesh is never rebuilt: each ray is moved into the mesh's space by
//! the inverse of the placement at its time (pbrt-v4's
//! `AnimatedPrimitive`). The lights of an emissive moving instance
//! (`lights/mesh.rs`) place their samples with the same placement.
//!
//! **The placement is cached per thread**, keyed by (motion, time): one
//! camera sample's path tests the same moving instance many times (every
//! ray that enters its swept box, its hit record, its light's samples and
//! densities), all at the sample's one time, and building a placement (a
//! slerp, a matrix, two inversions) costs several hundred instructions
//! where a cache hit costs a compare and a copy. The placement is a pure
//! function of the keys and the time, so a cached one is bit for bit the
//! one that would be built: renders do not depend on the cache.

use crate::anim::{TransformTrack, clock};
use glam::{Affine3A, Mat3A};
use std::cell::RefCell;
use std::sync::atomic::{AtomicU64, Ordering};

/// A moving instance's keys and the shutter interval it is traced over.
#[derive(Clone, Debug)]
pub struct InstanceMotion {
    /// `world_from_object` over time.
    pub track: TransformTrack,
    /// Shutter open and close, in frames: times outside are clamped in.
    pub shutter: (f32, f32),
    /// This motion's key in the placement cache: unique per
    /// [`InstanceMotion::new`], shared by clones (an instance and its
    /// lights move together, so they share cache entries).
    id: u64,
}

/// The transforms of a placement, as [`super::Instance`] keeps its static
/// ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// Object-to-world.
    pub world_from_object: Affine3A,
    /// Its inverse.
    pub object_from_world: Affine3A,
    /// Inverse transpose of the linear part, for normals.
    pub normal_from_object: Mat3A,
    /// `|det|` of the linear part: how volumes scale (areas scale by it
    /// times the length of the transformed unit normal, see
    /// [`Placement::area_scale`]).
    pub abs_det: f32,
}

impl Placement {
    /// The placement `world_from_object` and its inverses.
    pub fn new(world_from_object: Affine3A) -> Self {
        Self {
            world_from_object,
            object_from_world: world_from_object.inverse(),
            normal_from_object: world_from_object.matrix3.inverse().transpose(),
            abs_det: world_from_object.matrix3.determinant().abs(),
        }
    }

    /// The unit world normal of a surface whose object-space unit normal
    /// is `n`, and the factor `dA_world / dA_object` by which the placement
    /// scales its area: `|det M| · |M⁻ᵀ n|` (Nanson's formula).
    #[inline]
    pub fn normal_and_area_scale(&self, n: glam::Vec3A) -> (glam::Vec3A, f32) {
        let m = self.normal_from_object * n;
        let len = m.length();
        (m / len, self.abs_det * len)
    }

    /// `dA_world / dA_object` at a surface whose *world* unit normal is
    /// `n`: with `n = M⁻ᵀ n₀ / |M⁻ᵀ n₀|`, `Mᵀ n = n₀ / |M⁻ᵀ n₀|`, so the
    /// factor `|det M| · |M⁻ᵀ n₀|` is `|det M| / |Mᵀ n|`. What a density
    /// evaluated at a hit needs, where only the world normal is known.
    #[inline]
    pub fn area_scale(&self, n: glam::Vec3A) -> f32 {
        let m = &self.world_from_object.matrix3;
        let mt_n = glam::Vec3A::new(m.x_axis.dot(n), m.y_axis.dot(n), m.z_axis.dot(n));
        self.abs_det / mt_n.length()
    }
}

/// Cache slots per thread; motion `id` goes in slot `id % SLOTS`, so up to
/// this many moving instances never evict each other.
const SLOTS: usize = 16;

/// One cache slot: the motion's id, the time's bits, the placement.
#[derive(Clone, Copy)]
struct Slot {
    id: u64,
    time: u32,
    placement: Placement,
}

thread_local! {
    /// Recent placements of this thread (see the module docs).
    static CACHE: RefCell<[Option<Slot>; SLOTS]> = const { RefCell::new([None; SLOTS]) };
}

/// Ids handed to new motions; 0 is never given.
static NEXT_ID: AtomicU64 = AtomicU64::new(1);

impl InstanceMotion {
    /// The motion of `track` traced over `shutter` (open, close), in frames.
    pub fn new(track: TransformTrack, shutter: (f32, f32)) -> Self {
        Self {
            track,
            shutter,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// The placement at `time` (frames), clamped into the shutter; built,
    /// not cached.
    pub fn placement_at(&self, time: f32) -> Placement {
        let t = time.clamp(self.shutter.0, self.shutter.1);
        Placement::new(Affine3A::from_mat4(self.track.at(t)))
    }

    /// The placement at the time of the camera sample this thread traces,
    /// from the thread's cache when this motion was placed at that time
    /// last. Out of line: inlined into the still paths of its callers
    /// (hit records, light samples and densities), the cache lookup cost
    /// the static Cornell box 1.1% more instructions.
    #[inline(never)]
    pub fn now(&self) -> Placement {
        let t = clock::now().clamp(self.shutter.0, self.shutter.1);
        let time = t.to_bits();
        let k = (self.id % SLOTS as u64) as usize;
        CACHE.with_borrow_mut(|cache| match &cache[k] {
            Some(s) if s.id == self.id && s.time == time => s.placement,
            _ => {
                let placement = Placement::new(Affine3A::from_mat4(self.track.at(t)));
                cache[k] = Some(Slot {
                    id: self.id,
                    time,
                    placement,
                });
                placement
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::Interpolation;
    use glam::{Mat4, Quat, Vec3, Vec3A};

    fn turning() -> InstanceMotion {
        let a = Mat4::IDENTITY;
        let b = Mat4::from_scale_rotation_translation(
            Vec3::new(2.0, 1.0, 3.0),
            Quat::from_rotation_y(1.0),
            Vec3::new(1.0, 2.0, 0.0),
        );
        InstanceMotion::new(
            TransformTrack::new(&[(0.0, a), (1.0, b)], Interpolation::Linear),
            (0.0, 1.0),
        )
    }

    #[test]
    fn cached_placement_is_the_built_one_at_every_time() {
        let (m, other) = (turning(), turning());
        for s in 0..40 {
            // Two motions interleaved, times revisited: hits and misses.
            let t = (s % 7) as f32 / 6.0;
            clock::set(t);
            assert_eq!(m.now(), m.placement_at(t), "time {t}");
            assert_eq!(other.now(), other.placement_at(t), "time {t}");
            assert_eq!(m.now(), m.placement_at(t), "time {t}, again");
        }
        // Clamped into the shutter like the built one.
        clock::set(5.0);
        assert_eq!(m.now(), m.placement_at(1.0));
    }

    #[test]
    fn area_scale_follows_the_transformed_triangle() {
        let p = turning().placement_at(0.6);
        // A small object-space triangle and its image.
        let (a, b, c) = (
            Vec3A::new(0.1, 0.2, 0.3),
            Vec3A::new(0.4, 0.1, 0.2),
            Vec3A::new(0.2, 0.5, 0.1),
        );
        let n0 = (b - a).cross(c - a);
        let area0 = 0.5 * n0.length();
        let w = |q: Vec3A| p.world_from_object.transform_point3a(q);
        let nw = (w(b) - w(a)).cross(w(c) - w(a));
        let area_w = 0.5 * nw.length();
        let (n, scale) = p.normal_and_area_scale(n0.normalize());
        assert!(
            (scale - area_w / area0).abs() < 1e-4 * scale,
            "{scale} vs {}",
            area_w / area0
        );
        assert!((n - nw.normalize()).length() < 1e-5, "{n} vs {}", nw.normalize());
        let back = p.area_scale(nw.normalize());
        assert!((back - scale).abs() < 1e-4 * scale, "{back} vs {scale}");
    }
}
