//! A half-line `o + t d`, `t` in `[0, t_max)`.

use glam::Vec3A;

/// A ray: origin and direction, in whatever space it is traced (world space for the
/// scene, object space inside an instance).
#[derive(Clone, Copy, Debug)]
pub struct Ray {
    /// Origin.
    pub o: Vec3A,
    /// Not required to be normalised by the intersectors, but every ray the
    /// renderer spawns is, so `t` is a distance.
    pub d: Vec3A,
}

impl Ray {
    /// The ray from `o` along `d`; `d` is taken as given, not normalised.
    #[inline]
    pub fn new(o: Vec3A, d: Vec3A) -> Self {
        Self { o, d }
    }

    /// The point at parameter `t`, `o + t·d`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.o + self.d * t
    }
}
