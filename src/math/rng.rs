//! PCG32 (O'Neill 2014, <https://www.pcg-random.org/>): small state, good
//! statistics, and independent streams, so every (pixel, sample) gets its own
//! sequence and the image does not depend on thread scheduling.

use glam::Vec2;

/// PCG32 generator (XSH RR output, 64-bit state): one independent stream per camera
/// sample.
#[derive(Clone, Debug)]
pub struct Pcg32 {
    state: u64,
    inc: u64,
}

const MULT: u64 = 6364136223846793005;

impl Pcg32 {
    /// A generator seeded with `seed` on stream `stream`; different streams give
    /// independent sequences even for equal seeds.
    pub fn new(seed: u64, stream: u64) -> Self {
        let mut r = Self {
            state: 0,
            inc: (stream << 1) | 1,
        };
        r.next_u32();
        r.state = r.state.wrapping_add(seed);
        r.next_u32();
        r
    }

    /// The generator for one camera sample: a pure function of the pixel,
    /// the sample index and the scene seed.
    pub fn for_sample(x: u32, y: u32, sample: u32, seed: u64) -> Self {
        Self::for_pixel_sample(Self::pixel_seed(x, y, seed), sample)
    }

    /// The part of [`Pcg32::for_sample`] that depends on the pixel only:
    /// hashed once per pixel rather than once per sample.
    #[inline]
    pub fn pixel_seed(x: u32, y: u32, seed: u64) -> u64 {
        let pixel = ((y as u64) << 32) | x as u64;
        mix64(pixel ^ mix64(seed))
    }

    /// [`Pcg32::for_sample`] from the pixel's [`Pcg32::pixel_seed`].
    #[inline]
    pub fn for_pixel_sample(pixel_seed: u64, sample: u32) -> Self {
        Self::new(pixel_seed, mix64(sample as u64 ^ 0x9e37_79b9_7f4a_7c15))
    }

    /// The next uniform 32-bit value.
    #[inline]
    pub fn next_u32(&mut self) -> u32 {
        let old = self.state;
        self.state = old.wrapping_mul(MULT).wrapping_add(self.inc);
        let xorshifted = (((old >> 18) ^ old) >> 27) as u32;
        let rot = (old >> 59) as u32;
        xorshifted.rotate_right(rot)
    }

    /// Uniform in [0, 1): 24 random mantissa bits, never rounds up to 1.
    #[inline]
    pub fn next_f32(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    }

    /// Two uniform values in [0, 1)², x drawn first.
    #[inline]
    pub fn next_vec2(&mut self) -> Vec2 {
        Vec2::new(self.next_f32(), self.next_f32())
    }
}

/// SplitMix64 finaliser: spreads nearby integers (pixel coordinates) apart.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg32_is_uniform_and_below_one() {
        let mut r = Pcg32::new(42, 54);
        let n = 100_000;
        let mut sum = 0.0f64;
        for _ in 0..n {
            let u = r.next_f32();
            assert!((0.0..1.0).contains(&u));
            sum += u as f64;
        }
        let mean = sum / n as f64;
        assert!((mean - 0.5).abs() < 0.005, "mean {mean}");
    }

    #[test]
    fn pcg32_streams_differ() {
        let a = Pcg32::for_sample(3, 4, 0, 1).next_u32();
        let b = Pcg32::for_sample(3, 4, 1, 1).next_u32();
        let c = Pcg32::for_sample(4, 3, 0, 1).next_u32();
        assert!(a != b && a != c);
        let split = Pcg32::for_pixel_sample(Pcg32::pixel_seed(3, 4, 1), 1).next_u32();
        assert_eq!(split, b, "the per-pixel split must give the same stream");
    }
}
