//! Choosing one light per shading point: in proportion to its power, so a
//! bright light is not starved of shadow rays by many dim ones, or by a
//! light tree ([`LightTree`]), which also weighs distance and orientation
//! from the shading point.

use super::tree::Top;
use super::{Light, LightTree};
use crate::math::luminance;
use glam::Vec3A;

/// How [`LightPicker`] chooses (the scene's `light_selection`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Selection {
    /// In proportion to power.
    Power,
    /// Every light equally likely (comparisons, tests).
    Uniform,
    /// By a light tree, per shading point.
    Tree,
}

/// Picks the light each next-event estimate samples: from a precomputed
/// distribution over the scene's lights (by power or uniform), or by a light
/// tree at the shading point.
#[derive(Clone, Debug, Default)]
pub struct LightPicker {
    /// Probability of each light.
    pmf: Vec<f32>,
    /// Running sum of `pmf`; last entry 1.
    cdf: Vec<f32>,
    /// With [`Selection::Tree`] and at least two bounded lights with power.
    tree: Option<LightTree>,
}

impl LightPicker {
    /// A picker choosing as `selection` says. With a tree, the environment
    /// is weighed per point too; a scene with nothing to choose per point
    /// (one light with power, or only the environment) picks by power.
    pub fn new(lights: &[Light], selection: Selection) -> Self {
        let uniform = selection == Selection::Uniform;
        let mut w: Vec<f32> = lights
            .iter()
            .map(|l| {
                if uniform {
                    1.0
                } else {
                    // A sky's or a sun's power grows with the scene's size
                    // squared: past f32 in a scene 10¹⁵ wide, so taken as
                    // the largest f32 rather than an infinity (whose share
                    // would be NaN).
                    let x = luminance(l.power());
                    if x > 0.0 { x.min(f32::MAX) } else { 0.0 }
                }
            })
            .collect();
        // Scaled so the largest is 1: the sum cannot overflow.
        let largest = w.iter().fold(0.0f32, |a, &b| a.max(b));
        if largest > 0.0 {
            w.iter_mut().for_each(|x| *x /= largest);
        }
        let total: f32 = w.iter().sum();
        if total <= 0.0 {
            w.iter_mut().for_each(|x| *x = 1.0);
        }
        let total: f32 = w.iter().sum();
        let pmf: Vec<f32> = w.iter().map(|x| x / total).collect();
        let mut acc = 0.0;
        let mut cdf: Vec<f32> = pmf
            .iter()
            .map(|p| {
                acc += p;
                acc
            })
            .collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let tree = match selection {
            Selection::Tree => LightTree::new(lights),
            _ => None,
        };
        Self { pmf, cdf, tree }
    }

    /// Tells a tree the share of the sky's irradiance the scene's surfaces
    /// see (see [`LightTree::set_sky_visibility`]); nothing to do otherwise.
    pub fn set_sky_visibility(&mut self, v: f32) {
        if let Some(t) = &mut self.tree {
            t.set_sky_visibility(v);
        }
    }

    /// A light index and its probability, for `u` ∈ [0, 1), at a shading
    /// point `p` with normal `n` (zero: none; only a tree looks at them).
    #[inline]
    pub fn pick(&self, p: Vec3A, n: Vec3A, u: f32) -> Option<(usize, f32)> {
        if let Some(t) = &self.tree {
            return t.pick(p, n, u);
        }
        if self.cdf.is_empty() {
            return None;
        }
        let i = self.cdf.partition_point(|&c| c <= u).min(self.cdf.len() - 1);
        // Skip zero-probability entries that share a cdf value.
        Some((i, self.pmf[i])).filter(|&(_, p)| p > 0.0)
    }

    /// The tree's first step at `p`, `n` ([`LightTree::top`]), for
    /// [`Self::pick_from`] and, from the next vertex, [`Self::pmf_from`];
    /// `None` without a tree.
    #[inline]
    pub fn top(&self, p: Vec3A, n: Vec3A) -> Option<Top> {
        self.tree.as_ref().map(|t| t.top(p, n))
    }

    /// [`Self::pick`] with `top` = [`Self::top`]`(p, n)`. Always inlined:
    /// a dispatch on the selection, the tree's walk out of line.
    #[inline(always)]
    pub fn pick_from(&self, top: Option<&Top>, p: Vec3A, n: Vec3A, u: f32) -> Option<(usize, f32)> {
        match (&self.tree, top) {
            (Some(t), Some(top)) => t.pick_from(top, p, n, u),
            _ => self.pick(p, n, u),
        }
    }

    /// [`Self::pmf`] with `top` = [`Self::top`]`(p, n)` (or `None`: made here).
    #[inline]
    pub fn pmf_from(&self, top: Option<&Top>, p: Vec3A, n: Vec3A, i: usize) -> f32 {
        match (&self.tree, top) {
            (Some(t), Some(top)) => t.pmf_from(top, p, n, i),
            _ => self.pmf(p, n, i),
        }
    }

    /// Probability that [`Self::pick`] at `p`, `n` picks light `i`: what a
    /// light-sampled pdf is multiplied by when it is weighted against BSDF
    /// sampling.
    #[inline]
    pub fn pmf(&self, p: Vec3A, n: Vec3A, i: usize) -> f32 {
        if let Some(t) = &self.tree {
            return t.pmf(p, n, i);
        }
        self.pmf.get(i).copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lights::PointLight;
    use crate::math::Rgb;
    use glam::Vec3A;

    /// A sun over a scene 10¹⁵ wide has a power past f32 (π r² E): its
    /// share is still a number, and the picks still sum to one.
    #[test]
    fn powers_past_f32_still_give_probabilities() {
        use crate::lights::DirectionalLight;
        let mut sun = DirectionalLight::new(Vec3A::NEG_Y, Rgb::splat(1e12));
        sun.scene_radius = 1e15;
        assert!(!luminance(sun.power()).is_finite());
        let lamp = Light::Point(PointLight {
            position: Vec3A::ZERO,
            intensity: Rgb::ONE,
        });
        let lights = [Light::Directional(sun), lamp, Light::Directional(sun)];
        let p = LightPicker::new(&lights, Selection::Power);
        let pmfs: Vec<f32> = (0..3).map(|i| p.pmf(Vec3A::ZERO, Vec3A::ZERO, i)).collect();
        assert!(pmfs.iter().all(|x| x.is_finite()), "{pmfs:?}");
        assert!((pmfs.iter().sum::<f32>() - 1.0).abs() < 1e-6 && (pmfs[0] - 0.5).abs() < 1e-6);
        assert!(p.pick(Vec3A::ZERO, Vec3A::ZERO, 0.7).is_some());
    }

    #[test]
    fn light_picker_follows_power() {
        let l = |i: f32| {
            Light::Point(PointLight {
                position: Vec3A::ZERO,
                intensity: Rgb::splat(i),
            })
        };
        let p = LightPicker::new(&[l(1.0), l(3.0), l(0.0)], Selection::Power);
        let mut counts = [0u32; 3];
        for k in 0..10_000 {
            let (i, pmf) = p
                .pick(Vec3A::ZERO, Vec3A::ZERO, (k as f32 + 0.5) / 10_000.0)
                .expect("a light");
            assert!((pmf - p.pmf(Vec3A::ZERO, Vec3A::ZERO, i)).abs() < 1e-6);
            counts[i] += 1;
        }
        assert_eq!(counts, [2500, 7500, 0]);
    }
}
