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
    // 0.5 r ln r / dz = 0.25 ln(r²) r / dz → 0 as r → 0 (interior points
    // whose orbit collapses).
    let estimate = if m > 0.0 {
        0.25 * m.ln() * m.sqrt() / dz
    } else {
        0.0
    };
    estimate.max(p.length() - mandelbulb_radius(power))
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

/// [`pow_step`] for `n = 8` without trigonometry: Quilez's polynomial form
/// (<https://iquilezles.org/articles/mandelbulb/>). With `ρ² = x² + z²`,
/// `cos θ = y/r`, `sin θ = ρ/r`, `cos φ = z/ρ`, `sin φ = x/ρ`, the multiple-angle
/// formulas turn `r⁸ sin 8θ` and `cos 8θ` into polynomials in `x, y, z`, and
/// `sin 8φ`, `cos 8φ` into polynomials over `ρ⁸`; one `1/√(ρ⁷)` is the only
/// division. About 50 multiplications against two `sin_cos`, an `acos`, an
/// `atan2` and a `powf`.
#[inline]
pub(crate) fn pow8_step(w: Vec3A) -> Vec3A {
    let (x, y, z) = (w.x, w.y, w.z);
    let (x2, y2, z2) = (x * x, y * y, z * z);
    let (x4, y4, z4) = (x2 * x2, y2 * y2, z2 * z2);
    // ρ² and its 1/√(ρ²)⁷.
    let k3 = x2 + z2;
    let k3_2 = k3 * k3;
    let k2 = (k3_2 * k3_2 * k3_2 * k3).sqrt().recip();
    // r⁴ cos 4θ and −r² cos 2θ.
    let k1 = x4 + y4 + z4 - 6.0 * y2 * z2 - 6.0 * x2 * y2 + 2.0 * z2 * x2;
    let k4 = x2 - y2 + z2;
    // cos 8θ = 2 cos² 4θ − 1, times r⁸.
    let wy = -16.0 * y2 * k3 * k4 * k4 + k1 * k1;
    if !k2.is_finite() {
        // On the polar axis (ρ = 0, or ρ⁷ underflows): sin θ = 0, so the
        // azimuthal terms vanish (ρ⁸/ρ⁷ → 0).
        return Vec3A::new(0.0, wy, 0.0);
    }
    // r⁸ sin 8θ · sin 8φ and · cos 8φ.
    let wx = 64.0 * x * y * z * (x2 - z2) * k4 * (x4 - 6.0 * x2 * z2 + z4) * k1 * k2;
    let wz = -8.0
        * y
        * k4
        * (x4 * x4 - 28.0 * x4 * x2 * z2 + 70.0 * x4 * z4 - 28.0 * x2 * z2 * z4 + z4 * z4)
        * k1
        * k2;
    Vec3A::new(wx, wy, wz)
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
        // The centre's orbit stays at 0: inside.
        assert!(mandelbulb(Vec3A::ZERO, 8.0, 12, 2.0) <= 0.0);
        // Far away the estimate is the distance to the bounding ball.
        assert!(mandelbulb(Vec3A::splat(1e6), 16.0, 64, 16.0).is_finite());
    }

    #[test]
    fn pow8_polynomial_is_the_trigonometric_power() {
        let mut rng = Pcg32::new(10, 10);
        let mut worst = 0.0f32;
        for i in 0..20_000 {
            let mut w = uniform_sphere(rng.next_vec2()) * 1.5 * rng.next_f32();
            if i % 10 == 0 {
                // Near and on the polar axis, where ρ⁷ underflows.
                w.x *= 1e-6 * rng.next_f32();
                w.z = if i % 20 == 0 { 0.0 } else { w.z * 1e-6 };
            }
            let r = w.length();
            let (poly, trig) = (pow8_step(w), pow_step(w, r, r.powi(8), 8.0));
            let err = (poly - trig).length() / r.powi(8).max(1e-30);
            worst = worst.max(err);
            assert!(err < 1e-4, "z⁸ at {w}: polynomial {poly}, trigonometric {trig}");
        }
        // Rounding only: a few ulps of r⁸ (acos loses digits near the poles).
        assert!(worst < 1e-4, "worst relative difference {worst}");
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
