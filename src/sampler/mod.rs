//! Sample generators for the integrators, selectable in the scene.
//!
//! Every sampler is a pure function of (pixel, sample index, dimension,
//! seed), so images do not depend on scheduling, and a single pixel can be
//! re-rendered alone.
//!
//! - `Independent`: uniform random numbers (PCG32).
//! - `Stratified`: jittered strata per 2-D dimension pair, strata visited in
//!   a per-pixel, per-dimension random order (pbrt's `StratifiedSampler`).
//! - `Sobol`: the first two Sobol dimensions for every dimension pair
//!   ("padded" Sobol), with the sample order permuted and the points
//!   Owen-scrambled per pixel and dimension (Burley 2020,
//!   <https://jcgt.org/published/0009/04/01/>). Best at power-of-two spp.

mod sobol;

use crate::math::Pcg32;
use crate::math::rng::mix64;
use glam::Vec2;

/// Which sample generator a render uses (the scene's `film.sampler`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SamplerKind {
    /// Uniform random numbers from each sample's own PCG32 stream.
    #[default]
    Independent,
    /// Jittered strata per 2-D dimension pair, visited in a random order.
    Stratified,
    /// Padded, Owen-scrambled Sobol points: lowest error, best at power-of-two spp.
    Sobol,
}

/// The random numbers for one camera sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    /// Hash of (pixel, seed): decorrelates pixels.
    pixel_hash: u64,
    index: u32,
    spp: u32,
    dim: u32,
    rng: Pcg32,
}

impl Sampler {
    /// The sampler for sample `index` (of `spp`) of pixel `(x, y)` with the scene's
    /// `seed`: a pure function of those, so any pixel or sample can be rendered alone
    /// and give the same numbers.
    pub fn new(kind: SamplerKind, x: u32, y: u32, index: u32, spp: u32, seed: u64) -> Self {
        let pixel_hash = mix64(((y as u64) << 32 | x as u64) ^ mix64(seed.wrapping_add(0x5851_f42d)));
        Self {
            kind,
            pixel_hash,
            index,
            spp: spp.max(1),
            dim: 0,
            rng: Pcg32::for_sample(x, y, index, seed),
        }
    }

    /// A plain independent sampler (tests, analytic checks).
    pub fn independent(rng: Pcg32) -> Self {
        Self {
            kind: SamplerKind::Independent,
            pixel_hash: 0,
            index: 0,
            spp: 1,
            dim: 0,
            rng,
        }
    }

    #[inline]
    fn dim_hash(&mut self) -> u64 {
        let h = mix64(self.pixel_hash ^ (self.dim as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        self.dim += 1;
        h
    }

    /// The next dimension, uniform in [0, 1).
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        match self.kind {
            SamplerKind::Independent => self.rng.next_f32(),
            // The x of the 2-D point `next_vec2` would give, without its y.
            SamplerKind::Sobol => {
                let h = self.dim_hash();
                let i = permutation_element(self.index, self.spp.next_power_of_two(), h as u32);
                to_unit(sobol::owen_scramble_reversed(i, (h >> 32) as u32))
            }
            SamplerKind::Stratified => self.next_vec2().x,
        }
    }

    /// The next pair of dimensions, uniform in [0, 1)²: what the strata and Sobol
    /// points are built for, so 2-D draws (lens, light point, BSDF direction) should
    /// use it.
    #[inline]
    pub fn next_vec2(&mut self) -> Vec2 {
        match self.kind {
            SamplerKind::Independent => self.rng.next_vec2(),
            SamplerKind::Stratified => {
                let h = self.dim_hash();
                let n = self.spp;
                let nx = (n as f32).sqrt().floor().max(1.0) as u32;
                let ny = n / nx;
                let strata = nx * ny;
                if self.index >= strata {
                    // Samples beyond the largest full grid fall back to random.
                    return self.rng.next_vec2();
                }
                let s = permutation_element(self.index, strata, h as u32);
                let j = self.rng.next_vec2();
                Vec2::new(
                    ((s % nx) as f32 + j.x) / nx as f32,
                    ((s / nx) as f32 + j.y) / ny as f32,
                )
            }
            SamplerKind::Sobol => {
                let h = self.dim_hash();
                let i = permutation_element(self.index, self.spp.next_power_of_two(), h as u32);
                let (a, b) = sobol::sample_2d_reversed(i);
                let x = sobol::owen_scramble_reversed(a, (h >> 32) as u32);
                let y = sobol::owen_scramble_reversed(b, (mix64(h) >> 32) as u32);
                Vec2::new(to_unit(x), to_unit(y))
            }
        }
    }
}

#[inline]
fn to_unit(x: u32) -> f32 {
    // 24 bits so the result is strictly below 1.
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Element `i` of a random permutation of `0..n` chosen by `seed`, without
/// storing it (Kensler 2013, "Correlated Multi-Jittered Sampling").
pub fn permutation_element(mut i: u32, n: u32, seed: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    let l = n;
    let mut w = l - 1;
    w |= w >> 1;
    w |= w >> 2;
    w |= w >> 4;
    w |= w >> 8;
    w |= w >> 16;
    loop {
        i ^= seed;
        i = i.wrapping_mul(0xe170893d);
        i ^= seed >> 16;
        i ^= (i & w) >> 4;
        i ^= seed >> 8;
        i = i.wrapping_mul(0x0929eb3f);
        i ^= seed >> 23;
        i ^= (i & w) >> 1;
        i = i.wrapping_mul(1 | seed >> 27);
        i = i.wrapping_mul(0x6935fa69);
        i ^= (i & w) >> 11;
        i = i.wrapping_mul(0x74dcb303);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0x9e501cc3);
        i ^= (i & w) >> 2;
        i = i.wrapping_mul(0xc860a3df);
        i &= w;
        i ^= i >> 5;
        if i < l {
            break;
        }
    }
    // A power of two (Sobol's case) needs no division.
    let j = i.wrapping_add(seed);
    if l.is_power_of_two() { j & (l - 1) } else { j % l }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permutation_element_is_a_permutation() {
        for n in [1u32, 2, 7, 16, 100] {
            let mut seen: Vec<u32> = (0..n).map(|i| permutation_element(i, n, 12345)).collect();
            seen.sort_unstable();
            assert_eq!(seen, (0..n).collect::<Vec<_>>(), "n = {n}");
        }
    }

    /// Each sampler estimates ∫∫ x·y over the unit square (= 1/4); the
    /// stratified and Sobol ones must do it with far less error.
    #[test]
    fn sampler_stratification_lowers_error() {
        let spp = 64;
        let err = |kind| {
            let mut sq = 0.0f64;
            for px in 0..200u32 {
                let mut sum = 0.0f64;
                for s in 0..spp {
                    let mut smp = Sampler::new(kind, px, 3, s, spp, 9);
                    let _ = smp.next_vec2(); // skip a dimension pair
                    let u = smp.next_vec2();
                    assert!((0.0..1.0).contains(&u.x) && (0.0..1.0).contains(&u.y));
                    sum += (u.x * u.y) as f64;
                }
                sq += (sum / spp as f64 - 0.25).powi(2);
            }
            (sq / 200.0).sqrt()
        };
        let (ind, strat, sob) = (
            err(SamplerKind::Independent),
            err(SamplerKind::Stratified),
            err(SamplerKind::Sobol),
        );
        assert!(strat < 0.5 * ind, "stratified rmse {strat} vs independent {ind}");
        assert!(sob < 0.5 * ind, "sobol rmse {sob} vs independent {ind}");
    }
}
