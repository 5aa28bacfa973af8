//! Time: the checks of `animation`, the camera's `shutter` and `keys` and
//! the `keys` of instances, and the keyed values a frame is built with.
//!
//! A frame is built at its shutter's opening, `frame + shutter.0`: keyed
//! things are placed there. What moves between opening and closing is
//! handed to the renderer with its keys (`view::Shutter`,
//! `geometry::moving`), and each camera sample draws its time.

use super::transform::compose;
use super::validate::Checker;
use crate::anim::{Interpolation, MAX_KEYS, Track, TransformTrack};
use crate::camera::motion::CameraMotion;
use crate::desc::{CameraDesc, InterpolationDesc, ObjectDesc, SceneDesc, TransformKeyDesc};
use glam::Vec3;

/// Largest magnitude of a frame number, and of a key's time (twice it):
/// frames are counted, and 2²⁴ is where an `f32` time stops telling
/// frames apart.
pub const MAX_FRAME: i32 = 1_000_000;

impl Checker {
    /// The `animation` section, the camera's time fields, and every
    /// instance's `keys`.
    pub(super) fn animation(&mut self, scene: &SceneDesc) {
        if let Some(a) = &scene.animation {
            let (first, last) = a.frames;
            if first.abs() > MAX_FRAME || last.abs() > MAX_FRAME || first > last {
                self.push(
                    "animation.frames",
                    format!("frames ({first}, {last}) are not a range within ±{MAX_FRAME}"),
                    "give the first and the last frame, first ≤ last, e.g. `frames: (1, 48)`",
                );
            } else if let Some(f) = a.frame.filter(|f| !(first..=last).contains(f)) {
                self.push(
                    "animation.frame",
                    format!("frame {f} is outside the scene's frames {first}..={last}"),
                    format!("choose a frame from {first} to {last}, or widen `animation.frames`"),
                );
            }
            if !(a.fps > 0.0 && a.fps <= 1000.0) {
                self.push(
                    "animation.fps",
                    format!("{} frames per second is outside (0, 1000]", a.fps),
                    "films run at 24, video at 25, 30 or 60",
                );
            }
        }
        self.camera_time(&scene.camera);
        for (i, o) in scene.objects.iter().enumerate() {
            if let ObjectDesc::Instance { keys, transform, .. } = o
                && !keys.is_empty()
            {
                let path = format!("objects[{i}]");
                if !transform.is_empty() {
                    self.push(
                        &format!("{path}.transform"),
                        "an instance with `keys` takes its placement from them, not from `transform`",
                        "move the steps into each key's `transform`",
                    );
                }
                self.key_times(&format!("{path}.keys"), keys.iter().map(|k| k.frame));
                for (k, key) in keys.iter().enumerate() {
                    self.steps(&format!("{path}.keys[{k}].transform"), &key.transform);
                }
                self.mirror_flips(&path, keys);
            }
        }
    }

    /// Keys of which one mirrors and the next does not (their determinants
    /// differ in sign): the stretch interpolated between them passes
    /// through zero, where the instance is flat, cannot be inverted to
    /// trace rays, and as an emitter has no area to sample.
    fn mirror_flips(&mut self, path: &str, keys: &[TransformKeyDesc]) {
        let sign = |k: &TransformKeyDesc| {
            let d = compose(&k.transform).determinant();
            (d.is_finite() && d != 0.0).then_some(d > 0.0)
        };
        for (k, w) in keys.windows(2).enumerate() {
            if let (Some(a), Some(b)) = (sign(&w[0]), sign(&w[1]))
                && a != b
            {
                self.push(
                    &format!("{path}.keys[{}].transform", k + 1),
                    format!(
                        "key {} {} and key {k} {}: between them the instance turns inside out through a flat placement",
                        k + 1,
                        if b { "does not mirror" } else { "mirrors" },
                        if a { "does not" } else { "does" },
                    ),
                    "give every key the same handedness (an even or an odd number of negative scale factors)",
                );
            }
        }
    }

    /// The camera's `shutter` and `keys`.
    fn camera_time(&mut self, c: &CameraDesc) {
        if let Some((open, close)) = c.shutter
            && !(open.is_finite() && close.is_finite() && -1.0 <= open && open <= close && close <= 1.0)
        {
            self.push(
                "camera.shutter",
                format!("shutter ({open}, {close}) is not an interval within [−1, 1]"),
                "give when it opens and closes in frames from the frame's start, e.g. (0, 0.5)",
            );
        }
        self.key_times("camera.keys", c.keys.iter().map(|k| k.frame));
        for (k, key) in c.keys.iter().enumerate() {
            let at = format!("camera.keys[{k}]");
            let ok = self.finite(&format!("{at}.eye"), &key.eye)
                & self.finite(&format!("{at}.target"), &key.target);
            let up = key.up.unwrap_or(c.up);
            if let Some(u) = key.up {
                self.nonzero(&format!("{at}.up"), &u, "`up`");
            }
            let view = Vec3::from(key.target) - Vec3::from(key.eye);
            if ok
                && (view.length_squared() == 0.0
                    || view.normalize().cross(Vec3::from(up).normalize()).length() < 1e-4)
            {
                self.push(
                    &at,
                    "`target` equals `eye`, or `up` is parallel to the view",
                    "move `target` away from `eye` and keep `up` off the view direction",
                );
            }
        }
    }

    /// Key times at `path`: finite, within ±2·[`MAX_FRAME`], strictly
    /// increasing, at most [`MAX_KEYS`].
    fn key_times(&mut self, path: &str, times: impl Iterator<Item = f32>) {
        let mut last: Option<f32> = None;
        for (k, t) in times.enumerate() {
            if k == MAX_KEYS {
                self.push(
                    path,
                    format!("more than {MAX_KEYS} keys"),
                    "keep a key where the motion changes, not one per frame",
                );
                return;
            }
            let at = format!("{path}[{k}].frame");
            if !(t.is_finite() && t.abs() <= 2.0 * MAX_FRAME as f32) {
                self.push(
                    &at,
                    format!("key time {t} is not a frame within ±{}", 2 * MAX_FRAME),
                    "write the key's time in frames",
                );
                return;
            }
            if let Some(l) = last.filter(|l| t <= *l) {
                self.push(
                    &at,
                    format!("keys out of order: frame {t} comes after frame {l}"),
                    "list keys in increasing time, each time once",
                );
                return;
            }
            last = Some(t);
        }
    }
}

/// The interval a frame's camera samples are drawn in, in frames.
pub(super) fn shutter(desc: &SceneDesc) -> (f32, f32) {
    let (open, close) = desc.camera.shutter.unwrap_or((0.0, 0.0));
    let f = desc.frame() as f32;
    (f + open, f + close)
}

fn interpolation(i: InterpolationDesc) -> Interpolation {
    match i {
        InterpolationDesc::Linear => Interpolation::Linear,
        InterpolationDesc::Smooth => Interpolation::Smooth,
    }
}

/// The keys of an instance as a track, if it has any.
pub(super) fn instance_track(o: &ObjectDesc) -> Option<TransformTrack> {
    let ObjectDesc::Instance {
        keys,
        interpolation: how,
        ..
    } = o
    else {
        return None;
    };
    if keys.is_empty() {
        return None;
    }
    let keys: Vec<_> = keys
        .iter()
        .map(|TransformKeyDesc { frame, transform }| (*frame, compose(transform)))
        .collect();
    Some(TransformTrack::new(&keys, interpolation(*how)))
}

/// The camera's keys as tracks, if it has any; `base` is the camera built
/// at the shutter's opening.
pub(super) fn camera_motion(c: &CameraDesc, base: crate::camera::Camera) -> Option<CameraMotion> {
    if c.keys.is_empty() {
        return None;
    }
    let how = interpolation(c.interpolation);
    let track = |f: &dyn Fn(&crate::desc::CameraKeyDesc) -> [f32; 3]| Track {
        keys: c.keys.iter().map(|k| (k.frame, Vec3::from(f(k)))).collect(),
        interpolation: how,
    };
    Some(CameraMotion {
        eye: track(&|k| k.eye),
        target: track(&|k| k.target),
        up: track(&|k| k.up.unwrap_or(c.up)),
        base,
        focus_distance: c.focus_distance,
    })
}

/// The camera as the scene describes it at `time`: its keyed `eye`,
/// `target` and `up` put in place.
pub(super) fn camera_at(c: &CameraDesc, time: f32) -> CameraDesc {
    let Some(m) = camera_motion(c, still()) else {
        return c.clone();
    };
    CameraDesc {
        eye: Some(m.eye.at(time).to_array()),
        target: Some(m.target.at(time).to_array()),
        up: m.up.at(time).to_array(),
        ..c.clone()
    }
}

/// A stand-in base camera, for questions about keys alone.
fn still() -> crate::camera::Camera {
    crate::camera::Camera::look_at(Vec3::ZERO.into(), Vec3::Z.into(), Vec3::Y.into(), 40.0)
}

/// Whether the camera's keys move it between `open` and `close`.
pub(super) fn camera_moves(m: &CameraMotion, open: f32, close: f32) -> bool {
    [&m.eye, &m.target, &m.up]
        .iter()
        .any(|t| t.moves_between(open, close))
}

/// Whether anything moves while the shutter is open.
pub(super) fn moves(desc: &SceneDesc) -> bool {
    let (open, close) = shutter(desc);
    camera_motion(&desc.camera, still()).is_some_and(|m| camera_moves(&m, open, close))
        || desc
            .objects
            .iter()
            .filter_map(instance_track)
            .any(|t| t.moves_between(open, close))
}
