//! Conservative bounds of an SDF tree, computed bottom-up once per tree.
//!
//! A box that merely contains each child's surface is not enough for smooth
//! unions: they also add material where a child's distance is below `k/4`. So
//! each node carries a box `B` and a slack `c` with the invariant
//! `{p : d(p) ≤ δ} ⊆ B grown by c·δ` for every `δ ≥ 0`. Exact primitives,
//! the clamped Mandelbulb and the Menger sponge have `c = 1`; min, max and the
//! smooth operators keep the larger child slack; a rotation multiplies it by
//! the largest row sum of `|R|` (at most √3).

use super::fractal::mandelbulb_radius;
use super::node::SdfNode;
use crate::accel::Aabb;
use glam::{BVec3A, Mat3A, Vec3A};

/// The box containing everything: the bounds of an unbounded tree (a `Plane` not cut
/// by a bounded shape), which the BVH cannot cull.
pub const INFINITE: Aabb = Aabb {
    min: Vec3A::NEG_INFINITY,
    max: Vec3A::INFINITY,
};

/// Bounds and slack of node `i`.
pub(super) fn bounds_of(nodes: &[SdfNode], i: u32) -> (Aabb, f32) {
    let sym = |h: Vec3A| (Aabb { min: -h, max: h }, 1.0);
    match nodes[i as usize] {
        SdfNode::Sphere { radius } => sym(Vec3A::splat(radius)),
        SdfNode::Box { half_extents } | SdfNode::RoundBox { half_extents, .. } => sym(half_extents),
        SdfNode::Torus { major, minor } => sym(Vec3A::new(major + minor, minor, major + minor)),
        SdfNode::Capsule { a, b, radius } => (
            Aabb {
                min: a.min(b) - Vec3A::splat(radius),
                max: a.max(b) + Vec3A::splat(radius),
            },
            1.0,
        ),
        SdfNode::Cylinder { radius, half_height } => sym(Vec3A::new(radius, half_height, radius)),
        SdfNode::Plane { .. } => (INFINITE, 1.0),
        SdfNode::Mandelbulb { power, .. } => sym(Vec3A::splat(mandelbulb_radius(power))),
        SdfNode::Menger { .. } => sym(Vec3A::ONE),
        SdfNode::Union { children: [a, b] } => union(bounds_of(nodes, a), bounds_of(nodes, b), 0.0),
        SdfNode::SmoothUnion { children: [a, b], k } => {
            // smin ≥ min − k/4: the blend adds at most k/4 of distance.
            union(bounds_of(nodes, a), bounds_of(nodes, b), 0.25 * k.max(0.0))
        }
        // max and the smooth max (≥ max) only remove material.
        SdfNode::Intersection { children: [a, b] } | SdfNode::SmoothIntersection { children: [a, b], .. } => {
            let ((ba, ca), (bb, cb)) = (bounds_of(nodes, a), bounds_of(nodes, b));
            // Per axis [max lo, min hi]; disjoint boxes give an empty (inverted) box.
            (
                Aabb {
                    min: ba.min.max(bb.min),
                    max: ba.max.min(bb.max),
                },
                ca.max(cb),
            )
        }
        SdfNode::Difference { children: [a, _] } | SdfNode::SmoothDifference { children: [a, _], .. } => {
            bounds_of(nodes, a)
        }
        SdfNode::Transform {
            child,
            translate,
            rotate,
            scale,
        } => {
            let (b, c) = bounds_of(nodes, child);
            if !(b.min.is_finite() && b.max.is_finite()) {
                // An unbounded child stays unbounded.
                return (INFINITE, c);
            }
            // An inverted (empty) box goes through too: the hull of its
            // corners still contains it once grown, as the slack requires.
            let m = Mat3A::from_quat(rotate.normalize());
            // Box of the 8 transformed corners.
            let corners: [Vec3A; 8] = std::array::from_fn(|k| {
                let corner = Vec3A::select(BVec3A::new(k & 1 != 0, k & 2 != 0, k & 4 != 0), b.max, b.min);
                translate + m * (corner * scale)
            });
            // A cube of half side h, rotated, fits in one of half side h·max row sum |R|.
            let rows = m.transpose();
            let stretch = [rows.x_axis, rows.y_axis, rows.z_axis].map(|r| r.abs().element_sum());
            (
                Aabb::from_points(&corners),
                c * stretch.into_iter().fold(1.0, f32::max),
            )
        }
    }
}

fn union((ba, ca): (Aabb, f32), (bb, cb): (Aabb, f32), grow: f32) -> (Aabb, f32) {
    let c = ca.max(cb);
    let g = Vec3A::splat(c * grow);
    let b = ba.union(bb);
    (
        Aabb {
            min: b.min - g,
            max: b.max + g,
        },
        c,
    )
}

#[cfg(test)]
mod tests {
    use super::super::Sdf;
    use super::*;
    use crate::math::{Pcg32, sampling::uniform_sphere};
    use glam::Quat;

    fn contains(b: &Aabb, p: Vec3A, tol: f32) -> bool {
        p.cmpge(b.min - Vec3A::splat(tol)).all() && p.cmple(b.max + Vec3A::splat(tol)).all()
    }

    #[test]
    fn bounds_contain_the_solid() {
        let rotate = Quat::from_axis_angle(glam::Vec3::new(1.0, 2.0, 3.0).normalize(), 1.1);
        let nodes = vec![
            SdfNode::Torus {
                major: 1.0,
                minor: 0.3,
            },
            SdfNode::Transform {
                child: 0,
                translate: Vec3A::new(0.5, 0.0, 0.2),
                rotate,
                scale: 0.8,
            },
            SdfNode::Capsule {
                a: Vec3A::NEG_Y,
                b: Vec3A::new(0.3, 1.2, 0.0),
                radius: 0.2,
            },
            SdfNode::SmoothUnion {
                children: [1, 2],
                k: 0.8,
            },
            SdfNode::Mandelbulb {
                power: 8.0,
                iterations: 8,
                bailout: 2.0,
            },
            SdfNode::Transform {
                child: 4,
                translate: Vec3A::new(-1.5, 0.0, 0.0),
                rotate,
                scale: 0.5,
            },
            SdfNode::SmoothUnion {
                children: [3, 5],
                k: 0.5,
            },
            SdfNode::Transform {
                child: 6,
                translate: Vec3A::ZERO,
                rotate: rotate.inverse(),
                scale: 1.3,
            },
        ];
        let sdf = Sdf::new(nodes, 7);
        let b = sdf.bounds();
        assert!(b.min.is_finite() && b.max.is_finite(), "bounded tree gave {b:?}");
        let mut rng = Pcg32::new(6, 6);
        let mut inside = 0;
        for _ in 0..200_000 {
            let p = uniform_sphere(rng.next_vec2()) * 5.0 * rng.next_f32().cbrt();
            if sdf.distance(p) <= 0.0 {
                inside += 1;
                assert!(
                    contains(&b, p, 1e-4),
                    "{p} is inside the surface but outside {b:?}"
                );
            }
        }
        assert!(
            inside > 1000,
            "too few inside samples ({inside}) to test anything"
        );
    }

    #[test]
    fn bounds_of_plane_are_infinite_until_intersected() {
        let plane = SdfNode::Plane {
            normal: Vec3A::Y,
            offset: 0.0,
        };
        assert_eq!(Sdf::primitive(plane).bounds(), INFINITE);
        let cut = Sdf::new(
            vec![
                plane,
                SdfNode::Sphere { radius: 2.0 },
                SdfNode::Intersection { children: [0, 1] },
            ],
            2,
        );
        assert_eq!(
            cut.bounds(),
            Aabb {
                min: Vec3A::splat(-2.0),
                max: Vec3A::splat(2.0)
            }
        );
        let moved = Sdf::new(
            vec![
                plane,
                SdfNode::Transform {
                    child: 0,
                    translate: Vec3A::X,
                    rotate: Quat::IDENTITY,
                    scale: 1.0,
                },
            ],
            1,
        );
        assert_eq!(moved.bounds(), INFINITE);
    }
}
