//! A half-line `o + t d`, `t` in `[0, t_max)`.

use glam::Vec3A;

#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub o: Vec3A,
    /// Not required to be normalised by the intersectors, but every ray the
    /// renderer spawns is, so `t` is a distance.
    pub d: Vec3A,
}

impl Ray {
    #[inline]
    pub fn new(o: Vec3A, d: Vec3A) -> Self {
        Self { o, d }
    }

    #[inline]
    pub fn at(&self, t: f32) -> Vec3A {
        self.o + self.d * t
    }
}
