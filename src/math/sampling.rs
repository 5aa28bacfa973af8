//! Warps from the unit square to common domains, each with its density
//! (`*_pdf`, with respect to solid angle or area as named). Inputs `u` are
//! uniform in [0,1)².

use glam::{Vec2, Vec3A};
use std::f32::consts::{FRAC_1_PI, PI};
use wide::f32x4;

/// Shirley–Chiu concentric map: preserves stratification better than polar.
///
/// Written without branches on the point: which wedge a uniform point falls
/// in is a coin toss, so a branch there mispredicts half the time, on the
/// chain from one hit to the next ray (~1.5% of a diffuse render's time,
/// within the machine's noise; the points are bit for bit the same).
#[inline]
pub fn concentric_disk(u: Vec2) -> Vec2 {
    let [x, y, _, _] = concentric_lanes(u).to_array();
    Vec2::new(x, y)
}

/// [`concentric_disk`]'s point as lanes `(x, y, 0, 0)`. Every vector here
/// is built from defined lanes: written on `Vec2`, LLVM packed the point
/// into a 4-lane register whose upper lanes were left over from earlier
/// work and ran the arithmetic on all four. Leftover integer bits read as
/// denormal floats, and each operation on one took a microcode assist: on
/// 40% of the diffuse bounces of the Cornell box (MXCSR's denormal and
/// underflow flags, probed around each step of the path loop), 4–5% of the
/// render's wall time in alternated pairs (`docs/benchmarks.md`).
#[inline(always)]
fn concentric_lanes(u: Vec2) -> f32x4 {
    let o = f32x4::new([u.x, u.y, 0.0, 0.0]) * f32x4::splat(2.0) - f32x4::new([1.0, 1.0, 0.0, 0.0]);
    let [ox, oy, _, _] = o.to_array();
    // θ = π/4 · a with |a| ≤ 1 in the first wedge (|x| > |y|; a = y/x,
    // radius x), π/2 − π/4 · a in the second (a = x/y, radius y), whose
    // cosine and sine are the first wedge's swapped.
    // The wedge is a coin flip per sample, so it is chosen by a SIMD blend
    // on a vector compare's mask: a branch there mispredicts half the time
    // (callgrind's branch model: 0.46 M mispredicts on the Cornell box,
    // 64², 64 spp). A scalar condition is not enough, whatever it is written
    // as: bit masks on `to_bits`, `std::hint::select_unpredictable` and
    // glam's `Vec2::select` all became a branch (x86 lowers a float select
    // on a scalar flag to one; 58% of the path loop's mispredicts,
    // 2026-12-03), while a select on a vector mask is a `blendvps`.
    let first = f32x4::splat(ox.abs()).simd_gt(f32x4::splat(oy.abs()));
    let [num, r, _, _] = first
        .bitselect(f32x4::new([oy, ox, 0.0, 0.0]), f32x4::new([ox, oy, 0.0, 0.0]))
        .to_array();
    // r = 0 only at the centre (o = 0), which maps to itself.
    let a = if r == 0.0 { 0.0 } else { num / r };
    let (s, c) = super::trig::sin_cos_quarter(std::f32::consts::FRAC_PI_4 * a);
    let xy = first.bitselect(f32x4::new([c, s, 0.0, 0.0]), f32x4::new([s, c, 0.0, 0.0]));
    f32x4::splat(r) * xy
}

/// Malley's method: project the disk onto the hemisphere (+z).
#[inline]
pub fn cosine_hemisphere(u: Vec2) -> Vec3A {
    let d = concentric_lanes(u);
    // |d|² as `Vec2::length_squared` sums it, from defined lanes (see
    // `concentric_lanes`).
    let [x, y, _, _] = d.to_array();
    let [xx, yy, _, _] = (d * d).to_array();
    let z = (1.0 - (xx + yy)).max(0.0).sqrt();
    Vec3A::new(x, y, z)
}

/// Density (1/sr) of [`cosine_hemisphere`] at a direction of angle cosine `cos_theta`
/// to +z; 0 below the horizon.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cos_theta.max(0.0) * FRAC_1_PI
}

/// Uniform direction on the unit sphere from `u` ∈ [0, 1)²; density
/// [`UNIFORM_SPHERE_PDF`].
pub fn uniform_sphere(u: Vec2) -> Vec3A {
    let z = 1.0 - 2.0 * u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

/// Density (1/sr) of [`uniform_sphere`]: 1/(4π).
pub const UNIFORM_SPHERE_PDF: f32 = 1.0 / (4.0 * PI);

/// Uniform direction on the upper (+z) unit hemisphere from `u` ∈ [0, 1)²; density
/// [`UNIFORM_HEMISPHERE_PDF`].
pub fn uniform_hemisphere(u: Vec2) -> Vec3A {
    let z = u.x;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * u.y;
    Vec3A::new(r * phi.cos(), r * phi.sin(), z)
}

/// Density (1/sr) of [`uniform_hemisphere`]: 1/(2π).
pub const UNIFORM_HEMISPHERE_PDF: f32 = 1.0 / (2.0 * PI);

/// Veach's power heuristic (β = 2) for combining two strategies by MIS,
/// written as 1/(1 + (g/f)²) so huge densities (a light seen edge-on from
/// far away) cannot overflow to ∞/∞.
#[inline]
pub fn power_heuristic(f_pdf: f32, g_pdf: f32) -> f32 {
    if f_pdf.is_nan() || f_pdf <= 0.0 {
        return 0.0;
    }
    let r = g_pdf / f_pdf;
    if r.is_nan() {
        // Both infinite: split evenly.
        return 0.5;
    }
    1.0 / (1.0 + r * r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;

    #[test]
    fn cosine_hemisphere_is_normalised_and_upper() {
        let mut rng = Pcg32::new(1, 2);
        // E[1/pdf] over the hemisphere equals its solid angle 2π.
        let n = 200_000;
        let mut acc = 0.0f64;
        for _ in 0..n {
            let w = cosine_hemisphere(rng.next_vec2());
            assert!(w.z >= 0.0 && (w.length() - 1.0).abs() < 1e-4);
            let pdf = cosine_hemisphere_pdf(w.z);
            if pdf > 1e-4 {
                acc += (w.z as f64) / pdf as f64;
            }
        }
        // ∫ cos dω = π
        let est = acc / n as f64;
        assert!((est - PI as f64).abs() < 0.01, "∫cos = {est}");
    }

    #[test]
    fn power_heuristic_survives_extreme_densities() {
        assert_eq!(power_heuristic(1.2e20, 0.3), 1.0);
        assert_eq!(power_heuristic(0.3, 1.2e20), 0.0);
        assert_eq!(power_heuristic(0.0, 0.0), 0.0);
        assert_eq!(power_heuristic(f32::INFINITY, f32::INFINITY), 0.5);
        assert!((power_heuristic(1.0, 1.0) - 0.5).abs() < 1e-7);
        assert!((power_heuristic(2.0, 1.0) - 0.8).abs() < 1e-6);
    }

    #[test]
    fn concentric_disk_stays_inside() {
        let mut rng = Pcg32::new(3, 4);
        for _ in 0..10_000 {
            assert!(concentric_disk(rng.next_vec2()).length() <= 1.0 + 1e-6);
        }
    }

    /// The blended map is Shirley and Chiu's, written with branches as in
    /// pbrt-v4 (`SampleUniformDiskConcentric`), bit for bit: the lanes the
    /// blends pick are the right ones, in both wedges, on the diagonals and
    /// at the centre.
    #[test]
    fn concentric_disk_is_the_branchy_map() {
        let branchy = |u: Vec2| {
            let o = 2.0 * u - Vec2::ONE;
            if o == Vec2::ZERO {
                return Vec2::ZERO;
            }
            let q = std::f32::consts::FRAC_PI_4;
            if o.x.abs() > o.y.abs() {
                let (s, c) = crate::math::trig::sin_cos_quarter(q * (o.y / o.x));
                o.x * Vec2::new(c, s)
            } else {
                let (s, c) = crate::math::trig::sin_cos_quarter(q * (o.x / o.y));
                o.y * Vec2::new(s, c)
            }
        };
        let mut rng = Pcg32::new(5, 6);
        let edges = [0.0, 0.25, 0.5, 0.75, 0.999_999_94];
        let grid = edges
            .iter()
            .flat_map(|&x| edges.iter().map(move |&y| Vec2::new(x, y)));
        for u in grid.chain((0..10_000).map(|_| rng.next_vec2())) {
            let (a, b) = (concentric_disk(u), branchy(u));
            assert_eq!(
                (a.x.to_bits(), a.y.to_bits()),
                (b.x.to_bits(), b.y.to_bits()),
                "u = {u}: {a} vs {b}"
            );
        }
    }
}
