//! Desc → runtime for implicit surfaces: the hand-written [`SdfDesc`] tree
//! becomes the engine's post-order [`SdfNode`] arena, `of: [...]` lists fold
//! left into binary operators, and the object's `transform` (a similarity,
//! checked by `check.rs`) wraps the root as one `Transform` node, so the
//! runtime [`Sdf`] is already in world space.

use crate::desc::{MarchDesc, ProjectionDesc, SceneDesc, SdfDesc};
use crate::geometry::Shape;
use crate::geometry::sdf::{MarchParams, Sdf, SdfNode};
use crate::geometry::sdf_object::{MIN_EPS, SdfObject};
use crate::load::build_context::BuildContext;
use glam::{Mat3, Mat4, Quat, Vec3, Vec3A};

/// Builds one validated SDF object into `ctx`'s geometry and returns its
/// shape with whether it is bounded (BVH) or not (tested by every ray).
/// The scene's camera and film give the pixel size for the default hit
/// threshold.
pub(in crate::load) fn build_sdf(
    ctx: &mut BuildContext,
    shape: &SdfDesc,
    march: &MarchDesc,
    world_from_object: &Mat4,
    material: u32,
) -> (Shape, bool) {
    let sdfs = &mut ctx.geometry.sdfs;
    let scene = ctx.desc;
    let mut nodes = Vec::new();
    let mut root = lower(shape, &mut nodes);
    if *world_from_object != Mat4::IDENTITY {
        let (scale, rotate, translate) = similarity_parts(world_from_object);
        nodes.push(SdfNode::Transform {
            child: root,
            translate,
            rotate,
            scale,
        });
        root = nodes.len() as u32 - 1;
    }
    let sdf = Sdf::new(nodes, root);
    let eps_per_distance = march.eps_per_distance.unwrap_or(if sdf.is_exact() {
        MarchParams::default().eps_per_distance
    } else {
        half_pixel(scene)
    });
    let params = MarchParams {
        max_steps: march.max_steps,
        min_eps: MIN_EPS,
        eps_per_distance,
        over_relax: march.over_relax,
        estimate_step: march.estimate_step,
    };
    let object = SdfObject::new(sdf, params, material);
    let bounded = object.bounds().is_some();
    sdfs.push(object);
    (Shape::Sdf(sdfs.len() as u32 - 1), bounded)
}

/// Half the angle a pixel subtends at the image centre, in radians.
///
/// Why the default threshold for distance estimates: the march stops on the
/// level set `DE = eps`, so `eps` *is* the fractal's level of detail. Finer
/// than a pixel, the detail aliases into speckles at any affordable sample
/// count and costs steps (measured on the Mandelbulb at 192²: 1e-4 gave 32
/// steps per march and noise, half a pixel 15 steps and a clean surface).
///
/// An orthographic pixel has a constant size, not an angle: it is taken as
/// the angle it subtends from `eye` at the distance of `target`. A spherical
/// camera's row spans π / H radians.
pub fn half_pixel(scene: &SceneDesc) -> f32 {
    let c = &scene.camera;
    let rows = scene.film.height.max(1) as f32;
    match c.projection {
        ProjectionDesc::Perspective => {
            let tan_half_fov = (0.5 * c.fov_y_degrees.unwrap_or(40.0).to_radians()).tan();
            tan_half_fov / rows
        }
        ProjectionDesc::Orthographic { view_height } => {
            let (eye, target) = c.look();
            let distance = (Vec3::from(target) - Vec3::from(eye)).length();
            0.5 * view_height / distance.max(1e-6) / rows
        }
        ProjectionDesc::Spherical => 0.5 * std::f32::consts::PI / rows,
    }
}

/// Uniform scale, rotation and translation of a similarity without mirroring
/// (`p ↦ translate + rotate·(scale·p)`, the engine's `Transform` order).
pub fn similarity_parts(m: &Mat4) -> (f32, Quat, Vec3A) {
    let linear = Mat3::from_mat4(*m);
    let scale = linear.x_axis.length();
    let rotate = Quat::from_mat3(&(linear * scale.recip())).normalize();
    (scale, rotate, Vec3A::from(m.w_axis.truncate()))
}

/// The engine node of a primitive or fractal; `None` for operators.
pub fn leaf(d: &SdfDesc) -> Option<SdfNode> {
    let v = |x: &[f32; 3]| Vec3A::from(*x);
    Some(match *d {
        SdfDesc::Sphere { radius } => SdfNode::Sphere { radius },
        SdfDesc::Box { half_extents } => SdfNode::Box {
            half_extents: v(&half_extents),
        },
        SdfDesc::RoundBox { half_extents, radius } => SdfNode::RoundBox {
            half_extents: v(&half_extents),
            radius,
        },
        SdfDesc::Torus { major, minor } => SdfNode::Torus { major, minor },
        SdfDesc::Capsule { a, b, radius } => SdfNode::Capsule {
            a: v(&a),
            b: v(&b),
            radius,
        },
        SdfDesc::Cylinder { radius, half_height } => SdfNode::Cylinder { radius, half_height },
        SdfDesc::Plane { normal, offset } => SdfNode::Plane {
            normal: v(&normal),
            offset,
        },
        SdfDesc::Mandelbulb {
            power,
            iterations,
            bailout,
        } => SdfNode::Mandelbulb {
            power,
            iterations,
            bailout,
        },
        SdfDesc::Menger { iterations } => SdfNode::Menger { iterations },
        _ => return None,
    })
}

/// Makes an operator's binary node from its children and blend radius `k`.
pub type MakeBinary = fn([u32; 2], f32) -> SdfNode;

/// An n-ary operator's children, its binary node and its `k` (0 if sharp).
pub fn operator(d: &SdfDesc) -> Option<(&[SdfDesc], MakeBinary, f32)> {
    Some(match d {
        SdfDesc::Union { of } => (of, |children, _| SdfNode::Union { children }, 0.0),
        SdfDesc::Intersection { of } => (of, |children, _| SdfNode::Intersection { children }, 0.0),
        SdfDesc::Difference { of } => (of, |children, _| SdfNode::Difference { children }, 0.0),
        SdfDesc::SmoothUnion { k, of } => (of, |children, k| SdfNode::SmoothUnion { children, k }, *k),
        SdfDesc::SmoothIntersection { k, of } => {
            (of, |children, k| SdfNode::SmoothIntersection { children, k }, *k)
        }
        SdfDesc::SmoothDifference { k, of } => {
            (of, |children, k| SdfNode::SmoothDifference { children, k }, *k)
        }
        _ => return None,
    })
}

/// Appends `d` in post-order (children first) and returns its index.
fn lower(d: &SdfDesc, nodes: &mut Vec<SdfNode>) -> u32 {
    let node = if let Some(node) = leaf(d) {
        node
    } else if let Some((of, make, k)) = operator(d) {
        // ((a ∘ b) ∘ c) ∘ …: for Difference, the first minus each of the rest.
        let mut children = of.iter().map(|c| lower(c, nodes)).collect::<Vec<_>>().into_iter();
        // Validation rejects empty lists; a point stands in if one slips by.
        let Some(mut acc) = children.next() else {
            nodes.push(SdfNode::Sphere { radius: 0.0 });
            return nodes.len() as u32 - 1;
        };
        for c in children {
            nodes.push(make([acc, c], k));
            acc = nodes.len() as u32 - 1;
        }
        return acc;
    } else if let SdfDesc::Transform {
        translate,
        rotate,
        scale,
        of,
    } = d
    {
        let child = lower(of, nodes);
        let axis = Vec3::from(rotate.axis).normalize_or(Vec3::Y);
        SdfNode::Transform {
            child,
            translate: Vec3A::from(*translate),
            rotate: Quat::from_axis_angle(axis, rotate.degrees.to_radians()),
            scale: *scale,
        }
    } else {
        unreachable!("every SdfDesc variant is a leaf, an operator or a transform")
    };
    nodes.push(node);
    nodes.len() as u32 - 1
}
