//! Sample generators for the integrators, selectable in the scene.
//!
//! Every sampler is a pure function of (pixel, sample index, dimension,
//! seed), so images do not depend on scheduling, and a single pixel can be
//! re-rendered alone.
//!
//! - `Independent`: uniform random numbers (each sample's own
//!   [`SampleRng`] stream, SplitMix64).
//! - `Stratified`: jittered strata per 2-D dimension pair, strata visited in
//!   a per-pixel, per-dimension random order (pbrt's `StratifiedSampler`).
//! - `Sobol`: the first [`SOBOL_DRAWS`] draws of a camera sample (pixel
//!   jitter, lens, then the first vertex's light pick, light point, BSDF lobe
//!   and direction) are stratified: each draw is a point of the first two
//!   Sobol dimensions ("padded" Sobol), Owen-scrambled per pixel and draw (a
//!   1-D draw takes its x, a scrambled van der Corput point); every draw
//!   visits its points in its own shuffled order (Burley 2020,
//!   <https://jcgt.org/published/0009/04/01/>), one that keeps every
//!   multiple of 8 samples a union of nets (`pixel.rs`). Later draws are
//!   the sample's random stream's, as `Independent`.
//!
//! Why `Sobol` stops after a few draws: the draws that gain from
//! stratification are the low ones; deeper in the path the integrand has too
//! many dimensions for a 2-D net to matter. Its points are computed per
//! pixel, all samples of a draw in one vectorised loop ([`PixelSampler`]),
//! not per sample: one at a time, a scrambled point cost about five PCG32
//! draws and `Sobol` 6–11% more instructions per sample than `Independent`;
//! batched, about 1% (callgrind, see the commits); 1.8% since the random
//! stream became SplitMix64, which made `Independent` itself cheaper. pbrt-v4's
//! `ZSobolSampler` (Morton-ordered indices) was not taken: its per-dimension
//! index permutation hashes every base-4 digit of (pixel, sample), about ten
//! hashes per draw at 256² and 64 spp, and cannot be batched per pixel; its
//! gain is a blue-noise distribution of the error over the image rather than
//! a lower RMSE.

mod pixel;
mod sobol;

pub use pixel::PixelSampler;

use crate::math::SampleRng;
use crate::math::rng::mix64;
use glam::Vec2;

/// Which sample generator a render uses (the scene's `film.sampler`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SamplerKind {
    /// Uniform random numbers from each sample's own random stream ([`SampleRng`]).
    #[default]
    Independent,
    /// Jittered strata per 2-D dimension pair, visited in a random order.
    Stratified,
    /// Padded, Owen-scrambled Sobol points: lowest error, stratified at any
    /// multiple of 8 spp.
    Sobol,
}

/// Whether a draw's numbers are stratified across the pixel's samples (a
/// `Sobol` point, a jittered stratum) or independent. A warp that is exact
/// but not monotone in its numbers (an alias table: `lights/env_table.rs`)
/// loses nothing on independent numbers and is cheaper; on stratified ones
/// it would scatter the strata, so they take the monotone inversion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Draw {
    /// Spread evenly over the pixel's samples.
    Stratified,
    /// Uniform and independent of the other samples'.
    Independent,
}

/// How many draws (1-D or 2-D) of a camera sample `Sobol` stratifies: pixel
/// jitter and lens, then the first vertex's light pick, light point, BSDF
/// lobe and direction; later ones come from the sample's random stream. See the module docs.
pub const SOBOL_DRAWS: u32 = 6;

/// The random numbers for one camera sample.
#[derive(Clone, Debug)]
pub struct Sampler {
    kind: SamplerKind,
    /// Hash of (pixel, seed): decorrelates pixels.
    pixel_hash: u64,
    index: u32,
    spp: u32,
    /// `Sobol`: the bits of a sample index, and of a net index (a split
    /// continuation's number above the sample's; see [`Sampler::split`]).
    spp_bits: u32,
    index_bits: u32,
    dim: u32,
    /// Draws taken so far (`Sobol` only).
    draws: u32,
    /// `Sobol`: the stratified draws of this sample, computed per pixel
    /// ([`PixelSampler`]); a 1-D draw takes a point's x.
    points: [Vec2; SOBOL_DRAWS as usize],
    rng: SampleRng,
}

impl Sampler {
    /// The sampler for sample `index` (of `spp`) of pixel `(x, y)` with the scene's
    /// `seed`: a pure function of those, so any pixel or sample can be rendered alone
    /// and give the same numbers. A loop over a pixel's samples should make
    /// one [`PixelSampler`] and call its `sample`, which hashes the pixel once.
    pub fn new(kind: SamplerKind, x: u32, y: u32, index: u32, spp: u32, seed: u64) -> Self {
        let mut pixel = PixelSampler::new(kind, spp, seed);
        pixel.set_pixel(x, y, index..index);
        pixel.sample(index)
    }

    /// A plain independent sampler (tests, analytic checks).
    pub fn independent(rng: SampleRng) -> Self {
        Self {
            kind: SamplerKind::Independent,
            pixel_hash: 0,
            index: 0,
            spp: 1,
            spp_bits: 0,
            index_bits: 0,
            dim: 0,
            draws: 0,
            points: [Vec2::ZERO; SOBOL_DRAWS as usize],
            rng,
        }
    }

    #[inline]
    fn dim_hash(&mut self) -> u64 {
        let h = mix64(self.pixel_hash ^ (self.dim as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15));
        self.dim += 1;
        h
    }

    /// How many draws this sample has taken: where a split continuation
    /// ([`Sampler::split`]) starts drawing again.
    #[inline(always)]
    pub fn draws(&self) -> u32 {
        self.draws
    }

    /// Starts split continuation `k` (1, 2, …) of this camera sample, which
    /// draws again from draw `from` on: with `Sobol`, its stratified draws
    /// from `from` on are points of its own block of each draw's net (net
    /// index `k · 2^spp_bits + sample`), so each continuation's points are
    /// stratified across the pixel's samples as the first one's are, and
    /// apart from them. Other samplers go on with their stream.
    pub fn split(&mut self, k: u32, from: u32) {
        if self.kind != SamplerKind::Sobol || from >= SOBOL_DRAWS {
            return;
        }
        let index = (k << self.spp_bits) | self.index;
        for d in from as usize..SOBOL_DRAWS as usize {
            self.points[d] = pixel::point_at(self.pixel_hash, d, index, self.index_bits);
        }
        self.draws = from;
    }

    /// The next stratified `Sobol` point; `None` once [`SOBOL_DRAWS`] are taken.
    #[inline(always)]
    fn sobol_draw(&mut self) -> Option<Vec2> {
        let p = *self.points.get(self.draws as usize)?;
        self.draws += 1;
        Some(p)
    }

    /// Where in the shutter this camera sample is, in [0, 1): stratified
    /// over the pixel's samples (sample `i` takes stratum `π(i)` of `spp`,
    /// `π` a per-pixel permutation, jittered), and not a draw of the
    /// sample's stream but a hash of (pixel, sample), so that the other
    /// draws are the same whether the scene moves or not, and a static
    /// scene, which never asks, keeps its numbers exactly.
    pub fn time(&self) -> f32 {
        let n = self.spp.max(1);
        let h = mix64(self.pixel_hash ^ 0x7469_6d65_7469_6d65);
        let stratum = permutation_element(self.index % n, n, h as u32);
        let jitter = to_unit(mix64(h ^ u64::from(self.index)) as u32);
        ((stratum as f32 + jitter) / n as f32).min(1.0 - f32::EPSILON)
    }

    /// The next dimension, uniform in [0, 1).
    #[inline(always)]
    pub fn next_f32(&mut self) -> f32 {
        match self.kind {
            SamplerKind::Independent => self.rng.next_f32(),
            // A 1-D draw is the x of a 2-D point: Owen-scrambled van der
            // Corput, as stratified as jittered strata.
            SamplerKind::Sobol => match self.sobol_draw() {
                Some(p) => p.x,
                None => self.rng.next_f32(),
            },
            SamplerKind::Stratified => self.next_vec2().x,
        }
    }

    /// The next pair of dimensions, uniform in [0, 1)²: what the strata and Sobol
    /// points are built for, so 2-D draws (lens, light point, BSDF direction) should
    /// use it.
    #[inline(always)]
    pub fn next_vec2(&mut self) -> Vec2 {
        self.next_vec2_draw().0
    }

    /// [`Sampler::next_vec2`] and whether the pair is stratified across
    /// the pixel's samples ([`Draw`]): `Sobol`'s first draws and every
    /// `Stratified` draw are; `Independent`'s and `Sobol`'s later ones are not.
    #[inline(always)]
    pub fn next_vec2_draw(&mut self) -> (Vec2, Draw) {
        match self.kind {
            SamplerKind::Independent => (self.rng.next_vec2(), Draw::Independent),
            SamplerKind::Sobol => match self.sobol_draw() {
                Some(p) => (p, Draw::Stratified),
                None => (self.rng.next_vec2(), Draw::Independent),
            },
            SamplerKind::Stratified => (self.stratified_vec2(), Draw::Stratified),
        }
    }

    /// `Stratified`'s 2-D draw. Out of line so that the two common arms of
    /// [`Sampler::next_vec2`] inline into the integrators: the call was
    /// about 6% of a Cornell render's instructions.
    #[inline(never)]
    fn stratified_vec2(&mut self) -> Vec2 {
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
}

#[inline]
fn to_unit(x: u32) -> f32 {
    // 24 bits so the result is strictly below 1.
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Element `i` of a random permutation of `0..2^bits` chosen by `seed`: the
/// order in which one Sobol draw visits its points,
/// so that padded draws are decorrelated. Multiplication by an odd number and
/// `x ^= x >> k` are each bijections on the masked bits; three rounds of
/// them mix well enough at the few bits spp needs, for a fifth of the cost of
/// the general [`permutation_element`], whose loop and power-of-two rounding
/// dominated the draw.
#[inline]
fn shuffle_pow2(i: u32, bits: u32, seed: u32) -> u32 {
    let mask = ((1u64 << bits) - 1) as u32;
    // Shift by half the bit count, so the high bits fold into the low ones.
    let half = bits.div_ceil(2);
    let mut i = (i ^ seed).wrapping_mul(0xe170_893d) & mask;
    i ^= i >> half;
    i = i.wrapping_add(seed >> 16).wrapping_mul(0x0929_eb3f) & mask;
    i ^= i >> half;
    i.wrapping_add(seed >> 8).wrapping_mul(0x6935_fa69) & mask
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
    fn shuffle_pow2_is_a_permutation_that_depends_on_the_seed() {
        for n in [1u32, 2, 8, 64, 1024] {
            let order = |seed| {
                (0..n)
                    .map(|i| shuffle_pow2(i, n.trailing_zeros(), seed))
                    .collect::<Vec<_>>()
            };
            let mut seen = order(0xdead_beef);
            seen.sort_unstable();
            assert_eq!(seen, (0..n).collect::<Vec<_>>(), "n = {n}");
            if n >= 8 {
                assert_ne!(order(1), order(2), "n = {n}: seeds 1 and 2 give the same order");
            }
        }
    }

    #[test]
    fn sobol_first_draws_are_stratified_and_later_ones_uniform() {
        // Over the 16 samples of a pixel, the first 2-D draw puts one point in
        // each 1/4 × 1/4 cell and the first-vertex 1-D draw one value in each
        // 1/16 stratum; a draw past SOBOL_DRAWS is the random stream's, so only in range.
        let spp = 16;
        let (mut cells, mut strata) = ([0u32; 16], [0u32; 16]);
        for s in 0..spp {
            let mut smp = Sampler::new(SamplerKind::Sobol, 5, 7, s, spp, 3);
            let a = smp.next_vec2();
            let _lens = smp.next_vec2();
            let u = smp.next_f32();
            for _ in 3..SOBOL_DRAWS + 2 {
                let v = smp.next_vec2();
                assert!((0.0..1.0).contains(&v.x) && (0.0..1.0).contains(&v.y));
            }
            assert!((0.0..1.0).contains(&u), "{u}");
            cells[(a.x * 4.0) as usize * 4 + (a.y * 4.0) as usize] += 1;
            strata[(u * 16.0) as usize] += 1;
        }
        assert!(cells.iter().all(|&c| c == 1), "2-D cells {cells:?}");
        assert!(strata.iter().all(|&c| c == 1), "1-D strata {strata:?}");
    }

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
