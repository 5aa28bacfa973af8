//! Bounds on floating-point rounding error, so that a ray leaving a surface
//! is moved off it by what its hit point may actually be wrong by, not by an
//! epsilon guessed from the scene's size (pbrt-v4 §6.8, "Managing Rounding
//! Error", <https://pbr-book.org/4ed/Shapes/Managing_Rounding_Error>).
//!
//! Each shape bounds the error of the point it reports (`Hit::p_error`); the
//! integrators then move ray origins along the geometric normal by exactly
//! that bound and round the result away from the surface
//! ([`offset_along_normal`]). Far from the origin the bound grows with the
//! coordinates' ulp, as it must, but stays a few ulps: at 1,000 units it is
//! about 1e-4, where the old `1e-4·(1 + |p|)` offset was 0.1, wider than
//! the gap under a sphere resting on a floor near its contact point.

use glam::{Affine3A, Mat3A, Vec3A};

/// Half the distance from 1 to the next `f32`: the largest relative error of
/// one rounding (pbrt's `MachineEpsilon`).
pub const MACHINE_EPSILON: f32 = f32::EPSILON * 0.5;

/// γ(n) = nε/(1 − nε), the bound on the relative error accumulated by `n`
/// successive roundings (Higham 2002, §3.1; pbrt-v4 `gamma`).
#[inline]
pub const fn gamma(n: u32) -> f32 {
    let ne = n as f32 * MACHINE_EPSILON;
    ne / (1.0 - ne)
}

/// Error bound of `world_from_object · p` for a point `p` that is itself
/// off by at most `p_err` per axis (pbrt-v4 `Transform::operator()(Point3fi)`).
///
/// glam sums the three products and the translation one after another, so a
/// component goes through a product and three additions: γ(4) on the exact
/// terms, plus the carried error scaled by the matrix (times 1 + γ(4)). The
/// exact terms get the offset's two roundings too ([`gamma_offset`]): far
/// from the origin the translation is most of the transformed point.
#[inline]
pub fn transform_point_error(m: &Affine3A, p: Vec3A, p_err: Vec3A) -> Vec3A {
    let a = Mat3A::from_cols(
        m.matrix3.x_axis.abs(),
        m.matrix3.y_axis.abs(),
        m.matrix3.z_axis.abs(),
    );
    gamma_offset(4) * (a * p.abs() + m.translation.abs()) + (1.0 + gamma(4)) * (a * p_err)
}

/// The error of a point bounded per axis by `p_err`, measured along the unit
/// normal `n`: how far the true surface may lie from the computed point in
/// the only direction a spawned ray's origin is moved (pbrt-v4's
/// `Dot(Abs(n), pi.Error())`). A scalar suffices because every ray leaving a
/// hit is offset along the hit's geometric normal, known when the bound is.
#[inline]
pub fn error_along(n: Vec3A, p_err: Vec3A) -> f32 {
    n.abs().dot(p_err)
}

/// `p` moved by `d` along the unit normal `n`, to the side `w` points into
/// (pbrt-v4 `OffsetRayOrigin`).
///
/// pbrt then rounds each coordinate one `f32` further from `p`, so that
/// rounding the sum cannot bring it back inside the bound; three branches
/// per axis were 2.5% of the Cornell box's instructions (callgrind).
/// Instead every bound a shape reports counts two more roundings than its
/// point needs ([`ROUNDINGS_OF_THE_OFFSET`]): each is at least
/// `γ(k)·|p|` per axis, so the two extra give `2ε·|n|·|p|` along `n`, more
/// than the half ulp per coordinate (`ε·|pᵢ + offᵢ|`) that storing `p + n·d`
/// and forming `n·d` can take back.
#[inline]
pub fn offset_along_normal(p: Vec3A, n: Vec3A, d: f32, w: Vec3A) -> Vec3A {
    if n.dot(w) >= 0.0 { p + n * d } else { p - n * d }
}

/// Roundings added to every shape's error bound for the sum that moves a
/// ray origin off the surface (see [`offset_along_normal`]).
pub const ROUNDINGS_OF_THE_OFFSET: u32 = 2;

/// γ(`n` + [`ROUNDINGS_OF_THE_OFFSET`]): the factor a shape's bound uses
/// for a point computed with `n` roundings.
#[inline]
pub const fn gamma_offset(n: u32) -> f32 {
    gamma(n + ROUNDINGS_OF_THE_OFFSET)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_grows_with_the_number_of_roundings() {
        assert_eq!(gamma(0), 0.0);
        assert!(gamma(1) > MACHINE_EPSILON && gamma(1) < 1.000_001 * MACHINE_EPSILON);
        assert!(gamma(7) > 7.0 * MACHINE_EPSILON && gamma(7) < 7.01 * MACHINE_EPSILON);
    }

    #[test]
    fn offset_point_lies_beyond_the_error_bound_on_the_side_of_w() {
        let p = Vec3A::new(10_000.0, -3.0, 10_000.0);
        let n = Vec3A::new(0.0, 1.0, 0.0);
        let d = error_along(n, gamma_offset(3) * p.abs());
        let up = offset_along_normal(p, n, d, Vec3A::new(0.3, 0.2, 0.0));
        let down = offset_along_normal(p, n, d, Vec3A::new(0.3, -0.2, 0.0));
        let own = f64::from(error_along(n, gamma(3) * p.abs()));
        assert!(
            f64::from(up.y) - f64::from(p.y) > own,
            "{up} not above {p} by {own}"
        );
        assert!(
            f64::from(p.y) - f64::from(down.y) > own,
            "{down} not below {p} by {own}"
        );
        assert_eq!((up.x, up.z), (p.x, p.z), "no move along the surface");
    }

    #[test]
    fn offset_exceeds_the_bound_after_rounding_at_every_scale() {
        let mut rng = crate::math::Pcg32::new(5, 44);
        for i in 0..10_000 {
            let scale = 10f32.powi(i % 9 - 3);
            let u = |r: &mut crate::math::Pcg32| r.next_f32() * 2.0 - 1.0;
            let p = Vec3A::new(u(&mut rng), u(&mut rng), u(&mut rng)) * scale;
            let n = Vec3A::new(u(&mut rng), u(&mut rng), u(&mut rng)).normalize();
            // The point's own bound, and the one a shape reports for it.
            let own = error_along(n, gamma(1) * p.abs());
            let d = error_along(n, gamma_offset(1) * p.abs());
            let o = offset_along_normal(p, n, d, n);
            // Exactly, in f64: how far the stored point moved along n.
            let moved: f64 = (0..3)
                .map(|k| (f64::from(o[k]) - f64::from(p[k])) * f64::from(n[k]))
                .sum();
            assert!(
                moved > f64::from(own),
                "{p} along {n}: moved {moved:e}, own bound {own:e}"
            );
        }
    }

    #[test]
    fn transform_error_covers_the_rounding_of_a_far_translation() {
        let m = Affine3A::from_rotation_y(0.7) * Affine3A::from_translation(glam::Vec3::new(1e4, 0.0, -1e4));
        let p = Vec3A::new(0.3, 0.9, -0.2);
        let got = m.transform_point3a(p);
        // The stored f32 matrix is exact; its product with `p` in f64 nearly so.
        let d = |v: Vec3A| glam::DVec3::new(v.x.into(), v.y.into(), v.z.into());
        let (c, t) = (m.matrix3, m.translation);
        let exact =
            d(c.x_axis) * f64::from(p.x) + d(c.y_axis) * f64::from(p.y) + d(c.z_axis) * f64::from(p.z) + d(t);
        let err = transform_point_error(&m, p, Vec3A::ZERO);
        for i in 0..3 {
            assert!(
                (got[i] as f64 - exact[i]).abs() <= err[i] as f64,
                "axis {i}: {} vs {} exceeds {}",
                got[i],
                exact[i],
                err[i]
            );
        }
    }
}
