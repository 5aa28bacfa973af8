//! A heterogeneous medium: extinction from a density grid (Mitsuba's
//! `heterogeneous` medium with a `gridvolume` σ_t), free flights by delta
//! tracking and transmittance by ratio tracking against one majorant.
//!
//! The grid fills the box [`Grid::min`, `Grid::max`]; a point's grid
//! coordinate is `q·res − ½` with `q = (p − min)/(max − min)` (values sit at
//! texel centres), interpolated trilinearly with indices clamped to the grid,
//! and σ_t = 0 outside the box. σ_t(p) = `scale` × the interpolated value;
//! σ_s = `albedo` σ_t. These are Mitsuba 3's conventions, probed against it
//! (the Mitsuba reference set's notes on grid media; `src/media/vol.rs` reads the format).
//!
//! The majorant is the largest σ_t of the grid, one for the whole box, as
//! Mitsuba's default (`majorant_resolution_factor = 0`). Delta tracking
//! (Woodcock) takes steps of density σ̄ exp(−σ̄ t) and accepts a step as a
//! real collision with probability σ_t(p)/σ̄; ratio tracking (Novák et al.
//! 2014, <https://doi.org/10.1145/2661229.2661292>) multiplies the
//! transmittance estimate by 1 − σ_t(p)/σ̄ at each step. Both are unbiased.

use super::{Collision, HenyeyGreenstein};
use crate::math::Ray;
use glam::Vec3A;

/// Most tracking steps along one segment: with σ̄·length beyond this the
/// estimate stops early (a collision-free pass for delta tracking, the
/// product so far for ratio tracking). Validation keeps the optical
/// depth of the box below it (`load/medium.rs`), so renders never reach it.
pub const MAX_STEPS: u32 = 1 << 16;

/// A scalar density grid placed in a box, with its majorant.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Values along x, y, z.
    pub res: [u32; 3],
    /// `res[0]·res[1]·res[2]` values, x fastest: `(z·ny + y)·nx + x`.
    pub values: Vec<f32>,
    /// The box's lowest corner, in world space.
    pub min: Vec3A,
    /// The box's highest corner.
    pub max: Vec3A,
    /// σ_t per grid unit value (1/length).
    pub scale: f32,
    /// σ_s / σ_t per channel, in [0, 1].
    pub albedo: Vec3A,
    /// How scattered light leaves.
    pub phase: HenyeyGreenstein,
    /// The largest σ_t in the box.
    pub majorant: f32,
}

impl Grid {
    /// A grid with its majorant computed: values must be finite and ≥ 0
    /// (the loader checks), `res` matching their count.
    pub fn new(
        res: [u32; 3],
        values: Vec<f32>,
        (min, max): (Vec3A, Vec3A),
        scale: f32,
        albedo: Vec3A,
        phase: HenyeyGreenstein,
    ) -> Self {
        let top = values.iter().copied().fold(0.0f32, f32::max);
        Grid {
            res,
            values,
            min,
            max,
            scale,
            albedo,
            phase,
            majorant: top * scale,
        }
    }

    /// σ_t at world point `p` (0 outside the box).
    #[inline]
    pub fn sigma_t(&self, p: Vec3A) -> f32 {
        let q = (p - self.min) / (self.max - self.min);
        if q.min_element() < 0.0 || q.max_element() > 1.0 {
            return 0.0;
        }
        let [nx, ny, nz] = self.res;
        let g = q * Vec3A::new(nx as f32, ny as f32, nz as f32) - Vec3A::splat(0.5);
        let f = g - g.floor();
        let corner = |v: f32, n: u32| {
            let i = v.floor() as i64;
            let hi = n as i64 - 1;
            (i.clamp(0, hi) as usize, (i + 1).clamp(0, hi) as usize)
        };
        let (x0, x1) = corner(g.x, nx);
        let (y0, y1) = corner(g.y, ny);
        let (z0, z1) = corner(g.z, nz);
        let (nx, ny) = (nx as usize, ny as usize);
        let at =
            |x: usize, y: usize, z: usize| self.values.get((z * ny + y) * nx + x).copied().unwrap_or(0.0);
        let lerp = |a: f32, b: f32, t: f32| a + (b - a) * t;
        let c00 = lerp(at(x0, y0, z0), at(x1, y0, z0), f.x);
        let c10 = lerp(at(x0, y1, z0), at(x1, y1, z0), f.x);
        let c01 = lerp(at(x0, y0, z1), at(x1, y0, z1), f.x);
        let c11 = lerp(at(x0, y1, z1), at(x1, y1, z1), f.x);
        let c0 = lerp(c00, c10, f.y);
        let c1 = lerp(c01, c11, f.y);
        lerp(c0, c1, f.z) * self.scale
    }

    /// The part of `(0, t_max)` along `ray` inside the box (slab test).
    #[inline]
    fn clip(&self, ray: &Ray, t_max: f32) -> Option<(f32, f32)> {
        let inv = ray.d.recip();
        let a = (self.min - ray.o) * inv;
        let b = (self.max - ray.o) * inv;
        let t0 = a.min(b).max_element().max(0.0);
        let t1 = a.max(b).min_element().min(t_max);
        (t0 < t1).then_some((t0, t1))
    }

    /// The next real collision along `ray` before `t_max`, by delta
    /// tracking; `rand` gives uniform numbers in [0, 1). A collision weighs
    /// the albedo (σ_s/σ_t); going through weighs 1.
    pub fn sample(&self, ray: &Ray, t_max: f32, rand: &mut impl FnMut() -> f32) -> Collision {
        let through = Collision {
            t: None,
            weight: Vec3A::ONE,
        };
        let Some((mut t, t1)) = self.clip(ray, t_max) else {
            return through;
        };
        if self.majorant <= 0.0 {
            return through;
        }
        for _ in 0..MAX_STEPS {
            t -= (1.0 - rand()).ln() / self.majorant;
            if t >= t1 {
                return through;
            }
            if rand() * self.majorant < self.sigma_t(ray.at(t)) {
                return Collision {
                    t: Some(t),
                    weight: self.albedo,
                };
            }
        }
        through
    }

    /// An unbiased estimate of the transmittance along `ray` over
    /// `(0, t_max)`, by ratio tracking.
    pub fn transmittance(&self, ray: &Ray, t_max: f32, rand: &mut impl FnMut() -> f32) -> f32 {
        let Some((mut t, t1)) = self.clip(ray, t_max) else {
            return 1.0;
        };
        if self.majorant <= 0.0 {
            return 1.0;
        }
        let mut tr = 1.0;
        for _ in 0..MAX_STEPS {
            t -= (1.0 - rand()).ln() / self.majorant;
            if t >= t1 {
                break;
            }
            tr *= 1.0 - self.sigma_t(ray.at(t)) / self.majorant;
            if tr <= 0.0 {
                return 0.0;
            }
        }
        tr
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::Pcg32;

    /// A 4³ grid in the unit cube whose value grows along x.
    fn ramp() -> Grid {
        let mut values = Vec::new();
        for _z in 0..4 {
            for _y in 0..4 {
                for x in 0..4 {
                    values.push(x as f32 + 1.0);
                }
            }
        }
        Grid::new(
            [4, 4, 4],
            values,
            (Vec3A::ZERO, Vec3A::ONE),
            0.5,
            Vec3A::splat(0.8),
            HenyeyGreenstein { g: 0.0 },
        )
    }

    /// Texel centres hold the values, between them it interpolates, near
    /// the faces it clamps, and outside the box σ_t is 0.
    #[test]
    fn grid_lookup_is_trilinear_and_clamped() {
        let g = ramp();
        assert!((g.sigma_t(Vec3A::new(0.125, 0.5, 0.5)) - 0.5).abs() < 1e-6);
        assert!((g.sigma_t(Vec3A::new(0.25, 0.5, 0.5)) - 0.75).abs() < 1e-6);
        assert!((g.sigma_t(Vec3A::new(0.01, 0.5, 0.5)) - 0.5).abs() < 1e-6);
        assert!((g.sigma_t(Vec3A::new(0.99, 0.5, 0.5)) - 2.0).abs() < 1e-6);
        assert_eq!(g.sigma_t(Vec3A::new(1.5, 0.5, 0.5)), 0.0);
        assert_eq!(g.majorant, 2.0);
    }

    /// Ratio tracking's mean and delta tracking's pass-through rate both
    /// match exp(−∫σ_t) along a ray across the ramp (computed by the
    /// midpoint rule), and a ray beside the box passes untouched.
    #[test]
    fn grid_tracking_matches_the_optical_depth() {
        let g = ramp();
        let ray = Ray::new(Vec3A::new(-1.0, 0.3, 0.6), Vec3A::X);
        let steps = 10_000;
        let tau: f32 = (0..steps)
            .map(|i| g.sigma_t(Vec3A::new((i as f32 + 0.5) / steps as f32, 0.3, 0.6)) / steps as f32)
            .sum();
        let expect = (-tau).exp();
        let mut rng = Pcg32::new(5, 2);
        let mut rand = || rng.next_f32();
        let n = 200_000;
        let (mut ratio, mut passed) = (0.0f64, 0u32);
        for _ in 0..n {
            ratio += g.transmittance(&ray, 10.0, &mut rand) as f64;
            if g.sample(&ray, 10.0, &mut rand).t.is_none() {
                passed += 1;
            }
        }
        let ratio = ratio / n as f64;
        let rate = passed as f64 / n as f64;
        assert!(
            (ratio - expect as f64).abs() < 0.005,
            "ratio tracking {ratio} vs {expect}"
        );
        assert!(
            (rate - expect as f64).abs() < 0.005,
            "delta tracking {rate} vs {expect}"
        );
        let beside = Ray::new(Vec3A::new(-1.0, 2.0, 0.5), Vec3A::X);
        assert_eq!(g.transmittance(&beside, 10.0, &mut rand), 1.0);
    }
}
