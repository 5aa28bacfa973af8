//! A transform split into translate · rotate · stretch, the parts that
//! interpolate well on their own.

use glam::{Mat3, Mat4, Quat, Vec3};

/// `M = T · R · S`: a translation, a rotation (unit quaternion) and a
/// stretch (symmetric for a matrix without shear-then-rotate, a general
/// 3×3 otherwise), as pbrt-v4's `AnimatedTransform::Decompose`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trs {
    /// Where the origin goes.
    pub translation: Vec3,
    /// The rotation part, of unit length with `w ≥ 0`.
    pub rotation: Quat,
    /// What is left of the linear part once the rotation is taken out.
    pub stretch: Mat3,
}

impl Trs {
    /// Splits an affine `m` (its last row `(0, 0, 0, 1)`; the loader checks
    /// transforms are invertible). The rotation is the polar decomposition's
    /// orthogonal factor, by the iteration `R ← (R + R⁻ᵀ) / 2` (Higham),
    /// at most 100 steps; a mirroring matrix (det < 0) gives its mirror to
    /// the stretch so that the rotation stays a rotation.
    pub fn from_mat4(m: Mat4) -> Self {
        let translation = m.w_axis.truncate();
        let linear = Mat3::from_mat4(m);
        let mut r = linear;
        for _ in 0..100 {
            let next = (r + r.transpose().inverse()) * 0.5;
            // Largest change of any entry.
            let d = (next - r)
                .to_cols_array()
                .iter()
                .fold(0.0f32, |a, x| a.max(x.abs()));
            r = next;
            if d.is_nan() || d <= 1e-6 {
                break;
            }
        }
        if r.determinant() < 0.0 {
            r = -r;
        }
        let mut rotation = Quat::from_mat3(&r).normalize();
        if rotation.w < 0.0 {
            rotation = -rotation;
        }
        // S = R⁻¹ M, with R as the quaternion gives it back.
        let stretch = Mat3::from_quat(rotation).transpose() * linear;
        Self {
            translation,
            rotation,
            stretch,
        }
    }

    /// `T · R · S` as one matrix.
    pub fn to_mat4(&self) -> Mat4 {
        let linear = Mat3::from_quat(self.rotation) * self.stretch;
        Mat4::from_cols(
            linear.x_axis.extend(0.0),
            linear.y_axis.extend(0.0),
            linear.z_axis.extend(0.0),
            self.translation.extend(1.0),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Mat4, b: Mat4, tol: f32) -> bool {
        a.to_cols_array()
            .iter()
            .zip(b.to_cols_array())
            .all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn trs_puts_back_what_it_split() {
        let cases = [
            Mat4::IDENTITY,
            Mat4::from_scale_rotation_translation(
                Vec3::new(2.0, 0.5, 3.0),
                Quat::from_axis_angle(Vec3::new(1.0, 2.0, 3.0).normalize(), 2.5),
                Vec3::new(-4.0, 1.0, 7.0),
            ),
            Mat4::from_scale(Vec3::new(-1.0, 1.0, 1.0)),
            Mat4::from_rotation_y(3.1),
        ];
        for m in cases {
            let trs = Trs::from_mat4(m);
            assert!((trs.rotation.length() - 1.0).abs() < 1e-6);
            assert!(
                close(trs.to_mat4(), m, 1e-5),
                "{m} came back as {}",
                trs.to_mat4()
            );
        }
        // A rotation alone leaves no stretch.
        let r = Trs::from_mat4(Mat4::from_rotation_z(1.0));
        assert!(
            (r.stretch - Mat3::IDENTITY).abs_diff_eq(Mat3::ZERO, 1e-5),
            "{}",
            r.stretch
        );
    }
}
