//! Each rule's edges: when it must stay silent as much as when it speaks.

use super::*;
use std::path::Path;

/// A scene with `body` inside `Scene(camera: …, materials: { "w": … }, …)`.
fn scene(body: &str) -> SceneDesc {
    let text = format!(
        r#"Scene(camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
        materials: {{ "w": Lambert(albedo: 0.5) }}, {body})"#
    );
    crate::load::source::parse(Path::new("t.ron"), &text).unwrap_or_else(|r| panic!("{r}\n{text}"))
}

fn paths(desc: &SceneDesc) -> Vec<String> {
    warnings(desc).into_iter().map(|p| p.path).collect()
}

/// An upward-facing quad light at y = 3 over `objects`.
fn up_light(objects: &str) -> SceneDesc {
    scene(&format!(
        "integrator: Path(), lights: [Quad(corner: (0, 3, 0), edge_u: (0, 0, 1), edge_v: (1, 0, 0), \
         radiance: (1, 1, 1))], objects: [{objects}]"
    ))
}

#[test]
fn facing_away_counts_only_what_is_behind() {
    let below = r#"Sphere(center: (0, 0, 0), radius: 1, material: "w")"#;
    assert_eq!(paths(&up_light(below)), ["lights[0]"]);
    // A sphere that pokes through the light's plane is lit.
    let through = r#"Sphere(center: (0, 2.5, 0), radius: 1, material: "w")"#;
    assert!(paths(&up_light(through)).is_empty());
    // The transform is applied before judging.
    let moved = r#"Sphere(center: (0, 0, 0), radius: 1, material: "w", transform: [Translate((0, 5, 0))])"#;
    assert!(paths(&up_light(moved)).is_empty());
    // A tilted infinite plane reaches the front side; a parallel one below does not.
    let tilted = r#"Plane(point: (0, 0, 0), normal: (0, 1, 1), material: "w")"#;
    assert!(paths(&up_light(tilted)).is_empty());
    let floor = r#"Plane(point: (0, 0, 0), normal: (0, -1, 0), material: "w")"#;
    assert_eq!(paths(&up_light(floor)), ["lights[0]"]);
}

#[test]
fn facing_away_stays_silent_when_bounds_are_unknown_or_absent() {
    let mesh = r#"Sphere(center: (0, 0, 0), radius: 1, material: "w"), Mesh(file: "any.obj")"#;
    assert!(paths(&up_light(mesh)).is_empty(), "a mesh might be above");
    let sdf = r#"Sdf(shape: Sphere(radius: 1), material: "w")"#;
    assert!(paths(&up_light(sdf)).is_empty(), "an SDF might be above");
    assert!(paths(&up_light("")).is_empty(), "no objects: nothing to face");
}

#[test]
fn facing_away_rect_help_names_half_edges_and_ignores_its_own_surface() {
    let d = scene(
        r#"integrator: Path(), lights: [Rect(center: (0, 3, 0), half_u: (0, 0, 1), half_v: (1, 0, 0),
        radiance: (1, 1, 1), material: "w")], objects: [Sphere(center: (0, 0, 0), radius: 1, material: "w")]"#,
    );
    let w = warnings(&d);
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].help
            .as_deref()
            .is_some_and(|h| h.contains("swap `half_u` and `half_v`")),
        "{w:?}"
    );
}

#[test]
fn specular_warning_needs_direct_and_a_user() {
    let lights = "lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))]";
    let with = |integrator: &str, material: &str| {
        let mut d = scene(&format!(
            r#"{integrator} {lights}, objects: [Sphere(center: (0, 0, 0), radius: 1, material: "m")]"#
        ));
        let m = ron::from_str(material).unwrap_or_else(|e| panic!("{e}: {material}"));
        d.materials.insert("m".into(), m);
        paths(&d)
    };
    assert_eq!(with("", "Mirror()"), ["materials.m"], "Direct is the default");
    assert_eq!(with("integrator: Direct(),", "Glass()"), ["materials.m"]);
    assert!(with("integrator: Whitted(),", "Mirror()").is_empty());
    assert!(with("integrator: Path(),", "Glass()").is_empty());
    let ct = |r: f32| format!("CookTorrance(roughness: {r}, fresnel: Metal(Gold))");
    assert_eq!(
        with("", &ct(0.0)),
        ["materials.m"],
        "roughness 0 is a mirror in effect"
    );
    assert!(with("", &ct(0.1)).is_empty());
    let mp = |m: f32| format!("MetalPlastic(base_color: 0.5, roughness: 0, metalness: {m})");
    assert_eq!(with("", &mp(1.0)), ["materials.m"]);
    assert!(with("", &mp(0.5)).is_empty(), "its diffuse base is lit");
}

#[test]
fn no_light_counts_power_not_entries() {
    assert_eq!(paths(&scene("")), ["lights"]);
    let spot =
        "lights: [Spot(position: (0, 3, 0), direction: (0, -1, 0), intensity: (0, 0, 1), cone_degrees: 30)]";
    assert!(paths(&scene(spot)).is_empty());
}

#[test]
fn narrow_fov_offers_radians_only_when_they_make_sense() {
    let lit = "lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))]";
    let mut d = scene(lit);
    d.camera.fov_y_degrees = Some(MIN_FOV_DEGREES);
    assert!(warnings(&d).is_empty(), "5° itself is fine");
    d.camera.fov_y_degrees = Some(4.0);
    let w = warnings(&d);
    assert_eq!(w.len(), 1);
    assert!(
        !w[0].help.as_deref().unwrap_or("").contains("radians"),
        "4 rad > 180°: {w:?}"
    );
    d.camera.fov_y_degrees = Some(1.0);
    assert!(warnings(&d)[0].help.as_deref().unwrap_or("").contains("57.3"));
}

#[test]
fn a_sun_travelling_upward_is_warned_with_the_flipped_direction() {
    let objects = r#"objects: [Sphere(center: (0, 0, 0), radius: 1, material: "w")]"#;
    let with = |light: &str| scene(&format!("integrator: Path(), lights: [{light}], {objects}"));
    // Written toward the sun: 45° up. The help offers the reverse.
    let up = with("Directional(direction: (1, 1, 0), irradiance: (3, 3, 3))");
    let w = warnings(&up);
    assert_eq!(
        w.iter().map(|p| p.path.as_str()).collect::<Vec<_>>(),
        ["lights[0].direction"]
    );
    assert!(w[0].message.contains("45° above the horizon"), "{}", w[0].message);
    assert!(
        w[0].help
            .as_deref()
            .is_some_and(|h| h.contains("(-0.707, -0.707, -0.000)")),
        "{:?}",
        w[0].help
    );
    // Downward, horizontal, barely upward (under 5°) and dark suns are fine.
    for ok in [
        "Directional(direction: (1, -1, 0), irradiance: (3, 3, 3))",
        "Directional(direction: (1, 0, 0), irradiance: (3, 3, 3))",
        "Directional(direction: (1, 0.05, 0), irradiance: (3, 3, 3))",
        "Directional(direction: (0, 1, 0), irradiance: (0, 0, 0))",
    ] {
        let d = with(&format!("{ok}, Point(position: (0, 3, 0), intensity: (1, 1, 1))"));
        assert!(paths(&d).is_empty(), "{ok}: {:?}", paths(&d));
    }
    // "Up" is the camera's: with +z up, a sun travelling along +z rises.
    let mut tilted = with("Directional(direction: (0, 0, 1), irradiance: (3, 3, 3))");
    assert!(paths(&tilted).is_empty());
    tilted.camera.up = [0.0, 0.0, 1.0];
    assert_eq!(paths(&tilted), ["lights[0].direction"]);
    // A sun is a light: the scene is not "black".
    assert!(emits(&with(
        "Directional(direction: (0, -1, 0), irradiance: (1, 0, 0))"
    )));
    assert!(!emits(&with(
        "Directional(direction: (0, -1, 0), irradiance: (0, 0, 0))"
    )));
}
