//! The power-8 Mandelbulb estimate at four points at once, one SIMD lane
//! each: the four tetrahedron taps of a surface normal (`march::normal`)
//! and the four points of a lane march (`march/lanes.rs`).
//!
//! Why: a lone estimate is one long chain of dependent square roots,
//! divisions and complex squarings, so the CPU waits on each in turn; four
//! independent orbits fill those waits and share each instruction. The
//! arithmetic is [`mandelbulb`](super::fractal::mandelbulb)'s, operation for
//! operation in the same order, so every lane is bit for bit the scalar
//! estimate (`x4_matches_the_scalar_estimate_bit_for_bit`): a normal is the
//! same either way.

use super::fractal::{finish_estimate, mandelbulb_radius};
use glam::{BVec4A, Vec3A, Vec4};

/// [`mandelbulb`](super::fractal::mandelbulb)`(p, 8.0, iterations, bailout)`
/// at each of `points`.
pub fn mandelbulb8_x4(points: [Vec3A; 4], iterations: u32, bailout: f32) -> [f32; 4] {
    // Structure of arrays: lane k holds points[k].
    let px = Vec4::from_array(points.map(|p| p.x));
    let py = Vec4::from_array(points.map(|p| p.y));
    let pz = Vec4::from_array(points.map(|p| p.z));
    let (mut x, mut y, mut z) = (px, py, pz);
    let mut m = x * x + y * y + z * z;
    let bailout2 = Vec4::splat(bailout * bailout);
    let mut dz = Vec4::ONE;
    for _ in 0..iterations {
        // A lane stops for good once its orbit escapes (NaN keeps going, as
        // in the scalar loop, whose test is `m > bailout²`).
        let active = !m.cmpgt(bailout2);
        if !active.any() {
            break;
        }
        let m2 = m * m;
        let dz_next = Vec4::splat(8.0) * (m2 * m2 * m2 * m).sqrt() * dz + Vec4::ONE;
        let (wx, wy, wz) = pow8_step_x4(x, y, z);
        let (nx, ny, nz) = (px + wx, py + wy, pz + wz);
        let m_next = nx * nx + ny * ny + nz * nz;
        dz = Vec4::select(active, dz_next, dz);
        x = Vec4::select(active, nx, x);
        y = Vec4::select(active, ny, y);
        z = Vec4::select(active, nz, z);
        m = Vec4::select(active, m_next, m);
    }
    let ln_m = super::fast_ln::ln_x4(m).to_array();
    let (m, dz) = (m.to_array(), dz.to_array());
    let radius = mandelbulb_radius(8.0);
    std::array::from_fn(|k| finish_estimate(m[k], ln_m[k], dz[k], points[k], radius))
}

/// [`pow8_step`](super::fractal::pow8_step) lane by lane: `(re + iρ)⁸` for
/// the polar pair and `((z + ix)/ρ)⁸` for the azimuth, by complex squarings.
#[inline(always)]
fn pow8_step_x4(x: Vec4, y: Vec4, z: Vec4) -> (Vec4, Vec4, Vec4) {
    let rho = (x * x + z * z).sqrt();
    let (ct, st) = square3(y, rho);
    // On the polar axis (or NaN) sin θ = 0: no azimuthal part.
    let off_axis: BVec4A = rho.cmpgt(Vec4::ZERO);
    let inv = rho.recip();
    let (cp, sp) = square3(z * inv, x * inv);
    (
        Vec4::select(off_axis, st * sp, Vec4::ZERO),
        ct,
        Vec4::select(off_axis, st * cp, Vec4::ZERO),
    )
}

/// `(re + i·im)⁸` by three complex squarings, per lane.
#[inline(always)]
fn square3(mut re: Vec4, mut im: Vec4) -> (Vec4, Vec4) {
    for _ in 0..3 {
        (re, im) = (re * re - im * im, Vec4::splat(2.0) * re * im);
    }
    (re, im)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::sdf::fractal::mandelbulb;
    use crate::math::{Pcg32, sampling::uniform_sphere};

    #[test]
    fn x4_matches_the_scalar_estimate_bit_for_bit() {
        let mut rng = Pcg32::new(12, 12);
        for i in 0..20_000 {
            let mut points = [Vec3A::ZERO; 4];
            for p in &mut points {
                *p = uniform_sphere(rng.next_vec2()) * 1.4 * rng.next_f32();
                if i % 10 == 0 {
                    // Near and on the polar axis.
                    p.x *= 1e-6;
                    p.z = 0.0;
                }
            }
            if i == 0 {
                points[1] = Vec3A::ZERO;
            }
            let got = mandelbulb8_x4(points, 8, 2.0);
            for k in 0..4 {
                let want = mandelbulb(points[k], 8.0, 8, 2.0);
                assert_eq!(
                    got[k].to_bits(),
                    want.to_bits(),
                    "d({}) = {} in a lane, {want} alone",
                    points[k],
                    got[k]
                );
            }
        }
    }
}
