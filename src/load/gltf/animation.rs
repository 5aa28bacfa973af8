//! A glTF animation sampled at one time: each node's local transform and
//! morph-target weights with the animation's channels applied (glTF 2.0
//! §3.11). `nodes.rs` composes the transforms down the tree, `primitive.rs`
//! blends the morph targets and `skin.rs` moves skinned vertices by the
//! posed joints, so the loader builds the asset as it stands at the frame
//! drawn.
//!
//! Interpolation as the specification says: `STEP` holds a key's value,
//! `LINEAR` blends translations and scales and turns rotations along the
//! shortest arc (slerp), `CUBICSPLINE` is the Hermite spline through the
//! keys with their in- and out-tangents scaled by the interval. Before the
//! first key and after the last a channel holds its end value; with
//! `repeat` the time wraps at the animation's length first.
//!
//! The asset is posed once per frame, at the shutter's opening: a skinned
//! or animated part is not motion-blurred (a note says so when the
//! shutter is open).

use super::accessor::{Buffers, read_f32};
use glam::{Mat4, Quat, Vec3};
use gltf::Document;
use gltf::accessor::{DataType, Dimensions};
use gltf::animation::{Interpolation, Property};

/// The animation `name` names: its name in the asset, or `#k` for the
/// k-th. The error lists what the asset has.
pub fn find(doc: &Document, name: &str) -> Result<usize, String> {
    let count = doc.animations().count();
    if let Some(k) = name.strip_prefix('#').and_then(|k| k.parse::<usize>().ok())
        && k < count
    {
        return Ok(k);
    }
    if let Some(a) = doc.animations().find(|a| a.name() == Some(name)) {
        return Ok(a.index());
    }
    Err(if count == 0 {
        format!("the asset has no animation; there is no `{name}`")
    } else {
        format!("the asset has no animation `{name}`; it has {}", names(doc))
    })
}

/// The asset's animations as the scene may name them: `"Walk"`, or `"#2"`
/// for one without a name.
pub fn names(doc: &Document) -> String {
    doc.animations()
        .map(|a| match a.name() {
            Some(n) => format!("\"{n}\""),
            None => format!("\"#{}\"", a.index()),
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The asset posed at one time.
pub struct Posed {
    /// Every node's local transform (document order).
    pub locals: Vec<Mat4>,
    /// Every node's morph-target weights, where the node or the animation
    /// sets them (`None`: its mesh's own `weights`, else none).
    pub weights: Vec<Option<Vec<f32>>>,
}

/// What a channel sets on its node.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Target {
    Translation,
    Rotation,
    Scale,
    /// One weight per morph target of the node's mesh.
    Weights,
}

/// One channel, its accessors read and checked once.
struct Channel {
    node: usize,
    target: Target,
    interpolation: Interpolation,
    times: Vec<f32>,
    /// `width` numbers per key (three times as many for `CUBICSPLINE`).
    values: Vec<f32>,
    width: usize,
    /// Where it is in the asset, for errors found when it is sampled.
    at: String,
}

/// An animation read from the asset: sampled at as many times as a frame
/// and its shutter need, its accessors read once.
pub struct Animation {
    channels: Vec<Channel>,
    /// Its last key time over all channels: where `repeat` wraps.
    length: f32,
}

impl Animation {
    /// Reads animation `k`: every channel's key times and values, checked.
    /// Channels animating morph weights of a node without morph targets
    /// are skipped.
    pub fn read(doc: &Document, buffers: &Buffers, k: usize) -> Result<Self, String> {
        let anim = doc
            .animations()
            .nth(k)
            .ok_or_else(|| format!("animations[{k}] does not exist"))?;
        // Rotations and weights may be normalised integers.
        let quantised = [
            DataType::F32,
            DataType::I8,
            DataType::U8,
            DataType::I16,
            DataType::U16,
        ];
        let mut channels = Vec::new();
        for c in anim.channels() {
            let at = format!("animations[{k}].channels[{}]", c.index());
            let err = |e: String| format!("{at}: {e}");
            let s = c.sampler();
            let times: Vec<[f32; 1]> = read_f32(
                doc,
                buffers,
                s.input().index(),
                Dimensions::Scalar,
                &[DataType::F32],
                "animation input",
            )
            .map_err(err)?;
            let times: Vec<f32> = times.into_iter().map(|[t]| t).collect();
            check_times(&times).map_err(err)?;
            let node = c.target().node();
            let output = s.output().index();
            let (target, values, width) = match c.target().property() {
                Property::Translation | Property::Scale => {
                    let v: Vec<[f32; 3]> = read_f32(
                        doc,
                        buffers,
                        output,
                        Dimensions::Vec3,
                        &[DataType::F32],
                        "animation output",
                    )
                    .map_err(err)?;
                    let target = if c.target().property() == Property::Translation {
                        Target::Translation
                    } else {
                        Target::Scale
                    };
                    (target, v.as_flattened().to_vec(), 3)
                }
                Property::Rotation => {
                    let v: Vec<[f32; 4]> = read_f32(
                        doc,
                        buffers,
                        output,
                        Dimensions::Vec4,
                        &quantised,
                        "animation output",
                    )
                    .map_err(err)?;
                    (Target::Rotation, v.as_flattened().to_vec(), 4)
                }
                Property::MorphTargetWeights => {
                    let targets = node
                        .mesh()
                        .and_then(|m| m.primitives().next())
                        .map_or(0, |p| p.morph_targets().count());
                    if targets == 0 {
                        continue;
                    }
                    let v: Vec<[f32; 1]> = read_f32(
                        doc,
                        buffers,
                        output,
                        Dimensions::Scalar,
                        &quantised,
                        "animation output",
                    )
                    .map_err(err)?;
                    (Target::Weights, v.as_flattened().to_vec(), targets)
                }
            };
            channels.push(Channel {
                node: node.index(),
                target,
                interpolation: s.interpolation(),
                times,
                values,
                width,
                at,
            });
        }
        let length = channels
            .iter()
            .filter_map(|c| c.times.last().copied())
            .fold(0.0f32, f32::max);
        Ok(Self { channels, length })
    }
}

/// Every node's local transform and morph weights (document order): the
/// node's own, with the channels of `animation` at `time` seconds applied
/// (wrapped at the animation's length when `repeat`).
pub fn pose(doc: &Document, animation: Option<&Animation>, time: f32, repeat: bool) -> Result<Posed, String> {
    let mut trs: Vec<(Vec3, Quat, Vec3)> = doc
        .nodes()
        .map(|n| {
            let (t, r, s) = n.transform().decomposed();
            (Vec3::from(t), Quat::from_array(r), Vec3::from(s))
        })
        .collect();
    let mut posed = Posed {
        locals: doc
            .nodes()
            .map(|n| Mat4::from_cols_array_2d(&n.transform().matrix()))
            .collect(),
        weights: doc.nodes().map(|n| n.weights().map(<[f32]>::to_vec)).collect(),
    };
    let Some(anim) = animation else {
        return Ok(posed);
    };
    let t = if repeat && anim.length > 0.0 {
        time.rem_euclid(anim.length)
    } else {
        time
    };
    let mut animated = vec![false; trs.len()];
    for c in &anim.channels {
        let err = |e: String| format!("{}: {e}", c.at);
        let Some(slot) = trs.get_mut(c.node) else {
            return Err(err(format!("targets node {}, which does not exist", c.node)));
        };
        let v = sample(
            &c.times,
            &c.values,
            c.width,
            c.interpolation,
            t,
            c.target == Target::Rotation,
        )
        .map_err(err)?;
        match c.target {
            Target::Translation | Target::Scale => {
                let x = Vec3::from_slice(&v);
                if !x.is_finite() {
                    return Err(err("a value is not finite".into()));
                }
                if c.target == Target::Translation {
                    slot.0 = x;
                } else {
                    slot.2 = x;
                }
                animated[c.node] = true;
            }
            Target::Rotation => {
                let q = Quat::from_slice(&v);
                slot.1 = if q.is_finite() && q.length_squared() > 0.0 {
                    q.normalize()
                } else {
                    Quat::IDENTITY
                };
                animated[c.node] = true;
            }
            Target::Weights => {
                if !v.iter().all(|x| x.is_finite()) {
                    return Err(err("a weight is not finite".into()));
                }
                posed.weights[c.node] = Some(v);
            }
        }
    }
    for (i, (t, r, s)) in trs.into_iter().enumerate() {
        if animated[i] {
            posed.locals[i] = Mat4::from_scale_rotation_translation(s, r, t);
        }
    }
    Ok(posed)
}

/// Key times: at least one, every one a number, none before the one
/// before it.
fn check_times(times: &[f32]) -> Result<(), String> {
    if times.is_empty() {
        return Err("the sampler has no keys".into());
    }
    if let Some(k) = times.iter().position(|t| !t.is_finite()) {
        return Err(format!("key time {k} is not a number"));
    }
    if let Some(k) = times.windows(2).position(|w| w[1] < w[0]) {
        return Err(format!(
            "key times must increase: {} follows {}",
            times[k + 1],
            times[k]
        ));
    }
    Ok(())
}

/// The sampler's value at `t`, `width` numbers: `values` holds one element
/// of `width` numbers per key, or for `CUBICSPLINE` three (in-tangent,
/// value, out-tangent). `quat`: the elements are rotations (width 4),
/// turned by slerp under `LINEAR`.
pub fn sample(
    times: &[f32],
    values: &[f32],
    width: usize,
    interpolation: Interpolation,
    t: f32,
    quat: bool,
) -> Result<Vec<f32>, String> {
    let cubic = interpolation == Interpolation::CubicSpline;
    let per = if cubic { 3 } else { 1 };
    let expected = times.len() * per * width;
    if width == 0 || values.len() != expected {
        return Err(format!(
            "{} output values for {} keys (expected {expected})",
            values.len() / width.max(1),
            times.len(),
        ));
    }
    let element = |i: usize| &values[i * width..(i + 1) * width];
    let value = |k: usize| element(k * per + usize::from(cubic)).to_vec();
    let last = times.len() - 1;
    // The interval [times[k], times[k + 1]) holding t; the ends hold.
    let next = times.partition_point(|&x| x <= t);
    if next == 0 {
        return Ok(value(0));
    }
    if next > last {
        return Ok(value(last));
    }
    let k = next - 1;
    let dt = times[k + 1] - times[k];
    if dt <= 0.0 {
        return Ok(value(k + 1));
    }
    let s = (t - times[k]) / dt;
    Ok(match interpolation {
        Interpolation::Step => value(k),
        Interpolation::Linear if quat && width == 4 => {
            let (a, b) = (Quat::from_slice(element(k)), Quat::from_slice(element(k + 1)));
            a.slerp(b, s).to_array().to_vec()
        }
        Interpolation::Linear => {
            let (a, b) = (element(k), element(k + 1));
            a.iter().zip(b).map(|(a, b)| a + (b - a) * s).collect()
        }
        Interpolation::CubicSpline => {
            // glTF 2.0 Appendix C: p(s) = (2s³ − 3s² + 1)·v_k + (s³ − 2s² + s)·Δt·b_k
            //                            + (−2s³ + 3s²)·v_k+1 + (s³ − s²)·Δt·a_k+1.
            let (v0, b0) = (element(3 * k + 1), element(3 * k + 2));
            let (a1, v1) = (element(3 * (k + 1)), element(3 * (k + 1) + 1));
            let (s2, s3) = (s * s, s * s * s);
            let h = [
                2.0 * s3 - 3.0 * s2 + 1.0,
                (s3 - 2.0 * s2 + s) * dt,
                -2.0 * s3 + 3.0 * s2,
                (s3 - s2) * dt,
            ];
            (0..width)
                .map(|i| h[0] * v0[i] + h[1] * b0[i] + h[2] * v1[i] + h[3] * a1[i])
                .collect()
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const TIMES: [f32; 3] = [0.0, 1.0, 3.0];

    #[test]
    fn linear_blends_and_the_ends_hold() {
        let v = [0.0, 2.0, 6.0];
        let at = |t| sample(&TIMES, &v, 1, Interpolation::Linear, t, false).unwrap()[0];
        assert_eq!(at(-1.0), 0.0);
        assert_eq!(at(0.5), 1.0);
        assert_eq!(at(2.0), 4.0);
        assert_eq!(at(3.0), 6.0);
        assert_eq!(at(10.0), 6.0);
    }

    #[test]
    fn step_holds_each_key_until_the_next() {
        let v = [0.0, 2.0, 6.0];
        let at = |t| sample(&TIMES, &v, 1, Interpolation::Step, t, false).unwrap()[0];
        assert_eq!(at(0.99), 0.0);
        assert_eq!(at(1.0), 2.0);
        assert_eq!(at(2.9), 2.0);
    }

    #[test]
    fn cubic_spline_passes_its_keys_with_their_tangents() {
        // Keys of x(t) = t³ on [0, 1, 3] with the exact derivatives as
        // tangents: the Hermite spline of a cubic is the cubic.
        let f = |t: f32| t * t * t;
        let d = |t: f32| 3.0 * t * t;
        let v: Vec<f32> = TIMES.iter().flat_map(|&t| [d(t), f(t), d(t)]).collect();
        for t in [0.0, 0.25, 0.5, 1.0, 1.7, 2.5, 3.0] {
            let got = sample(&TIMES, &v, 1, Interpolation::CubicSpline, t, false).unwrap()[0];
            assert!((got - f(t)).abs() < 1e-4, "t {t}: {got} vs {}", f(t));
        }
    }

    #[test]
    fn linear_rotations_turn_along_the_shortest_arc() {
        let a = Quat::IDENTITY;
        // The same half turn about y written with the opposite sign: the
        // short way from identity is a quarter turn at s = 0.5 either way.
        let b = -Quat::from_rotation_y(std::f32::consts::FRAC_PI_2);
        let v = [a.to_array(), b.to_array()];
        let q = Quat::from_slice(
            &sample(&[0.0, 1.0], v.as_flattened(), 4, Interpolation::Linear, 0.5, true).unwrap(),
        );
        let angle = q.angle_between(Quat::IDENTITY);
        assert!(
            (angle - std::f32::consts::FRAC_PI_4).abs() < 1e-5,
            "turned {angle}"
        );
    }

    #[test]
    fn wide_elements_blend_number_by_number() {
        // Two morph weights per key.
        let v = [0.0, 1.0, 1.0, 0.0, 0.5, 0.5];
        let w = sample(&TIMES, &v, 2, Interpolation::Linear, 0.25, false).unwrap();
        assert_eq!(w, vec![0.25, 0.75]);
        let w = sample(&TIMES, &v, 2, Interpolation::Linear, 2.0, false).unwrap();
        assert_eq!(w, vec![0.75, 0.25]);
    }

    #[test]
    fn a_short_output_is_refused() {
        let e = sample(&TIMES, &[0.0, 1.0], 1, Interpolation::Linear, 0.5, false).unwrap_err();
        assert!(e.contains("2 output values for 3 keys"), "{e}");
        let e = sample(&TIMES, &[0.0; 3], 1, Interpolation::CubicSpline, 0.5, false).unwrap_err();
        assert!(e.contains("expected 9"), "{e}");
        // Two morph weights per key: a short output is counted in elements.
        let e = sample(&TIMES, &[0.0; 5], 2, Interpolation::Linear, 0.5, false).unwrap_err();
        assert!(e.contains("expected 6"), "{e}");
        assert!(
            check_times(&[0.0, 2.0, 1.0])
                .unwrap_err()
                .contains("must increase")
        );
        assert!(check_times(&[f32::NAN]).is_err());
        assert!(check_times(&[]).is_err());
    }
}
