//! No file the user did not name is ever written (issue 39): a scene's own
//! output or golden that is a link out of its folder, `assemble -o` naming
//! one of its pieces, `fmt` through links, hard links and read-only files,
//! and a render killed while it writes.

use crate::common;

use common::{ronray_in, root};
use std::io::{BufRead, BufReader};
use std::os::unix::fs::{PermissionsExt, symlink};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A tiny scene writing `film.output: "out.png"`.
const SCENE: &str = r#"Scene(
    camera: (eye: (0, 1, 4), target: (0, 0, 0), fov_y_degrees: 40),
    film: (width: 8, height: 8, spp: 1, output: "out.png"),
    materials: { "m": Lambert(albedo: (0.5, 0.5, 0.5)) },
    lights: [Point(position: (0, 3, 0), intensity: (1, 1, 1))],
    objects: [Sphere(center: (0, 0, 0), radius: 1, material: "m")],
    test: (width: 8, height: 8, spp: 1),
)
"#;

const NOTES: &str = "my notes, not an image\n";

/// `dir/notes.txt` beside `dir/repo/scene.ron`, whose `out.png` is a link
/// to `../notes.txt`: the repository a stranger ships.
fn hostile_repo() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("temp dir");
    let repo = dir.path().join("repo");
    std::fs::create_dir(&repo).expect("mkdir");
    std::fs::write(repo.join("scene.ron"), SCENE).expect("write");
    std::fs::write(dir.path().join("notes.txt"), NOTES).expect("write");
    symlink("../notes.txt", repo.join("out.png")).expect("link");
    (dir, repo)
}

fn notes(dir: &Path) -> String {
    std::fs::read_to_string(dir.join("notes.txt")).expect("notes")
}

fn stderr(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn render_refuses_a_scene_output_linked_out_of_its_folder() {
    let (dir, repo) = hostile_repo();
    let o = ronray_in(&repo, &["render", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("outside"), "{}", stderr(&o));
    assert_eq!(notes(dir.path()), NOTES, "the notes were replaced");
    // Also from another folder, and under --root.
    let r = dir.path().display().to_string();
    let o = ronray_in(dir.path(), &["--root", &r, "render", "repo/scene.ron"]);
    assert!(o.status.success(), "--root widens the fence: {}", stderr(&o));
    std::fs::write(dir.path().join("notes.txt"), NOTES).expect("restore");
    let r = repo.display().to_string();
    let o = ronray_in(dir.path(), &["--root", &r, "render", "repo/scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(notes(dir.path()), NOTES);
    // A link that stays inside the folder is followed, and `-o` is the
    // user's own choice.
    std::fs::remove_file(repo.join("out.png")).expect("rm");
    std::fs::create_dir(repo.join("renders")).expect("mkdir");
    symlink("renders/latest.png", repo.join("out.png")).expect("link");
    let o = ronray_in(&repo, &["render", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(repo.join("renders/latest.png").is_file());
    let o = ronray_in(&repo, &["render", "scene.ron", "-o", "../picked.png"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

#[test]
fn a_folder_link_on_the_way_out_is_refused_too() {
    let dir = tempfile::tempdir().expect("temp dir");
    let repo = dir.path().join("repo");
    std::fs::create_dir(&repo).expect("mkdir");
    std::fs::write(
        repo.join("scene.ron"),
        SCENE.replace("\"out.png\"", "\"up/notes.png\""),
    )
    .expect("write");
    symlink("..", repo.join("up")).expect("link");
    let o = ronray_in(&repo, &["render", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(!dir.path().join("notes.png").exists());
}

#[test]
fn watch_refuses_a_scene_output_linked_out_of_its_folder() {
    let (dir, repo) = hostile_repo();
    let mut child = Command::new(env!("CARGO_BIN_EXE_ronray"))
        .current_dir(&repo)
        .args(["watch", "scene.ron"])
        .stdin(Stdio::null())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("watch starts");
    let err = child.stderr.take().expect("stderr");
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(err).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    let start = Instant::now();
    let mut seen = Vec::new();
    while start.elapsed() < Duration::from_secs(60) {
        if let Ok(line) = rx.recv_timeout(Duration::from_millis(100)) {
            seen.push(line);
            if seen.iter().any(|l| l.contains("outside")) {
                break;
            }
        }
    }
    let _ = child.kill();
    let _ = child.wait();
    assert!(seen.iter().any(|l| l.contains("outside")), "{seen:?}");
    assert_eq!(notes(dir.path()), NOTES, "the notes were replaced");
}

#[test]
fn check_bless_refuses_a_golden_linked_out_of_the_folder() {
    let (dir, repo) = hostile_repo();
    std::fs::create_dir(repo.join("golden")).expect("mkdir");
    symlink("../../notes.txt", repo.join("golden/scene.png")).expect("link");
    let o = ronray_in(&repo, &["check", "scene.ron", "--bless", "--force"]);
    assert_ne!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("outside") || String::from_utf8_lossy(&o.stdout).contains("outside"),
        "{}{}",
        stderr(&o),
        String::from_utf8_lossy(&o.stdout)
    );
    assert_eq!(notes(dir.path()), NOTES, "the notes were replaced");
}

#[test]
fn assemble_refuses_an_output_that_is_one_of_its_pieces() {
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = root().join("scenes/cornell.ron").display().to_string();
    for i in 0..2 {
        let tile = format!("{i}/2");
        let o = ronray_in(
            dir.path(),
            &[
                "render",
                &scene,
                "--size",
                "16x16",
                "--spp",
                "1",
                "--tile",
                &tile,
                "-o",
                "t{tile}.exr",
            ],
        );
        assert!(o.status.success(), "{}", stderr(&o));
    }
    symlink("t1.exr", dir.path().join("link.exr")).expect("link");
    let before = std::fs::read(dir.path().join("t1.exr")).expect("piece");
    for out in ["t1.exr", "link.exr", "./t1.exr"] {
        let o = ronray_in(dir.path(), &["assemble", "t0.exr", "t1.exr", "-o", out]);
        assert_eq!(o.status.code(), Some(1), "-o {out}: {}", stderr(&o));
        assert!(stderr(&o).contains("would replace the piece"), "{}", stderr(&o));
        assert_eq!(std::fs::read(dir.path().join("t1.exr")).expect("piece"), before);
    }
    let o = ronray_in(dir.path(), &["assemble", "t0.exr", "t1.exr", "-o", "frame.exr"]);
    assert!(o.status.success(), "{}", stderr(&o));
}

/// A scene file laid out badly, so that `fmt` has something to write.
const UGLY: &str = "Scene(camera:(eye:(0,1,4),target:(0,0,0),fov_y_degrees:40),\nlights:[Point(position:(0,3,0),intensity:(1,1,1))])\n";

#[test]
fn fmt_writes_through_links_keeps_mode_and_hard_links_and_refuses_read_only_files() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    // Through a symlink: the link stays, its target is formatted.
    std::fs::create_dir(d.join("real")).expect("mkdir");
    std::fs::write(d.join("real/a.ron"), UGLY).expect("write");
    std::fs::set_permissions(d.join("real/a.ron"), std::fs::Permissions::from_mode(0o664)).expect("chmod");
    symlink("real/a.ron", d.join("link.ron")).expect("link");
    let o = ronray_in(d, &["fmt", "link.ron"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let meta = std::fs::symlink_metadata(d.join("link.ron")).expect("meta");
    assert!(meta.file_type().is_symlink(), "the link was replaced by a file");
    let formatted = std::fs::read_to_string(d.join("real/a.ron")).expect("read");
    assert_ne!(formatted, UGLY, "the target was not formatted");
    let mode = std::fs::metadata(d.join("real/a.ron"))
        .expect("meta")
        .permissions()
        .mode()
        & 0o7777;
    assert_eq!(mode, 0o664, "mode {mode:o}");
    // A hard link keeps sharing the file.
    std::fs::write(d.join("b.ron"), UGLY).expect("write");
    std::fs::hard_link(d.join("b.ron"), d.join("b2.ron")).expect("hard link");
    let o = ronray_in(d, &["fmt", "b.ron"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        std::fs::read_to_string(d.join("b2.ron")).expect("read"),
        std::fs::read_to_string(d.join("b.ron")).expect("read"),
        "the hard link was broken"
    );
    assert_ne!(std::fs::read_to_string(d.join("b2.ron")).expect("read"), UGLY);
    // A read-only file is refused and left alone.
    std::fs::write(d.join("c.ron"), UGLY).expect("write");
    std::fs::set_permissions(d.join("c.ron"), std::fs::Permissions::from_mode(0o444)).expect("chmod");
    let o = ronray_in(d, &["fmt", "c.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("read-only"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(d.join("c.ron")).expect("read"), UGLY);
}

#[test]
fn fmt_keeps_json_numbers_as_written() {
    let dir = tempfile::tempdir().expect("temp dir");
    let text = r#"{"camera": {"eye": [1e-50, 1, 4], "target": [0,0,0], "fov_y_degrees": 40},
"lights": [{"Point": {"position": [0, 3, 0], "intensity": [1e38, 1, 1]}}]}"#;
    std::fs::write(dir.path().join("s.json"), text).expect("write");
    let o = ronray_in(dir.path(), &["fmt", "s.json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = std::fs::read_to_string(dir.path().join("s.json")).expect("read");
    assert!(out.contains("1e-50") && out.contains("1e38"), "{out}");
}

fn temporaries(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .expect("list")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(".ronray-"))
        .collect()
}

/// SIGTERM (what a scheduler sends a job it cancels) while the image is
/// being written: the temporary file goes, as on Ctrl-C.
#[test]
fn sigterm_during_the_final_write_removes_the_temporary_file() {
    let dir = tempfile::tempdir().expect("temp dir");
    // A large, cheap frame: rendering is quick and the PNG takes a while to
    // encode, so the temporary file is seen before the write ends.
    std::fs::write(
        dir.path().join("big.ron"),
        SCENE.replace("width: 8, height: 8", "width: 4096, height: 4096"),
    )
    .expect("write");
    for attempt in 0..3 {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ronray"))
            .current_dir(dir.path())
            .args(["render", "big.ron", "-o", "big.png"])
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("render starts");
        let start = Instant::now();
        let mut seen = false;
        while start.elapsed() < Duration::from_secs(120) {
            if !temporaries(dir.path()).is_empty() {
                seen = true;
                break;
            }
            if child.try_wait().expect("wait").is_some() {
                break;
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        if seen {
            let pid = child.id().to_string();
            let kill = Command::new("kill").args(["-TERM", &pid]).status().expect("kill");
            assert!(kill.success());
            let status = child.wait().expect("wait");
            if status.success() {
                // The write ended before the signal landed: try again.
                continue;
            }
            assert!(
                temporaries(dir.path()).is_empty(),
                "left behind: {:?}",
                temporaries(dir.path())
            );
            return;
        }
        let _ = child.kill();
        let _ = child.wait();
        eprintln!("attempt {attempt}: the write was over before it was seen");
    }
    panic!("never caught the render while it wrote");
}
