//! What the environment sends to a surface, cheaply: its irradiance as a
//! function of the surface normal, from the sky's first nine spherical
//! harmonics (Ramamoorthi & Hanrahan 2001, "An Efficient Representation
//! for Irradiance Environment Maps",
//! <https://graphics.stanford.edu/papers/envmap/>).
//!
//! Why: light selection ([`super::LightTree`]) weighs the environment
//! against area and point lights at each shading point. Its power through
//! the scene's bounding disk (pbrt-v4's `Phi`) grows with the square of the
//! scene's size, so a 40 × 40 floor under a dim sky once sent ~90% of the
//! shadow rays to the sky while one area light did nearly all the lighting.
//! What matters at a point is what the sky sends *there*: the unoccluded
//! irradiance `E(n) = ∫ L(ω) max(0, n·ω) dω`, in the same units as the
//! tree's estimate for a small area light (`Φ cos θ' cos θ / d²` is π times
//! that light's irradiance, so the environment's importance is `π E`).
//!
//! The clamped cosine is smooth, so nine coefficients give `E` to a few
//! percent for any sky (Ramamoorthi & Hanrahan: 1% on average, 3% at
//! worst for real skies); a small sun alone is the worst case, `E` off by
//! at most 0.1 of the sun's own irradiance at normal incidence. Exact for
//! a constant sky (`E = π L`). The expansion is stored as a quadratic form
//! `E(n) = c + b·n + nᵀ M n`, so an evaluation is a dozen multiply-adds and
//! no trigonometry.

use crate::math::{Rgb, luminance};
use glam::{Mat3A, Vec3A};
use std::f32::consts::PI;

/// Luminance irradiance of an environment as a quadratic form in the unit
/// normal; see the module docs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyIrradiance {
    c: f32,
    b: Vec3A,
    m: Mat3A,
}

/// Real spherical-harmonic basis constants, bands 0–2.
const Y0: f32 = 0.282_095;
const Y1: f32 = 0.488_603;
const Y2A: f32 = 1.092_548;
const Y2B: f32 = 0.315_392;
const Y2C: f32 = 0.546_274;

impl SkyIrradiance {
    /// A sky of luminance `l` in every direction: `E = π l` for any normal.
    pub fn constant(radiance: Rgb) -> Self {
        Self {
            c: PI * luminance(radiance).max(0.0),
            b: Vec3A::ZERO,
            m: Mat3A::ZERO,
        }
    }

    /// From luminance samples `(direction, luminance × solid angle)` that
    /// cover the sphere (a map's texels, each with the solid angle it
    /// subtends). Non-finite or negative samples count as zero. (Maps are
    /// projected in parallel through [`ShSum`]; this is the tests' way in.)
    #[cfg(test)]
    pub fn from_samples(samples: impl Iterator<Item = (Vec3A, f32)>) -> Self {
        let mut sum = ShSum::default();
        samples.for_each(|(d, w)| sum.add(d, w));
        sum.irradiance()
    }
    /// Irradiance (luminance, W/m²) on a surface of unit normal `n`, never
    /// negative (nine coefficients ring slightly below zero behind a sun).
    #[inline]
    pub fn at(&self, n: Vec3A) -> f32 {
        (self.c + self.b.dot(n) + n.dot(self.m * n)).max(0.0)
    }

    /// The larger of the irradiance on either side of a surface of normal
    /// `n` (the light tree takes `|cos|` too: a transmitting surface is lit
    /// from both sides). For `n` zero (a point with no surface), `∫ L dω`,
    /// as the tree takes no cosine there: four times the irradiance
    /// averaged over all normals, `c + tr(M)/3` (the linear part averages
    /// out).
    #[inline]
    pub fn either_side(&self, n: Vec3A) -> f32 {
        if n == Vec3A::ZERO {
            let trace = self.m.x_axis.x + self.m.y_axis.y + self.m.z_axis.z;
            return (4.0 * (self.c + trace / 3.0)).max(0.0);
        }
        (self.c + self.b.dot(n).abs() + n.dot(self.m * n)).max(0.0)
    }
}

/// The sky's weight in light selection at a surface: π × its irradiance
/// there, times the share of it that sampling the BSDF would not find by
/// itself.
///
/// Why: next-event estimation and BSDF sampling are combined by MIS, so a
/// light sample is worth spending on what BSDF samples collect badly. A
/// cosine-distributed sample gathers a constant sky above a Lambert
/// surface with no variance at all; a 0.5° sun it almost never hits. On the
/// generated open scenes (`tests/open_scenes.rs`) the sky at its full
/// irradiance cost the constant-sky scenes 10–30% more noise than a sky
/// with only the uniform share of the picks, while the sun scenes needed
/// all of it (issue 37). The share is measured by the relative variance
/// `v` of the cosine-sampled estimate `π L(ω)` of the irradiance `E`:
/// `1 + v = π E₂ / E²`, with `E₂ = ∫ L² cos⁺ dω` the irradiance of the
/// squared sky (nine harmonics too), and the weight is
/// `π E · v / (1 + v) = π E − E³ / E₂`: 0 for a constant sky (and for a
/// half-sky seen by a surface that faces it), ½·πE for a vertical wall
/// under a uniform half-sky, πE for a sun.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyWeight {
    /// Irradiance of the sky's luminance, `E(n)`.
    pub irradiance: SkyIrradiance,
    /// Irradiance of its squared luminance, `E₂(n)`.
    pub second: SkyIrradiance,
    /// A constant sky: its weight is 0 exactly, without the arithmetic
    /// (which rounds to within an ulp of it).
    flat: bool,
    /// The weight for `n` zero (a point with no surface), made once here.
    /// Computed in [`SkyWeight::at`], it depended on nothing that changes
    /// along a path, so the compiler computed it ahead of the path loop
    /// even for scenes without a light tree — from the bytes of the
    /// picker's empty `Option<LightTree>`, which read as denormal floats:
    /// a microcode assist per operation (`tests/denormals.rs`, on an AMD
    /// EPYC).
    whole: f32,
}

impl SkyWeight {
    /// The weight of a sky of irradiance `irradiance` and squared
    /// irradiance `second` (see the type's docs).
    pub fn new(irradiance: SkyIrradiance, second: SkyIrradiance) -> Self {
        let w = Self {
            irradiance,
            second,
            flat: false,
            whole: 0.0,
        };
        Self {
            whole: w.weigh(Vec3A::ZERO),
            ..w
        }
    }

    /// A sky of radiance `radiance` in every direction (weight 0).
    pub fn constant(radiance: Rgb) -> Self {
        let l = luminance(radiance).max(0.0);
        Self {
            irradiance: SkyIrradiance::constant(radiance),
            second: SkyIrradiance::constant(Rgb::splat(l * l)),
            flat: true,
            whole: 0.0,
        }
    }

    /// Whether this is a constant sky's weight: zero at every point.
    pub fn is_flat(&self) -> bool {
        self.flat
    }

    /// The weight at a surface of normal `n`, lit from either side (the
    /// larger; for `n` zero, a point in a medium, over the whole sphere
    /// against uniform sampling: `∫L − (∫L)³ / (4π ∫L²)`). Never negative
    /// or above `π E`; 0 where either moment is 0 or not finite.
    #[inline]
    pub fn at(&self, n: Vec3A) -> f32 {
        if self.flat {
            return 0.0;
        }
        if n == Vec3A::ZERO {
            return self.whole;
        }
        self.weigh(n)
    }

    /// [`SkyWeight::at`] of a sky that is not flat, computed, for any `n`.
    #[inline]
    fn weigh(&self, n: Vec3A) -> f32 {
        let e = self.irradiance.either_side(n);
        let e2 = self.second.either_side(n);
        let (full, base) = if n == Vec3A::ZERO {
            (e, 4.0 * PI)
        } else {
            (PI * e, PI)
        };
        // full · (1 − E² / (base · E₂)): the share BSDF sampling misses.
        let w = full * (1.0 - e * e / (base * e2));
        if w.is_finite() && e2 > 0.0 {
            w.clamp(0.0, full)
        } else {
            0.0
        }
    }
}

/// A running projection of radiance onto the first nine spherical
/// harmonics (`f64`: a 16k × 8k map adds 10⁸ terms), mergeable across
/// threads.
#[derive(Clone, Copy, Debug, Default)]
pub struct ShSum {
    l: [f64; 9],
}

impl ShSum {
    /// Adds radiance × solid angle `w` arriving from unit direction `d`;
    /// ignores `w` that is negative, NaN or infinite.
    #[inline]
    pub fn add(&mut self, d: Vec3A, w: f32) {
        if !(w.is_finite() && w > 0.0) {
            return;
        }
        let w = w as f64;
        let (x, y, z) = (d.x as f64, d.y as f64, d.z as f64);
        let y_lm = [
            Y0 as f64,
            Y1 as f64 * y,
            Y1 as f64 * z,
            Y1 as f64 * x,
            Y2A as f64 * x * y,
            Y2A as f64 * y * z,
            Y2B as f64 * (3.0 * z * z - 1.0),
            Y2A as f64 * x * z,
            Y2C as f64 * (x * x - y * y),
        ];
        for (acc, y) in self.l.iter_mut().zip(y_lm) {
            *acc += w * y;
        }
    }

    /// Both sums.
    pub fn merge(mut self, o: ShSum) -> ShSum {
        for (a, b) in self.l.iter_mut().zip(o.l) {
            *a += b;
        }
        self
    }

    /// The irradiance by normal of the projected radiance: each band
    /// convolved with the clamped cosine (Â0 = π, Â1 = 2π/3, Â2 = π/4),
    /// `E(n) = Σ Âl Llm Ylm(n)` gathered by monomial.
    pub fn irradiance(&self) -> SkyIrradiance {
        let l = self.l.map(|v| if v.is_finite() { v as f32 } else { 0.0 });
        let (a0, a1, a2) = (PI, 2.0 * PI / 3.0, PI / 4.0);
        let c = a0 * l[0] * Y0 - a2 * l[6] * Y2B;
        let b = a1 * Y1 * Vec3A::new(l[3], l[1], l[2]);
        let (xy, yz, xz) = (a2 * Y2A * l[4], a2 * Y2A * l[5], a2 * Y2A * l[7]);
        let (xx, yy, zz) = (a2 * Y2C * l[8], -a2 * Y2C * l[8], 3.0 * a2 * Y2B * l[6]);
        let m = Mat3A::from_cols(
            Vec3A::new(xx, 0.5 * xy, 0.5 * xz),
            Vec3A::new(0.5 * xy, yy, 0.5 * yz),
            Vec3A::new(0.5 * xz, 0.5 * yz, zz),
        );
        SkyIrradiance { c, b, m }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;
    use crate::math::sampling::uniform_sphere;

    /// A latitude-longitude grid of `f(direction)` over the sphere, as
    /// `(direction, value × solid angle)`.
    fn grid(f: impl Fn(Vec3A) -> f32) -> Vec<(Vec3A, f32)> {
        let (w, h) = (256, 128);
        let mut v = Vec::new();
        for j in 0..h {
            let theta = PI * (j as f32 + 0.5) / h as f32;
            let d_omega = (2.0 * PI / w as f32) * (PI / h as f32) * theta.sin();
            for i in 0..w {
                let phi = 2.0 * PI * (i as f32 + 0.5) / w as f32;
                let d = Vec3A::new(theta.sin() * phi.cos(), theta.cos(), theta.sin() * phi.sin());
                v.push((d, f(d) * d_omega));
            }
        }
        v
    }

    /// `∫ f(ω) max(0, n·ω) dω` by the same grid.
    fn exact(f: &impl Fn(Vec3A) -> f32, n: Vec3A) -> f32 {
        grid(|d| f(d) * n.dot(d).max(0.0)).iter().map(|s| s.1).sum()
    }

    #[test]
    fn irradiance_of_a_constant_sky_is_pi_l_for_every_normal() {
        let sky = SkyIrradiance::constant(Rgb::splat(0.7));
        let projected = SkyIrradiance::from_samples(grid(|_| 0.7).into_iter());
        let mut rng = Pcg32::new(1, 1);
        for _ in 0..100 {
            let n = uniform_sphere(rng.next_vec2());
            assert!((sky.at(n) - PI * 0.7).abs() < 1e-5);
            assert!(
                (projected.at(n) - PI * 0.7).abs() < 2e-3 * PI,
                "{}",
                projected.at(n)
            );
            assert!((projected.either_side(n) - PI * 0.7).abs() < 2e-3 * PI);
        }
        // No surface: ∫ L dω = 4π L.
        assert!((projected.either_side(Vec3A::ZERO) - 4.0 * PI * 0.7).abs() < 1e-2);
    }

    /// `SkyWeight` of `f` from the grid, as `map_weight` projects a map.
    fn weight_of(f: impl Fn(Vec3A) -> f32) -> SkyWeight {
        SkyWeight::new(
            SkyIrradiance::from_samples(grid(&f).into_iter()),
            SkyIrradiance::from_samples(grid(|d| f(d) * f(d)).into_iter()),
        )
    }

    /// The sky's weight is π E times the share of E a cosine-sampled BSDF
    /// sample would not find alone: none of a constant sky, none of a
    /// half-sky above a surface facing it, half of it for a wall beside it,
    /// nearly all of a small sun's.
    #[test]
    fn sky_weight_follows_what_bsdf_sampling_misses() {
        let constant = SkyWeight::constant(Rgb::splat(0.7));
        let mut rng = Pcg32::new(4, 4);
        for _ in 0..50 {
            let n = uniform_sphere(rng.next_vec2());
            assert!(constant.at(n) < 1e-4, "{}", constant.at(n));
        }
        assert!(constant.at(Vec3A::ZERO) < 1e-4);
        let grid_constant = weight_of(|_| 0.7);
        assert!(grid_constant.at(Vec3A::Y) < 0.01 * PI * PI * 0.7);
        // Upper hemisphere of radiance 1: E = π facing it, π/2 on a wall.
        let half = weight_of(|d| if d.y > 0.0 { 1.0 } else { 0.0 });
        let up = half.at(Vec3A::Y);
        assert!(up < 0.1 * PI * PI, "facing the half-sky: {up}");
        let wall = half.at(Vec3A::X) / (PI * 0.5 * PI);
        assert!((wall - 0.5).abs() < 0.1, "a wall gets {wall} of π E, not ½");
        // A 3° sun and a dim sky: nearly all of π E, everywhere it lights.
        let s = Vec3A::new(0.3, 0.8, -0.5).normalize();
        let sun = weight_of(|d| {
            if d.dot(s) > 3f32.to_radians().cos() {
                1000.0
            } else {
                0.05
            }
        });
        for n in [s, Vec3A::Y, Vec3A::new(0.6, 0.2, 0.0).normalize()] {
            let full = PI * sun.irradiance.either_side(n);
            assert!(sun.at(n) > 0.9 * full, "n {n}: {} of {full}", sun.at(n));
            assert!(sun.at(n) <= full);
        }
        // Black sky, non-finite moments: nothing, never NaN.
        assert_eq!(SkyWeight::constant(Rgb::ZERO).at(Vec3A::Y), 0.0);
        assert_eq!(SkyWeight::constant(Rgb::splat(f32::INFINITY)).at(Vec3A::Y), 0.0);
    }

    #[test]
    fn irradiance_of_a_gradient_sky_matches_the_integral() {
        // A bright zenith fading to a dark ground: smooth, so nine
        // coefficients hold it to a few percent of the zenith irradiance.
        let f = |d: Vec3A| 0.1 + (d.y + 0.2).max(0.0) * 2.0 + 0.3 * d.x.max(0.0);
        let sh = SkyIrradiance::from_samples(grid(f).into_iter());
        let scale = exact(&f, Vec3A::Y);
        let mut rng = Pcg32::new(2, 5);
        for _ in 0..64 {
            let n = uniform_sphere(rng.next_vec2());
            let (got, want) = (sh.at(n), exact(&f, n));
            assert!((got - want).abs() < 0.04 * scale, "n {n}: {got} vs {want}");
        }
    }

    #[test]
    fn irradiance_of_a_sun_alone_stays_within_a_tenth_of_its_peak() {
        // A 3° sun: the hardest case for nine coefficients.
        let s = Vec3A::new(0.3, 0.8, -0.5).normalize();
        let f = move |d: Vec3A| {
            if d.dot(s) > 3f32.to_radians().cos() {
                1000.0
            } else {
                0.0
            }
        };
        let sh = SkyIrradiance::from_samples(grid(f).into_iter());
        let peak = exact(&f, s);
        assert!(peak > 0.0);
        let mut rng = Pcg32::new(7, 3);
        for _ in 0..200 {
            let n = uniform_sphere(rng.next_vec2());
            let (got, want) = (sh.at(n), exact(&f, n));
            assert!(
                (got - want).abs() < 0.1 * peak,
                "n {n}: {got} vs {want} (peak {peak})"
            );
            assert!(sh.either_side(n) >= got);
        }
    }
}
