//! Paths a scene may touch (issue 13): `--root DIR` fences every input of
//! an untrusted scene, an include must be a scene fragment beside the scene
//! (its content is never echoed otherwise), and `validate -v` shows what a
//! scene reads and writes, resolved.

use crate::common;

use common::{ronray_in, root};
use ronray::load::{Overrides, load_str};
use std::path::Path;

const HEAD: &str = r#"camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40), film: (width: 8, height: 8, spp: 1),
    lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],"#;

/// A folder with `inside/` (the root) and `outside/` holding a secret, an
/// OBJ, an MTL and a texture, with links from inside to outside.
fn layout() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    let (inside, outside) = (dir.path().join("inside"), dir.path().join("outside"));
    std::fs::create_dir_all(&inside).expect("mkdir");
    std::fs::create_dir_all(&outside).expect("mkdir");
    let obj = root().join("tests/fixtures/hardening/block.obj");
    std::fs::copy(&obj, outside.join("block.obj")).expect("copy");
    std::fs::copy(&obj, inside.join("block.obj")).expect("copy");
    std::fs::write(
        outside.join("secret.ron"),
        "(materials: { \"stolen\": Lambert(albedo: (1, 1, 1)) })",
    )
    .expect("w");
    std::fs::write(outside.join("secret.txt"), "password=hunter2\n").expect("w");
    std::os::unix::fs::symlink(outside.join("secret.ron"), inside.join("linked.ron")).expect("link");
    std::os::unix::fs::symlink(outside.join("block.obj"), inside.join("linked.obj")).expect("link");
    std::fs::copy(root().join("scenes/golden/cornell.png"), outside.join("tex.png")).expect("copy");
    std::fs::copy(root().join("assets/sky_sun.exr"), outside.join("sky.exr")).expect("copy");
    // An OBJ inside whose MTL (and the MTL's texture) is outside.
    let text = std::fs::read_to_string(&obj).expect("read");
    std::fs::write(
        inside.join("with_mtl.obj"),
        format!("mtllib ../outside/m.mtl\nusemtl red\n{text}"),
    )
    .expect("w");
    std::fs::write(outside.join("m.mtl"), "newmtl red\nKd 1 0 0\n").expect("w");
    std::fs::write(
        inside.join("m_in.mtl"),
        "newmtl red\nKd 1 0 0\nmap_Kd ../outside/tex.png\n",
    )
    .expect("w");
    std::fs::write(
        inside.join("tex_mtl.obj"),
        format!("mtllib m_in.mtl\nusemtl red\n{text}"),
    )
    .expect("w");
    dir
}

fn fenced(root: &Path) -> Overrides {
    Overrides {
        root: Some(root.to_path_buf()),
        ..Default::default()
    }
}

/// Each kind of input outside `--root` is refused, symlinks resolved, with
/// a located error naming the path; the same scene loads without `--root`.
#[test]
fn root_refuses_every_input_outside_it() {
    let dir = layout();
    let inside = dir.path().join("inside");
    let m = r#"materials: { "m": Lambert(albedo: (0.5, 0.5, 0.5)) },"#;
    let cases = [
        (
            "include",
            format!("Scene({HEAD} include: [\"linked.ron\"])"),
            "secret.ron",
        ),
        (
            "OBJ",
            format!("Scene({HEAD} {m} objects: [Mesh(file: \"linked.obj\", material: \"m\")])"),
            "block.obj",
        ),
        (
            "OBJ ..",
            format!("Scene({HEAD} {m} objects: [Mesh(file: \"../outside/block.obj\", material: \"m\")])"),
            "block.obj",
        ),
        (
            "texture",
            format!(
                "Scene({HEAD} materials: {{ \"t\": Lambert(albedo: \"../outside/tex.png\") }}, objects: [Sphere(center: (0, 0, 0), radius: 1, material: \"t\")])"
            ),
            "tex.png",
        ),
        (
            "environment map",
            format!("Scene({HEAD} lights: [Environment(map: \"../outside/sky.exr\")])")
                .replace("lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],", ""),
            "sky.exr",
        ),
        (
            "MTL",
            format!("Scene({HEAD} objects: [Mesh(file: \"with_mtl.obj\")])"),
            "m.mtl",
        ),
        (
            "MTL texture",
            format!("Scene({HEAD} objects: [Mesh(file: \"tex_mtl.obj\")])"),
            "tex.png",
        ),
    ];
    for (what, text, named) in cases {
        let scene = inside.join("s.ron");
        let e = match load_str(&scene, &text, &fenced(&inside)) {
            Ok(_) => panic!("{what}: loaded under --root"),
            Err(e) => e,
        };
        let shown = common::message(&e);
        assert!(
            shown.contains("outside") && shown.contains(named),
            "{what}: {shown}"
        );
        let located = e
            .report()
            .expect("diagnostics")
            .diagnostics
            .iter()
            .any(|d| d.line > 0);
        assert!(located, "{what}: not located: {shown}");
        if what != "include" {
            assert!(
                load_str(&scene, &text, &Overrides::default()).is_ok(),
                "{what}: the scene itself is fine without --root"
            );
        }
    }
    // The scene file itself, from the command line.
    let o = ronray_in(
        dir.path(),
        &["validate", "outside/secret.ron", "--root", "inside"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("outside --root"),
        "{o:?}"
    );
    let ok = format!(
        "Scene({HEAD} objects: [Mesh(file: \"block.obj\", material: \"m\")], materials: {{ \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }})"
    );
    std::fs::write(inside.join("ok.ron"), ok).expect("w");
    let o = ronray_in(
        dir.path(),
        &[
            "render",
            "inside/ok.ron",
            "-o",
            "inside/ok.png",
            "--root",
            "inside",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// An include of a file that is not a scene fragment (`/etc/passwd`, a
/// `.txt`, a key) is refused at the include entry without reading it: its
/// content is never shown. Includes stay in the scene's folder.
#[test]
fn an_include_of_any_readable_file_does_not_echo_its_content() {
    let dir = layout();
    let inside = dir.path().join("inside");
    for (inc, expect) in [
        ("../outside/secret.txt", "not a scene file"),
        ("/etc/passwd", "not a scene file"),
        ("../outside/secret.ron", "outside the scene's folder"),
        ("linked.ron", "outside the scene's folder"),
    ] {
        let scene = inside.join("s.ron");
        std::fs::write(&scene, format!("Scene({HEAD} include: [\"{inc}\"])")).expect("w");
        let o = ronray_in(&inside, &["validate", "s.ron"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{inc}: {err}");
        assert!(err.contains(expect), "{inc}: {err}");
        assert!(
            !err.contains("hunter2") && !err.contains("root:") && !err.contains("stolen"),
            "{inc} echoed: {err}"
        );
    }
    // A non-UTF-8 fragment beside the scene: refused, none of it shown.
    std::fs::write(inside.join("binary.ron"), b"materials: \xff\xfe secret \x80").expect("w");
    std::fs::write(
        inside.join("s.ron"),
        format!("Scene({HEAD} include: [\"binary.ron\"])"),
    )
    .expect("w");
    let o = ronray_in(&inside, &["validate", "s.ron"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(err.contains("UTF-8") && !err.contains("secret"), "{err}");
    // --root widens where includes may come from.
    std::fs::write(
        inside.join("s.ron"),
        format!("Scene({HEAD} include: [\"../outside/secret.ron\"])"),
    )
    .expect("w");
    let o = ronray_in(dir.path(), &["validate", "inside/s.ron", "--root", "."]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `validate -v` lists every input and the output, resolved; `render`
/// names the file it wrote.
#[test]
fn validate_lists_inputs_and_outputs_resolved() {
    let dir = layout();
    let inside = dir.path().join("inside");
    let text = format!(
        "Scene({HEAD} film: (width: 8, height: 8, spp: 1, output: \"out/o.png\"), materials: {{ \"m\": Lambert(albedo: (0.5, 0.5, 0.5)) }}, objects: [Mesh(file: \"linked.obj\", material: \"m\")])"
    )
    .replacen("film: (width: 8, height: 8, spp: 1),", "", 1);
    std::fs::write(inside.join("s.ron"), text).expect("w");
    let o = ronray_in(&inside, &["validate", "-v", "s.ron"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let real = |p: &Path| std::fs::canonicalize(p).expect("exists").display().to_string();
    assert!(
        out.contains(&format!("reads  {}", real(&inside.join("s.ron")))),
        "{out}"
    );
    assert!(
        out.contains(&format!("reads  {}", real(&dir.path().join("outside/block.obj")))),
        "the link is resolved: {out}"
    );
    assert!(
        out.contains(&format!("writes {}", real(&inside).to_string() + "/out/o.png")),
        "{out}"
    );
    let o = ronray_in(&inside, &["render", "s.ron"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("wrote"), "{o:?}");
}
