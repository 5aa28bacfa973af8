//! Exact, order-free sums of radiance samples.
//!
//! A pixel is the mean of its samples. Summed in `f32`, the total depends on
//! how the additions are grouped (float addition is not associative): samples
//! 0..8 and 8..16 summed on two machines and then added differ in the last
//! bits from samples 0..16 summed in one run, because the second machine
//! starts from 0 instead of the first machine's running sum. So each sample is
//! instead turned once into a fixed-point integer with 64 fractional bits
//! (a *superaccumulator* in the sense of Kulisch, narrowed to the range
//! radiance needs), and integers add associatively: any split of a pixel's
//! samples, summed in any order on any number of machines, gives the same
//! integer, and [`ExactSum::mean`] the same `f32`.
//!
//! - **Range**: a sample is clamped to ±2³⁰ (about 1.07·10⁹; radiance beyond
//!   that is a numerical accident). With at most 2³² samples a channel's sum
//!   stays below 2⁶² · 2⁶⁴ = 2¹²⁶, inside `i128`.
//! - **Precision**: the conversion keeps every bit of the sample down to
//!   2⁻⁶⁴ ≈ 5.4·10⁻²⁰ and truncates below, so every `f32` of magnitude
//!   ≥ 2⁻⁴⁰ ≈ 9·10⁻¹³ is held exactly.
//! - **Mean**: the integer is rounded to `f64`, scaled, divided by the sample
//!   count and rounded to `f32`: a pure function of (sum, count).

use super::Rgb;

/// Fractional bits of the fixed-point representation.
const FRACTION_BITS: i32 = 64;
/// Largest sample magnitude kept (2³⁰); larger samples are clamped to it.
const LIMIT: f32 = (1u32 << 30) as f32;

/// The exact sum of a pixel's samples, one fixed-point integer per channel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ExactSum(pub [i128; 3]);

impl ExactSum {
    /// No samples yet.
    pub const ZERO: ExactSum = ExactSum([0; 3]);

    /// Adds one sample; non-finite channels must be filtered by the caller.
    #[inline]
    pub fn add_sample(&mut self, c: Rgb) {
        debug_assert!(c.is_finite(), "non-finite sample {c}");
        for (s, v) in self.0.iter_mut().zip(c.to_array()) {
            *s = s.wrapping_add(to_fixed(v));
        }
    }

    /// Adds another sum (wrapping, so the result never depends on order even
    /// for sums read from damaged files).
    #[inline]
    pub fn add(&mut self, other: &ExactSum) {
        for (s, o) in self.0.iter_mut().zip(other.0) {
            *s = s.wrapping_add(o);
        }
    }

    /// The mean over `n` samples (0 for `n == 0`).
    #[inline]
    pub fn mean(&self, n: u32) -> Rgb {
        if n == 0 {
            return Rgb::ZERO;
        }
        let scale = (-FRACTION_BITS as f64).exp2() / n as f64;
        Rgb::from_array(self.0.map(|s| (s as f64 * scale) as f32))
    }

    /// The three sums as little-endian 32-bit words, channel by channel (how
    /// piece files store them).
    pub fn to_words(&self) -> [[u32; 4]; 3] {
        self.0.map(|s| {
            let u = s as u128;
            [0, 1, 2, 3].map(|k| (u >> (32 * k)) as u32)
        })
    }

    /// The inverse of [`ExactSum::to_words`].
    pub fn from_words(words: [[u32; 4]; 3]) -> Self {
        ExactSum(words.map(|w| {
            w.iter()
                .enumerate()
                .fold(0u128, |acc, (k, &x)| acc | (x as u128) << (32 * k)) as i128
        }))
    }
}

/// A pixel's running [`ExactSum`] while its samples come in, cheaper per
/// sample: [`SampleSum::total`] is bit for bit the `ExactSum` that
/// [`ExactSum::add_sample`] would have built from the same samples.
///
/// Why: converting each channel to an `i128` took ~100 instructions a
/// sample, 3% of a textured scene's render (callgrind). Here a sample is
/// cut into three 32-bit chunks of 2⁻⁶⁴ units, all channels at once in
/// four `f64` lanes: `c0 = trunc(x)`, `c1 = trunc(frac(x)·2³²)`,
/// `c2 = trunc(frac(frac(x)·2³²)·2³²)`. Each step is exact in `f64` (x has
/// 24 significant bits and the integer part taken off is a subset of them)
/// and truncates toward zero with x's sign, so `c0·2⁶⁴ + c1·2³² + c2` is
/// `trunc(x·2⁶⁴)`, [`to_fixed`]'s value. Each chunk is an integer below
/// 2⁵¹ in magnitude, turned into an `i64` by adding 1.5·2⁵² and reading the
/// bits (exact below 2⁵¹), and summed in `i64` lanes: below 2³² per sample,
/// so the sums cannot overflow before 2³¹ samples; they are folded into the
/// `i128` total every [`SampleSum::FOLD`] samples.
#[derive(Clone, Copy, Debug)]
pub struct SampleSum {
    folded: ExactSum,
    chunks: [wide::i64x4; 3],
    pending: u32,
}

impl Default for SampleSum {
    fn default() -> Self {
        Self::ZERO
    }
}

impl SampleSum {
    /// No samples yet.
    pub const ZERO: SampleSum = SampleSum {
        folded: ExactSum::ZERO,
        chunks: [wide::i64x4::ZERO; 3],
        pending: 0,
    };

    /// Samples summed in the `i64` lanes before they are folded into the
    /// `i128` total (their chunks stay below 2³² · 2³⁰ = 2⁶²).
    const FOLD: u32 = 1 << 30;

    /// Adds one sample: [`ExactSum::add_sample`]'s value (a non-finite
    /// channel adds 0; magnitudes are clamped to 2³⁰).
    #[inline]
    pub fn add_sample(&mut self, c: Rgb) {
        use wide::f64x4;
        const TWO_32: f64 = 4_294_967_296.0;
        // 1.5·2⁵²: an integer n with |n| < 2⁵¹ added to it lands in the
        // low mantissa bits, so bits(n + M) − bits(M) = n.
        const MAGIC: f64 = 6_755_399_441_055_744.0;
        let a = c.to_array();
        let x = f64x4::new([a[0] as f64, a[1] as f64, a[2] as f64, 0.0]);
        // Infinities and NaN add 0, as in `to_fixed`.
        let limit = f64x4::splat(LIMIT as f64);
        let x = x
            .is_finite()
            .bitselect(x.fast_max(-limit).fast_min(limit), f64x4::ZERO);
        let c0 = x.trunc();
        let r1 = (x - c0) * TWO_32;
        let c1 = r1.trunc();
        let c2 = ((r1 - c1) * TWO_32).trunc();
        let magic = f64x4::splat(MAGIC);
        let bits = |v: f64x4| -> wide::i64x4 {
            bytemuck::cast::<f64x4, wide::i64x4>(v + magic) - bytemuck::cast::<f64x4, wide::i64x4>(magic)
        };
        self.chunks[0] += bits(c0);
        self.chunks[1] += bits(c1);
        self.chunks[2] += bits(c2);
        self.pending += 1;
        if self.pending == Self::FOLD {
            self.fold();
        }
    }

    /// Moves the `i64` lanes into the `i128` total.
    #[cold]
    fn fold(&mut self) {
        self.folded = self.total();
        self.chunks = [wide::i64x4::ZERO; 3];
        self.pending = 0;
    }

    /// The exact sum of every sample added.
    pub fn total(&self) -> ExactSum {
        let [c0, c1, c2] = self.chunks.map(|c| c.to_array());
        let mut s = self.folded;
        for (ch, acc) in s.0.iter_mut().enumerate() {
            let v = ((c0[ch] as i128) << 64) + ((c1[ch] as i128) << 32) + c2[ch] as i128;
            *acc = acc.wrapping_add(v);
        }
        s
    }
}

/// `x` in units of 2⁻⁶⁴, truncated toward zero; exact for |x| ≥ 2⁻⁴⁰.
///
/// In two `f64` halves rather than by taking the float's bits apart: x·2³²
/// is exact in `f64` (x has 24 significant bits), its integer part `hi`
/// (below 2⁶²) and the remainder `r` (|r| < 1, exact too) both truncate
/// toward zero and share x's sign, so `hi`·2³² + trunc(r·2³²) is
/// trunc(x·2⁶⁴). Branch-free, and fewer instructions than the bit-by-bit
/// conversion it replaced (kept in the tests, which compare the two).
#[inline]
fn to_fixed(x: f32) -> i128 {
    if !x.is_finite() {
        return 0;
    }
    let scaled = x.clamp(-LIMIT, LIMIT) as f64 * 4_294_967_296.0;
    let hi = scaled.trunc();
    let lo = ((scaled - hi) * 4_294_967_296.0) as i64;
    ((hi as i64 as i128) << 32) + lo as i128
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;

    /// The first conversion, by the float's exponent and mantissa: the
    /// reference [`to_fixed`] must agree with bit for bit.
    fn to_fixed_by_bits(x: f32) -> i128 {
        if !x.is_finite() {
            return 0;
        }
        let bits = x.clamp(-LIMIT, LIMIT).to_bits();
        let biased = ((bits >> 23) & 0xff) as i32;
        let fraction = (bits & 0x7f_ffff) as i128;
        // x = m · 2^e with an integer mantissa m < 2²⁴ (subnormals have no
        // implicit bit and the smallest exponent).
        let (m, e) = if biased == 0 {
            (fraction, -149)
        } else {
            (fraction | 0x80_0000, biased - 150)
        };
        // In fixed-point units x = m · 2^(e + 64); e + 64 ≤ 30 − 23 + 64 = 71.
        let shift = e + FRACTION_BITS;
        let magnitude = if shift >= 0 {
            m << shift
        } else if shift > -32 {
            m >> -shift
        } else {
            0
        };
        if bits >> 31 == 1 { -magnitude } else { magnitude }
    }

    /// The running sum is the `ExactSum` of the same samples bit for bit:
    /// random magnitudes across the whole range, both signs, zeros,
    /// subnormals, the clamp and non-finite channels, folded midway too.
    #[test]
    fn sample_sum_totals_are_exact_sums() {
        let mut rng = Pcg32::new(5, 9);
        let special = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            f32::MIN_POSITIVE,
            1e-45,
            -1e-45,
            1e-30,
            2e-13,
            LIMIT,
            -LIMIT,
            3e9,
            -3e9,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            0.1,
            0.7,
            123_456.79,
        ];
        for round in 0..40 {
            let mut exact = ExactSum::ZERO;
            let mut running = SampleSum::ZERO;
            for k in 0..200 {
                let mut pick = || {
                    let u = rng.next_f32();
                    if u < 0.2 {
                        special[(rng.next_u32() % special.len() as u32) as usize]
                    } else {
                        let e = (rng.next_f32() * 80.0 - 50.0).exp2();
                        if rng.next_f32() < 0.3 { -u * e } else { u * e }
                    }
                };
                let c = Rgb::new(pick(), pick(), pick());
                // `ExactSum::add_sample` refuses non-finite channels in
                // debug builds (its callers filter them); `to_fixed` reads
                // them as 0, as `SampleSum` does.
                for (s, v) in exact.0.iter_mut().zip(c.to_array()) {
                    *s = s.wrapping_add(to_fixed(v));
                }
                running.add_sample(c);
                if round % 3 == 0 && k == 100 {
                    running.fold();
                }
            }
            assert_eq!(running.total(), exact, "round {round}");
        }
        assert_eq!(SampleSum::ZERO.total(), ExactSum::ZERO);
    }

    #[test]
    fn to_fixed_matches_the_bit_by_bit_conversion() {
        let mut rng = Pcg32::new(11, 3);
        let special = [
            0.0f32,
            -0.0,
            f32::MIN_POSITIVE,
            -f32::MIN_POSITIVE,
            1e-45,
            2.0f32.powi(-40),
            2.0f32.powi(-41),
            -(2.0f32.powi(-64)),
            2.0f32.powi(-63) * 1.5,
            0.999_999_94,
            1.0,
            LIMIT,
            -LIMIT,
            LIMIT * 4.0,
            f32::MAX,
            f32::MIN,
            f32::INFINITY,
            f32::NAN,
        ];
        let random = (0..200_000).map(|_| f32::from_bits(rng.next_u32()));
        for x in special.into_iter().chain(random) {
            assert_eq!(to_fixed(x), to_fixed_by_bits(x), "{x:e} ({:#010x})", x.to_bits());
        }
    }

    fn samples(n: usize, seed: u64) -> Vec<Rgb> {
        let mut rng = Pcg32::new(seed, 7);
        (0..n)
            .map(|_| {
                // Radiance-like values over many octaves, some zero.
                let v = |r: &mut Pcg32| {
                    let u = r.next_f32();
                    if u < 0.1 {
                        0.0
                    } else {
                        (40.0 * u - 30.0).exp2() * r.next_f32()
                    }
                };
                Rgb::new(v(&mut rng), v(&mut rng), v(&mut rng))
            })
            .collect()
    }

    #[test]
    fn exact_sum_is_the_same_for_every_split_and_order() {
        let s = samples(257, 3);
        let mut whole = ExactSum::ZERO;
        s.iter().for_each(|&c| whole.add_sample(c));
        for cuts in [vec![1], vec![100, 200], vec![5, 6, 7, 250]] {
            let mut bounds = vec![0];
            bounds.extend(&cuts);
            bounds.push(s.len());
            let mut merged = ExactSum::ZERO;
            // Pieces added last to first: order must not matter either.
            for w in bounds.windows(2).rev() {
                let mut piece = ExactSum::ZERO;
                s[w[0]..w[1]].iter().rev().for_each(|&c| piece.add_sample(c));
                merged.add(&piece);
            }
            assert_eq!(merged, whole, "split at {cuts:?} changed the sum");
        }
    }

    #[test]
    fn exact_sum_mean_is_close_to_the_f64_mean() {
        let s = samples(1000, 5);
        let mut sum = ExactSum::ZERO;
        s.iter().for_each(|&c| sum.add_sample(c));
        let f64_mean: f64 = s.iter().map(|c| c.x as f64).sum::<f64>() / s.len() as f64;
        let got = sum.mean(s.len() as u32).x as f64;
        assert!(
            ((got - f64_mean) / f64_mean).abs() < 1e-7,
            "mean {got} vs f64 reference {f64_mean}"
        );
    }

    #[test]
    fn fixed_conversion_is_exact_in_range_and_clamps_outside() {
        for x in [1.0f32, 0.5, 3.75e-12, 123456.78, -2.5, 1e-30, 2.0f32.powi(-40)] {
            let mut s = ExactSum::ZERO;
            s.add_sample(Rgb::splat(x));
            let back = s.mean(1).x;
            if x.abs() >= 2.0f32.powi(-40) {
                assert_eq!(back, x, "{x} did not survive the fixed-point round trip");
            } else {
                assert!((back - x).abs() < 1e-19, "{x} came back as {back}");
            }
        }
        let mut s = ExactSum::ZERO;
        s.add_sample(Rgb::splat(1e20));
        assert_eq!(s.mean(1).x, LIMIT, "a huge sample is clamped to 2^30");
    }

    #[test]
    fn exact_sum_words_round_trip() {
        let mut s = ExactSum::ZERO;
        s.add_sample(Rgb::new(1.5, -3.25e-9, 7e8));
        assert_eq!(ExactSum::from_words(s.to_words()), s);
    }
}
