//! Semantic checks of an `Sdf` object, on the scene's own tree so every path
//! follows what the user wrote: `objects[2].shape.of[1].of.minor` is the
//! `minor` of the torus inside the second shape's `Transform`, and
//! `spans.rs` finds it in the file. Parameter ranges come from the engine's
//! [`validate_node`], so the scene and the engine cannot disagree on them.
//!
//! Unbounded trees (a `Plane` not cut by a bounded shape) are rejected here,
//! at the plane responsible, rather than marched: a ray that misses an
//! unbounded SDF would spend every one of its `max_steps` finding out, and a
//! floor is better served by the analytic `Plane` object.

use super::super::transform::{compose, is_similarity};
use super::build::{leaf, operator};
use crate::desc::{MarchDesc, SdfDesc, TransformDesc};
use crate::diagnostic::Problem;
use crate::geometry::sdf::{SdfNode, validate_node};
use glam::Vec3;

/// Every problem of the `Sdf` object at `path` (`objects[i]`).
pub fn validate_sdf(
    path: &str,
    shape: &SdfDesc,
    march: &MarchDesc,
    transform: &[TransformDesc],
) -> Vec<Problem> {
    let mut out = Vec::new();
    let shape_path = format!("{path}.shape");
    walk(shape, &shape_path, &mut out);
    if let Some(plane) = unbounded_plane(shape, &shape_path) {
        out.push(Problem::new(plane, "this `Plane` makes the SDF unbounded").help(
            "intersect it with a bounded shape, e.g. `Intersection(of: [Plane(...), Box(...)])`, \
                 or use a `Plane` object for an infinite floor",
        ));
    }
    similarity(path, transform, &mut out);
    march_settings(&format!("{path}.march"), march, &mut out);
    out
}

fn walk(d: &SdfDesc, path: &str, out: &mut Vec<Problem>) {
    if let Some(node) = leaf(d) {
        validate_node(&node, path, out);
    } else if let Some((of, _, k)) = operator(d) {
        // `k` has the same range for every smooth operator.
        validate_node(&SdfNode::SmoothUnion { children: [0, 0], k }, path, out);
        if of.is_empty() {
            out.push(
                Problem::new(format!("{path}.of"), "nothing to combine: the list is empty")
                    .help("give at least one shape, e.g. `of: [Sphere(radius: 1)]`"),
            );
        }
        for (i, c) in of.iter().enumerate() {
            walk(c, &format!("{path}.of[{i}]"), out);
        }
    } else if let SdfDesc::Transform {
        translate,
        rotate,
        scale,
        of,
    } = d
    {
        let finite = |v: &[f32]| v.iter().all(|x| x.is_finite());
        if !finite(translate) {
            out.push(Problem::new(
                format!("{path}.translate"),
                format!("translation {translate:?} is not finite"),
            ));
        }
        if !finite(&rotate.axis) || Vec3::from(rotate.axis).length_squared() == 0.0 {
            out.push(
                Problem::new(
                    format!("{path}.rotate.axis"),
                    format!("rotation axis {:?} has no direction", rotate.axis),
                )
                .help("give a finite, non-zero axis, e.g. (0, 1, 0)"),
            );
        }
        if !rotate.degrees.is_finite() {
            out.push(Problem::new(
                format!("{path}.rotate.degrees"),
                "the angle is not finite",
            ));
        }
        if !(*scale > 0.0 && scale.is_finite()) {
            out.push(
                Problem::new(
                    format!("{path}.scale"),
                    format!("`scale` must be positive, found {scale}"),
                )
                .help("a uniform factor; mirror a shape by rotating it instead"),
            );
        }
        walk(of, &format!("{path}.of"), out);
    }
}

/// Path of a `Plane` that leaves the tree at `path` unbounded, if any; it
/// mirrors how the engine's bounds combine (union: either child; intersection:
/// all children; difference: the first).
fn unbounded_plane(d: &SdfDesc, path: &str) -> Option<String> {
    let child = |of: &[SdfDesc], i: usize| unbounded_plane(&of[i], &format!("{path}.of[{i}]"));
    match d {
        SdfDesc::Plane { .. } => Some(path.to_string()),
        SdfDesc::Union { of } | SdfDesc::SmoothUnion { of, .. } => (0..of.len()).find_map(|i| child(of, i)),
        SdfDesc::Intersection { of } | SdfDesc::SmoothIntersection { of, .. } => {
            let all: Option<Vec<String>> = (0..of.len()).map(|i| child(of, i)).collect();
            all.and_then(|planes| planes.into_iter().next())
        }
        SdfDesc::Difference { of } | SdfDesc::SmoothDifference { of, .. } if !of.is_empty() => child(of, 0),
        SdfDesc::Transform { of, .. } => unbounded_plane(of, &format!("{path}.of")),
        _ => None,
    }
}

/// The engine's `Transform` holds rotation, uniform scale and translation;
/// a mirror image would need `d(−p)`, which no node provides.
fn similarity(path: &str, steps: &[TransformDesc], out: &mut Vec<Problem>) {
    let m = compose(steps);
    if steps.is_empty() || !m.is_finite() {
        // Nothing to check, or `validate` already reported the bad step.
        return;
    }
    if !is_similarity(&m) {
        out.push(
            Problem::new(
                format!("{path}.transform"),
                "an SDF's transform must keep its shape",
            )
            .help("use equal scale factors on all axes; stretch the shapes inside the SDF instead"),
        );
    } else if m.determinant() < 0.0 {
        out.push(
            Problem::new(
                format!("{path}.transform"),
                "an SDF's transform must not mirror it",
            )
            .help("use positive scale factors; a rotation by 180° flips one axis pair"),
        );
    }
}

fn march_settings(path: &str, m: &MarchDesc, out: &mut Vec<Problem>) {
    let mut check = |field: &str, ok: bool, message: String, help: &str| {
        if !ok {
            out.push(Problem::new(format!("{path}.{field}"), message).help(help));
        }
    };
    check(
        "max_steps",
        (1..=100_000).contains(&m.max_steps),
        format!("max_steps {} is outside 1..=100000", m.max_steps),
        "512 (the default) suits most shapes; fractals seen close up may need more",
    );
    let eps = m.eps_per_distance.unwrap_or(1e-4);
    check(
        "eps_per_distance",
        (0.0..=0.05).contains(&eps),
        format!("eps_per_distance {eps} is outside [0, 0.05]"),
        "the hit threshold per unit of distance, in radians; half a pixel is about tan(fov/2)/height",
    );
    check(
        "over_relax",
        (1.0..2.0).contains(&m.over_relax),
        format!("over_relax {} is outside [1, 2)", m.over_relax),
        "1 is plain sphere tracing; the default 1.6 saves steps near surfaces",
    );
    check(
        "estimate_step",
        m.estimate_step > 0.0 && m.estimate_step <= 1.0,
        format!("estimate_step {} is outside (0, 1]", m.estimate_step),
        "the fraction of a distance estimate stepped; lower it (e.g. 0.5) if a fractal shows holes",
    );
}
