//! The first two dimensions of the Sobol sequence and hash-based Owen
//! scrambling (Burley 2020, <https://jcgt.org/published/0009/04/01/>).

/// Point `i` of the 2-D Sobol (0,2)-sequence as 32-bit fixed point (the
/// sampler uses the reversed form below; this one states what it computes).
#[cfg(test)]
pub fn sample_2d(i: u32) -> (u32, u32) {
    let (x, y) = sample_2d_reversed(i);
    (x.reverse_bits(), y.reverse_bits())
}

/// [`sample_2d`] with the bits of each coordinate reversed: the form the
/// sampler works in (index `i` itself and [`dim1_reversed`]). Owen
/// scrambling works on reversed bits, and x86 has no bit-reversal
/// instruction (each `reverse_bits` is a dozen shifts and masks), so the
/// sampler stays in this form until the end, where [`owen_scramble_net`]
/// reverses only the digits the net has.
#[cfg(test)]
pub fn sample_2d_reversed(i: u32) -> (u32, u32) {
    // Dimension 0 is the van der Corput sequence: reversed, the index.
    (i, dim1_reversed(i))
}

/// Dimension 1 of point `i`, bit-reversed: what [`sample_2d_reversed`] gives
/// as its second value, without its loop or a table.
///
/// Reversed, generator column `b` is the polynomial `(1 + x)^b` over GF(2)
/// (bit `k` holding `x^k`), so the value is the index polynomial `I(t)`
/// taken at `t = 1 + x`: a Taylor shift by one. Splitting a block of `2h`
/// bits as `lo + x^h·hi`, and since `(1 + x)^h = 1 + x^h` for `h` a power of
/// two, the shifted block is `lo' + hi' + x^h·hi'` (halves shifted first):
/// five rounds of `y ^= (y & high halves) >> h`, for `h` = 1, 2, 4, 8, 16.
/// Fifteen branch-free word operations, which the per-pixel loop of
/// `sampler/pixel.rs` vectorises; a table lookup there would be a gather,
/// which the compiler declines to vectorise.
#[inline(always)]
pub fn dim1_reversed(i: u32) -> u32 {
    let mut y = i;
    y ^= (y & 0xaaaa_aaaa) >> 1;
    y ^= (y & 0xcccc_cccc) >> 2;
    y ^= (y & 0xf0f0_f0f0) >> 4;
    y ^= (y & 0xff00_ff00) >> 8;
    y ^= (y & 0xffff_0000) >> 16;
    y
}

/// Laine–Karras style hash acting as a nested uniform scramble on
/// bit-reversed values: each bit is flipped depending only on the bits above
/// it, which is exactly Owen scrambling.
#[cfg(test)]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    owen_scramble_reversed(x.reverse_bits(), seed)
}

/// [`owen_scramble`] of the value whose reversed bits are `r`.
#[cfg(test)]
pub fn owen_scramble_reversed(r: u32, seed: u32) -> u32 {
    laine_karras(r, seed).reverse_bits()
}

/// Laine and Karras's hash: each bit of the result depends only on the bits
/// below it (and the seed), so on reversed bits it is an Owen scramble.
#[inline]
fn laine_karras(r: u32, seed: u32) -> u32 {
    let mut v = r.wrapping_add(seed);
    v ^= v.wrapping_mul(0x6c50_b47c);
    v ^= v.wrapping_mul(0xb82f_1e52);
    v ^= v.wrapping_mul(0xc7af_e638);
    v ^= v.wrapping_mul(0x8d22_f6e6);
    v
}

/// A nested uniform shuffle of `i`: bit `j` of the result depends only on
/// bits `j` and up of `i` (and the seed), the mirror of [`laine_karras`]'s
/// order, so every aligned block of `2^k` indices maps onto an aligned block
/// of `2^k` (Burley 2020, §4). The hash is pbrt-v4's `FastOwenScrambler`
/// (Vegdahl 2021), better mixed than Laine–Karras's.
#[inline(always)]
pub fn nested_shuffle(i: u32, seed: u32) -> u32 {
    let mut v = i.reverse_bits();
    v ^= v.wrapping_mul(0x3d20_adea);
    v = v.wrapping_add(seed);
    v = v.wrapping_mul((seed >> 16) | 1);
    v ^= v.wrapping_mul(0x0552_6c56);
    v ^= v.wrapping_mul(0x53a2_2864);
    v.reverse_bits()
}

/// The Owen-scrambled coordinate, as 32-bit fixed point, of a point of a
/// `2^m`-point net (`m` < 32) whose `m` digits, bit-reversed, are the low
/// bits of `r` (the form [`sample_2d_reversed`] gives).
///
/// The top `m` digits are [`owen_scramble`]'s: Laine–Karras on the reversed
/// digits, then those `m` bits reversed back. The digits below them are
/// where this saves: a full Owen scramble gives each point of the net
/// independent uniform digits there (no two points share a prefix), so any
/// hash bits that depend on the point's top digits and the seed keep the
/// nesting; they are the top `32 − m` bits of the same hash (its best-mixed
/// ones, the most significant jitter digit from the hash's top bit), shifted
/// down rather than reversed. Branch-free and table-free, so a loop over a
/// net vectorises (`sampler/pixel.rs`).
#[inline]
pub fn owen_scramble_net(r: u32, m: u32, seed: u32) -> u32 {
    let s = laine_karras(r, seed);
    let digits = s & (1u32 << m).wrapping_sub(1);
    digits.reverse_bits() | s >> m
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reversed_form_matches_the_plain_generator() {
        // The generator as first written: columns from the top bit down.
        let plain = |mut i: u32| {
            let x = i.reverse_bits();
            let (mut y, mut v) = (0u32, 1u32 << 31);
            while i != 0 {
                if i & 1 != 0 {
                    y ^= v;
                }
                i >>= 1;
                v ^= v >> 1;
            }
            (x, y)
        };
        for i in (0..4096).chain([u32::MAX, 0x8000_0001, 123_456_789]) {
            assert_eq!(sample_2d(i), plain(i), "point {i}");
        }
    }

    #[test]
    fn nested_shuffle_maps_aligned_blocks_onto_aligned_blocks() {
        for seed in [0u32, 77, 0xdead_beef] {
            for k in 0..8u32 {
                for block in 0..4u32 {
                    let mut seen: Vec<u32> = (block << k..(block + 1) << k)
                        .map(|i| nested_shuffle(i, seed))
                        .collect();
                    let high = seen[0] >> k;
                    assert!(seen.iter().all(|&v| v >> k == high), "k {k}, block {block}");
                    seen.sort_unstable();
                    seen.dedup();
                    assert_eq!(seen.len(), 1 << k, "k {k}, block {block}: not a permutation");
                }
            }
        }
    }

    #[test]
    fn taylor_shift_gives_the_generator_columns() {
        // Dimension 1 as the generator loop computes it: column b, reversed,
        // is v ← v ⊕ (v << 1) applied b times to 1, XORed in for each set bit.
        let by_columns = |mut i: u32| {
            let (mut y, mut v) = (0u32, 1u32);
            while i != 0 {
                y ^= v & (i & 1).wrapping_neg();
                i >>= 1;
                v ^= v << 1;
            }
            y
        };
        for i in (0..70_000u32).chain([u32::MAX, 0x8000_0001, 123_456_789, 1 << 24, 1 << 31]) {
            assert_eq!(dim1_reversed(i), by_columns(i), "point {i}");
        }
    }

    #[test]
    fn net_scramble_has_the_full_scrambles_top_digits_and_stays_stratified() {
        for m in [0u32, 1, 3, 4, 8, 9, 12] {
            for seed in [0u32, 77, 0xdead_beef] {
                let mut strata = vec![0u32; 1 << m];
                for i in 0..1u32 << m {
                    let (a, b) = sample_2d_reversed(i);
                    for (r, s) in [(a, seed), (b, seed ^ 0x5bd1_e995)] {
                        let x = owen_scramble_net(r, m, s);
                        let full = owen_scramble_reversed(r, s);
                        let top = |v: u32| ((v as u64) >> (32 - m)) as u32;
                        assert!(m < 32);
                        assert_eq!(top(x), top(full), "m = {m}, seed {seed}, point {i}");
                    }
                    strata[((owen_scramble_net(a, m, seed) as u64) >> (32 - m)) as usize] += 1;
                }
                assert!(strata.iter().all(|&c| c == 1), "m = {m}: strata {strata:?}");
            }
        }
    }

    #[test]
    fn sobol_first_16_points_are_a_0_4_2_net() {
        // Every 1/4 × 1/4 cell holds exactly one of the first 16 points, before
        // and after scrambling.
        for seed in [None, Some(77u32)] {
            let mut cells = [0u32; 16];
            for i in 0..16 {
                let (mut x, mut y) = sample_2d(i);
                if let Some(s) = seed {
                    x = owen_scramble(x, s);
                    y = owen_scramble(y, s ^ 0xabcdef);
                }
                cells[((x >> 30) * 4 + (y >> 30)) as usize] += 1;
            }
            assert!(cells.iter().all(|&c| c == 1), "cells {cells:?} (seed {seed:?})");
        }
    }
}
