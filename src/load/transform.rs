//! Transforms as a scene file writes them (a list of steps) made into
//! matrices, for objects, meshes, instances and SDFs alike.

use crate::desc::TransformDesc;
use glam::{Mat4, Vec3};

/// A 4×4 matrix written as rows.
pub fn matrix(rows: &[[f32; 4]; 4]) -> Mat4 {
    Mat4::from_cols_array_2d(rows).transpose()
}

/// The steps in written order: the first is applied to the object first.
pub fn compose(steps: &[TransformDesc]) -> Mat4 {
    steps.iter().fold(Mat4::IDENTITY, |acc, t| {
        let step = match t {
            TransformDesc::Translate(v) => Mat4::from_translation(Vec3::from(*v)),
            TransformDesc::Rotate { axis, degrees } => {
                Mat4::from_axis_angle(Vec3::from(*axis).normalize(), degrees.to_radians())
            }
            TransformDesc::Scale(s) => Mat4::from_scale(Vec3::from(*s)),
            TransformDesc::Matrix(m) => matrix(m),
        };
        step * acc
    })
}

/// Rotation, uniform scale and translation only (keeps spheres spheres).
pub fn is_similarity(m: &Mat4) -> bool {
    let (x, y, z) = (
        m.transform_vector3(Vec3::X),
        m.transform_vector3(Vec3::Y),
        m.transform_vector3(Vec3::Z),
    );
    let s = x.length();
    let tol = 1e-4 * s.max(1e-12);
    (y.length() - s).abs() < tol
        && (z.length() - s).abs() < tol
        && x.dot(y).abs() < tol * s
        && y.dot(z).abs() < tol * s
        && x.dot(z).abs() < tol * s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compose_applies_steps_in_written_order() {
        let m = compose(&[
            TransformDesc::Scale([2.0, 2.0, 2.0]),
            TransformDesc::Translate([1.0, 0.0, 0.0]),
        ]);
        // scale first, then translate: (1,0,0) → (2,0,0) → (3,0,0)
        assert!((m.transform_point3(Vec3::X) - Vec3::new(3.0, 0.0, 0.0)).length() < 1e-6);
        let r = compose(&[TransformDesc::Rotate {
            axis: [0.0, 1.0, 0.0],
            degrees: 90.0,
        }]);
        assert!(
            (r.transform_vector3(Vec3::X) - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6,
            "right-handed about y"
        );
        assert!(is_similarity(&r) && !is_similarity(&compose(&[TransformDesc::Scale([1.0, 2.0, 1.0])])));
    }
}
