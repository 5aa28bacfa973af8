//! Area lights that light nothing: every receiver lies behind the plane of
//! the light's emitting side.
//!
//! Receivers are the scene's objects, with their transforms applied as
//! `build` applies them, and area lights that have a surface `material`.
//! Only extents known from the description itself count: corners of quads
//! and rects, spheres, infinite planes (behind only when parallel to the
//! light). Meshes, instances and SDFs would need files read or trees built,
//! so they count as lit and keep the warning quiet.

use crate::desc::{LightDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::Problem;
use crate::load::transform::compose;
use glam::Vec3;

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
    /// Extent unknown without loading a file or building a tree.
    Unknown,
}

impl Receiver {
    /// The object in world space (its `transform` applied, as `build` does).
    fn of_object(o: &ObjectDesc) -> Self {
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
            ObjectDesc::Sdf { .. } | ObjectDesc::Mesh { .. } | ObjectDesc::Instance { .. } => {
                Receiver::Unknown
            }
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
        LightDesc::Point { .. } | LightDesc::Spot { .. } | LightDesc::Environment { .. } => None,
    }
}

/// Area lights whose emitting side faces away from every receiver: the
/// scene's objects, and area lights that have a surface `material`.
/// Nothing is said when there are no receivers at all.
pub(super) fn lights_facing_away(desc: &SceneDesc) -> Vec<Problem> {
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
        .map(Receiver::of_object)
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
