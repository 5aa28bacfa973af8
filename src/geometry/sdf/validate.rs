//! Parameter checks for an SDF arena before it becomes an [`Sdf`]: every
//! problem is reported, each with its path.
//!
//! Path naming, under the caller's prefix `P` (say `objects[2].sdf`):
//! - a parameter of the node at `P` is `P.<field>` with the [`SdfNode`] field
//!   name: `P.radius`, `P.half_extents`, `P.k`, `P.scale`;
//! - child `i` of an operator at `P` is `P.<operator>[i]`, the operator named
//!   in snake_case: `P.union[1]`, `P.smooth_difference[0]`, `P.transform[0]`.
//!
//! So a bad radius reads `objects[2].sdf.union[1].transform[0].radius`. A
//! loader whose scene syntax nests differently can instead call
//! [`validate_node`] on each node with the path it knows.
//!
//! [`Sdf`]: super::Sdf

use super::node::SdfNode;
use crate::diagnostic::Problem;
use glam::Vec3A;

/// All problems of the tree at `nodes[root]`, located under `path`.
pub fn validate(nodes: &[SdfNode], root: u32, path: &str) -> Vec<Problem> {
    let mut out = Vec::new();
    if nodes.is_empty() {
        out.push(
            Problem::new(path, "the SDF has no shapes").help("give it at least one primitive, e.g. a sphere"),
        );
    } else if root as usize >= nodes.len() {
        out.push(Problem::new(
            path,
            format!("root {root} is past the last of {} SDF nodes", nodes.len()),
        ));
    } else {
        walk(nodes, root, path, &mut out);
    }
    out
}

fn walk(nodes: &[SdfNode], i: u32, path: &str, out: &mut Vec<Problem>) {
    let node = &nodes[i as usize];
    validate_node(node, path, out);
    for (slot, &child) in node.children().iter().enumerate() {
        let child_path = format!("{}[{slot}]", join(path, node.name()));
        // Children before parents: no cycles, bounded recursion.
        if child >= i {
            out.push(
                Problem::new(
                    child_path,
                    format!("child node {child} is not before its parent {i}"),
                )
                .help("build the arena in post-order, children first"),
            );
        } else {
            walk(nodes, child, &child_path, out);
        }
    }
}

/// Problems of one node's own parameters (not its children), at `path.<field>`.
pub fn validate_node(node: &SdfNode, path: &str, out: &mut Vec<Problem>) {
    let mut c = Check { path, out };
    match *node {
        SdfNode::Sphere { radius } => {
            c.positive("radius", radius);
        }
        SdfNode::Box { half_extents } => {
            c.positive_vec("half_extents", half_extents);
        }
        SdfNode::RoundBox { half_extents, radius } => {
            // The rounding fits inside the box: 0 ≤ radius ≤ the smallest half extent.
            let most = if c.positive_vec("half_extents", half_extents) {
                half_extents.min_element()
            } else {
                f32::MAX
            };
            c.range("radius", radius, 0.0, most);
        }
        SdfNode::Torus { major, minor } => {
            if c.positive("major", major) && c.positive("minor", minor) && minor > major {
                let message = format!("minor radius {minor} exceeds the major radius {major}");
                c.push(
                    "minor",
                    message,
                    Some("the tube would pass through the axis; make `minor` at most `major`"),
                );
            }
        }
        SdfNode::Capsule { a, b, radius } => {
            c.finite_vec("a", a);
            c.finite_vec("b", b);
            c.positive("radius", radius);
        }
        SdfNode::Cylinder { radius, half_height } => {
            c.positive("radius", radius);
            c.positive("half_height", half_height);
        }
        SdfNode::Plane { normal, offset } => {
            if c.finite_vec("normal", normal) && normal == Vec3A::ZERO {
                c.push(
                    "normal",
                    "the normal is zero".into(),
                    Some("give the direction the plane faces"),
                );
            }
            c.finite("offset", offset);
        }
        SdfNode::Mandelbulb {
            power,
            iterations,
            bailout,
        } => {
            c.range("power", power, 2.0, 16.0);
            c.range("iterations", iterations as f32, 1.0, 64.0);
            // ≥ 2: every escaping orbit is caught; ≤ 8: bailoutⁿ stays finite.
            c.range("bailout", bailout, 2.0, 8.0);
        }
        SdfNode::Menger { iterations } => {
            c.range("iterations", iterations as f32, 0.0, 6.0);
        }
        SdfNode::Union { .. } | SdfNode::Intersection { .. } | SdfNode::Difference { .. } => {}
        SdfNode::SmoothUnion { k, .. }
        | SdfNode::SmoothIntersection { k, .. }
        | SdfNode::SmoothDifference { k, .. } => {
            c.range("k", k, 0.0, f32::MAX);
        }
        SdfNode::Transform {
            translate,
            rotate,
            scale,
            ..
        } => {
            c.finite_vec("translate", translate);
            if !rotate.is_finite() || rotate.length_squared() == 0.0 {
                let message = format!("rotation {rotate} is not a usable quaternion");
                c.push(
                    "rotate",
                    message,
                    Some("use a finite, non-zero quaternion (it is normalised)"),
                );
            }
            c.positive("scale", scale);
        }
    }
}

fn join(path: &str, field: &str) -> String {
    if path.is_empty() {
        field.to_string()
    } else {
        format!("{path}.{field}")
    }
}

struct Check<'a> {
    path: &'a str,
    out: &'a mut Vec<Problem>,
}

impl Check<'_> {
    fn push(&mut self, field: &str, message: String, help: Option<&str>) {
        let problem = Problem::new(join(self.path, field), message);
        self.out.push(match help {
            Some(help) => problem.help(help),
            None => problem,
        });
    }

    fn finite(&mut self, field: &str, v: f32) -> bool {
        if !v.is_finite() {
            self.push(field, format!("`{field}` is {v}, not a finite number"), None);
        }
        v.is_finite()
    }

    fn finite_vec(&mut self, field: &str, v: Vec3A) -> bool {
        if !v.is_finite() {
            self.push(field, format!("`{field}` is {v}, not finite"), None);
        }
        v.is_finite()
    }

    fn positive(&mut self, field: &str, v: f32) -> bool {
        let ok = self.finite(field, v) && v > 0.0;
        if v.is_finite() && !ok {
            self.push(field, format!("`{field}` must be positive, found {v}"), None);
        }
        ok
    }

    fn positive_vec(&mut self, field: &str, v: Vec3A) -> bool {
        let ok = self.finite_vec(field, v) && v.min_element() > 0.0;
        if v.is_finite() && !ok {
            self.push(
                field,
                format!("every component of `{field}` must be positive, found {v}"),
                None,
            );
        }
        ok
    }

    fn range(&mut self, field: &str, v: f32, lo: f32, hi: f32) -> bool {
        let ok = self.finite(field, v) && (lo..=hi).contains(&v);
        if v.is_finite() && !ok {
            let allowed = if hi == f32::MAX {
                format!("at least {lo}")
            } else {
                format!("in [{lo}, {hi}]")
            };
            self.push(field, format!("`{field}` must be {allowed}, found {v}"), None);
        }
        ok
    }
}

#[cfg(test)]
mod tests;
