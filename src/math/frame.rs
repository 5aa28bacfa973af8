//! Orthonormal frame with its normal along +z: the local shading frame of
//! `materials/` (see the direction convention there).

use glam::Vec3A;

/// A right-handed orthonormal basis `(s, t, n)`: world ↔ local shading frame.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// First tangent: the local +x axis.
    pub s: Vec3A,
    /// Second tangent: the local +y axis, `n × s`.
    pub t: Vec3A,
    /// The normal: the local +z axis.
    pub n: Vec3A,
}

impl Frame {
    /// Builds a frame around a unit normal without branches on its direction.
    /// Duff et al., "Building an Orthonormal Basis, Revisited", JCGT 2017:
    /// <https://jcgt.org/published/0006/01/01/>
    pub fn from_normal(n: Vec3A) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3A::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3A::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// World-space vector `v` in this frame's coordinates (normal along +z).
    #[inline]
    pub fn to_local(&self, v: Vec3A) -> Vec3A {
        Vec3A::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    /// Local vector `v` back in world space; the inverse of [`Frame::to_local`].
    #[inline]
    pub fn to_world(&self, v: Vec3A) -> Vec3A {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_round_trips() {
        let mut rng = crate::math::Pcg32::new(7, 1);
        for _ in 0..1000 {
            let n = crate::math::sampling::uniform_sphere(rng.next_vec2());
            let f = Frame::from_normal(n);
            assert!((f.s.length() - 1.0).abs() < 1e-4, "|s| = {}", f.s.length());
            assert!((f.t.length() - 1.0).abs() < 1e-4);
            assert!(f.s.dot(f.t).abs() < 1e-4 && f.s.dot(n).abs() < 1e-4);
            assert!(f.s.cross(f.t).dot(n) > 0.999, "frame must be right-handed");
            let v = Vec3A::new(0.3, -0.2, 0.9);
            assert!((f.to_local(f.to_world(v)) - v).length() < 1e-4);
        }
    }
}
