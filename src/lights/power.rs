//! Choosing one light per shading point, in proportion to its power, so a
//! bright light is not starved of shadow rays by many dim ones.

use super::Light;
use crate::math::luminance;

/// Picks the light each next-event estimate samples, from a precomputed distribution
/// over the scene's lights (by power or uniform).
#[derive(Clone, Debug, Default)]
pub struct LightPicker {
    /// Probability of each light.
    pmf: Vec<f32>,
    /// Running sum of `pmf`; last entry 1.
    cdf: Vec<f32>,
}

impl LightPicker {
    /// By luminance of emitted power; `uniform` ignores power (for
    /// comparison and tests).
    pub fn new(lights: &[Light], uniform: bool) -> Self {
        let mut w: Vec<f32> = lights
            .iter()
            .map(|l| {
                if uniform {
                    1.0
                } else {
                    luminance(l.power()).max(0.0)
                }
            })
            .collect();
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
        Self { pmf, cdf }
    }

    /// A light index and its probability, for `u` ∈ [0, 1).
    #[inline]
    pub fn pick(&self, u: f32) -> Option<(usize, f32)> {
        if self.cdf.is_empty() {
            return None;
        }
        let i = self.cdf.partition_point(|&c| c <= u).min(self.cdf.len() - 1);
        // Skip zero-probability entries that share a cdf value.
        Some((i, self.pmf[i])).filter(|&(_, p)| p > 0.0)
    }

    /// Probability of picking light `i`: what a light-sampled pdf is multiplied by
    /// when it is weighted against BSDF sampling.
    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lights::PointLight;
    use crate::math::Rgb;
    use glam::Vec3A;

    #[test]
    fn light_picker_follows_power() {
        let l = |i: f32| {
            Light::Point(PointLight {
                position: Vec3A::ZERO,
                intensity: Rgb::splat(i),
            })
        };
        let p = LightPicker::new(&[l(1.0), l(3.0), l(0.0)], false);
        let mut counts = [0u32; 3];
        for k in 0..10_000 {
            let (i, pmf) = p.pick((k as f32 + 0.5) / 10_000.0).expect("a light");
            assert!((pmf - p.pmf(i)).abs() < 1e-6);
            counts[i] += 1;
        }
        assert_eq!(counts, [2500, 7500, 0]);
    }
}
