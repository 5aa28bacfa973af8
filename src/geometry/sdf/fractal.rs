//! Fractal distance functions: the Mandelbulb (an estimate) and the Menger
//! sponge (a bound).

use glam::Vec3A;

/// Radius of a ball certain to contain the Mandelbulb of power `n ≥ 2`.
///
/// The triplex power keeps `|zⁿ| = |z|ⁿ`, so with `r = |p| > 2^(1/(n-1))`
/// the orbit `z₁ = p, zₖ₊₁ = zₖⁿ + p` grows: `|zₖ₊₁| ≥ |zₖ|ⁿ − r ≥
/// |zₖ|(rⁿ⁻¹ − 1)` with `rⁿ⁻¹ − 1 > 1`, so `p` escapes and is not in the set.
/// For the classic power 8 this is 2^(1/7) ≈ 1.104, inside the ~1.2 usually
/// quoted; power 2 gives 2, as for the Mandelbrot set.
pub fn mandelbulb_radius(power: f32) -> f32 {
    if power == 8.0 {
        // 2^(1/7) · 1.001 = 1.1051936, rounded up: every distance estimate
        // clamps against it, and a `powf` there was a tenth of its cost.
        return 1.105_2;
    }
    // A hair of margin for the rounding of `powf`.
    2f32.powf(1.0 / (power - 1.0)) * 1.001
}

/// Hart's derivative-based distance estimate `0.5 ln r · r / |dz|`, as in
/// <https://iquilezles.org/articles/mandelbulb/>, clamped below by the
/// distance to [`mandelbulb_radius`]. The clamp is itself a bound (the set lies
/// inside that ball), makes far steps long, and keeps the estimate's
/// sub-level sets inside the bounding box, which the bounds of smooth unions
/// rely on.
///
/// Power 8 (the classic bulb) takes [`pow8_step`], multiplications only; any
/// other power the trigonometric [`pow_step`]. Both compute the same map.
pub fn mandelbulb(p: Vec3A, power: f32, iterations: u32, bailout: f32) -> f32 {
    let mut w = p;
    // |w|², so the loop needs no square root until the derivative.
    let mut m = w.length_squared();
    let bailout2 = bailout * bailout;
    // |dz/dp|, the running derivative of the orbit.
    let mut dz = 1.0f32;
    if power == 8.0 {
        for _ in 0..iterations {
            if m > bailout2 {
                break;
            }
            // d(z⁸ + p)/dp = 8 z⁷ dz + 1, in magnitude: |z|⁷ = √(m⁷).
            let m2 = m * m;
            dz = 8.0 * (m2 * m2 * m2 * m).sqrt() * dz + 1.0;
            w = p + pow8_step(w);
            m = w.length_squared();
        }
    } else {
        for _ in 0..iterations {
            if m > bailout2 {
                break;
            }
            let r = m.sqrt();
            // d(zⁿ + p)/dp = n zⁿ⁻¹ dz + 1, in magnitude.
            let r_pow = r.powf(power - 1.0);
            dz = power * r_pow * dz + 1.0;
            w = p + pow_step(w, r, r_pow * r, power);
            m = w.length_squared();
        }
    }
    finish_estimate(m, super::fast_ln::ln(m), dz, p, mandelbulb_radius(power))
}

/// The estimate from an orbit's last `m = |w|²`, `ln m` and `|dz|`, clamped
/// below by the distance from `p` to the ball of `radius`: shared with the
/// SIMD lanes (`mandelbulb_x4.rs`) so both end with the same operations.
#[inline(always)]
pub(super) fn finish_estimate(m: f32, ln_m: f32, dz: f32, p: Vec3A, radius: f32) -> f32 {
    // 0.5 r ln r / dz = 0.25 ln(r²) r / dz → 0 as r → 0 (interior points
    // whose orbit collapses).
    let estimate = if m > 0.0 { 0.25 * ln_m * m.sqrt() / dz } else { 0.0 };
    estimate.max(p.length() - radius)
}

/// The triplex power `wⁿ` in spherical coordinates: raise `r = |w|` to `n`
/// (`r_n`), multiply both angles by `n`. The polar axis is `y`, the azimuth
/// `atan2(x, z)`.
#[inline]
fn pow_step(w: Vec3A, r: f32, r_n: f32, n: f32) -> Vec3A {
    let cos_theta = if r > 0.0 { (w.y / r).clamp(-1.0, 1.0) } else { 1.0 };
    let theta = n * cos_theta.acos();
    let phi = n * w.x.atan2(w.z);
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = phi.sin_cos();
    r_n * Vec3A::new(st * sp, ct, st * cp)
}

/// [`pow_step`] for `n = 8` without trigonometry. With `ρ = √(x² + z²)`,
/// the polar pair `(r cos θ, r sin θ) = (y, ρ)` and the azimuth pair
/// `(cos φ, sin φ) = (z, x)/ρ` are complex numbers; raising each to the 8th
/// power by three complex squarings gives `r⁸(cos 8θ, sin 8θ)` and
/// `(cos 8φ, sin 8φ)` (de Moivre), so `w⁸ = (r⁸ sin 8θ sin 8φ, r⁸ cos 8θ,
/// r⁸ sin 8θ cos 8φ)`. That is 24 multiplications and adds, a square root
/// and a reciprocal; Quilez's expanded polynomials
/// (<https://iquilezles.org/articles/mandelbulb/>) took about 50, and his
/// division by `ρ⁷` underflows in `f32` within 10⁻⁶ of the polar axis, which
/// normalising the azimuth pair first avoids.
#[inline]
pub(crate) fn pow8_step(w: Vec3A) -> Vec3A {
    let (x, y, z) = (w.x, w.y, w.z);
    // r⁸ (cos 8θ, sin 8θ) = (y + iρ)⁸; sin θ ≥ 0 as ρ ≥ 0.
    let rho = (x * x + z * z).sqrt();
    let (ct, st) = square3(y, rho);
    if rho.is_nan() || rho <= 0.0 {
        // On the polar axis sin θ = 0: no azimuthal part.
        return Vec3A::new(0.0, ct, 0.0);
    }
    // (cos 8φ, sin 8φ) = ((z + ix)/ρ)⁸.
    let inv = rho.recip();
    let (cp, sp) = square3(z * inv, x * inv);
    Vec3A::new(st * sp, ct, st * cp)
}

/// `(re + i·im)⁸` by three complex squarings.
#[inline(always)]
fn square3(mut re: f32, mut im: f32) -> (f32, f32) {
    for _ in 0..3 {
        (re, im) = (re * re - im * im, 2.0 * re * im);
    }
    (re, im)
}

/// Menger sponge in `[-1, 1]³`: the cube minus `iterations` levels of crosses,
/// <https://iquilezles.org/articles/menger/>. Each term is a Chebyshev
/// distance, no more than the Euclidean one, so the result is a bound.
pub fn menger(p: Vec3A, iterations: u32) -> f32 {
    let mut d = super::primitives::cuboid(p, Vec3A::ONE);
    let mut s = 1.0f32;
    for _ in 0..iterations {
        // Fold space into one cell of the current level, centred at 0.
        let a = (p * s).rem_euclid(Vec3A::splat(2.0)) - Vec3A::ONE;
        s *= 3.0;
        // Distance to the cross of three square bars through the cell.
        let r = (Vec3A::ONE - 3.0 * a.abs()).abs();
        let da = r.x.max(r.y);
        let db = r.y.max(r.z);
        let dc = r.z.max(r.x);
        let c = (da.min(db).min(dc) - 1.0) / s;
        // Carve the cross out of what is left.
        d = d.max(c);
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{Pcg32, sampling::uniform_sphere};

    #[test]
    fn mandelbulb_is_finite_and_inside_its_radius() {
        let mut rng = Pcg32::new(8, 8);
        for _ in 0..20_000 {
            let p = uniform_sphere(rng.next_vec2()) * 3.0 * rng.next_f32();
            let d = mandelbulb(p, 8.0, 12, 2.0);
            assert!(d.is_finite(), "d({p}) = {d}");
            assert!(d >= p.length() - mandelbulb_radius(8.0), "clamp lost at {p}");
        }
        // The power-8 constant is the formula's bound, rounded up.
        assert!(mandelbulb_radius(8.0) >= 2f32.powf(1.0 / 7.0) * 1.001);
        assert!(mandelbulb_radius(8.0) - 2f32.powf(1.0 / 7.0) * 1.001 < 1e-5);
        // The centre's orbit stays at 0: inside.
        assert!(mandelbulb(Vec3A::ZERO, 8.0, 12, 2.0) <= 0.0);
        // Far away the estimate is the distance to the bounding ball.
        assert!(mandelbulb(Vec3A::splat(1e6), 16.0, 64, 16.0).is_finite());
    }

    /// `pow_step(w, |w|, |w|⁸, 8)` in `f64`: near the poles the `f32`
    /// `acos` of `y/r` loses the digits the comparison needs.
    fn pow8_f64(w: Vec3A) -> [f64; 3] {
        let (x, y, z) = (w.x as f64, w.y as f64, w.z as f64);
        let r = (x * x + y * y + z * z).sqrt();
        let theta = 8.0 * (y / r).clamp(-1.0, 1.0).acos();
        let phi = 8.0 * x.atan2(z);
        let r8 = r.powi(8);
        [
            r8 * theta.sin() * phi.sin(),
            r8 * theta.cos(),
            r8 * theta.sin() * phi.cos(),
        ]
    }

    #[test]
    fn pow8_polynomial_is_the_trigonometric_power() {
        let mut rng = Pcg32::new(10, 10);
        let mut worst = 0.0f64;
        for i in 0..20_000 {
            let mut w = uniform_sphere(rng.next_vec2()) * 1.5 * rng.next_f32();
            if i % 10 == 0 {
                // Near and on the polar axis, where ρ⁷ would underflow.
                w.x *= 1e-6 * rng.next_f32();
                w.z = if i % 20 == 0 { 0.0 } else { w.z * 1e-6 };
            }
            let (poly, want) = (pow8_step(w), pow8_f64(w));
            let r8 = (w.length() as f64).powi(8).max(1e-30);
            let err = (0..3)
                .map(|k| (poly[k] as f64 - want[k]).abs())
                .fold(0.0, f64::max)
                / r8;
            worst = worst.max(err);
            assert!(err < 1e-5, "z⁸ at {w}: polynomial {poly}, f64 {want:?}");
        }
        // Rounding only: a few ulps of r⁸.
        eprintln!("z⁸: worst difference {worst:e} of r⁸");
    }

    #[test]
    fn power_8_estimate_matches_the_trigonometric_one() {
        // The same estimate through the general path (power 8 + 0 ulp).
        let mut rng = Pcg32::new(11, 11);
        for _ in 0..5_000 {
            let p = uniform_sphere(rng.next_vec2()) * 1.3 * rng.next_f32();
            let fast = mandelbulb(p, 8.0, 8, 2.0);
            // Reference: the general loop with the trigonometric step.
            let (mut w, mut dz, mut m) = (p, 1.0f32, p.length_squared());
            for _ in 0..8 {
                if m > 4.0 {
                    break;
                }
                let r = m.sqrt();
                dz = 8.0 * r.powi(7) * dz + 1.0;
                w = p + pow_step(w, r, r.powi(8), 8.0);
                m = w.length_squared();
            }
            let slow = (0.25 * m.ln() * m.sqrt() / dz).max(p.length() - mandelbulb_radius(8.0));
            // The orbit is chaotic near the surface: compare where the
            // estimate is far from 0, relative to the distance itself.
            if slow.abs() > 1e-3 {
                assert!(
                    (fast - slow).abs() <= 0.02 * slow.abs(),
                    "d({p}): polynomial {fast}, trigonometric {slow}"
                );
            }
        }
    }

    #[test]
    fn menger_is_bounded_by_its_cube() {
        let mut rng = Pcg32::new(9, 9);
        for _ in 0..20_000 {
            let p = uniform_sphere(rng.next_vec2()) * 2.0 * rng.next_f32();
            let d = menger(p, 4);
            assert!(d >= super::super::primitives::cuboid(p, Vec3A::ONE) - 1e-6);
        }
        // The centre of the cube is drilled out by the first cross.
        assert!(menger(Vec3A::ZERO, 1) > 0.0);
        assert!(menger(Vec3A::new(0.9, 0.9, 0.9), 1) < 0.0);
    }
}
