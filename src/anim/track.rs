//! Keys in time order, and where a time falls among them.

use glam::Vec3;

/// Most keys one track may hold: a scene file is read whole, and a track
/// of millions of keys is a mistake, not an animation (24 fps for seven
/// minutes is 10,000).
pub const MAX_KEYS: usize = 10_000;

/// How values between two keys are made (the scene's `interpolation`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// Straight from one key to the next at constant speed (rotations at
    /// constant angular speed, by slerp).
    #[default]
    Linear,
    /// A Catmull-Rom spline through the keys: positions and scales keep
    /// their velocity across a key. Rotations still slerp (constant
    /// angular speed within each segment).
    Smooth,
}

/// Where a time falls among a track's keys.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Place {
    /// On key `i` (or before the first, or after the last): its value,
    /// exactly.
    At(usize),
    /// Between keys `i` and `i + 1`, a fraction `u` ∈ (0, 1) of the way.
    Between(usize, f32),
}

/// Keys `(time, value)` sorted by strictly increasing time, at least one
/// (the loader checks the order and the count).
#[derive(Clone, Debug, PartialEq)]
pub struct Track<T> {
    /// The keys, in time order.
    pub keys: Vec<(f32, T)>,
    /// How values between keys are made.
    pub interpolation: Interpolation,
}

impl<T: Copy> Track<T> {
    /// Where `time` falls: clamped to the first and last keys, so a track
    /// holds still outside its keys.
    pub fn place(&self, time: f32) -> Place {
        let n = self.keys.len();
        debug_assert!(n > 0);
        // First key whose time is above `time`.
        let above = self.keys.partition_point(|(k, _)| *k <= time);
        if above == 0 {
            return Place::At(0);
        }
        let i = above - 1;
        if i + 1 >= n || self.keys[i].0 == time {
            return Place::At(i);
        }
        let (t0, t1) = (self.keys[i].0, self.keys[i + 1].0);
        let u = (time - t0) / (t1 - t0);
        if u > 0.0 && u < 1.0 {
            Place::Between(i, u)
        } else {
            Place::At(if u >= 1.0 { i + 1 } else { i })
        }
    }

    /// Whether the value changes between `t0` and `t1` (`t0 < t1`).
    pub fn moves_between(&self, t0: f32, t1: f32) -> bool {
        let (a, b) = (self.place(t0), self.place(t1));
        t0 < t1 && (a != b || matches!(a, Place::Between(..)))
    }

    /// The value of key `i`.
    pub fn value(&self, i: usize) -> T {
        self.keys[i].1
    }
}

impl Track<Vec3> {
    /// The value at `time`.
    pub fn at(&self, time: f32) -> Vec3 {
        match self.place(time) {
            Place::At(i) => self.value(i),
            Place::Between(i, u) => between(&self.keys, self.interpolation, i, u, |v| v),
        }
    }
}

/// The value a fraction `u` of the way from key `i` to key `i + 1` of the
/// part `part` of each key's value (a transform's translation, its
/// stretch): linear, or a Catmull-Rom
/// (cubic Hermite) segment whose tangent at a key is the slope between its
/// neighbours, `(p[i+1] − p[i−1]) / (t[i+1] − t[i−1])`, one-sided at the
/// ends — the non-uniform form, so unevenly spaced keys do not overshoot
/// in time.
pub fn between<T: Copy, V>(
    keys: &[(f32, T)],
    how: Interpolation,
    i: usize,
    u: f32,
    part: impl Fn(T) -> V,
) -> V
where
    V: Copy + std::ops::Add<Output = V> + std::ops::Sub<Output = V> + std::ops::Mul<f32, Output = V>,
{
    let (t1, p1) = (keys[i].0, part(keys[i].1));
    let (t2, p2) = (keys[i + 1].0, part(keys[i + 1].1));
    match how {
        Interpolation::Linear => p1 * (1.0 - u) + p2 * u,
        Interpolation::Smooth => {
            // Slopes (value per frame) at both ends of the segment.
            let slope = |a: usize, b: usize| {
                let (ta, pa) = (keys[a].0, part(keys[a].1));
                let (tb, pb) = (keys[b].0, part(keys[b].1));
                (pb - pa) * (1.0 / (tb - ta))
            };
            let m1 = slope(i.saturating_sub(1), i + 1);
            let m2 = slope(i, (i + 2).min(keys.len() - 1));
            let dt = t2 - t1;
            // Cubic Hermite basis.
            let (u2, u3) = (u * u, u * u * u);
            let h00 = 2.0 * u3 - 3.0 * u2 + 1.0;
            let h10 = u3 - 2.0 * u2 + u;
            let h01 = -2.0 * u3 + 3.0 * u2;
            let h11 = u3 - u2;
            p1 * h00 + m1 * (h10 * dt) + p2 * h01 + m2 * (h11 * dt)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn track(how: Interpolation) -> Track<Vec3> {
        Track {
            keys: vec![
                (0.0, Vec3::ZERO),
                (10.0, Vec3::new(10.0, 0.0, 0.0)),
                (30.0, Vec3::new(30.0, 5.0, 0.0)),
            ],
            interpolation: how,
        }
    }

    #[test]
    fn track_holds_still_outside_its_keys_and_passes_through_them() {
        for how in [Interpolation::Linear, Interpolation::Smooth] {
            let t = track(how);
            assert_eq!(t.at(-5.0), Vec3::ZERO);
            assert_eq!(t.at(99.0), Vec3::new(30.0, 5.0, 0.0));
            for (k, v) in &t.keys {
                assert_eq!(t.at(*k), *v, "{how:?} at key {k}");
            }
        }
        assert_eq!(track(Interpolation::Linear).place(5.0), Place::Between(0, 0.5));
    }

    #[test]
    fn smooth_track_keeps_its_velocity_across_a_key() {
        let t = track(Interpolation::Smooth);
        let h = 1e-2;
        let before = (t.at(10.0) - t.at(10.0 - h)) / h;
        let after = (t.at(10.0 + h) - t.at(10.0)) / h;
        assert!((before - after).length() < 0.02, "velocity {before} then {after}");
        let lin = track(Interpolation::Linear);
        let jump = (lin.at(10.0 + h) - lin.at(10.0)) / h - (lin.at(10.0) - lin.at(10.0 - h)) / h;
        assert!(jump.length() > 0.2, "linear keys do turn at a key: {jump}");
    }
}
