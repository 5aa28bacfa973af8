//! Absorption inside coloured glass (`Glass`/`RoughGlass` `attenuation`):
//! Beer–Lambert's exp(−σ·t) over every length `t` a path travels inside a
//! solid whose surface has an absorption coefficient σ
//! (`Material::absorption`). It is what Mitsuba 3 and pbrt-v4 render with a
//! dielectric holding a purely absorbing homogeneous medium, but applied in
//! closed form along each segment: no distance is sampled, so the
//! absorption adds no noise (a volumetric path tracer's free-flight
//! sampling, with an albedo of 0, ends paths at random instead).
//!
//! A path knows which solid it is in by the crossings it made: a
//! transmission into an absorbing material's surface (against its outward
//! geometric normal) enters σ, a transmission out of it leaves it for the
//! clear outside. So a ray between two objects inside the solid (a straw in
//! tea) is absorbed like the rest. What the path cannot know is where it
//! started: a camera or a light inside a solid starts as outside, and the
//! first surface it reaches from the inside of an absorbing material
//! (along its outward normal) tells it — that segment is absorbed with that
//! material's σ. So a camera under water sees the water's colour on the
//! segment to the surface it looks at; what it sees of an object inside the
//! water before that surface is not absorbed on the way (stated in
//! `docs/materials.md`).
//!
//! Meshes must be closed and wound outward (`KHR_materials_volume` asks the
//! same); solids must not overlap (a single absorbing solid at a time:
//! a path entering an absorbing solid from inside another takes the new
//! one's σ, and leaving it takes the clear outside).

use crate::geometry::Hit;
use crate::math::Rgb;
use crate::scene::Scene;
use glam::Vec3A;

/// The absorption coefficient of the solid a path is in (zero: outside
/// every absorbing solid, or not known to be in one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Interior(Rgb);

impl Interior {
    /// Outside every absorbing solid.
    pub const OUTSIDE: Interior = Interior(Rgb::ZERO);

    /// What a path keeps over a segment of length `t` that ends at `hit`,
    /// arriving along unit direction `d`: exp(−σt) for the solid the path
    /// is in, or, when it is not known to be in one and arrives at the
    /// inside of an absorbing surface, that surface's σ (a start inside).
    #[inline]
    pub fn to_hit(self, scene: &Scene, hit: &Hit, d: Vec3A) -> Rgb {
        if scene.absorption.is_empty() {
            return Rgb::ONE;
        }
        let sigma = if self.0 != Rgb::ZERO {
            self.0
        } else if d.dot(hit.ng) > 0.0 {
            absorption_of(scene, hit)
        } else {
            return Rgb::ONE;
        };
        transmittance(sigma, hit.t)
    }

    /// What a path keeps over `t` (up to a light sample, or to infinity for
    /// a ray that leaves the scene) in this solid.
    #[inline]
    pub fn over(self, t: f32) -> Rgb {
        if self.0 == Rgb::ZERO {
            Rgb::ONE
        } else {
            transmittance(self.0, t)
        }
    }

    /// The solid a ray leaving `hit` along `w` is in: an absorbing
    /// surface's inside behind its outward normal, the clear outside in
    /// front of it; past any other surface, the same as before.
    #[inline]
    pub fn beyond(self, scene: &Scene, hit: &Hit, w: Vec3A) -> Interior {
        let sigma = absorption_of(scene, hit);
        if sigma == Rgb::ZERO {
            self
        } else if w.dot(hit.ng) < 0.0 {
            Interior(sigma)
        } else {
            Interior::OUTSIDE
        }
    }
}

/// The absorption coefficient of the material at `hit` (zero when the
/// scene has none).
#[inline]
fn absorption_of(scene: &Scene, hit: &Hit) -> Rgb {
    scene
        .absorption
        .get(hit.material as usize)
        .copied()
        .unwrap_or(Rgb::ZERO)
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
        assert_eq!(Interior::OUTSIDE.over(f32::INFINITY), Rgb::ONE);
        assert_eq!(Interior(sigma).over(0.5), t);
    }
}
