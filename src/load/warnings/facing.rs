//! Area lights that light nothing: every receiver lies behind the plane of
//! the light's emitting side.
//!
//! Receivers are the scene's objects, with their transforms applied as
//! `build` applies them, and area lights that have a surface `material`.
//! Quads, rects, spheres and infinite planes (behind only when parallel to
//! the light) are judged from the description. Meshes, instances and SDFs
//! are judged by their world bounds once built ([`object_extents`]); before
//! a build, or unbounded, they count as lit and keep the warning quiet.
//! A box is behind when its eight corners are: a bound larger than the
//! object errs on the side of silence.

use crate::accel::Aabb;
use crate::desc::{LightDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::Problem;
use crate::load::transform::compose;
use crate::scene::Scene;
use glam::Vec3;

/// The world bounds of each of the scene's first `objects` objects as
/// built (`None` where one has an unbounded part, an unbounded SDF).
pub fn object_extents(scene: &Scene, objects: usize) -> Vec<Option<Aabb>> {
    let mut out = vec![Some(Aabb::EMPTY); objects];
    for (shape, &id) in scene.shapes.iter().zip(&scene.objects) {
        // Object ids are 1 + the index in `objects`; area lights follow.
        let Some(slot) = (id as usize).checked_sub(1).and_then(|i| out.get_mut(i)) else {
            continue;
        };
        *slot = match (*slot, shape.bounds(&scene.geometry)) {
            (Some(b), Some(s)) => Some(b.union(s)),
            _ => None,
        };
    }
    out
}

/// What an area light could shine on, as far as it is cheaply known.
enum Receiver {
    /// A flat shape: its corners.
    Corners([Vec3; 4]),
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// An infinite plane.
    Plane {
        point: Vec3,
        normal: Vec3,
    },
    /// A box around what a file or a tree holds.
    Bounds(Aabb),
    /// Extent unknown without loading a file or building a tree.
    Unknown,
}

impl Receiver {
    /// The object in world space (its `transform` applied, as `build` does).
    fn of_object(o: &ObjectDesc, built: Option<Aabb>) -> Self {
        let m = compose(o.transform());
        let point = |p: &[f32; 3]| m.transform_point3(Vec3::from(*p));
        let vector = |v: &[f32; 3]| m.transform_vector3(Vec3::from(*v));
        match o {
            ObjectDesc::Sphere { center, radius, .. } => Receiver::Sphere {
                center: point(center),
                radius: radius * m.transform_vector3(Vec3::X).length(),
            },
            ObjectDesc::Plane { point: p, normal, .. } => Receiver::Plane {
                point: point(p),
                normal: m.inverse().transpose().transform_vector3(Vec3::from(*normal)),
            },
            ObjectDesc::Quad {
                corner,
                edge_u,
                edge_v,
                ..
            } => Receiver::parallelogram(point(corner), vector(edge_u), vector(edge_v)),
            ObjectDesc::Rect {
                center,
                half_u,
                half_v,
                ..
            } => {
                let (u, v) = (vector(half_u), vector(half_v));
                Receiver::parallelogram(point(center) - u - v, 2.0 * u, 2.0 * v)
            }
            ObjectDesc::Sdf { .. }
            | ObjectDesc::Mesh { .. }
            | ObjectDesc::Instance { .. }
            | ObjectDesc::Gltf { .. } => built.map_or(Receiver::Unknown, Receiver::Bounds),
        }
    }

    fn parallelogram(corner: Vec3, u: Vec3, v: Vec3) -> Self {
        Receiver::Corners([corner, corner + u, corner + v, corner + u + v])
    }

    /// Whether all of it lies behind, or in, the plane through `center` with
    /// unit normal `n` (`tolerance` absorbs rounding; touching the plane
    /// receives only grazing light, which is none).
    fn behind(&self, center: Vec3, n: Vec3, tolerance: f32) -> bool {
        let height = |p: Vec3| (p - center).dot(n);
        match self {
            Receiver::Corners(c) => c.iter().all(|&p| height(p) <= tolerance),
            Receiver::Sphere { center: s, radius } => height(*s) + radius <= tolerance,
            Receiver::Plane { point, normal } => {
                let parallel = normal.normalize_or_zero().cross(n).length() <= 1e-6;
                parallel && height(*point) <= tolerance
            }
            Receiver::Bounds(b) => (0..8).all(|k| {
                let pick = |bit: usize, lo: f32, hi: f32| if k & bit == 0 { lo } else { hi };
                let p = Vec3::new(
                    pick(1, b.min.x, b.max.x),
                    pick(2, b.min.y, b.max.y),
                    pick(4, b.min.z, b.max.z),
                );
                height(p) <= tolerance
            }),
            Receiver::Unknown => false,
        }
    }
}

/// An area light's emitting plane: corner, the two edges, and which fields
/// name the edges (for the help).
fn area_light(l: &LightDesc) -> Option<(Vec3, Vec3, Vec3, [&'static str; 2])> {
    match l {
        LightDesc::Quad {
            corner,
            edge_u,
            edge_v,
            ..
        } => Some((
            Vec3::from(*corner),
            Vec3::from(*edge_u),
            Vec3::from(*edge_v),
            ["edge_u", "edge_v"],
        )),
        LightDesc::Rect {
            center,
            half_u,
            half_v,
            ..
        } => {
            let (u, v) = (Vec3::from(*half_u), Vec3::from(*half_v));
            Some((
                Vec3::from(*center) - u - v,
                2.0 * u,
                2.0 * v,
                ["half_u", "half_v"],
            ))
        }
        LightDesc::Point { .. }
        | LightDesc::Spot { .. }
        | LightDesc::Directional { .. }
        | LightDesc::Environment { .. } => None,
    }
}

/// Area lights whose emitting side faces away from every receiver: the
/// scene's objects (`built[i]`: the world bounds of object `i` once built,
/// if known), and area lights that have a surface `material`. Nothing is
/// said when there are no receivers at all.
pub(super) fn lights_facing_away(desc: &SceneDesc, built: &[Option<Aabb>]) -> Vec<Problem> {
    let surfaces = desc
        .lights
        .iter()
        .filter(|l| {
            matches!(
                l,
                LightDesc::Quad {
                    material: Some(_),
                    ..
                } | LightDesc::Rect {
                    material: Some(_),
                    ..
                }
            )
        })
        .filter_map(area_light)
        .map(|(c, u, v, _)| Receiver::parallelogram(c, u, v));
    let receivers: Vec<Receiver> = desc
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| Receiver::of_object(o, built.get(i).copied().flatten()))
        .chain(surfaces)
        .collect();
    if receivers.is_empty() {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (i, l) in desc.lights.iter().enumerate() {
        let Some((corner, u, v, [un, vn])) = area_light(l) else {
            continue;
        };
        let Some(n) = u.cross(v).try_normalize() else {
            continue;
        };
        let center = corner + 0.5 * (u + v);
        let tolerance = 1e-4 * center.length().max(u.length()).max(v.length()).max(1.0);
        // The light's own surface is among the receivers; it is in its plane.
        if receivers.iter().all(|r| r.behind(center, n, tolerance)) {
            out.push(
                Problem::new(
                    format!("lights[{i}]"),
                    format!(
                        "this area light emits toward ({:.3}, {:.3}, {:.3}), and every object lies behind it: \
                         it lights nothing",
                        n.x, n.y, n.z
                    ),
                )
                .help(format!(
                    "a light emits on the side of `{un} × {vn}`; swap `{un}` and `{vn}` to flip it"
                )),
            );
        }
    }
    out
}
