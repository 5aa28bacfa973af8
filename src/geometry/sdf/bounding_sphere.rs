//! A bounding sphere of an SDF tree, where one is tighter than its box.
//!
//! The Mandelbulb is a ball-shaped set (it lies in the ball of
//! [`mandelbulb_radius`]); its box, rotated, is up to √3 times wider than the
//! ball, and rays through the corners marched for nothing. [`trace`] clips a
//! ray to the box and to this sphere, so rays that miss the ball never
//! evaluate the fractal, and those that hit it start marching at its surface.
//!
//! Only nodes whose solid is known to lie in a ball get one: spheres, the
//! fractals, and unions and transforms of those. Anything else (`None`)
//! leaves the box alone to clip.
//!
//! [`trace`]: super::trace

use super::fractal::mandelbulb_radius;
use super::node::SdfNode;
use glam::Vec3A;

/// Centre and radius of a ball that contains `{p : d(p) ≤ 0}` of node `i`.
pub(super) fn bounding_sphere(nodes: &[SdfNode], i: u32) -> Option<(Vec3A, f32)> {
    match nodes[i as usize] {
        SdfNode::Sphere { radius } => Some((Vec3A::ZERO, radius)),
        SdfNode::Mandelbulb { power, .. } => Some((Vec3A::ZERO, mandelbulb_radius(power))),
        // The cube [-1, 1]³ (the sponge removes material only).
        SdfNode::Menger { .. } => Some((Vec3A::ZERO, 3f32.sqrt())),
        SdfNode::Union { children: [a, b] } => {
            let (ca, ra) = bounding_sphere(nodes, a)?;
            let (cb, rb) = bounding_sphere(nodes, b)?;
            Some(enclosing(ca, ra, cb, rb))
        }
        // Intersections and differences remove material: either ball holds it.
        SdfNode::Intersection { children: [a, b] } => {
            match (bounding_sphere(nodes, a), bounding_sphere(nodes, b)) {
                (Some(sa), Some(sb)) => Some(if sa.1 <= sb.1 { sa } else { sb }),
                (s, None) | (None, s) => s,
            }
        }
        SdfNode::Difference { children: [a, _] } => bounding_sphere(nodes, a),
        SdfNode::Transform {
            child,
            translate,
            rotate,
            scale,
        } => {
            // p = translate + rotate · (scale · q): a rigid motion and a
            // uniform scale map balls to balls.
            let (c, r) = bounding_sphere(nodes, child)?;
            Some((translate + rotate.normalize() * (c * scale), r * scale))
        }
        _ => None,
    }
}

/// Smallest ball containing both balls.
fn enclosing(ca: Vec3A, ra: f32, cb: Vec3A, rb: f32) -> (Vec3A, f32) {
    let d = (cb - ca).length();
    if d + rb <= ra {
        return (ca, ra);
    }
    if d + ra <= rb {
        return (cb, rb);
    }
    let r = 0.5 * (d + ra + rb);
    // From a's far side toward b's far side: the centre sits r − ra from ca.
    (ca + (cb - ca) * ((r - ra) / d), r)
}

/// Ray parameters `[t0, t1]` where `o + t·d` is inside the ball, if any.
/// The radius is padded by a relative 1e-5 so rounding never clips a hit.
#[inline]
pub(super) fn clip_to_sphere(c: Vec3A, r: f32, o: Vec3A, d: Vec3A) -> Option<(f32, f32)> {
    let r = r * (1.0 + 1e-5);
    // |oc + t d|² = r²: a t² + 2 b t + k = 0 with the half coefficient b.
    let oc = o - c;
    let a = d.length_squared();
    let b = oc.dot(d);
    // b² − a k computed as a (r² − |oc − (b/a) d|²), which keeps its digits
    // when the origin is far (pbrt-v4's sphere test).
    let perp = oc - d * (b / a);
    let disc = a * (r * r - perp.length_squared());
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    // Stable roots: q = −(b + sign(b)·√disc), t = q/a and k/q.
    let q = -(b + disc.sqrt().copysign(b));
    let k = oc.length_squared() - r * r;
    let (t0, t1) = (q / a, k / q);
    let (t0, t1) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
    // q = 0 (origin at the centre of a degenerate ball) gives NaN.
    (t0.is_finite() && t1.is_finite()).then_some((t0, t1))
}

#[cfg(test)]
mod tests {
    use super::super::Sdf;
    use super::*;
    use crate::math::{Pcg32, sampling::uniform_sphere};
    use glam::Quat;

    #[test]
    fn ball_contains_the_solid() {
        let rotate = Quat::from_axis_angle(glam::Vec3::new(1.0, 2.0, 3.0).normalize(), 1.1);
        let nodes = vec![
            SdfNode::Mandelbulb {
                power: 8.0,
                iterations: 6,
                bailout: 2.0,
            },
            SdfNode::Transform {
                child: 0,
                translate: Vec3A::new(-0.7, 0.2, 0.0),
                rotate,
                scale: 0.8,
            },
            SdfNode::Sphere { radius: 0.5 },
            SdfNode::Transform {
                child: 2,
                translate: Vec3A::new(1.0, 0.0, 0.3),
                rotate,
                scale: 1.5,
            },
            SdfNode::Union { children: [1, 3] },
        ];
        let (c, r) = bounding_sphere(&nodes, 4).expect("a union of balls has a ball");
        let sdf = Sdf::new(nodes, 4);
        let mut rng = Pcg32::new(7, 7);
        let mut inside = 0;
        for _ in 0..100_000 {
            let p = uniform_sphere(rng.next_vec2()) * 3.0 * rng.next_f32().cbrt();
            if sdf.distance(p) <= 0.0 {
                inside += 1;
                assert!(
                    (p - c).length() <= r * (1.0 + 1e-5),
                    "{p} inside the solid, outside the ball"
                );
            }
        }
        assert!(inside > 1000, "too few inside samples ({inside})");
    }

    #[test]
    fn clip_matches_the_analytic_chord() {
        let mut rng = Pcg32::new(8, 8);
        let (c, r) = (Vec3A::new(0.3, -0.2, 0.1), 1.1);
        let (mut hits, mut misses) = (0, 0);
        for _ in 0..10_000 {
            let o = c + uniform_sphere(rng.next_vec2()) * 4.0;
            let d = (uniform_sphere(rng.next_vec2()) * 0.5 + (c - o).normalize()) * 2.0;
            // Closest approach of the ray's line to the centre.
            let t_mid = (c - o).dot(d) / d.length_squared();
            let gap = (o + d * t_mid - c).length();
            match clip_to_sphere(c, r, o, d) {
                Some((t0, t1)) => {
                    hits += 1;
                    assert!(gap <= r * 1.001, "hit with gap {gap}");
                    for t in [t0, t1] {
                        let at = (o + d * t - c).length();
                        assert!((at - r).abs() < 1e-4, "|p(t) − c| = {at}, not {r}");
                    }
                }
                None => {
                    misses += 1;
                    assert!(gap >= r * 0.999, "missed with gap {gap}");
                }
            }
        }
        assert!(hits > 1000 && misses > 1000, "{hits} hits, {misses} misses");
    }
}
