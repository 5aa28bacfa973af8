//! A glTF asset's camera as the scene's (`camera: (gltf: (file: ..))`):
//! placed by its node chain, the object's transform and the animation at
//! the frame drawn; chosen by name or index; its projection converted; and
//! every way the choice can be wrong a located error.

use super::{Asset, animated, explain, load, notes_of, triangle, trs};
use glam::{Mat4, Quat, Vec3, Vec3A};
use ronray::camera::Projection;
use ronray::load::LoadError;
use serde_json::{Value, json};

/// An asset with a triangle and the cameras `cameras` placed by `nodes`
/// (node 0 holds the triangle; the scene's roots are `roots`), `rest`
/// merged in.
fn asset(cameras: Value, nodes: Value, roots: Value, rest: Value) -> String {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    let mut doc = json!({
        "scenes": [{"nodes": roots}],
        "nodes": nodes,
        "meshes": [tri],
        "cameras": cameras,
    });
    for (k, v) in rest.as_object().expect("an object") {
        doc[k] = v.clone();
    }
    a.gltf(doc)
}

/// A scene that looks through `camera` (the inside of `camera: (..)`) at
/// `a.gltf`, placed by `Gltf(file: "a.gltf", ..{object})`.
fn scene(camera: &str, object: &str) -> String {
    format!(
        r#"Scene(
            camera: ({camera}),
            integrator: Path(max_depth: 3),
            materials: {{ "grey": Lambert(albedo: 0.5) }},
            lights: [Point(position: (2, 4, 5), intensity: (30, 30, 30))],
            objects: [Gltf(file: "a.gltf", material: "grey"{object})],
        )"#
    )
}

fn perspective(yfov: f32) -> Value {
    json!({"type": "perspective", "perspective": {"yfov": yfov, "znear": 0.1}})
}

fn close(got: Vec3A, want: Vec3, what: &str) {
    assert!(
        (Vec3::from(got) - want).length() < 1e-5,
        "{what}: {got}, expected {want}"
    );
}

fn error(files: &[(&str, &[u8])], scene: &str) -> String {
    match load(files, scene) {
        Ok(_) => panic!("loaded:\n{scene}"),
        Err(LoadError::Invalid(r)) => r.render(false),
        Err(e) => panic!("not a located error: {e}"),
    }
}

/// The camera sits where its node chain and the object's transform put
/// the node's origin, looks down the node's −z with its +y up, and takes
/// the camera's vertical field of view; a note tells the asset's aspect
/// ratio from the film's.
#[test]
fn a_gltf_camera_is_placed_by_its_nodes_and_the_object() {
    let parent = ([1.0, 2.0, 3.0], Quat::from_rotation_y(0.7), [1.0, 1.0, 1.0]);
    let child = ([0.0, 0.5, 2.0], Quat::from_rotation_x(-0.3), [1.0, 1.0, 1.0]);
    let node = |(t, r, _): ([f32; 3], Quat, [f32; 3])| json!({"translation": t, "rotation": r.to_array()});
    let mut parent_node = node(parent);
    parent_node["children"] = json!([2]);
    let mut child_node = node(child);
    child_node["camera"] = json!(0);
    let cam = json!({"type": "perspective", "perspective": {"yfov": 0.6, "aspectRatio": 1.5, "znear": 0.1}});
    let doc = asset(
        json!([cam]),
        json!([{"mesh": 0}, parent_node, child_node]),
        json!([0, 1]),
        json!({}),
    );
    let loaded = load(
        &[("a.gltf", doc.as_bytes())],
        &scene(
            r#"gltf: (file: "a.gltf")"#,
            ", transform: [Rotate(axis: (0, 1, 0), degrees: 90), Translate((0, 1, 0))]",
        ),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let object = Mat4::from_translation(Vec3::Y) * Mat4::from_rotation_y(90f32.to_radians());
    let world = object * trs(parent.0, parent.1, parent.2) * trs(child.0, child.1, child.2);
    let c = &loaded.view.camera;
    close(c.eye, world.transform_point3(Vec3::ZERO), "eye");
    close(
        c.forward,
        world.transform_vector3(-Vec3::Z).normalize(),
        "forward",
    );
    close(c.up, world.transform_vector3(Vec3::Y).normalize(), "up");
    assert!(
        (c.tan_half_fov - 0.3f32.tan()).abs() < 1e-6,
        "tan(fov/2) {}",
        c.tan_half_fov
    );
    assert!(matches!(c.projection, Projection::Perspective));
    let notes = notes_of(&loaded);
    assert!(
        notes.iter().any(|n| n.contains("aspect ratio is 1.500")),
        "no aspect note: {notes:?}"
    );
    assert!(
        !notes.iter().any(|n| n.contains("not used")),
        "the taken camera is called unused: {notes:?}"
    );

    // Without `gltf`, the asset's cameras are named in a note and the
    // scene's own is used.
    let own = load(
        &[("a.gltf", doc.as_bytes())],
        &scene("eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40", ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    close(own.view.camera.eye, Vec3::new(0.0, 0.0, 5.0), "own eye");
    let notes = notes_of(&own);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("1 camera(s) are not used") && n.contains("gltf: (file:")),
        "no note for the unused camera: {notes:?}"
    );
}

/// A camera far from the origin keeps its view direction: its target is
/// not one f32 step away from its eye (at 10⁷ a unit is one step).
#[test]
fn a_gltf_camera_far_out_keeps_its_direction() {
    let turn = Quat::from_rotation_y(0.3) * Quat::from_rotation_x(-0.2);
    let doc = asset(
        json!([perspective(0.5)]),
        json!([{"mesh": 0}, {"camera": 0, "translation": [1.0e7, 3.0e6, -2.0e7], "rotation": turn.to_array()}]),
        json!([0, 1]),
        json!({}),
    );
    let loaded = load(
        &[("a.gltf", doc.as_bytes())],
        &scene(r#"gltf: (file: "a.gltf")"#, ""),
    )
    .unwrap_or_else(|e| panic!("loads: {}", explain(e)));
    let want = turn * -Vec3::Z;
    let got = Vec3::from(loaded.view.camera.forward);
    assert!(got.angle_between(want) < 1e-4, "forward {got} against {want}");
}

/// `camera` picks by node name, camera name or `#index`; the first placed
/// is the default; an orthographic camera's `ymag` is half the view
/// height.
#[test]
fn a_gltf_camera_is_chosen_by_name_or_index() {
    let ortho = json!({"type": "orthographic", "name": "Plan",
        "orthographic": {"xmag": 3.0, "ymag": 3.0, "znear": 0.1, "zfar": 100.0}});
    let doc = asset(
        json!([perspective(0.5), ortho]),
        json!([
            {"mesh": 0},
            {"name": "Front", "camera": 0, "translation": [0, 0, 5]},
            {"name": "Top", "camera": 1, "translation": [0, 9, 0], "rotation": Quat::from_rotation_x(-std::f32::consts::FRAC_PI_2).to_array()},
        ]),
        json!([0, 1, 2]),
        json!({}),
    );
    let files: &[(&str, &[u8])] = &[("a.gltf", doc.as_bytes())];
    let eye_of = |camera: &str| {
        let loaded = load(files, &scene(camera, "")).unwrap_or_else(|e| panic!("{camera}: {}", explain(e)));
        (Vec3::from(loaded.view.camera.eye), loaded.view.camera.projection)
    };
    let (eye, projection) = eye_of(r#"gltf: (file: "a.gltf")"#);
    assert_eq!(eye, Vec3::new(0.0, 0.0, 5.0));
    assert!(matches!(projection, Projection::Perspective));
    for chosen in ["Top", "Plan", "#1"] {
        let (eye, projection) = eye_of(&format!(r#"gltf: (file: "a.gltf", camera: "{chosen}")"#));
        assert_eq!(eye, Vec3::new(0.0, 9.0, 0.0), "{chosen}");
        match projection {
            Projection::Orthographic { view_height } => assert_eq!(view_height, 6.0),
            p => panic!("{chosen}: {p:?}"),
        }
    }
    let e = error(files, &scene(r#"gltf: (file: "a.gltf", camera: "Side")"#, ""));
    assert!(
        e.contains("no camera named `Side`") && e.contains("`Front`") && e.contains("`Top`"),
        "{e}"
    );
}

/// A camera node the animation moves puts the camera where the keys say
/// at the frame drawn, and with an open shutter the camera moves while it
/// is open (motion blur), as the asset's rigid parts do.
/// A triangle and a camera 10 units down +z, which animation `dolly`
/// moves one unit a frame away from it (at 24 fps); also a fuzz seed.
pub(super) fn dolly_asset() -> String {
    let mut a = Asset::default();
    let tri = triangle(&mut a);
    // z from 10 to 34 over 1 s: one unit per frame at 24 fps.
    let times = a.floats(&[0.0, 1.0], "SCALAR");
    let values = a.floats(&[0.0, 0.0, 10.0, 0.0, 0.0, 34.0], "VEC3");
    a.gltf(json!({
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"camera": 0, "translation": [0, 0, 10]}],
        "meshes": [tri],
        "cameras": [perspective(0.5)],
        "animations": [{
            "name": "dolly",
            "channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
            "samplers": [{"input": times, "output": values}],
        }],
    }))
}

#[test]
fn an_animated_gltf_camera_follows_the_frame_and_blurs() {
    let doc = dolly_asset();
    let files: &[(&str, &[u8])] = &[("a.gltf", doc.as_bytes())];
    let at = |frame: i32, shutter: &str| {
        let camera = format!(r#"gltf: (file: "a.gltf"){shutter}"#);
        let text = scene(&camera, r#", animation: "dolly""#).replacen("Scene(", &animated(1, 48, frame), 1);
        load(files, &text).unwrap_or_else(|e| panic!("frame {frame}: {}", explain(e)))
    };
    let still = at(13, "");
    close(still.view.camera.eye, Vec3::new(0.0, 0.0, 22.0), "frame 13");
    assert!(still.view.shutter.is_none(), "a closed shutter moves nothing");
    let blurred = at(13, ", shutter: (0, 0.5)");
    close(blurred.view.camera.eye, Vec3::new(0.0, 0.0, 22.0), "the opening");
    let shutter = blurred
        .view
        .shutter
        .as_ref()
        .expect("an open shutter over a moving camera");
    let motion = shutter
        .camera
        .as_ref()
        .expect("the camera moves while the shutter is open");
    close(motion.at(13.5).eye, Vec3::new(0.0, 0.0, 22.5), "half a frame on");
}

/// Every way the camera choice can be wrong is located at what is wrong.
#[test]
fn a_wrong_gltf_camera_is_a_located_error() {
    let doc = asset(
        json!([perspective(0.5)]),
        json!([{"mesh": 0}, {"camera": 0, "translation": [0, 0, 5]}]),
        json!([0, 1]),
        json!({}),
    );
    let files: &[(&str, &[u8])] = &[("a.gltf", doc.as_bytes())];
    let cases = [
        // No object reads the file.
        (r#"gltf: (file: "b.gltf")"#, "", "no `Gltf` object reads `b.gltf`"),
        // The fields the asset's camera gives, written as well.
        (
            r#"eye: (0, 0, 3), fov_y_degrees: 30, gltf: (file: "a.gltf")"#,
            "",
            "`eye` is given by the glTF camera",
        ),
        // A lens with no distance in focus.
        (
            r#"aperture_radius: 0.1, gltf: (file: "a.gltf")"#,
            "",
            "needs `focus_distance`",
        ),
        // Neither an eye nor an asset's camera.
        (
            "target: (0, 0, 0), fov_y_degrees: 40",
            "",
            "the camera has no `eye`",
        ),
    ];
    for (camera, object, want) in cases {
        let e = error(files, &scene(camera, object));
        assert!(e.contains(want), "{camera}: wanted `{want}` in\n{e}");
        assert!(e.contains("scene.ron:"), "{camera}: not located\n{e}");
    }
    // An asset without a camera, one whose camera's node is scaled to
    // nothing, and one whose field of view is no angle.
    let broken = [
        (json!([]), json!([{"mesh": 0}]), json!([0]), "has no camera"),
        (
            json!([perspective(0.5)]),
            json!([{"mesh": 0}, {"camera": 0, "scale": [0, 0, 0]}]),
            json!([0, 1]),
            "no view direction",
        ),
        (
            json!([perspective(3.5)]),
            json!([{"mesh": 0}, {"camera": 0}]),
            json!([0, 1]),
            "yfov 3.5",
        ),
    ];
    for (cameras, nodes, roots, want) in broken {
        let doc = asset(cameras, nodes, roots, json!({}));
        let e = error(
            &[("a.gltf", doc.as_bytes())],
            &scene(r#"gltf: (file: "a.gltf")"#, ""),
        );
        assert!(e.contains(want), "wanted `{want}` in\n{e}");
    }
    // A camera whose type's object is missing (the `gltf` crate unwraps
    // it unchecked): an error at the object's file, whatever the camera.
    let mismatched = asset(
        json!([{"type": "perspective", "orthographic": {"xmag": 1, "ymag": 1, "znear": 0.1, "zfar": 9}}]),
        json!([{"mesh": 0}, {"camera": 0}]),
        json!([0, 1]),
        json!({}),
    );
    for camera in [
        r#"gltf: (file: "a.gltf")"#,
        "eye: (0, 0, 5), target: (0, 0, 0), fov_y_degrees: 40",
    ] {
        let e = error(&[("a.gltf", mismatched.as_bytes())], &scene(camera, ""));
        assert!(e.contains("cameras[0] has no `perspective` object"), "{e}");
    }
}
