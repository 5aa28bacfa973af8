//! `ln x` for the Mandelbulb estimate, one lane or four, by the same
//! operations in the same order, so the SIMD march and the scalar one agree
//! bit for bit.
//!
//! Why: the estimate `0.25 ln(m) √m / dz` ends every evaluation with a
//! natural log; libm's `logf` is a call per lane (~35 instructions, a tenth
//! of a four-lane evaluation, callgrind), this is ~20 SIMD instructions for
//! four. Accuracy: within 2e-7 relative of `f64::ln` on normal inputs
//! (tested), far below what a distance estimate needs. Zero, subnormal,
//! infinite, negative and NaN inputs go to `f32::ln`.

use glam::{IVec4, UVec4, Vec4};

/// `√½` as bits: mantissas are reduced into `[√½, √2)`, where the series
/// below converges fastest.
const SQRT_HALF_BITS: u32 = 0x3f35_04f3;

/// `ln x` for `x` normal and positive (else `f32::ln`).
#[inline]
pub fn ln(x: f32) -> f32 {
    if !(f32::MIN_POSITIVE..=f32::MAX).contains(&x) {
        return x.ln();
    }
    // x = 2^e · m with m ∈ [√½, √2).
    let bits = x.to_bits();
    let e = (bits.wrapping_sub(SQRT_HALF_BITS) as i32) >> 23;
    let m = f32::from_bits(bits.wrapping_sub((e << 23) as u32));
    series(m, e as f32)
}

/// [`ln`] of each lane, bit for bit.
#[inline]
pub fn ln_x4(x: Vec4) -> Vec4 {
    let normal = x.cmpge(Vec4::splat(f32::MIN_POSITIVE)) & x.cmple(Vec4::splat(f32::MAX));
    if !normal.all() {
        return Vec4::from_array(x.to_array().map(ln));
    }
    let bits = UVec4::from_array(x.to_array().map(f32::to_bits));
    let e: IVec4 = bits.wrapping_sub(UVec4::splat(SQRT_HALF_BITS)).as_ivec4() >> 23;
    let shifted: IVec4 = e << 23;
    let m = bits
        .wrapping_sub(shifted.as_uvec4())
        .to_array()
        .map(f32::from_bits);
    series(Vec4::from_array(m), e.as_vec4())
}

/// `e ln 2 + ln m` for `m ∈ [√½, √2)`, by `ln m = 2 atanh s`,
/// `s = (m − 1)/(m + 1)`, `|s| ≤ 0.172`: five odd terms leave < 1e-9.
#[inline(always)]
fn series<T>(m: T, e: T) -> T
where
    T: Copy
        + std::ops::Add<Output = T>
        + std::ops::Sub<Output = T>
        + std::ops::Mul<Output = T>
        + std::ops::Div<Output = T>
        + std::ops::Mul<f32, Output = T>
        + std::ops::Add<f32, Output = T>
        + std::ops::Sub<f32, Output = T>,
{
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let p = (((s2 * (1.0 / 9.0) + 1.0 / 7.0) * s2 + 1.0 / 5.0) * s2 + 1.0 / 3.0) * s2 * s;
    e * std::f32::consts::LN_2 + (s * 2.0 + p * 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;

    #[test]
    fn ln_is_accurate_and_the_lanes_match_it_bit_for_bit() {
        let mut rng = Pcg32::new(5, 17);
        let mut worst = 0.0f64;
        for i in 0..200_000 {
            // Logarithmically spread over the normal range, plus edge cases.
            let mut x = [0.0f32; 4].map(|_| (rng.next_f32() * 170.0 - 85.0).exp2());
            match i {
                0 => x = [1.0, f32::MIN_POSITIVE, f32::MAX, 2.0],
                1 => x = [0.0, -1.0, f32::NAN, f32::INFINITY],
                2 => x = [1e-40, 0.5, std::f32::consts::SQRT_2, 0.707_106_77],
                _ => {}
            }
            let lanes = ln_x4(Vec4::from_array(x)).to_array();
            for k in 0..4 {
                let got = ln(x[k]);
                assert_eq!(
                    got.to_bits(),
                    lanes[k].to_bits(),
                    "ln({}) alone {got}, in a lane {}",
                    x[k],
                    lanes[k]
                );
                if x[k] > 0.0 && x[k].is_finite() {
                    let want = (x[k] as f64).ln();
                    let err = (got as f64 - want).abs() / want.abs().max(1.0);
                    worst = worst.max(err);
                } else {
                    assert_eq!(got.to_bits(), x[k].ln().to_bits(), "ln({})", x[k]);
                }
            }
        }
        assert!(worst < 2e-7, "worst error {worst:e}");
    }
}
