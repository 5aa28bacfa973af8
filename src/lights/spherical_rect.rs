//! Uniform solid-angle sampling of a rectangle seen from a point: Ureña,
//! Fajardo and King 2013, "An Area-Preserving Parametrization for Spherical
//! Rectangles" (<https://www.arnoldrenderer.com/research/egsr2013_spherical_rectangle.pdf>),
//! the method of pbrt-v4's `SampleSphericalRectangle`.
//!
//! Sampling by area gives a density d²/(cos θl A) in solid angle, which
//! explodes for shading points close to the light (the ceiling beside a
//! Cornell lamp): sampling the solid angle directly makes that factor
//! constant, 1/Ω. The setup costs four square roots and four `acos`, so
//! the caller falls back to area sampling where Ω is tiny (the two
//! densities agree there) or close to a hemisphere (where the `acos` terms
//! cancel and lose precision), as pbrt does.

use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Below this solid angle (sr) area sampling is as good and cheaper; pbrt-v4's
/// `MinSphericalSampleArea`.
pub const MIN_SOLID_ANGLE: f32 = 3e-4;
/// Above this solid angle (sr, nearly 2π: the point is almost on the light's
/// plane, right under it) the spherical terms lose precision; pbrt-v4's
/// `MaxSphericalSampleArea`.
pub const MAX_SOLID_ANGLE: f32 = 6.22;

/// A rectangle in the local frame of one shading point `p`: `p` at the
/// origin, the rectangle spanning `[x0, x1] × [y0, y1]` at height `z0 < 0`
/// (the frame's z is flipped so that the rectangle lies below).
#[derive(Clone, Copy, Debug)]
pub struct SphericalRect {
    p: Vec3A,
    ex: Vec3A,
    ey: Vec3A,
    ez: Vec3A,
    x0: f32,
    x1: f32,
    y0: f32,
    y1: f32,
    z0: f32,
    /// z components of the first and third edge-plane normals (the paper's b0, b1).
    b0: f32,
    b1: f32,
    /// 2π − γ2 − γ3: the solid angle's offset in the paper's `au`.
    k: f32,
    /// The rectangle's solid angle seen from `p`, in sr.
    pub solid_angle: f32,
}

impl SphericalRect {
    /// The rectangle `corner + s·ex·len_x + t·ey·len_y` (s, t ∈ [0, 1]; `ex`,
    /// `ey` orthonormal, `n = ex × ey`) as seen from `p`; `None` when `p` lies
    /// in its plane (no solid angle).
    #[inline]
    pub fn new(p: Vec3A, corner: Vec3A, ex: Vec3A, ey: Vec3A, n: Vec3A, len: Vec2) -> Option<Self> {
        let d = corner - p;
        let (x0, y0) = (d.dot(ex), d.dot(ey));
        let mut z0 = d.dot(n);
        let mut ez = n;
        // Flip z to point toward the rectangle's side.
        if z0 > 0.0 {
            z0 = -z0;
            ez = -ez;
        }
        if z0 == 0.0 || !z0.is_finite() {
            return None;
        }
        let (x1, y1) = (x0 + len.x, y0 + len.y);
        // Normals of the planes through p and each edge (v00→v10, v10→v11,
        // v11→v01, v01→v00), each with one zero component.
        let n0 = Vec2::new(z0, -y0).normalize(); // (0, y, z)
        let n1 = Vec2::new(-z0, x1).normalize(); // (x, 0, z)
        let n2 = Vec2::new(-z0, y1).normalize(); // (0, y, z)
        let n3 = Vec2::new(z0, -x0).normalize(); // (x, 0, z)
        // Interior angles γᵢ = acos(−nᵢ·nᵢ₊₁); only z components overlap.
        let g0 = (-n0.y * n1.y).clamp(-1.0, 1.0).acos();
        let g1 = (-n1.y * n2.y).clamp(-1.0, 1.0).acos();
        let g2 = (-n2.y * n3.y).clamp(-1.0, 1.0).acos();
        let g3 = (-n3.y * n0.y).clamp(-1.0, 1.0).acos();
        let k = 2.0 * PI - g2 - g3;
        Some(Self {
            p,
            ex,
            ey,
            ez,
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: n0.y,
            b1: n2.y,
            k,
            solid_angle: g0 + g1 - k,
        })
    }

    /// Whether the spherical parametrisation should be used here (see
    /// [`MIN_SOLID_ANGLE`], [`MAX_SOLID_ANGLE`]); otherwise sample by area.
    #[inline]
    pub fn worth_it(&self) -> bool {
        (MIN_SOLID_ANGLE..=MAX_SOLID_ANGLE).contains(&self.solid_angle)
    }

    /// The point on the rectangle in direction `u` ∈ [0, 1)², uniform in solid
    /// angle (density 1/Ω).
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec3A {
        let z0 = self.z0;
        // 1. The x coordinate: invert the area of the sub-rectangle left of it.
        let au = u.x * self.solid_angle + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = (1.0 / (fu * fu + self.b0 * self.b0).sqrt())
            .copysign(fu)
            .clamp(-1.0 + f32::EPSILON, 1.0 - f32::EPSILON);
        let xu = (-(cu * z0) / (1.0 - cu * cu).max(0.0).sqrt()).clamp(self.x0, self.x1);
        // 2. The y coordinate: uniform in the sine of the elevation along that column.
        let dd = (xu * xu + z0 * z0).sqrt();
        let h0 = self.y0 / (dd * dd + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (dd * dd + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-6 {
            (hv * dd / (1.0 - hv2).sqrt()).clamp(self.y0, self.y1)
        } else {
            self.y1
        };
        self.p + xu * self.ex + yv * self.ey + z0 * self.ez
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;

    /// A 2 × 1 rectangle in the plane y = 1, normal down, corner at (−1, 1, −0.5).
    fn rect_from(p: Vec3A) -> Option<SphericalRect> {
        SphericalRect::new(
            p,
            Vec3A::new(-1.0, 1.0, -0.5),
            Vec3A::X,
            Vec3A::Z,
            Vec3A::NEG_Y,
            Vec2::new(2.0, 1.0),
        )
    }

    #[test]
    fn spherical_rect_solid_angle_matches_integral() {
        // Ω = ∫ cos θl / d² dA by a fine midpoint rule over the rectangle.
        for p in [
            Vec3A::ZERO,
            Vec3A::new(0.9, 0.95, 0.3),
            Vec3A::new(3.0, 2.0, -4.0),
        ] {
            let r = rect_from(p).expect("off the plane");
            let n = 400;
            let mut want = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let q = Vec3A::new(
                        -1.0 + 2.0 * (i as f32 + 0.5) / n as f32,
                        1.0,
                        -0.5 + (j as f32 + 0.5) / n as f32,
                    );
                    let d = q - p;
                    let d2 = d.length_squared();
                    want += (d.y.abs() / d2.sqrt() / d2) as f64 * 2.0 / (n * n) as f64;
                }
            }
            let got = r.solid_angle as f64;
            assert!(((got - want) / want).abs() < 2e-3, "from {p}: Ω {got} vs {want}");
        }
        assert!(rect_from(Vec3A::new(0.0, 1.0, 0.0)).is_none(), "in the plane");
    }

    #[test]
    fn spherical_rect_samples_lie_on_the_rectangle_and_are_uniform() {
        // Uniform in solid angle: u.x = ½ must split Ω in halves (the
        // irradiance tests in lights/tests.rs check the full density).
        let p = Vec3A::new(0.7, 0.6, 0.1);
        let r = rect_from(p).expect("off the plane");
        let mut rng = Pcg32::new(5, 9);
        for _ in 0..10_000 {
            let q = r.sample(rng.next_vec2());
            assert!(
                (q.y - 1.0).abs() < 1e-4 && (-1.0..=1.0).contains(&q.x) && (-0.5..=0.5).contains(&q.z),
                "{q} is off the rectangle"
            );
        }
        // The x of u = (½, ·) splits Ω in halves.
        let mid = r.sample(Vec2::new(0.5, 0.5));
        let left = SphericalRect::new(
            p,
            Vec3A::new(-1.0, 1.0, -0.5),
            Vec3A::X,
            Vec3A::Z,
            Vec3A::NEG_Y,
            Vec2::new(mid.x + 1.0, 1.0),
        )
        .expect("left part");
        assert!(
            (left.solid_angle / r.solid_angle - 0.5).abs() < 1e-3,
            "left of u.x = ½ holds {} of Ω",
            left.solid_angle / r.solid_angle
        );
    }
}
