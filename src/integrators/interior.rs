//! Absorption inside coloured glass (`Glass`/`RoughGlass` `attenuation`):
//! Beer–Lambert's exp(−σ·t) over every length `t` a path travels inside a
//! solid whose surface has an absorption coefficient σ
//! (`Material::interior`). It is what Mitsuba 3 and pbrt-v4 render with a
//! dielectric holding a purely absorbing homogeneous medium, applied in
//! closed form along each segment (no distance is sampled: no noise), but
//! as a property of the material: it needs no `interior` on the object (a
//! glTF asset is one object with many materials), and a scene keeps the
//! surface path tracer and its light-traced caustics, which a scene with
//! media gives up (`vol_path`).
//!
//! A path knows which solid it is in by the crossings it made: a
//! transmission into a solid's surface (`Glass` but a thin sheet,
//! `RoughGlass`; against its outward geometric normal) enters its σ (zero
//! for clear glass), a transmission out of it leaves it for the clear
//! outside; other surfaces (a straw in tea) leave the path where it was, so
//! a ray between two objects inside the solid is absorbed like the rest.
//! What the path cannot know is where it started, or what is around a solid
//! it leaves: a path that is not known to be in coloured glass and reaches
//! the inside of a coloured glass surface (along its outward normal) was in
//! it, and that segment is absorbed with that material's σ. So a camera
//! under water sees the water's colour on the segment to the surface it
//! looks at, and a path leaving an ice cube in a drink is absorbed by the
//! drink up to the glass; what lies on the way (an object inside the water
//! seen before any such surface, or between the ice and the glass) is not
//! absorbed on that segment (stated in `docs/materials.md`).
//!
//! Meshes must be closed and wound outward (`KHR_materials_volume` asks the
//! same), and solids must not overlap: the path keeps one solid, not a
//! stack of nested ones.

use crate::geometry::Hit;
use crate::math::Rgb;
use crate::scene::Scene;
use glam::Vec3A;

/// The solid a path is in: the index of the material bounding it (its σ in
/// `Scene::absorption`, zero for clear glass), or none — outside every
/// solid, or not known to be in one. An index rather than σ keeps the
/// path tracer's state small (4 bytes against 16; clear scenes pay for it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Interior(u32);

impl Interior {
    /// Outside every solid.
    pub const OUTSIDE: Interior = Interior(u32::MAX);

    /// What a path keeps over a segment of length `t` that ends at `hit`,
    /// arriving along unit direction `d`: exp(−σt) for the solid the path
    /// is in, or, when it is not known to be in one and arrives at the
    /// inside of an absorbing surface, that surface's σ (a start inside).
    #[inline]
    pub fn to_hit(self, scene: &Scene, hit: &Hit, d: Vec3A) -> Rgb {
        if scene.absorption.is_empty() {
            return Rgb::ONE;
        }
        let sigma = match sigma_of(scene, self.0) {
            Some(sigma) => sigma,
            None if d.dot(hit.ng) > 0.0 => sigma_of(scene, hit.material).unwrap_or(Rgb::ZERO),
            None => return Rgb::ONE,
        };
        transmittance(sigma, hit.t)
    }

    /// What a path keeps over `t` (up to a light sample, or to infinity for
    /// a ray that leaves the scene) in this solid.
    #[inline]
    pub fn over(self, scene: &Scene, t: f32) -> Rgb {
        match sigma_of(scene, self.0) {
            Some(sigma) => transmittance(sigma, t),
            None => Rgb::ONE,
        }
    }

    /// The solid a ray leaving `hit` along `w` is in: a solid's inside
    /// behind its outward normal (clear or coloured), the clear outside in
    /// front of it; past any other surface, the same as before.
    #[inline]
    pub fn beyond(self, scene: &Scene, hit: &Hit, w: Vec3A) -> Interior {
        match sigma_of(scene, hit.material) {
            None => self,
            Some(_) if w.dot(hit.ng) < 0.0 => Interior(hit.material),
            Some(_) => Interior::OUTSIDE,
        }
    }
}

/// The absorption inside the solid material `m` bounds; `None` when it
/// bounds none (or the scene has no coloured glass, or `m` is none).
#[inline]
fn sigma_of(scene: &Scene, m: u32) -> Option<Rgb> {
    scene.absorption.get(m as usize).copied().flatten()
}

/// exp(−σt) per channel; a channel with σ = 0 keeps 1 even at t = ∞, and
/// a length that is not a number keeps nothing.
#[inline]
pub(crate) fn transmittance(sigma: Rgb, t: f32) -> Rgb {
    let keep = |s: f32| {
        if s <= 0.0 {
            1.0
        } else if t >= 0.0 {
            (-s * t).exp()
        } else {
            0.0
        }
    };
    Rgb::new(keep(sigma.x), keep(sigma.y), keep(sigma.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transmittance_is_beer_lambert_and_never_nan() {
        let sigma = Rgb::new(0.0, 1.0, 2.0);
        let t = transmittance(sigma, 0.5);
        assert_eq!(t.x, 1.0);
        assert!((t.y - (-0.5f32).exp()).abs() < 1e-6);
        assert!((t.z - (-1.0f32).exp()).abs() < 1e-6);
        // Infinite lengths: a clear channel keeps all, an absorbing one none.
        assert_eq!(transmittance(sigma, f32::INFINITY), Rgb::new(1.0, 0.0, 0.0));
        assert_eq!(transmittance(sigma, 0.0), Rgb::ONE);
        assert_eq!(transmittance(sigma, f32::NAN), Rgb::new(1.0, 0.0, 0.0));
    }
}
