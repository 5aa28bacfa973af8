//! An instance that moves while the shutter is open: its placement at the
//! time of the camera sample being traced ([`crate::anim::clock`]).
//!
//! The scene BVH holds the box the instance sweeps over the shutter
//! ([`TransformTrack::bounds`]); the mesh's own BVH is untouched, so a
//! moving mesh is never rebuilt: each ray is moved into the mesh's space by
//! the inverse of the placement at its time (pbrt-v4's
//! `AnimatedPrimitive`). That inverse is computed per ray test: moving
//! instances pay it, static ones nothing.

use crate::anim::{TransformTrack, clock};
use glam::{Affine3A, Mat3A};

/// A moving instance's keys and the shutter interval it is traced over.
#[derive(Clone, Debug)]
pub struct InstanceMotion {
    /// `world_from_object` over time.
    pub track: TransformTrack,
    /// Shutter open and close, in frames: times outside are clamped in.
    pub shutter: (f32, f32),
}

/// The transforms of a placement, as [`super::Instance`] keeps its static
/// ones.
#[derive(Clone, Copy, Debug)]
pub struct Placement {
    /// Object-to-world.
    pub world_from_object: Affine3A,
    /// Its inverse.
    pub object_from_world: Affine3A,
    /// Inverse transpose of the linear part, for normals.
    pub normal_from_object: Mat3A,
}

impl Placement {
    /// The placement `world_from_object` and its inverses.
    pub fn new(world_from_object: Affine3A) -> Self {
        Self {
            world_from_object,
            object_from_world: world_from_object.inverse(),
            normal_from_object: world_from_object.matrix3.inverse().transpose(),
        }
    }
}

impl InstanceMotion {
    /// The placement at the time of the camera sample this thread traces.
    #[inline]
    pub fn now(&self) -> Placement {
        let t = clock::now().clamp(self.shutter.0, self.shutter.1);
        Placement::new(Affine3A::from_mat4(self.track.at(t)))
    }
}
