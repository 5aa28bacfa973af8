//! The first two dimensions of the Sobol sequence and hash-based Owen
//! scrambling (Burley 2020, <https://jcgt.org/published/0009/04/01/>).

/// Point `i` of the 2-D Sobol (0,2)-sequence as 32-bit fixed point.
#[inline]
pub fn sample_2d(mut i: u32) -> (u32, u32) {
    // Dimension 0 is the van der Corput sequence: bit reversal.
    let x = i.reverse_bits();
    // Dimension 1: generator matrix of the polynomial x + 1, whose columns
    // are built by v ← v ⊕ (v >> 1) from the top bit.
    let mut y = 0u32;
    let mut v = 1u32 << 31;
    while i != 0 {
        if i & 1 != 0 {
            y ^= v;
        }
        i >>= 1;
        v ^= v >> 1;
    }
    (x, y)
}

/// Laine–Karras style hash acting as a nested uniform scramble on
/// bit-reversed values: each bit is flipped depending only on the bits above
/// it, which is exactly Owen scrambling.
#[inline]
pub fn owen_scramble(x: u32, seed: u32) -> u32 {
    let mut v = x.reverse_bits();
    v = v.wrapping_add(seed);
    v ^= v.wrapping_mul(0x6c50_b47c);
    v ^= v.wrapping_mul(0xb82f_1e52);
    v ^= v.wrapping_mul(0xc7af_e638);
    v ^= v.wrapping_mul(0x8d22_f6e6);
    v.reverse_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

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
