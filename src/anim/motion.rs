//! A keyed transform: its matrix at any time, and the box it sweeps.

use super::track::{Interpolation, Place, Track, between};
use super::trs::Trs;
use glam::{Mat4, Vec3};

/// One key of a [`TransformTrack`]: the matrix as the scene wrote it, and
/// its parts for interpolation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TransformKey {
    /// The key's own matrix, returned unchanged at the key's time.
    pub matrix: Mat4,
    /// Its translate · rotate · stretch split.
    pub trs: Trs,
}

/// Samples per key segment when bounding a motion (see
/// [`TransformTrack::bounds`]).
const BOUND_STEPS: usize = 32;

/// A transform given by keys: a moving object's `world_from_object`.
#[derive(Clone, Debug, PartialEq)]
pub struct TransformTrack {
    track: Track<TransformKey>,
}

impl TransformTrack {
    /// The track of `keys` (time in frames, matrix), sorted by strictly
    /// increasing time and not empty (the loader checks both).
    pub fn new(keys: &[(f32, Mat4)], interpolation: Interpolation) -> Self {
        let mut keys: Vec<(f32, TransformKey)> = keys
            .iter()
            .map(|&(t, matrix)| {
                let trs = Trs::from_mat4(matrix);
                (t, TransformKey { matrix, trs })
            })
            .collect();
        // Shortest arcs: each key's quaternion on the side of the previous one.
        for i in 1..keys.len() {
            let prev = keys[i - 1].1.trs.rotation;
            let q = &mut keys[i].1.trs.rotation;
            if prev.dot(*q) < 0.0 {
                *q = -*q;
            }
        }
        Self {
            track: Track { keys, interpolation },
        }
    }

    /// Whether the transform changes between `t0` and `t1`.
    pub fn moves_between(&self, t0: f32, t1: f32) -> bool {
        self.track.moves_between(t0, t1)
    }

    /// The matrix at `time` (frames): a key's own matrix on the key, and
    /// outside the keys the nearest one's; between keys translation and
    /// stretch interpolated (linear or Catmull-Rom) and the rotation by
    /// slerp along the shortest arc.
    pub fn at(&self, time: f32) -> Mat4 {
        match self.track.place(time) {
            Place::At(i) => self.track.value(i).matrix,
            Place::Between(i, u) => {
                let keys = &self.track.keys;
                let how = self.track.interpolation;
                let translation = between(keys, how, i, u, |k| k.trs.translation);
                let stretch = between(keys, how, i, u, |k| k.trs.stretch);
                let (a, b) = (keys[i].1.trs.rotation, keys[i + 1].1.trs.rotation);
                Trs {
                    translation,
                    rotation: a.slerp(b, u).normalize(),
                    stretch,
                }
                .to_mat4()
            }
        }
    }

    /// A box holding the box `[lo, hi]` (object space) moved by the track
    /// at every time in `[t0, t1]`: the corners at the interval's ends, at
    /// every key inside and at [`BOUND_STEPS`] times per key segment, and
    /// the union grown by the largest step any corner takes between two of
    /// those times. Between two samples a corner moves along an arc of at
    /// most 180°/32 (a segment's shortest arc) or a cubic, which stays within
    /// its chord's length of both ends; pbrt-v4 solves for the extrema of
    /// each coordinate instead, which is tighter and much longer to write.
    pub fn bounds(&self, lo: Vec3, hi: Vec3, t0: f32, t1: f32) -> (Vec3, Vec3) {
        let corners: [Vec3; 8] = std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        });
        let mut times = vec![t0];
        let keys = &self.track.keys;
        for w in keys.windows(2) {
            let (a, b) = (w[0].0.max(t0), w[1].0.min(t1));
            if a < b {
                times.extend((0..=BOUND_STEPS).map(|s| a + (b - a) * s as f32 / BOUND_STEPS as f32));
            }
        }
        times.push(t1);
        let (mut min, mut max) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
        let mut step = 0.0f32;
        let mut last: Option<[Vec3; 8]> = None;
        for t in times {
            let m = self.at(t);
            let now = corners.map(|c| m.transform_point3(c));
            for (i, p) in now.iter().enumerate() {
                min = min.min(*p);
                max = max.max(*p);
                if let Some(l) = &last {
                    step = step.max(p.distance(l[i]));
                }
            }
            last = Some(now);
        }
        (min - Vec3::splat(step), max + Vec3::splat(step))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Quat;

    fn turn() -> TransformTrack {
        let a = Mat4::from_scale_rotation_translation(Vec3::splat(2.0), Quat::IDENTITY, Vec3::ZERO);
        let b = Mat4::from_scale_rotation_translation(
            Vec3::splat(2.0),
            Quat::from_rotation_y(150f32.to_radians()),
            Vec3::new(4.0, 0.0, 0.0),
        );
        TransformTrack::new(&[(0.0, a), (10.0, b)], Interpolation::Linear)
    }

    #[test]
    fn motion_keys_at_the_ends_give_the_static_matrices_exactly() {
        let m = Mat4::from_rotation_x(0.3) * Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0));
        let n = Mat4::from_scale(Vec3::new(1.0, 3.0, 1.0));
        let t = TransformTrack::new(&[(2.0, m), (5.0, n)], Interpolation::Smooth);
        assert_eq!(t.at(2.0), m);
        assert_eq!(t.at(-7.0), m);
        assert_eq!(t.at(5.0), n);
        assert_eq!(t.at(1e9), n);
        assert!(!t.moves_between(-3.0, 2.0) && t.moves_between(2.0, 2.5) && !t.moves_between(3.0, 3.0));
    }

    #[test]
    fn motion_rotation_keeps_unit_length_and_constant_angular_speed() {
        let t = turn();
        let mut angles = Vec::new();
        for s in 0..=20 {
            let trs = Trs::from_mat4(t.at(s as f32 * 0.5));
            assert!(
                (trs.rotation.length() - 1.0).abs() < 1e-5,
                "|q| = {}",
                trs.rotation.length()
            );
            // Scale stays 2 all along: no shrinking through the turn.
            assert!((t.at(s as f32 * 0.5).transform_vector3(Vec3::X).length() - 2.0).abs() < 1e-4);
            angles.push(trs.rotation.angle_between(Quat::IDENTITY));
        }
        for w in angles.windows(2) {
            let step = w[1] - w[0];
            assert!(
                (step - 7.5f32.to_radians()).abs() < 1e-3,
                "angular step {step} rad, expected 7.5°"
            );
        }
    }

    #[test]
    fn motion_takes_the_shortest_arc() {
        // +170° then −170° (= +190°): the short way is 20° through 180°.
        let a = Mat4::from_rotation_y(170f32.to_radians());
        let b = Mat4::from_rotation_y(-170f32.to_radians());
        let t = TransformTrack::new(&[(0.0, a), (1.0, b)], Interpolation::Linear);
        let mid = t.at(0.5).transform_vector3(Vec3::X);
        // Rotated by 180° about y, x goes to −x.
        assert!((mid - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-4, "{mid}");
    }

    #[test]
    fn motion_bounds_hold_every_corner_at_every_time() {
        let t = turn();
        let (lo, hi) = (Vec3::splat(-1.0), Vec3::new(1.0, 2.0, 0.5));
        let (min, max) = t.bounds(lo, hi, 1.0, 9.0);
        for s in 0..=800 {
            let m = t.at(1.0 + s as f32 * 0.01);
            for i in 0..8 {
                let c = Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                );
                let p = m.transform_point3(c);
                assert!(
                    p.cmpge(min).all() && p.cmple(max).all(),
                    "{p} outside {min}..{max}"
                );
            }
        }
    }
}
