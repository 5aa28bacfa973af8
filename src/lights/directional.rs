//! A directional light: parallel light from infinitely far away, the way a
//! renderer draws the sun (Mitsuba 3's `directional`, pbrt-v4's
//! `DistantLight`, glTF's `KHR_lights_punctual` `directional`).
//!
//! Units: `irradiance` is what a surface facing the light receives, in
//! W/m² per channel; a surface at angle θ to it receives `E cos θ`. The
//! light has no position and no area: next-event estimation samples its one
//! direction exactly (a delta light, like a point), BSDF samples never reach
//! it, and its shadow rays are unbounded. Its power is its irradiance
//! through the scene's bounding disk, `π r² E` (pbrt-v4's `Phi`), which is
//! what selection by power weighs; the light tree weighs it, like the sky,
//! by what it sends the shading point (`tree.rs`).

use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::math::Rgb;
use glam::Vec3A;
use std::f32::consts::PI;

/// Parallel light travelling along `direction`.
#[derive(Clone, Copy, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels (from the light toward the scene).
    pub direction: Vec3A,
    /// Irradiance on a surface facing the light, W/m² per channel.
    pub irradiance: Rgb,
    /// Radius of the scene's bounding sphere, for [`Self::power`]; 1 until
    /// the scene is built.
    pub scene_radius: f32,
}

impl DirectionalLight {
    /// The light along `direction` (any non-zero, finite length) with
    /// `irradiance`. The direction is scaled by its largest component
    /// before normalising, so that `(1e30, 1e30, 0)` or `(1e-25, 0, 0)` keep
    /// their direction (their squared length leaves f32).
    pub fn new(direction: Vec3A, irradiance: Rgb) -> Self {
        let largest = direction.abs().max_element();
        let scaled = if largest > 0.0 && largest.is_finite() {
            direction / largest
        } else {
            direction
        };
        Self {
            direction: scaled.normalize_or(Vec3A::NEG_Y),
            irradiance,
            scene_radius: 1.0,
        }
    }

    /// The light reaching `p`: from `−direction`, `E` with density 1.
    #[inline]
    pub fn sample(&self, p: Vec3A) -> Option<LightSample> {
        Some(LightSample {
            wi: -self.direction,
            dist: f32::INFINITY,
            p,
            n: Vec3A::ZERO,
            li: self.irradiance,
            pdf: 1.0,
            delta: true,
        })
    }

    /// Φ = π r² E through the scene's bounding disk.
    pub fn power(&self) -> Rgb {
        PI * self.scene_radius * self.scene_radius * self.irradiance
    }
}

impl LightModel for DirectionalLight {
    /// No position: the tree weighs it beside the sky, by its irradiance at
    /// the point.
    fn bounds(&self, _phi: f32) -> Option<LightBounds> {
        None
    }
    fn is_delta(&self) -> bool {
        true
    }
    /// Its caustics are light traced as a parallel beam through the
    /// specular objects (`lights/caustic.rs`): the path tracer cannot find
    /// them, since no BSDF sample reaches a delta direction.
    fn emits_caustics(&self) -> bool {
        true
    }
    fn as_directional(&self) -> Option<&DirectionalLight> {
        Some(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_its_one_direction_unbounded_with_its_irradiance() {
        let l = DirectionalLight::new(Vec3A::new(0.0, -2.0, 0.0), Rgb::new(1.0, 2.0, 3.0));
        let s = l.sample(Vec3A::new(5.0, 1.0, -3.0)).unwrap();
        assert_eq!(s.wi, Vec3A::Y);
        assert_eq!(s.dist, f32::INFINITY);
        assert_eq!(s.li, Rgb::new(1.0, 2.0, 3.0));
        assert!(s.delta && s.pdf == 1.0 && s.n == Vec3A::ZERO);
    }

    #[test]
    fn huge_and_tiny_directions_keep_their_way() {
        for (d, want) in [
            (Vec3A::new(1e30, 1e30, 0.0), Vec3A::new(1.0, 1.0, 0.0).normalize()),
            (Vec3A::new(0.0, -1e-25, 0.0), Vec3A::NEG_Y),
            (
                Vec3A::new(-3e38, 0.0, 3e38),
                Vec3A::new(-1.0, 0.0, 1.0).normalize(),
            ),
        ] {
            let l = DirectionalLight::new(d, Rgb::ONE);
            assert!((l.direction - want).length() < 1e-6, "{d} gave {}", l.direction);
        }
    }

    #[test]
    fn power_is_the_irradiance_through_the_scene_disk() {
        let mut l = DirectionalLight::new(Vec3A::X, Rgb::splat(2.0));
        l.scene_radius = 3.0;
        assert!((l.power().y - PI * 9.0 * 2.0).abs() < 1e-4);
    }
}
