use super::*;
use glam::Quat;

const P: &str = "objects[2].sdf";

fn paths(nodes: &[SdfNode], root: u32) -> Vec<String> {
    validate(nodes, root, P).into_iter().map(|p| p.path).collect()
}

/// One bad node at the root: exactly one problem, at `P.<field>`.
fn assert_one(node: SdfNode, field: &str) {
    let got = paths(&[node], 0);
    assert_eq!(got, vec![format!("{P}.{field}")], "for {node:?}");
}

#[test]
fn validate_accepts_a_sane_tree() {
    let nodes = [
        SdfNode::Sphere { radius: 1.0 },
        SdfNode::RoundBox {
            half_extents: Vec3A::ONE,
            radius: 0.0,
        },
        SdfNode::SmoothUnion {
            children: [0, 1],
            k: 0.0,
        },
        SdfNode::Menger { iterations: 0 },
        SdfNode::Mandelbulb {
            power: 8.0,
            iterations: 10,
            bailout: 2.0,
        },
        SdfNode::Difference { children: [3, 4] },
        SdfNode::Transform {
            child: 5,
            translate: Vec3A::X,
            rotate: Quat::from_xyzw(0.0, 0.0, 0.0, 2.0),
            scale: 0.5,
        },
        SdfNode::Union { children: [2, 6] },
    ];
    assert!(validate(&nodes, 7, P).is_empty(), "{:?}", validate(&nodes, 7, P));
}

#[test]
fn validate_names_each_bad_parameter() {
    let v = Vec3A::new(1.0, 0.0, 1.0);
    assert_one(SdfNode::Sphere { radius: 0.0 }, "radius");
    assert_one(SdfNode::Sphere { radius: f32::NAN }, "radius");
    assert_one(SdfNode::Box { half_extents: v }, "half_extents");
    assert_one(
        SdfNode::Box {
            half_extents: Vec3A::new(1.0, f32::INFINITY, 1.0),
        },
        "half_extents",
    );
    assert_one(
        SdfNode::RoundBox {
            half_extents: Vec3A::ONE,
            radius: -0.1,
        },
        "radius",
    );
    assert_one(
        SdfNode::RoundBox {
            half_extents: Vec3A::splat(0.5),
            radius: 0.6,
        },
        "radius",
    );
    assert_one(
        SdfNode::Torus {
            major: -1.0,
            minor: 0.2,
        },
        "major",
    );
    assert_one(
        SdfNode::Torus {
            major: 1.0,
            minor: 0.0,
        },
        "minor",
    );
    assert_one(
        SdfNode::Torus {
            major: 1.0,
            minor: 1.5,
        },
        "minor",
    );
    assert_one(
        SdfNode::Capsule {
            a: Vec3A::ZERO,
            b: Vec3A::ONE,
            radius: -1.0,
        },
        "radius",
    );
    assert_one(
        SdfNode::Capsule {
            a: Vec3A::splat(f32::NAN),
            b: Vec3A::ONE,
            radius: 1.0,
        },
        "a",
    );
    assert_one(
        SdfNode::Cylinder {
            radius: 1.0,
            half_height: 0.0,
        },
        "half_height",
    );
    assert_one(
        SdfNode::Plane {
            normal: Vec3A::ZERO,
            offset: 0.0,
        },
        "normal",
    );
    assert_one(
        SdfNode::Plane {
            normal: Vec3A::Y,
            offset: f32::NEG_INFINITY,
        },
        "offset",
    );
    assert_one(
        SdfNode::Mandelbulb {
            power: 1.5,
            iterations: 8,
            bailout: 2.0,
        },
        "power",
    );
    assert_one(
        SdfNode::Mandelbulb {
            power: 17.0,
            iterations: 8,
            bailout: 2.0,
        },
        "power",
    );
    assert_one(
        SdfNode::Mandelbulb {
            power: 8.0,
            iterations: 0,
            bailout: 2.0,
        },
        "iterations",
    );
    assert_one(
        SdfNode::Mandelbulb {
            power: 8.0,
            iterations: 65,
            bailout: 2.0,
        },
        "iterations",
    );
    assert_one(
        SdfNode::Mandelbulb {
            power: 8.0,
            iterations: 8,
            bailout: 1.0,
        },
        "bailout",
    );
    assert_one(SdfNode::Menger { iterations: 7 }, "iterations");
    let sphere = SdfNode::Sphere { radius: 1.0 };
    let op = |node: SdfNode, field: &str| {
        assert_eq!(paths(&[sphere, sphere, node], 2), vec![format!("{P}.{field}")])
    };
    op(
        SdfNode::SmoothUnion {
            children: [0, 1],
            k: -0.1,
        },
        "k",
    );
    op(
        SdfNode::SmoothIntersection {
            children: [0, 1],
            k: f32::NAN,
        },
        "k",
    );
    op(
        SdfNode::SmoothDifference {
            children: [0, 1],
            k: -1.0,
        },
        "k",
    );
    let t = |translate, rotate, scale| SdfNode::Transform {
        child: 0,
        translate,
        rotate,
        scale,
    };
    op(t(Vec3A::ZERO, Quat::IDENTITY, 0.0), "scale");
    op(t(Vec3A::ZERO, Quat::IDENTITY, -2.0), "scale");
    op(t(Vec3A::NAN, Quat::IDENTITY, 1.0), "translate");
    op(t(Vec3A::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0), 1.0), "rotate");
}

#[test]
fn validate_paths_follow_the_tree() {
    let nodes = [
        SdfNode::Sphere { radius: -1.0 },
        SdfNode::Transform {
            child: 0,
            translate: Vec3A::ZERO,
            rotate: Quat::IDENTITY,
            scale: 1.0,
        },
        SdfNode::Torus {
            major: 1.0,
            minor: 2.0,
        },
        SdfNode::SmoothDifference {
            children: [2, 1],
            k: -0.5,
        },
        SdfNode::Box {
            half_extents: Vec3A::ZERO,
        },
        SdfNode::Union { children: [4, 3] },
    ];
    let got = paths(&nodes, 5);
    let want = [
        "objects[2].sdf.union[0].half_extents",
        "objects[2].sdf.union[1].k",
        "objects[2].sdf.union[1].smooth_difference[0].minor",
        "objects[2].sdf.union[1].smooth_difference[1].transform[0].radius",
    ];
    assert_eq!(got, want);
    // An empty prefix gives paths relative to the SDF itself.
    assert_eq!(validate(&nodes[..1], 0, "")[0].path, "radius");
}

#[test]
fn validate_reports_a_malformed_arena() {
    assert_eq!(paths(&[], 0), vec![P.to_string()]);
    assert_eq!(paths(&[SdfNode::Sphere { radius: 1.0 }], 3), vec![P.to_string()]);
    // A child after its parent (here itself) would loop forever.
    let cyclic = [
        SdfNode::Sphere { radius: 1.0 },
        SdfNode::Union { children: [0, 1] },
    ];
    assert_eq!(paths(&cyclic, 1), vec![format!("{P}.union[1]")]);
}
