//! What the samplers of one pixel share, computed once per pixel instead of
//! once per sample.
//!
//! For every sampler: the pixel's hash and its random-stream seed. For `Sobol`, the
//! stratified draws themselves: draw `d` of sample `s` is point
//! [`net_index`]`(s)` of the pixel's Owen-scrambled 2-D Sobol net for that
//! draw (`2^m` points, `m = ⌈log2 spp⌉`). The points of all the pixel's
//! samples are computed together, one loop per draw over the samples, which
//! the compiler turns into 8-lane AVX2 arithmetic (the shuffle, dimension 1
//! and the scrambles are all branch-free integer code, no table). Done one
//! sample at a time the same points cost about three times the instructions
//! of the PCG32 draws they replace: `Sobol` cost 6–11% more per sample than
//! `Independent`; batched, about 1% (callgrind, Cornell box, 64 and 256
//! spp; 1.8% against the cheaper SplitMix64 stream that replaced PCG32). A pixel that renders only a few of its samples (progressive passes,
//! sample splits) is served one point at a time by the same formula, so
//! every sample's numbers are the same whichever way they were made.

use super::{SOBOL_DRAWS, Sampler, SamplerKind, shuffle_pow2, sobol, to_unit};
use crate::math::rng::mix64;
use crate::math::{Pcg32, SampleRng};
use glam::Vec2;
use std::ops::Range;

const DRAWS: usize = SOBOL_DRAWS as usize;

/// The most samples of a pixel whose points are computed together: 2^16,
/// 3.6 MB of buffers per worker. More (up to 2^20 spp) compute each point
/// when its sample asks, at a cost nobody sees beside that many paths.
const MAX_BATCHED: usize = 1 << 16;

/// Per-pixel sampler state; one per worker, reused pixel after pixel so its
/// buffers are allocated once. [`PixelSampler::sample`] gives exactly what
/// [`Sampler::new`] gives for that pixel and sample.
#[derive(Clone, Debug)]
pub struct PixelSampler {
    kind: SamplerKind,
    seed: u64,
    spp: u32,
    /// log2 of the power of two ≥ spp: the bits of a sample index.
    spp_bits: u32,
    /// The bits of a Sobol point index: `spp_bits` and, above them, the
    /// bits of a split continuation's number (see [`Sampler::split`]).
    index_bits: u32,
    pixel_hash: u64,
    pcg_seed: u64,
    /// `Sobol`: a hash of (pixel, seed, draw) per stratified draw.
    draw_hashes: [u64; DRAWS],
    /// `Sobol`: the points of samples `first..first + points.len()`.
    first: u32,
    points: Vec<[Vec2; DRAWS]>,
    /// Scratch: one draw's coordinates for each sample.
    xs: Vec<f32>,
    ys: Vec<f32>,
}

impl PixelSampler {
    /// A sampler for a render of `spp` samples per pixel with the scene's
    /// `seed`; [`Self::set_pixel`] before the first [`Self::sample`].
    pub fn new(kind: SamplerKind, spp: u32, seed: u64) -> Self {
        Self::with_splits(kind, spp, 1, seed)
    }

    /// [`Self::new`] for paths that split into `splits` continuations
    /// ([`Sampler::split`]): each continuation takes its `Sobol` points from
    /// its own block of the nets.
    pub fn with_splits(kind: SamplerKind, spp: u32, splits: u32, seed: u64) -> Self {
        let spp = spp.max(1);
        // At most 31 in all: `1 << m` must fit in a u32.
        let spp_bits = spp.next_power_of_two().trailing_zeros().min(31);
        let split_bits = splits.max(1).next_power_of_two().trailing_zeros();
        Self {
            kind,
            seed,
            spp,
            spp_bits,
            index_bits: (spp_bits + split_bits).min(31),
            pixel_hash: 0,
            pcg_seed: 0,
            draw_hashes: [0; DRAWS],
            first: 0,
            points: Vec::new(),
            xs: Vec::new(),
            ys: Vec::new(),
        }
    }

    /// Moves to pixel `(x, y)`, whose samples `samples` are about to be
    /// taken (others may still be asked for, at a higher cost).
    pub fn set_pixel(&mut self, x: u32, y: u32, samples: Range<u32>) {
        self.pixel_hash = mix64(((y as u64) << 32 | x as u64) ^ mix64(self.seed.wrapping_add(0x5851_f42d)));
        self.pcg_seed = Pcg32::pixel_seed(x, y, self.seed);
        self.first = samples.start;
        if self.kind != SamplerKind::Sobol {
            self.points.clear();
            return;
        }
        let pixel_hash = self.pixel_hash;
        self.draw_hashes = std::array::from_fn(|d| draw_hash(pixel_hash, d));
        // Batch unless a worker's buffers would pass a few MB.
        let n = samples.len();
        if n == 0 || n > MAX_BATCHED {
            self.points.clear();
            return;
        }
        // Every entry is overwritten below; resizing keeps the buffer.
        self.points.resize(n, [Vec2::ZERO; DRAWS]);
        for d in 0..DRAWS {
            self.fill_draw(d, samples.clone());
        }
    }

    /// Draw `d`'s point for every sample of `samples`, computed sample by
    /// sample in a loop of plain integer arithmetic that the compiler turns
    /// into 8-lane AVX2 code, then stored into each sample's points.
    fn fill_draw(&mut self, d: usize, samples: Range<u32>) {
        let m = self.index_bits;
        let seeds = seeds(self.draw_hashes[d]);
        let n = samples.len();
        // Resized, not cleared and refilled: the lengths repeat from pixel
        // to pixel, and a loop over a fixed slice has no capacity checks.
        self.xs.resize(n, 0.0);
        self.ys.resize(n, 0.0);
        let first = samples.start;
        for (k, (x, y)) in self.xs.iter_mut().zip(self.ys.iter_mut()).enumerate() {
            (*x, *y) = net_point(first.wrapping_add(k as u32), m, seeds);
        }
        for (p, (&x, &y)) in self.points.iter_mut().zip(self.xs.iter().zip(&self.ys)) {
            p[d] = Vec2::new(x, y);
        }
    }

    /// The sampler of sample `index` of the current pixel.
    #[inline]
    pub fn sample(&self, index: u32) -> Sampler {
        let points = match self.kind {
            SamplerKind::Sobol => match index
                .checked_sub(self.first)
                .and_then(|i| self.points.get(i as usize))
            {
                Some(p) => *p,
                None => std::array::from_fn(|d| self.point(d, index)),
            },
            _ => [Vec2::ZERO; DRAWS],
        };
        Sampler {
            kind: self.kind,
            pixel_hash: self.pixel_hash,
            index,
            spp: self.spp,
            spp_bits: self.spp_bits,
            index_bits: self.index_bits,
            dim: 0,
            draws: 0,
            points,
            rng: SampleRng::for_pixel_sample(self.pcg_seed, index),
        }
    }

    /// Draw `d` of sample `index`, one point alone: what [`Self::fill_draw`]
    /// computes for it.
    fn point(&self, d: usize, index: u32) -> Vec2 {
        let (x, y) = net_point(index, self.index_bits, seeds(self.draw_hashes[d]));
        Vec2::new(x, y)
    }
}

/// The hash of draw `d` of the pixel with hash `pixel_hash`, which seeds
/// its net's order and scrambles. One multiply–xorshift round (half of
/// SplitMix64's) separates the draws: `pixel_hash` is already mixed.
#[inline]
fn draw_hash(pixel_hash: u64, d: usize) -> u64 {
    let h =
        (pixel_hash ^ (d as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    h ^ (h >> 31)
}

/// Draw `d`'s point of net index source `index` (a sample, or a split
/// continuation's block above the samples) for the pixel with hash
/// `pixel_hash`: what [`PixelSampler::sample`] stores, one point alone.
pub(super) fn point_at(pixel_hash: u64, d: usize, index: u32, index_bits: u32) -> Vec2 {
    let (x, y) = net_point(index, index_bits, seeds(draw_hash(pixel_hash, d)));
    Vec2::new(x, y)
}

/// The point sample `s` takes of a draw's Owen-scrambled `2^m`-point net:
/// net point [`net_index`] of the first two Sobol dimensions, each
/// coordinate scrambled with its own seed.
#[inline(always)]
fn net_point(s: u32, m: u32, (order, sx, sy): (u32, u32, u32)) -> (f32, f32) {
    let i = net_index(s, m, order);
    (
        to_unit(sobol::owen_scramble_net(i, m, sx)),
        to_unit(sobol::owen_scramble_net(sobol::dim1_reversed(i), m, sy)),
    )
}

/// Sample `s`'s point of a draw's `2^m`-point net (`m` < 32): a shuffle that
/// keeps prefixes stratified and the draws apart.
///
/// - Above the low [`BLOCK_BITS`] bits, [`sobol::nested_shuffle`]: bit `j`
///   of the result depends only on bits `j` and up of `s`, so samples
///   `0..2^k` land on an aligned block of `2^k` net indices, which is itself
///   a net. A pixel's first `n` samples, `n` a multiple of 8, are a union of
///   nets whatever `n` is (and a pixel that stops early under
///   `film.noise_threshold`, with `min_spp` a multiple of 8, stops on whole
///   strata). The plain random permutation this replaced stratified only
///   the full `2^m` points: at 96 or 192 spp its first samples were a
///   random subset of the net, and the error off the light was 3–17%
///   higher than here on the five reference scenes, the whole-image error
///   on the Cornell box twice as high (light-edge pixels).
/// - The low bits, which choose among the coarsest strata (a net's leading
///   digits come from the low bits of its index), are a random permutation
///   of their block keyed by the block and the draw. Nested all the way
///   down, every draw's leading digit flips between samples `2k` and
///   `2k + 1` together, correlating the draws (the light pick with the
///   light point). What is left of that costs `emissive_shapes` 0–3% more
///   error at 64 and 128 spp than the full random permutation (three
///   seeds; 1–4% nested all the way down); the other scenes are within
///   their noise or better (`env_spheres` 5–9%).
#[inline]
fn net_index(s: u32, m: u32, order: u32) -> u32 {
    let nested = sobol::nested_shuffle(s, order);
    let q = m.min(BLOCK_BITS);
    let low_mask = (1u32 << q) - 1;
    let k = ((s >> BLOCK_BITS).wrapping_mul(0x9e37_79b9) ^ order).wrapping_mul(0x85eb_ca6b);
    let low = shuffle_pow2(s & low_mask, q, k ^ (k >> 13));
    ((nested & !low_mask) | low) & (1u32 << m).wrapping_sub(1)
}

/// Samples shuffled freely within aligned blocks of `2^BLOCK_BITS` (see
/// [`net_index`]); [`crate::film::adaptive::CHECK_EVERY`] matches.
const BLOCK_BITS: u32 = 3;

/// Three 32-bit seeds from a draw's hash: the order in which the samples
/// visit the net, and the x and y scrambles.
#[inline]
fn seeds(h: u64) -> (u32, u32, u32) {
    (h as u32, (h >> 32) as u32, (h >> 16) as u32 ^ 0x5bd1_e995)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batched_and_single_samples_get_the_same_numbers() {
        for spp in [1u32, 5, 16, 300] {
            let mut batched = PixelSampler::new(SamplerKind::Sobol, spp, 11);
            batched.set_pixel(3, 9, 0..spp);
            for s in [0, spp / 2, spp - 1] {
                let mut a = batched.sample(s);
                let mut b = Sampler::new(SamplerKind::Sobol, 3, 9, s, spp, 11);
                for _ in 0..SOBOL_DRAWS + 2 {
                    assert_eq!(a.next_vec2(), b.next_vec2(), "spp {spp}, sample {s}");
                    assert_eq!(a.next_f32(), b.next_f32(), "spp {spp}, sample {s}");
                }
            }
        }
    }

    /// Exactly one of the `n` points in each 1/n-wide column and each 1/n-high row.
    fn is_net(pts: &[Vec2]) -> bool {
        let n = pts.len();
        let (mut cols, mut rows) = (vec![0; n], vec![0; n]);
        for p in pts {
            cols[(p.x * n as f32) as usize] += 1;
            rows[(p.y * n as f32) as usize] += 1;
        }
        cols.iter().chain(&rows).all(|&c| c == 1)
    }

    #[test]
    fn split_continuations_are_stratified_and_apart() {
        // 40 spp, three continuations per camera sample, redrawing from draw
        // 4 (a first vertex's BSDF lobe and direction): over a pixel's first
        // 8, 16 and 32 samples each continuation's points are a net of their
        // own, continuation 0's are the batched ones, and the others differ.
        let spp = 40;
        let mut pixel = PixelSampler::with_splits(SamplerKind::Sobol, spp, 3, 5);
        pixel.set_pixel(3, 9, 0..spp);
        let from = 4;
        let point = |s: u32, k: u32, d: usize| {
            let mut sample = pixel.sample(s);
            sample.split(k, from);
            sample.points[d]
        };
        for n in [8u32, 16, 32] {
            for d in from as usize..DRAWS {
                for k in 0..3 {
                    let pts: Vec<Vec2> = (0..n).map(|s| point(s, k, d)).collect();
                    assert!(is_net(&pts), "n {n}, draw {d}, continuation {k}");
                }
            }
        }
        for s in 0..spp {
            for d in 0..DRAWS {
                assert_eq!(point(s, 0, d), pixel.sample(s).points[d]);
                if d >= from as usize {
                    assert_ne!(point(s, 1, d), point(s, 0, d));
                    assert_ne!(point(s, 2, d), point(s, 1, d));
                } else {
                    // Draws before the split are the camera sample's own.
                    assert_eq!(point(s, 1, d), point(s, 0, d));
                }
            }
        }
    }

    #[test]
    fn every_multiple_of_8_samples_is_stratified() {
        // 40 spp draws from a 64-point net; the first 8, 16 and 32 samples of
        // every draw are (0, k, 2)-nets of their own: exactly one point in
        // each 1/n-wide column and in each 1/n-high row.
        for (x, y) in [(3u32, 9u32), (0, 0), (1000, 7)] {
            let spp = 40;
            let mut pixel = PixelSampler::new(SamplerKind::Sobol, spp, 5);
            pixel.set_pixel(x, y, 0..spp);
            for n in [8usize, 16, 32] {
                for d in 0..DRAWS {
                    let pts: Vec<Vec2> = (0..n as u32).map(|s| pixel.sample(s).points[d]).collect();
                    assert!(is_net(&pts), "n {n}, draw {d}: {pts:?}");
                }
            }
        }
    }

    #[test]
    fn net_index_is_a_permutation_that_depends_on_the_seed() {
        for m in [0u32, 1, 3, 6, 10] {
            let order = |seed| (0..1u32 << m).map(|s| net_index(s, m, seed)).collect::<Vec<_>>();
            let mut seen = order(0xdead_beef);
            seen.sort_unstable();
            assert_eq!(seen, (0..1u32 << m).collect::<Vec<_>>(), "m = {m}");
            if m >= 3 {
                assert_ne!(order(1), order(2), "m = {m}: seeds 1 and 2 give the same order");
            }
        }
    }

    #[test]
    fn independent_pixel_sampler_matches_the_per_sample_stream() {
        let mut pixel = PixelSampler::new(SamplerKind::Independent, 8, 5);
        pixel.set_pixel(7, 2, 0..8);
        let mut a = pixel.sample(3);
        let mut b = Sampler::independent(SampleRng::for_sample(7, 2, 3, 5));
        assert_eq!(a.next_vec2(), b.next_vec2());
    }
}
