//! A glTF asset's camera as the scene's: `camera: (gltf: (file: ..))`.
//!
//! The camera's node places it looking down the node's −z with +y up
//! (glTF 2.0 §3.10), posed as the `Gltf` object that reads the file poses
//! its meshes (its `scene`, its `animation` at the frame's time) and then
//! moved by the object's `transform`. A perspective camera's `yfov` is the
//! scene's `fov_y_degrees`; an orthographic camera's `ymag` is half its
//! view height. The film keeps its own size: an asset camera whose
//! `aspectRatio` (or `xmag / ymag`) differs keeps its vertical extent, and
//! a note says so, as Blender's importer does. While the shutter is open an
//! animated camera is keyed at [`super::BLUR_STEPS`] poses, as the asset's
//! rigid parts are, so it is motion-blurred like them.
//!
//! The file is read once more for the camera, before the objects are built
//! (an SDF's default precision depends on the camera): its JSON and
//! buffers, not its images. A file the object cannot read is the object's
//! error; this step then leaves the camera to it.

use super::{animation, document, nodes};
use crate::desc::{CameraDesc, CameraKeyDesc, ObjectDesc, ProjectionDesc, SceneDesc};
use crate::diagnostic::Problem;
use glam::{Mat4, Vec3};
use std::path::Path;

/// What the asset's camera gives the scene's: where it is, where it looks
/// and its projection.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pose {
    eye: Vec3,
    forward: Vec3,
    up: Vec3,
}

/// The scene's camera with what its `gltf` asks for filled in (`eye`,
/// `target`, `up`, the projection, keys over an open shutter), or `None`
/// when it asks for none, or when the asset cannot be read (the object
/// reports that). Notes go to `notes`.
pub(crate) fn resolve(
    desc: &SceneDesc,
    base: &Path,
    root: Option<&Path>,
    notes: &mut Vec<String>,
) -> Result<Option<CameraDesc>, Problem> {
    let Some(g) = &desc.camera.gltf else {
        return Ok(None);
    };
    let Some((i, scene, chosen_animation, repeat, transform)) =
        desc.objects.iter().enumerate().find_map(|(i, o)| match o {
            ObjectDesc::Gltf {
                file,
                scene,
                animation,
                repeat,
                transform,
                ..
            } if *file == g.file => Some((i, *scene, animation.as_deref(), *repeat, transform)),
            _ => None,
        })
    else {
        // Validation named the missing object.
        return Ok(None);
    };
    let Ok(asset) = document::read(&base.join(&g.file), root) else {
        return Ok(None);
    };
    let doc = &asset.doc;
    let read = match chosen_animation.map(|a| animation::find(doc, a)) {
        Some(Ok(k)) => match animation::Animation::read(doc, &asset.buffers, k) {
            Ok(a) => Some(a),
            Err(_) => return Ok(None),
        },
        Some(Err(_)) => return Ok(None),
        None => None,
    };
    let at = "camera.gltf";
    let label = format!("objects[{i}]");
    let world_from_object = crate::load::transform::compose(transform);
    let (open, close) = super::super::animation::shutter(desc);
    // The cameras the scene's node tree places under the pose at `frame`;
    // `None` for a broken tree or animation, which the object reports.
    let cameras_at = |frame: f32| -> Option<Vec<nodes::CameraPlacement>> {
        let seconds = super::animation_seconds(desc, frame);
        let posed = animation::pose(doc, read.as_ref(), seconds, repeat).ok()?;
        nodes::walk(doc, scene, &posed.locals).ok().map(|w| w.cameras)
    };
    let Some(cameras) = cameras_at(open) else {
        return Ok(None);
    };
    let placed = match choose(doc, &cameras, g.camera.as_deref()) {
        Ok(Some(c)) => c,
        Ok(None) => {
            let count = doc.cameras().count();
            let what = if count == 0 {
                format!("`{}` has no camera", g.file)
            } else {
                format!(
                    "`{}` has {count} camera(s), none placed by a node of the scene drawn",
                    g.file
                )
            };
            return Err(Problem::new(at, what).help(
                "export the asset with its camera (Blender: Include ▸ Cameras), or describe the \
                 camera with `eye`, `target` and `fov_y_degrees`",
            ));
        }
        Err(e) => {
            return Err(Problem::new(format!("{at}.camera"), e).help(
                "name a camera by its node's name or its own, or by index (`\"#0\"`); leave \
                       `camera` out for the first",
            ));
        }
    };
    let first = pose_of(world_from_object * placed.world);
    check_pose(at, &first, &placed)?;
    let camera = doc.cameras().nth(placed.camera).ok_or_else(|| {
        Problem::new(
            at,
            format!("nodes[{}] names a camera that does not exist", placed.node),
        )
    })?;
    let mut out = desc.camera.clone();
    let aspect = desc.film.width as f32 / desc.film.height.max(1) as f32;
    let (projection, fov, theirs) = match camera.projection() {
        gltf::camera::Projection::Perspective(p) => {
            let yfov = p.yfov();
            if !(yfov > 0.0 && yfov < std::f32::consts::PI) {
                return Err(Problem::new(
                    at,
                    format!("the camera's yfov {yfov} is not an angle in (0, π) radians"),
                )
                .help(
                    "fix the asset's camera, or describe the camera with `eye`, `target` and `fov_y_degrees`",
                ));
            }
            (
                ProjectionDesc::Perspective,
                Some(yfov.to_degrees()),
                p.aspect_ratio(),
            )
        }
        gltf::camera::Projection::Orthographic(o) => {
            let (x, y) = (o.xmag(), o.ymag());
            let limit = super::super::validate::MAX_COORD;
            if !(y > 0.0 && 2.0 * y <= limit) {
                return Err(Problem::new(
                    at,
                    format!("the orthographic camera's ymag {y} is not a positive half-height"),
                )
                .help(
                    "fix the asset's camera, or describe the camera with `eye`, `target` and `projection`",
                ));
            }
            let ratio = (x > 0.0 && x.is_finite()).then(|| x / y);
            (ProjectionDesc::Orthographic { view_height: 2.0 * y }, None, ratio)
        }
    };
    if let Some(r) = theirs.filter(|r| r.is_finite() && (r / aspect - 1.0).abs() > 0.01) {
        notes.push(format!(
            "{label}: its camera's aspect ratio is {r:.3}, the film's {aspect:.3}: the vertical view is kept \
             (set the film's size to {r:.3}:1 for the asset's framing)"
        ));
    }
    // Focus (a lens with an aperture needs `focus_distance`, checked)
    // lies at `focus_distance`. A pinhole has none: its target is a unit
    // on, or a 64th of the eye's distance from the origin when that is
    // more, so that `target − eye` keeps the view direction in f32 for a
    // camera far out (at 10⁷ a unit is one f32 step).
    let reach = out
        .focus_distance
        .unwrap_or_else(|| (first.eye.abs().max_element() / 64.0).max(1.0));
    let look = |p: &Pose| {
        (
            p.eye.to_array(),
            (p.eye + reach * p.forward).to_array(),
            p.up.to_array(),
        )
    };
    let (eye, target, up) = look(&first);
    out.eye = Some(eye);
    out.target = Some(target);
    out.up = up;
    out.fov_y_degrees = fov;
    out.projection = projection;
    // Keyed over the open shutter when the animation moves the camera.
    if read.is_some() && close > open {
        let mut keys = vec![(open, first)];
        for k in 1..=super::BLUR_STEPS {
            let t = open + (close - open) * k as f32 / super::BLUR_STEPS as f32;
            let later = cameras_at(t).and_then(|all| all.into_iter().find(|c| c.node == placed.node));
            if let Some(c) = later {
                let p = pose_of(world_from_object * c.world);
                if check_pose(at, &p, &c).is_ok() {
                    keys.push((t, p));
                }
            }
        }
        if keys.windows(2).any(|w| w[0].1 != w[1].1) {
            out.keys = keys
                .iter()
                .map(|(frame, p)| {
                    let (eye, target, up) = look(p);
                    CameraKeyDesc {
                        frame: *frame,
                        eye,
                        target,
                        up: Some(up),
                    }
                })
                .collect();
        }
    }
    Ok(Some(out))
}

/// The camera `wanted` names (a node's or a camera's name, or `#k`, the
/// document's camera `k`), else the first placed; `None` when the scene
/// places no camera, an error when `wanted` matches none.
fn choose(
    doc: &gltf::Document,
    placed: &[nodes::CameraPlacement],
    wanted: Option<&str>,
) -> Result<Option<nodes::CameraPlacement>, String> {
    let Some(w) = wanted else {
        return Ok(placed.first().copied());
    };
    let index = w.strip_prefix('#').and_then(|k| k.parse::<usize>().ok());
    let name_of = |c: &nodes::CameraPlacement| {
        let node = doc.nodes().nth(c.node).and_then(|n| n.name().map(str::to_string));
        let camera = doc
            .cameras()
            .nth(c.camera)
            .and_then(|n| n.name().map(str::to_string));
        (node, camera)
    };
    let found = placed.iter().find(|c| {
        let (node, camera) = name_of(c);
        index == Some(c.camera) || node.as_deref() == Some(w) || camera.as_deref() == Some(w)
    });
    match found {
        Some(c) => Ok(Some(*c)),
        None if placed.is_empty() => Ok(None),
        None => {
            let names: Vec<String> = placed
                .iter()
                .map(|c| match name_of(c) {
                    (Some(n), Some(k)) if n != k => format!("`{n}` (camera `{k}`)"),
                    (Some(n), _) | (None, Some(n)) => format!("`{n}`"),
                    (None, None) => format!("`#{}`", c.camera),
                })
                .collect();
            Err(format!(
                "the asset places no camera named `{w}`; its cameras are {}",
                names.join(", ")
            ))
        }
    }
}

/// Where a node's world transform puts a camera: its origin, its −z and
/// its +y.
fn pose_of(world: Mat4) -> Pose {
    Pose {
        eye: world.transform_point3(Vec3::ZERO),
        forward: world.transform_vector3(Vec3::NEG_Z).normalize_or_zero(),
        up: world.transform_vector3(Vec3::Y).normalize_or_zero(),
    }
}

/// A pose the scene's camera can take: finite, within the coordinate
/// limit, a view direction and an up that is not along it.
fn check_pose(at: &str, p: &Pose, placed: &nodes::CameraPlacement) -> Result<(), Problem> {
    let limit = super::super::validate::MAX_COORD;
    let help =
        "fix the camera's node in the asset, or describe the camera with `eye`, `target` and `fov_y_degrees`";
    if !(p.eye.is_finite() && p.eye.abs().max_element() <= limit) {
        return Err(Problem::new(
            at,
            format!(
                "nodes[{}] places the camera at {}, beyond ±{limit:e} (the scene's coordinate limit)",
                placed.node, p.eye
            ),
        )
        .help(help));
    }
    if p.forward == Vec3::ZERO || p.up == Vec3::ZERO || p.forward.cross(p.up).length() < 1e-4 {
        return Err(Problem::new(
            at,
            format!(
                "nodes[{}] gives the camera no view direction or no up (its node is scaled to nothing \
                 or flattened)",
                placed.node
            ),
        )
        .help(help));
    }
    Ok(())
}
