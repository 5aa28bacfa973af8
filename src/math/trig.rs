//! `atan2`, `sin` and `cos` without the libm calls: environment lookups do
//! two `atan2` per light sample and per escaped ray, and glibc's `atan2f` (a
//! wrapper, special cases, then `atanf`) was 10.5% of the instructions of
//! `env_spheres` (callgrind, 64×64, 128 spp); every cone, microfacet and
//! environment sample turns an angle `2π·u` into its sine and cosine, and
//! glibc's `sincosf`/`sinf`/`cosf` took 110–120 instructions a pair there.

use glam::Vec4;
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI};

/// `atan2(y, x)` in `[-π, π]`, within 3e-7 rad of the exact angle for
/// finite inputs whose magnitudes add up to a finite number (each below
/// ~1.7·10³⁸: the reduction divides by |x| + |y|; the renderer passes
/// components of unit vectors) (Cephes' `atanf` polynomial on
/// `[0, tan π/8]` after range reduction; Moshier, *Methods and Programs for
/// Mathematical Functions*, 1989). Signed zeros follow IEEE `atan2`; NaN
/// in, NaN out.
#[inline]
pub fn atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    if den == 0.0 {
        // Both zero: ±0 toward +x, ±π toward −x.
        let r = if x.is_sign_negative() { PI } else { 0.0 };
        return r.copysign(y);
    }
    // a = num/den is the tangent of the angle to the nearer axis, in
    // [0, 1]; past tan π/8 the polynomial takes tan(angle − π/4) =
    // (a − 1)/(a + 1), computed as (num − den)/(num + den): one division
    // either way rather than two in a row (the angle's latency chain: a
    // sphere's UVs and the sky's lookup wait on it).
    let far = num > 0.414_213_57 * den;
    let (base, t) = if far {
        (FRAC_PI_4, (num - den) / (num + den))
    } else {
        (0.0, num / den)
    };
    let z = t * t;
    let p = (((8.053_744_5e-2 * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1) * z * t + t;
    let mut r = base + p;
    if steep {
        r = FRAC_PI_2 - r;
    }
    if x < 0.0 {
        r = PI - r;
    }
    r.copysign(y)
}

/// [`atan2`] of four pairs at once, lane by lane: the same operations in
/// the same order (selects for its branches), so each lane is bit for bit
/// the scalar value. A direction's two angles (a sphere's or the sky's `u`
/// and `v`) are independent: in lanes their two latency chains (a
/// division and a polynomial each) overlap, and the branches on the
/// octant, which no predictor guesses for scattered rays, are gone.
#[inline]
pub fn atan2_lanes(y: Vec4, x: Vec4) -> Vec4 {
    let (ax, ay) = (x.abs(), y.abs());
    let steep = ay.cmpgt(ax);
    let num = Vec4::select(steep, ax, ay);
    let den = Vec4::select(steep, ay, ax);
    // Both zero: ±0 toward +x, ±π toward −x.
    let flat = den.cmpeq(Vec4::ZERO);
    let on_axis = Vec4::select(x.is_negative_mask(), Vec4::splat(PI), Vec4::ZERO);
    let far = num.cmpgt(Vec4::splat(0.414_213_57) * den);
    let base = Vec4::select(far, Vec4::splat(FRAC_PI_4), Vec4::ZERO);
    let t = Vec4::select(far, num - den, num) / Vec4::select(far, num + den, den);
    let z = t * t;
    let p = (((Vec4::splat(8.053_744_5e-2) * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1)
        * z
        * t
        + t;
    let mut r = base + p;
    r = Vec4::select(steep, FRAC_PI_2 - r, r);
    r = Vec4::select(x.cmplt(Vec4::ZERO), PI - r, r);
    Vec4::select(flat, on_axis, r).copysign(y)
}

/// A direction's two angles in turns: lane 0 is `atan2(y, x) / 2π` (in
/// [−½, ½]), lane 1 `atan2(y, x) / π` (in [0, 1] for y ≥ 0), by
/// [`atan2_lanes`] and the reciprocals (a division was on the chain): π·(1/π)
/// and π·(1/2π) round to exactly 1 and ½. The sky's lookup and a sphere's
/// UVs take φ and θ from it.
#[inline]
pub fn turns_lanes(y: Vec4, x: Vec4) -> Vec4 {
    atan2_lanes(y, x) * Vec4::new(0.5 * FRAC_1_PI, FRAC_1_PI, 1.0, 1.0)
}

/// `(sin a, cos a)` for |a| ≤ π/4 by Taylor polynomials (errors below 3e-7
/// and 3e-8 there): libm's `sincosf` was 3.6% of a diffuse render. Horner
/// steps are fused multiply–adds where the target has them ([`fma`]): the
/// chain is on the critical path of every diffuse bounce.
#[inline]
pub(crate) fn sin_cos_quarter(a: f32) -> (f32, f32) {
    let a2 = a * a;
    let s = a * fma(a2, fma(a2, fma(a2, -1.0 / 5040.0, 1.0 / 120.0), -1.0 / 6.0), 1.0);
    let c = fma(
        a2,
        fma(
            a2,
            fma(a2, fma(a2, 1.0 / 40320.0, -1.0 / 720.0), 1.0 / 24.0),
            -0.5,
        ),
        1.0,
    );
    (s, c)
}

/// `a·b + c`, rounded once on targets with FMA instructions (the default
/// build, x86-64-v3), as two operations elsewhere: `f32::mul_add` without
/// the instruction is a libm call.
#[inline(always)]
pub(crate) fn fma(a: f32, b: f32, c: f32) -> f32 {
    if cfg!(target_feature = "fma") {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// `(sin 2πt, cos 2πt)` for an angle given in turns, within 4e-7 of the
/// exact values for |t| < 2²² (sampling passes t ∈ [0, 1)). Reducing a
/// count of turns is exact, unlike reducing radians by an inexact π: the
/// nearest quarter turn `q/4` is subtracted without rounding, the rest
/// (|r| ≤ ⅛ turn) goes to [`sin_cos_quarter`], and the quadrant swaps and
/// negates the pair.
#[inline]
pub fn sin_cos_turns(t: f32) -> (f32, f32) {
    let q = (4.0 * t).round();
    let (s, c) = sin_cos_quarter(std::f32::consts::TAU * (t - 0.25 * q));
    // q mod 4 (two's complement keeps negative quadrants right): quadrants
    // 1 and 3 swap the pair, 2 and 3 negate the sine, 1 and 2 the cosine.
    // By selects and sign flips rather than a four-way branch on a random
    // quadrant (the same numbers; no change in time measured).
    let k = (q as i32) & 3;
    let (s, c) = if k & 1 == 1 { (c, s) } else { (s, c) };
    let flip = |x: f32, negate: bool| f32::from_bits(x.to_bits() ^ (u32::from(negate) << 31));
    (flip(s, k >= 2), flip(c, k == 1 || k == 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_sin_cos_match_libm() {
        for i in -1000..=1000 {
            let a = std::f32::consts::FRAC_PI_4 * i as f32 / 1000.0;
            let (s, c) = sin_cos_quarter(a);
            assert!(
                (s - a.sin()).abs() < 4e-7 && (c - a.cos()).abs() < 2e-7,
                "a = {a}"
            );
        }
    }

    /// Against f64 over [−2, 2) turns on a fine grid (every quadrant and
    /// its edges, where the polynomial pieces meet).
    #[test]
    fn sin_cos_turns_matches_f64() {
        let mut worst = 0.0f64;
        for k in -400_000..400_000 {
            let t = k as f32 / 200_000.0;
            let (s, c) = sin_cos_turns(t);
            let a = std::f64::consts::TAU * f64::from(t);
            worst = worst
                .max((f64::from(s) - a.sin()).abs())
                .max((f64::from(c) - a.cos()).abs());
        }
        assert!(worst < 4e-7, "worst error {worst:e}");
        assert_eq!(sin_cos_turns(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_turns(0.5).1, -1.0);
    }

    /// The lanes are the scalar function bit for bit: random pairs over
    /// many magnitudes, both signs, the octant edges, zeros, infinities
    /// and NaN, each in every lane.
    #[test]
    fn atan2_lanes_are_the_scalar_atan2() {
        let mut rng = crate::math::Pcg32::new(7, 13);
        let mut values = vec![
            0.0f32,
            -0.0,
            1.0,
            -1.0,
            0.414_213_57,
            -0.414_213_57,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
            1e-45,
            3.0,
        ];
        for _ in 0..4000 {
            let m = (rng.next_f32() * 60.0 - 30.0).exp2();
            let s = if rng.next_f32() < 0.5 { -1.0 } else { 1.0 };
            values.push(s * m * rng.next_f32());
        }
        let n = values.len();
        for k in 0..n * 4 {
            let ys = [0, 1, 2, 3].map(|l| values[(k * 7 + l * 131) % n]);
            let xs = [0, 1, 2, 3].map(|l| values[(k * 13 + l * 57 + 3) % n]);
            let got = atan2_lanes(Vec4::from_array(ys), Vec4::from_array(xs)).to_array();
            for l in 0..4 {
                let want = atan2(ys[l], xs[l]);
                assert!(
                    got[l].to_bits() == want.to_bits() || (got[l].is_nan() && want.is_nan()),
                    "atan2({}, {}): lanes {} scalar {want}",
                    ys[l],
                    xs[l],
                    got[l]
                );
            }
        }
        // Equal magnitudes (the octant's edge: not steep).
        let e = atan2_lanes(Vec4::new(2.0, -2.0, 2.0, -2.0), Vec4::new(2.0, 2.0, -2.0, -2.0)).to_array();
        for (l, (y, x)) in [(2.0, 2.0), (-2.0, 2.0), (2.0, -2.0), (-2.0, -2.0)]
            .into_iter()
            .enumerate()
        {
            assert_eq!(e[l].to_bits(), atan2(y, x).to_bits());
        }
    }

    /// Against `f64::atan2` on a dense circle of directions at several
    /// radii, the axes, and the signed zeros.
    #[test]
    fn atan2_matches_the_exact_angle_everywhere() {
        let mut worst = 0.0f64;
        for r in [1e-30f32, 1e-3, 1.0, 7.5, 1e20, 1e37] {
            for k in 0..100_000 {
                let phi = (k as f64 / 100_000.0) * std::f64::consts::TAU - std::f64::consts::PI;
                let (y, x) = ((r as f64 * phi.sin()) as f32, (r as f64 * phi.cos()) as f32);
                let exact = f64::from(y).atan2(f64::from(x));
                let err = (f64::from(atan2(y, x)) - exact).abs();
                worst = worst.max(err);
            }
        }
        assert!(worst < 3e-7, "worst error {worst:e} rad");
        for (y, x) in [
            (0.0f32, 1.0f32),
            (-0.0, 1.0),
            (0.0, -1.0),
            (-0.0, -1.0),
            (0.0, 0.0),
            (-0.0, -0.0),
            (1.0, 0.0),
            (-1.0, -0.0),
            (3.0, -3.0),
        ] {
            let (got, want) = (atan2(y, x), y.atan2(x));
            assert!(
                got == want || (got - want).abs() < 3e-7,
                "atan2({y}, {x}) = {got}, std says {want}"
            );
            assert_eq!(
                got.is_sign_negative(),
                want.is_sign_negative(),
                "sign of atan2({y}, {x})"
            );
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
    }
}
