//! Scene composition with `include`.

use ronray::load::{LoadError, Overrides, load_with};
use std::path::Path;

fn write(dir: &Path, name: &str, text: &str) {
    let p = dir.join(name);
    if let Some(parent) = p.parent() {
        std::fs::create_dir_all(parent).expect("mkdir");
    }
    std::fs::write(p, text).expect("write");
}

const CAMERA: &str = "camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40)";

/// The errors of a scene that must not load (the warnings shown with them
/// are left out).
fn diagnostics(path: &Path) -> Vec<ronray::diagnostic::Diagnostic> {
    match load_with(path, &Overrides::default()) {
        Err(LoadError::Invalid(r)) => r
            .diagnostics
            .into_iter()
            .filter(|d| d.severity == ronray::diagnostic::Severity::Error)
            .collect(),
        Err(e) => panic!("expected diagnostics, got {e}"),
        Ok(_) => panic!("{} should not load", path.display()),
    }
}

#[test]
fn include_composes_and_the_including_file_wins() {
    let d = tempfile::tempdir().expect("tmp");
    write(
        d.path(),
        "rig/studio.ron",
        r#"Include(
            materials: { "floor": Lambert(albedo: (0.5, 0.5, 0.5)), "white": Lambert(albedo: (0.9, 0.9, 0.9)) },
            lights: [Point(position: (0, 3, 0), intensity: (5, 5, 5))],
            objects: [Mesh(file: "block.obj", material: "floor")],
        )"#,
    );
    write(d.path(), "rig/block.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write(
        d.path(),
        "scene.ron",
        &format!(
            r#"Scene(include: ["rig/studio.ron"], {CAMERA},
            materials: {{ "white": Lambert(albedo: (0.1, 0.2, 0.3)) }},
            objects: [Sphere(center: (0, 0, 0), radius: 1, material: "white"), Plane(point: (0, -1, 0), normal: (0, 1, 0), material: "floor")],
        )"#
        ),
    );
    let l = load_with(&d.path().join("scene.ron"), &Overrides::default()).expect("composed scene loads");
    assert_eq!(l.desc.materials.len(), 2);
    assert_eq!(
        format!("{:?}", l.desc.materials["white"]),
        "Lambert { albedo: Rgb([0.1, 0.2, 0.3]) }",
        "the including file overrides"
    );
    assert_eq!(l.desc.lights.len(), 1, "lights from the include");
    assert_eq!(
        l.desc.objects.len(),
        3,
        "included objects first, then the scene's"
    );
    assert!(
        l.files.iter().any(|f| f.ends_with("rig/studio.ron")),
        "watch mode sees the include"
    );
    assert!(
        l.files.iter().any(|f| f.ends_with("rig/block.obj")),
        "the OBJ resolves next to the include"
    );
}

#[test]
fn problems_in_an_include_point_into_that_file() {
    let d = tempfile::tempdir().expect("tmp");
    write(
        d.path(),
        "parts.ron",
        "Include(\n    objects: [\n        Sphere(center: (0, 0, 0), radius: -2, material: \"white\"),\n    ],\n)\n",
    );
    write(
        d.path(),
        "scene.ron",
        &format!(
            "Scene(include: [\"parts.ron\"], {CAMERA}, materials: {{ \"white\": Lambert(albedo: (1, 1, 1)) }})"
        ),
    );
    let diags = diagnostics(&d.path().join("scene.ron"));
    assert_eq!(diags.len(), 1, "{diags:?}");
    assert!(
        diags[0].file.ends_with("parts.ron"),
        "reported in {}",
        diags[0].file.display()
    );
    assert_eq!((diags[0].line, diags[0].column), (3, 43), "{}", diags[0]);
    assert_eq!(diags[0].path.as_deref(), Some("objects[0].radius"));
}

#[test]
fn include_cycle_is_a_located_error() {
    let d = tempfile::tempdir().expect("tmp");
    write(d.path(), "a.ron", "Include(include: [\"b.ron\"])");
    write(d.path(), "b.ron", "Include(\n  include: [\"a.ron\"],\n)");
    write(
        d.path(),
        "scene.ron",
        &format!("Scene(include: [\"a.ron\"], {CAMERA})"),
    );
    let diags = diagnostics(&d.path().join("scene.ron"));
    assert_eq!(diags.len(), 1, "{diags:?}");
    let d0 = &diags[0];
    assert!(
        d0.message.contains("include cycle") && d0.message.contains("a.ron") && d0.message.contains("b.ron"),
        "{d0}"
    );
    assert!(
        d0.file.ends_with("b.ron") && d0.line == 2,
        "the include that closes the cycle: {d0}"
    );
    assert!(
        d0.help.as_deref().unwrap_or("").contains("a.ron"),
        "names the first inclusion: {d0}"
    );
}

#[test]
fn duplicate_name_across_includes_shows_both_locations() {
    let d = tempfile::tempdir().expect("tmp");
    write(
        d.path(),
        "one.ron",
        "Include(materials: {\n  \"metal\": Mirror(tint: (1, 1, 1)),\n})",
    );
    write(
        d.path(),
        "two.ron",
        "Include(\n  materials: {\n    \"metal\": Mirror(tint: (0.5, 0.5, 0.5)),\n  },\n)",
    );
    write(
        d.path(),
        "scene.ron",
        &format!("Scene(include: [\"one.ron\", \"two.ron\"], {CAMERA})"),
    );
    let diags = diagnostics(&d.path().join("scene.ron"));
    assert_eq!(diags.len(), 1, "{diags:?}");
    let d0 = &diags[0];
    assert!(
        d0.file.ends_with("two.ron") && d0.line == 3,
        "second definition located: {d0}"
    );
    let help = d0.help.clone().unwrap_or_default();
    assert!(
        help.contains("one.ron:2:"),
        "first definition located in the help: {help}"
    );
}

/// An included file is parsed like the scene: each mistake in it gets the
/// same did-you-mean, points into that file, and comes in the same run as
/// the including file's own mistakes. Its broken material keeps its name.
#[test]
fn mistakes_in_an_include_are_all_reported_with_the_scene_ones() {
    let d = tempfile::tempdir().expect("tmp");
    write(
        d.path(),
        "parts.ron",
        "Include(\n  materials: {\n    \"glass\": Glas(ior: 1.5),\n  },\n  objects: [\n    Sphere(center: (0, 0, 0), radius: 1, material: \"glass\"),\n    Sphere(center: (0, 0, 0), raduis: 1, material: \"glass\"),\n    Sphere(center: (0, 0, 0), radius: -3, material: \"glass\"),\n  ],\n)\n",
    );
    write(
        d.path(),
        "scene.ron",
        &format!(
            "Scene(include: [\"parts.ron\"], {CAMERA},\n  objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"glas\")],\n)"
        ),
    );
    let diags = diagnostics(&d.path().join("scene.ron"));
    let all: String = diags.iter().map(|d| format!("{d}\n")).collect();
    assert_eq!(diags.len(), 4, "{all}");
    let in_parts: Vec<_> = diags.iter().filter(|d| d.file.ends_with("parts.ron")).collect();
    assert_eq!(in_parts.len(), 3, "{all}");
    let variant = in_parts
        .iter()
        .find(|d| d.message.contains("unknown variant `Glas`"))
        .unwrap_or_else(|| panic!("{all}"));
    assert_eq!(
        (variant.line, variant.help.as_deref()),
        (3, Some("did you mean `Glass`?"))
    );
    let field = in_parts
        .iter()
        .find(|d| d.message.contains("unknown field `raduis`"))
        .unwrap_or_else(|| panic!("{all}"));
    assert_eq!(
        (field.line, field.help.as_deref()),
        (7, Some("did you mean `radius`?"))
    );
    let radius = in_parts
        .iter()
        .find(|d| d.path.as_deref() == Some("objects[2].radius"))
        .unwrap_or_else(|| panic!("the written index survives the dropped element:\n{all}"));
    assert_eq!(radius.line, 8, "{radius}");
    let top = diags
        .iter()
        .find(|d| d.file.ends_with("scene.ron"))
        .unwrap_or_else(|| panic!("{all}"));
    assert_eq!(top.path.as_deref(), Some("objects[0].material"), "{top}");
    assert_eq!(top.help.as_deref(), Some("did you mean `glass`?"), "{top}");
}

/// 27 files, each including the next twice: read once each, so the scene
/// loads at once instead of reading 2^27 files (issue 13).
#[test]
fn includes_named_twice_are_read_once() {
    let dir = tempfile::tempdir().expect("temp dir");
    let n = 27;
    for i in 0..n {
        let next = if i + 1 < n {
            format!("include: [\"f{}.ron\", \"f{}.ron\"],", i + 1, i + 1)
        } else {
            String::new()
        };
        write(
            dir.path(),
            &format!("f{i}.ron"),
            &format!("({next} materials: {{ \"m{i}\": Lambert(albedo: (0.5, 0.5, 0.5)) }})"),
        );
    }
    write(
        dir.path(),
        "scene.ron",
        &format!(
            "Scene(include: [\"f0.ron\"], {CAMERA}, lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))], objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"m26\")])"
        ),
    );
    let t = std::time::Instant::now();
    let loaded = load_with(&dir.path().join("scene.ron"), &Overrides::default())
        .unwrap_or_else(|e| panic!("{}", e.report().map(|r| r.render(false)).unwrap_or_default()));
    assert_eq!(loaded.desc.materials.len(), n);
    assert!(t.elapsed().as_secs() < 10, "took {:?}", t.elapsed());
}

/// A chain of includes deeper than the limit is a located error, not a
/// stack overflow.
#[test]
fn include_chain_deeper_than_the_limit_is_an_error() {
    let dir = tempfile::tempdir().expect("temp dir");
    let n = ronray::load::include::MAX_INCLUDE_DEPTH + 5;
    for i in 0..n {
        write(
            dir.path(),
            &format!("f{i}.ron"),
            &format!("(include: [\"f{}.ron\"])", i + 1),
        );
    }
    write(dir.path(), &format!("f{n}.ron"), "()");
    write(
        dir.path(),
        "scene.ron",
        &format!("Scene(include: [\"f0.ron\"], {CAMERA})"),
    );
    let d = diagnostics(&dir.path().join("scene.ron"));
    assert!(d.iter().any(|d| d.message.contains("nest deeper than")), "{d:?}");
}

/// A FIFO named as a scene or an include is refused at once: reading it
/// would block for ever (issue 13).
#[cfg(unix)]
#[test]
fn a_fifo_as_scene_or_include_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("temp dir");
    let fifo = dir.path().join("pipe.ron");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("skipped: mkfifo is not available");
        return;
    }
    match load_with(&fifo, &Overrides::default()) {
        Err(LoadError::Io { source, .. }) => {
            assert!(source.to_string().contains("not a regular file"), "{source}")
        }
        Err(e) => panic!("expected an I/O error, got {e}"),
        Ok(_) => panic!("a FIFO loaded"),
    }
    write(
        dir.path(),
        "scene.ron",
        &format!("Scene(include: [\"pipe.ron\"], {CAMERA})"),
    );
    let d = diagnostics(&dir.path().join("scene.ron"));
    assert!(
        d.iter().any(|d| d.message.contains("not a regular file")),
        "{d:?}"
    );
}

#[test]
fn included_environment_map_stays_relative_to_its_file() {
    let d = tempfile::tempdir().expect("tmp");
    write(
        d.path(),
        "rig/sky.ron",
        r#"Include(lights: [Environment(map: "maps/sky.exr", strength: 2)])"#,
    );
    std::fs::create_dir_all(d.path().join("rig/maps")).expect("mkdir");
    image::Rgb32FImage::from_pixel(8, 4, image::Rgb([0.5, 0.6, 0.7]))
        .save(d.path().join("rig/maps/sky.exr"))
        .expect("write exr");
    write(
        d.path(),
        "scene.ron",
        &format!(r#"Scene(include: ["rig/sky.ron"], {CAMERA})"#),
    );
    let l = load_with(&d.path().join("scene.ron"), &Overrides::default()).expect("the sky is found");
    let (_, env) = l.scene.environment().expect("an environment");
    assert!((env.le(glam::Vec3A::Y) - glam::Vec3A::new(1.0, 1.2, 1.4)).length() < 1e-5);
    assert!(
        l.files.iter().any(|f| f.ends_with("rig/maps/sky.exr")),
        "watch mode watches the map: {:?}",
        l.files
    );
}
