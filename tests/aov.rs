//! AOV layers (`film.aovs`): written to EXR beside an unchanged beauty pass,
//! with the channel names compositors expect and first-hit values a Lambert
//! plane lets us check exactly; and their scene-file checks.

use crate::common;

use common::{load_in, ronray_in};
use ronray::aov::{AovSet, render_aovs};
use ronray::load::{LoadError, Overrides, load_str};
use std::collections::HashMap;
use std::path::Path;

/// A Lambert plane z = 0 seen head-on from z = 2, filling the view.
fn plane_scene(aovs: &str, output: &str) -> String {
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 2), target: (0, 0, 0), fov_y_degrees: 40),
    film: (width: 16, height: 16, spp: 4, output: "{output}", aovs: [{aovs}]),
    materials: {{ "paint": Lambert(albedo: (0.2, 0.5, 0.7)) }},
    lights: [Point(position: (0, 0, 1), intensity: (1, 1, 1))],
    objects: [Plane(point: (0, 0, 0), normal: (0, 0, 1), material: "paint")],
)"#
    )
}

/// Every channel of the EXR file at `path`, by name.
fn channels(path: &Path) -> HashMap<String, Vec<f64>> {
    use exr::prelude::{FlatSamples, read_all_flat_layers_from_file};
    let img = read_all_flat_layers_from_file(path).expect("the EXR reads back");
    assert_eq!(img.layer_data.len(), 1, "one part");
    img.layer_data[0]
        .channel_data
        .list
        .iter()
        .map(|c| {
            let v: Vec<f64> = match &c.sample_data {
                FlatSamples::F32(v) => v.iter().map(|x| f64::from(*x)).collect(),
                FlatSamples::U32(v) => v.iter().map(|x| f64::from(*x)).collect(),
                FlatSamples::F16(v) => v.iter().map(|x| f64::from(x.to_f32())).collect(),
            };
            (c.name.to_string(), v)
        })
        .collect()
}

#[test]
fn a_lambert_planes_layers_hold_its_albedo_normal_and_distance() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = plane_scene(
        "Albedo, Normal, Depth, Position, MaterialIndex, ObjectIndex",
        "plane.exr",
    );
    std::fs::write(dir.path().join("plane.ron"), &scene).expect("write scene");
    let out = ronray_in(dir.path(), &["render", "plane.ron"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let ch = channels(&dir.path().join("plane.exr"));
    let mut names: Vec<&str> = ch.keys().map(String::as_str).collect();
    names.sort_unstable();
    assert_eq!(
        names,
        [
            "B",
            "G",
            "N.X",
            "N.Y",
            "N.Z",
            "P.X",
            "P.Y",
            "P.Z",
            "R",
            "Z",
            "albedo.B",
            "albedo.G",
            "albedo.R",
            "materialId",
            "objectId"
        ]
    );
    let close = |name: &str, want: f64, tol: f64| {
        for (i, v) in ch[name].iter().enumerate() {
            assert!(
                (v - want).abs() <= tol,
                "{name} at pixel {i}: {v}, expected {want}"
            );
        }
    };
    // Albedo and normal are the same at every sample: exact up to f32.
    close("albedo.R", 0.2, 1e-6);
    close("albedo.G", 0.5, 1e-6);
    close("albedo.B", 0.7, 1e-6);
    close("N.X", 0.0, 1e-6);
    close("N.Y", 0.0, 1e-6);
    close("N.Z", 1.0, 1e-6);
    close("P.Z", 0.0, 1e-5);
    close("materialId", 1.0, 0.0);
    close("objectId", 1.0, 0.0);
    // Depth is the distance along each ray, eye to plane: the mean distance
    // to the pixel's hits is the distance to their mean point up to the
    // spread of 1/cos θ across one pixel (below 1e-3 here).
    let z = &ch["Z"];
    for i in 0..z.len() {
        let (px, py) = (ch["P.X"][i], ch["P.Y"][i]);
        let dist = (px * px + py * py + 4.0).sqrt();
        assert!(
            (z[i] - dist).abs() < 1e-3,
            "Z at pixel {i}: {}, eye to P {dist}",
            z[i]
        );
        assert!(
            z[i] >= 2.0 - 1e-5,
            "nothing on the plane is nearer than 2: {}",
            z[i]
        );
    }
    // The centre pixels look almost straight down the axis.
    let centre = z[8 * 16 + 8];
    assert!((centre - 2.0).abs() < 2e-3, "centre depth {centre}");
}

#[test]
fn layers_leave_the_beauty_pass_unchanged() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (name, aovs) in [("plain", ""), ("layered", "Albedo, Depth")] {
        std::fs::write(
            dir.path().join(format!("{name}.ron")),
            plane_scene(aovs, &format!("{name}.exr")),
        )
        .expect("write scene");
        let out = ronray_in(dir.path(), &["render", &format!("{name}.ron")]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let plain = channels(&dir.path().join("plain.exr"));
    let layered = channels(&dir.path().join("layered.exr"));
    assert_eq!(plain.len(), 3, "no layers unless asked");
    for c in ["R", "G", "B"] {
        assert_eq!(plain[c], layered[c], "beauty channel {c} changed");
    }
}

#[test]
fn layers_do_not_depend_on_the_thread_count() {
    let scene = r#"Scene(
    camera: (eye: (0, 1, 3), target: (0, 0, 0), fov_y_degrees: 50),
    film: (width: 24, height: 20, spp: 5),
    materials: { "a": Lambert(albedo: (0.8, 0.2, 0.2)), "b": Mirror(tint: (0.9, 0.9, 0.9)) },
    lights: [Point(position: (0, 3, 0), intensity: (5, 5, 5))],
    objects: [
        Sphere(center: (0, 0, 0), radius: 0.7, material: "b"),
        Plane(point: (0, -0.7, 0), normal: (0, 1, 0), material: "a"),
    ],
)"#;
    let l = load_in(Path::new("."), scene, &Overrides::default());
    let one = render_aovs(&l.scene, &l.view, AovSet::EMPTY, Some(1));
    let two = render_aovs(&l.scene, &l.view, AovSet::EMPTY, Some(2));
    assert!(one == two, "AOV layers differ between 1 and 2 threads");
    // The sphere's silhouette mixes ids: the majority wins, so every id is
    // one of the scene's (0 = sky, 1 = "a", 2 = "b").
    assert!(one.material_id.iter().all(|&m| m <= 2));
    assert!(one.material_id.contains(&1) && one.material_id.contains(&2) && one.material_id.contains(&0));
    // Object ids: 1 = the sphere, 2 = the plane (`objects` order), 0 = sky.
    assert!(one.object_id.iter().all(|&o| o <= 2));
    assert!(one.object_id.contains(&1) && one.object_id.contains(&2) && one.object_id.contains(&0));
    assert!(
        one.depth.iter().any(|d| d.is_infinite()),
        "sky pixels have infinite depth"
    );
}

/// Object ids tell apart objects that share a material, every triangle of a
/// mesh carries its object's id, and an area light's surface comes after
/// the objects. One sample per pixel, so no vote is split.
#[test]
fn object_ids_follow_the_objects_list_then_the_lights() {
    let scene = r#"Scene(
    camera: (eye: (0, 0, 4), target: (0, 0, 0), fov_y_degrees: 60),
    film: (width: 32, height: 32, spp: 1),
    materials: { "grey": Lambert(albedo: (0.5, 0.5, 0.5)) },
    lights: [Rect(center: (0, 1.4, 0), half_u: (0.3, 0, 0), half_v: (0, 0, 0.3), radiance: (1, 1, 1))],
    objects: [
        Sphere(center: (-1, 0, 0), radius: 0.5, material: "grey"),
        Mesh(file: "tall_block.obj", material: "grey", transform: [Scale((0.8, 0.8, 0.8)), Translate((1.3, 0, 0))]),
    ],
)"#;
    let l = load_in(&common::root().join("assets"), scene, &Overrides::default());
    let layers = render_aovs(&l.scene, &l.view, AovSet::EMPTY, Some(1));
    let at = |x: u32, y: u32| layers.object_id[(y * 32 + x) as usize];
    let ids: std::collections::BTreeSet<u32> = layers.object_id.iter().copied().collect();
    assert_eq!(
        ids.into_iter().collect::<Vec<_>>(),
        [0, 1, 2, 3],
        "sky, sphere, mesh, light"
    );
    assert!(
        layers.material_id.iter().all(|&m| m <= 2),
        "one material and the emitter"
    );
    // Left of centre the sphere, right of it the block, above them the light.
    assert_eq!(at(8, 16), 1);
    assert_eq!(at(0, 0), 0);
    let light_rows: Vec<u32> = (0..32).filter(|&y| at(16, y) == 3).collect();
    let block_rows: Vec<u32> = (0..32).filter(|&y| (20..32).any(|x| at(x, y) == 2)).collect();
    assert!(!light_rows.is_empty() && !block_rows.is_empty(), "{layers:?}");
    assert!(
        light_rows.iter().max() < block_rows.iter().min(),
        "the light is above the block"
    );
}

fn problems(text: &str) -> Vec<ronray::diagnostic::Diagnostic> {
    match load_str(Path::new("test.ron"), text, &Overrides::default()) {
        Err(LoadError::Invalid(r)) => r.diagnostics,
        Err(e) => panic!("expected diagnostics, got {e}"),
        Ok(_) => panic!("loaded, but it is broken on purpose:\n{text}"),
    }
}

#[test]
fn layers_into_a_png_or_twice_are_located_errors() {
    let d = problems(&plane_scene("Depth", "out.png"));
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path.as_deref(), Some("film.aovs"));
    assert_eq!(d[0].line, 3, "{}", d[0]);
    assert!(d[0].message.contains("only to EXR"), "{}", d[0]);
    let d = problems(&plane_scene("Depth, Normal, Depth", "out.exr"));
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path.as_deref(), Some("film.aovs[2]"));
    assert_eq!(d[0].line, 3, "{}", d[0]);
    assert!(d[0].message.contains("`Depth` is listed twice"), "{}", d[0]);
    let d = problems(&plane_scene("Albedo, Colour", "out.exr"));
    assert!(!d.is_empty() && d[0].line == 3, "{d:?}");
}

#[test]
fn a_png_output_with_layers_is_refused_on_the_command_line() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("p.ron"), plane_scene("Depth", "p.exr")).expect("write scene");
    let out = ronray_in(dir.path(), &["render", "p.ron", "-o", "p.png"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("not .exr"), "{err}");
    assert!(!dir.path().join("p.png").exists());
}

#[cfg(not(feature = "denoise"))]
#[test]
fn denoising_without_the_feature_says_how_to_enable_it() {
    let text = plane_scene("", "out.exr").replace("aovs: []", "denoise: true");
    let d = problems(&text);
    assert_eq!(d.len(), 1, "{d:?}");
    assert_eq!(d[0].path.as_deref(), Some("film.denoise"));
    assert!(
        d[0].help.as_deref().unwrap_or("").contains("--features denoise"),
        "{:?}",
        d[0]
    );
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("p.ron"), plane_scene("", "p.exr")).expect("write scene");
    let out = ronray_in(dir.path(), &["render", "p.ron", "--denoise"]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("fetch-oidn.sh") && err.contains("--features denoise"),
        "{err}"
    );
}
