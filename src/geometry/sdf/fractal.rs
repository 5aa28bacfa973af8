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
pub fn mandelbulb(p: Vec3A, power: f32, iterations: u32, bailout: f32) -> f32 {
    let mut w = p;
    let mut r = w.length();
    // |dz/dp|, the running derivative of the orbit.
    let mut dz = 1.0f32;
    for _ in 0..iterations {
        if r > bailout {
            break;
        }
        // d(zⁿ + p)/dp = n zⁿ⁻¹ dz + 1, in magnitude.
        let r_pow = r.powf(power - 1.0);
        dz = power * r_pow * dz + 1.0;
        // zⁿ in spherical coordinates: raise r to n, multiply both angles by n.
        let cos_theta = if r > 0.0 { (w.y / r).clamp(-1.0, 1.0) } else { 1.0 };
        let theta = power * cos_theta.acos();
        let phi = power * w.x.atan2(w.z);
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        w = p + r_pow * r * Vec3A::new(st * sp, ct, st * cp);
        r = w.length();
    }
    // 0.5 r ln r / dz → 0 as r → 0 (interior points whose orbit collapses).
    let estimate = if r > 0.0 { 0.5 * r.ln() * r / dz } else { 0.0 };
    estimate.max(p.length() - mandelbulb_radius(power))
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
