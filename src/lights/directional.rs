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
//!
//! # A sun with a size (`angle_degrees`)
//! Given an angular diameter 2θ (Blender's sun `Angle`; the real sun's is
//! about 0.53°), the light is a disk of uniform radiance L = E / (π sin²θ)
//! at infinity, so a surface facing it still receives E, and shadows get
//! penumbrae that widen with the distance to the occluder. Next-event
//! estimation samples a direction uniformly in the cone (density
//! 1/(2π(1 − cos θ))): the sample's weight L·2π(1 − cos θ) = E·2/(1 + cos θ)
//! is carried, as the hard sun's E is, without MIS. BSDF samples never count
//! the disk (as with the hard sun, a mirror shows no sun), so every estimate
//! counts the sun exactly once; the cost is variance on glossy lobes
//! narrower than the disk, which the light sample alone finds. The light
//! tracer's caustics start each beam ray in a direction of the cone.

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
    /// 1 − cos θ of the disk's angular radius θ (0: a hard sun), kept as
    /// 2 sin²(θ/2) so that a half-degree sun keeps its digits.
    pub one_minus_cos: f32,
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
            one_minus_cos: 0.0,
        }
    }

    /// The light with an angular diameter of `degrees` (0: hard; at most
    /// 180, a hemisphere).
    pub fn with_angle(mut self, degrees: f32) -> Self {
        let half = (0.5 * degrees.clamp(0.0, 180.0)).to_radians();
        let s = (0.5 * half).sin();
        self.one_minus_cos = 2.0 * s * s;
        self
    }

    /// The direction toward the light for `u` ∈ [0, 1)², uniform over the
    /// disk's cone (`−direction` for a hard sun), and the weight its
    /// irradiance carries: E for a hard sun, L·2π(1 − cos θ) for a disk.
    #[inline]
    pub fn toward(&self, u: glam::Vec2) -> (Vec3A, Rgb) {
        let toward = -self.direction;
        if self.one_minus_cos <= 0.0 {
            return (toward, self.irradiance);
        }
        let omc = u.x * self.one_minus_cos;
        let cos = 1.0 - omc;
        let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let local = Vec3A::new(sin * phi.cos(), sin * phi.sin(), cos);
        let w = crate::math::Frame::from_normal(toward).to_world(local);
        (w, self.irradiance * (2.0 / (2.0 - self.one_minus_cos)))
    }

    /// The light reaching `p`: from `−direction`, `E` with density 1; from
    /// a direction of the disk's cone for a sun with a size (module docs).
    #[inline]
    pub fn sample(&self, p: Vec3A, u: glam::Vec2) -> Option<LightSample> {
        let (wi, li) = self.toward(u);
        Some(LightSample {
            wi,
            dist: f32::INFINITY,
            p,
            n: Vec3A::ZERO,
            li,
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
        let s = l
            .sample(Vec3A::new(5.0, 1.0, -3.0), glam::Vec2::splat(0.5))
            .unwrap();
        assert_eq!(s.wi, Vec3A::Y);
        assert_eq!(s.dist, f32::INFINITY);
        assert_eq!(s.li, Rgb::new(1.0, 2.0, 3.0));
        assert!(s.delta && s.pdf == 1.0 && s.n == Vec3A::ZERO);
    }

    /// A sun with a size samples its disk's cone uniformly, and a surface
    /// facing it still receives E on average; a hard sun's one direction is
    /// `−direction` exactly, weight E.
    #[test]
    fn a_sun_with_a_size_samples_its_cone_and_keeps_its_irradiance() {
        let hard = DirectionalLight::new(Vec3A::new(0.3, -1.0, 0.2), Rgb::splat(3.0));
        let (w, e) = hard.toward(glam::Vec2::new(0.7, 0.2));
        assert!(w == -hard.direction && e == Rgb::splat(3.0));
        for degrees in [0.53f32, 10.0, 90.0] {
            let sun = hard.with_angle(degrees);
            let cos_max = (0.5 * degrees).to_radians().cos();
            let mut rng = crate::math::Pcg32::new(5, 1);
            let (n, mut irradiance, mut below_mid) = (100_000, 0.0f64, 0);
            let mid = 1.0 - 0.5 * (1.0 - cos_max);
            for _ in 0..n {
                let (w, e) = sun.toward(rng.next_vec2());
                let cos = w.dot(-sun.direction);
                assert!(
                    cos >= cos_max - 1e-6 && (w.length() - 1.0).abs() < 1e-5,
                    "{degrees}°: {w}"
                );
                irradiance += (e.x * cos) as f64;
                below_mid += usize::from(cos < mid);
            }
            let mean = irradiance / n as f64;
            assert!((mean - 3.0).abs() < 0.01 * 3.0, "{degrees}°: E {mean}");
            // Uniform in solid angle: uniform in cos θ.
            let half = below_mid as f32 / n as f32;
            assert!(
                (half - 0.5).abs() < 0.01,
                "{degrees}°: {half} below the middle cos"
            );
        }
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
