//! `ronray watch` driven as a user drives it: a real process on a temp
//! folder, edited the ways editors save, read through the lines it prints.
//! Every wait has a deadline and the process dies with its guard.

use ronray::frame::{Pixels, Plan, RenderOptions, Request, render_whole};
use ronray::imageio::SampleSums;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::AtomicBool;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime};

/// Generous for a loaded 2-core machine; a passing test takes about a second.
const DEADLINE: Duration = Duration::from_secs(30);
/// How long nothing must happen for "nothing happened" to count.
const SETTLE: Duration = Duration::from_millis(1200);

const TRIANGLE: &str = "v -0.6 -0.6 0\nv 0.4 -0.6 0\nv -0.1 0.4 0\nf 1 2 3\n";

fn scene(albedo: &str, radius: f32, mesh: &str) -> String {
    format!(
        r#"Scene(
    camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
    film: (width: 48, height: 48, spp: 8, seed: 3),
    materials: {{ "ball": Lambert(albedo: ({albedo})), "grey": Lambert(albedo: (0.6, 0.6, 0.6)) }},
    lights: [ Point(position: (0, 2, 3), intensity: (6, 6, 6)) ],
    objects: [
        Sphere(center: (0.5, 0.2, 0), radius: {radius}, material: "ball"),
        Mesh(file: "{mesh}", material: "grey"),
    ],
)
"#
    )
}

/// A running `ronray watch` on its own folder; killed when dropped.
struct Watch {
    child: Child,
    log: Arc<Mutex<Vec<String>>>,
    dir: tempfile::TempDir,
}

impl Drop for Watch {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn collect(stream: impl Read + Send + 'static, log: Arc<Mutex<Vec<String>>>) {
    std::thread::spawn(move || {
        for line in BufReader::new(stream).lines().map_while(Result::ok) {
            log.lock().expect("log").push(line);
        }
    });
}

impl Watch {
    /// Writes the default scene and its OBJ, starts watching, and waits for
    /// the first complete image.
    fn start() -> Watch {
        Watch::start_with(&[
            ("tri.obj", TRIANGLE),
            ("scene.ron", &scene("0.8, 0.2, 0.2", 0.4, "tri.obj")),
        ])
    }

    /// Writes `files` (`scene.ron` among them), starts watching, and waits
    /// for the first complete image.
    fn start_with(files: &[(&str, &str)]) -> Watch {
        let dir = tempfile::tempdir().expect("temp dir");
        for (name, text) in files {
            std::fs::write(dir.path().join(name), text).expect("write");
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_ronray"))
            .current_dir(dir.path())
            .args(["watch", "scene.ron", "-o", "out.png"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("ronray watch starts");
        let log = Arc::new(Mutex::new(Vec::new()));
        collect(child.stdout.take().expect("stdout"), log.clone());
        collect(child.stderr.take().expect("stderr"), log.clone());
        let w = Watch { child, log, dir };
        w.wait_finals(1);
        w
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    fn log(&self) -> Vec<String> {
        self.log.lock().expect("log").clone()
    }

    fn image(&self) -> Vec<u8> {
        std::fs::read(self.path("out.png")).expect("out.png exists")
    }

    fn wait_until(&self, what: &str, done: impl Fn(&[String]) -> bool) {
        let start = Instant::now();
        while !done(&self.log()) {
            assert!(
                start.elapsed() < DEADLINE,
                "waited {DEADLINE:?} for {what}; output was:\n{}",
                self.log().join("\n")
            );
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    /// Waits until `n` complete images (last passes) have been written.
    fn wait_finals(&self, n: usize) {
        self.wait_until(&format!("{n} complete images"), |log| finals(log) >= n);
    }

    /// Waits until nothing has been printed for [`SETTLE`]; returns the log.
    fn settle(&self) -> Vec<String> {
        let start = Instant::now();
        let mut seen = self.log().len();
        let mut since = Instant::now();
        while since.elapsed() < SETTLE {
            std::thread::sleep(Duration::from_millis(20));
            let now = self.log().len();
            if now != seen {
                (seen, since) = (now, Instant::now());
            }
            assert!(
                start.elapsed() < DEADLINE,
                "never settled:\n{}",
                self.log().join("\n")
            );
        }
        self.log()
    }

    /// `ronray render` of the scene file as it is now, for comparison.
    fn reference(&self) -> Vec<u8> {
        let out = self.path("reference.png");
        let o = Command::new(env!("CARGO_BIN_EXE_ronray"))
            .current_dir(self.dir.path())
            .args(["render", "scene.ron", "-o"])
            .arg(&out)
            .output()
            .expect("ronray render runs");
        assert!(
            o.status.success(),
            "render failed: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        std::fs::read(out).expect("reference written")
    }
}

/// Last passes written: `pass n/n: … written`.
fn finals(log: &[String]) -> usize {
    log.iter()
        .filter(|l| {
            l.strip_prefix("pass ")
                .and_then(|r| r.split_once(':'))
                .and_then(|(k, rest)| k.split_once('/').filter(|(a, b)| a == b).map(|_| rest))
                .is_some_and(|rest| rest.contains("written to"))
        })
        .count()
}

fn changes(log: &[String]) -> usize {
    log.iter().filter(|l| l.starts_with("change ")).count()
}

#[test]
fn watch_renders_an_edit_identically_to_render() {
    let w = Watch::start();
    let first = w.image();
    assert_eq!(
        first,
        w.reference(),
        "the first image is not what `render` writes"
    );
    std::fs::write(w.path("scene.ron"), scene("0.2, 0.3, 0.9", 0.4, "tri.obj")).expect("edit");
    w.wait_finals(2);
    let second = w.image();
    assert_ne!(first, second, "the edit did not change the image");
    assert_eq!(
        second,
        w.reference(),
        "the progressive image is not what `render` writes"
    );
    let log = w.log();
    assert!(
        log.iter()
            .any(|l| l.starts_with("pass 1/4: 1 spp written to out.png")),
        "{log:?}"
    );
}

#[test]
fn watch_follows_a_rename_over_save() {
    let w = Watch::start();
    let first = w.image();
    // What vim and most IDEs do: write a new file, rename it over the old.
    let tmp = w.path(".scene.ron.swp");
    std::fs::write(&tmp, scene("0.2, 0.9, 0.2", 0.3, "tri.obj")).expect("write temp");
    std::fs::rename(&tmp, w.path("scene.ron")).expect("rename over");
    w.wait_finals(2);
    assert_ne!(first, w.image());
    assert_eq!(w.image(), w.reference());
    // The watch survived the old file's inode going away.
    std::fs::write(w.path("scene.ron"), scene("0.9, 0.9, 0.2", 0.3, "tri.obj")).expect("edit");
    w.wait_finals(3);
}

#[test]
fn watch_keeps_the_last_good_image_on_an_invalid_edit() {
    let w = Watch::start();
    let good = w.image();
    let broken = scene("0.2, 0.3, 0.9", 0.4, "tri.obj").replace("material: \"ball\"", "material: \"bal\"");
    std::fs::write(w.path("scene.ron"), broken).expect("edit");
    w.wait_until("the diagnostics", |log| {
        log.iter().any(|l| l.contains("keeping the last good image"))
    });
    let log = w.settle();
    let text = log.join("\n");
    assert!(text.contains("unknown material `bal`"), "no diagnostic:\n{text}");
    assert!(text.contains("scene.ron:7:"), "no location:\n{text}");
    assert!(text.contains("did you mean `ball`?"), "no suggestion:\n{text}");
    assert_eq!(finals(&log), 1, "an invalid edit rendered:\n{text}");
    assert_eq!(w.image(), good, "an invalid edit touched the image");
    std::fs::write(w.path("scene.ron"), scene("0.2, 0.3, 0.9", 0.4, "tri.obj")).expect("fix");
    w.wait_finals(2);
    assert_ne!(w.image(), good);
    assert_eq!(w.image(), w.reference());
}

#[test]
fn watch_rerenders_when_a_referenced_obj_changes() {
    let w = Watch::start();
    let first = w.image();
    std::fs::write(w.path("tri.obj"), TRIANGLE.replace("-0.1 0.4 0", "-0.5 0.6 0")).expect("edit obj");
    w.wait_finals(2);
    let second = w.image();
    assert_ne!(first, second, "moving a vertex did not change the image");
    assert_eq!(second, w.reference());
    // Touching the file (a build tool re-exporting it) renders again.
    let obj = std::fs::File::options()
        .write(true)
        .open(w.path("tri.obj"))
        .expect("open");
    obj.set_modified(SystemTime::now() + Duration::from_secs(5))
        .expect("touch");
    w.wait_finals(3);
    assert_eq!(w.image(), second);
}

/// A triangle whose material comes from its MTL file (the scene names none).
const MTL_TRIANGLE: &str =
    "mtllib tri.mtl\nv -0.6 -0.6 0\nv 0.4 -0.6 0\nv -0.1 0.4 0\nusemtl paint\nf 1 2 3\n";

/// The scene of [`scene`] with the triangle keeping its MTL material.
fn mtl_scene(albedo: &str) -> String {
    scene(albedo, 0.4, "tri.obj").replace(
        r#"Mesh(file: "tri.obj", material: "grey")"#,
        r#"Mesh(file: "tri.obj")"#,
    )
}

/// Falsehood 1 of issue 46: after an MTL colour edit and a scene edit, the
/// watch image kept the old colour while `render` gave the new one (the MTL
/// was not watched, and the mesh cache kept the materials it was first read
/// with).
#[test]
fn watch_follows_an_mtl_edit() {
    let w = Watch::start_with(&[
        ("tri.obj", MTL_TRIANGLE),
        ("tri.mtl", "newmtl paint\nKd 0.8 0.1 0.1\n"),
        ("scene.ron", &mtl_scene("0.8, 0.2, 0.2")),
    ]);
    let first = w.image();
    std::fs::write(w.path("tri.mtl"), "newmtl paint\nKd 0.1 0.7 0.15\n").expect("edit mtl");
    std::fs::write(w.path("scene.ron"), mtl_scene("0.2, 0.3, 0.9")).expect("edit scene");
    w.wait_finals(2);
    let log = w.settle();
    assert_ne!(w.image(), first, "the edits did not change the image");
    assert_eq!(w.image(), w.reference(), "after an MTL edit and a scene edit");
    assert!(
        log.iter().any(|l| l.contains("3 files watched")),
        "the scene, the OBJ and the MTL are watched:\n{}",
        log.join("\n")
    );
    // An MTL edit alone re-renders.
    let n = finals(&log);
    std::fs::write(w.path("tri.mtl"), "newmtl paint\nKd 0.7 0.7 0.1\n").expect("edit mtl");
    w.wait_finals(n + 1);
    w.settle();
    assert_eq!(w.image(), w.reference(), "after an MTL edit alone");
}

#[test]
fn watch_rearms_when_a_missing_obj_appears_in_another_folder() {
    let w = Watch::start();
    std::fs::create_dir(w.path("meshes")).expect("mkdir");
    std::fs::write(w.path("scene.ron"), scene("0.8, 0.2, 0.2", 0.4, "meshes/new.obj")).expect("edit");
    w.wait_until("a missing-OBJ diagnostic", |log| {
        log.iter().any(|l| l.contains("keeping the last good image"))
    });
    std::fs::write(
        w.path("meshes/new.obj"),
        TRIANGLE.replace("0.4 -0.6 0", "0.6 -0.2 0"),
    )
    .expect("obj");
    w.wait_finals(2);
    assert_eq!(w.image(), w.reference());
    std::fs::write(w.path("meshes/new.obj"), TRIANGLE).expect("edit obj");
    w.wait_finals(3);
    assert_eq!(w.image(), w.reference());
}

#[test]
fn watch_burst_of_saves_ends_in_the_last_content() {
    let w = Watch::start();
    let before = changes(&w.log());
    for i in 0..20 {
        let colour = format!("0.{}, 0.5, 0.{}", 9 - i % 9, 1 + i % 8);
        std::fs::write(
            w.path("scene.ron"),
            scene(&colour, 0.2 + 0.01 * i as f32, "tri.obj"),
        )
        .expect("save");
        std::thread::sleep(Duration::from_millis(15));
    }
    let log = w.settle();
    let last = log.last().cloned().unwrap_or_default();
    assert!(
        last.starts_with("pass 4/4:"),
        "did not end on a complete image: {last}"
    );
    assert!(changes(&log) - before < 20, "every save reloaded: no debouncing");
    assert_eq!(
        w.image(),
        w.reference(),
        "the final image is not the last content's"
    );
}

/// An editor that saves twice, or a save of unchanged text, does not start
/// the render again: the complete image on screen is already that scene's.
#[test]
fn watch_does_not_rerender_a_save_that_changed_nothing() {
    let w = Watch::start();
    let text = std::fs::read_to_string(w.path("scene.ron")).expect("scene");
    std::fs::write(w.path("scene.ron"), &text).expect("same text again");
    std::fs::write(w.path("scene.ron"), &text).expect("and again");
    let log = w.settle();
    assert_eq!(
        changes(&log),
        1,
        "an unchanged save re-rendered:\n{}",
        log.join("\n")
    );
    // A real edit still renders.
    std::fs::write(w.path("scene.ron"), scene("0.2, 0.2, 0.8", 0.4, "tri.obj")).expect("edit");
    w.wait_finals(2);
    assert_eq!(changes(&w.settle()), 2);
}

#[test]
fn watch_ignores_its_own_output() {
    let w = Watch::start();
    let log = w.settle();
    assert_eq!(
        changes(&log),
        1,
        "writing the image triggered a reload:\n{}",
        log.join("\n")
    );
    std::fs::write(w.path("out.png"), b"not a png").expect("overwrite output");
    std::fs::write(w.path(".ronray-x1.png.tmp"), b"temp").expect("temp");
    std::fs::rename(w.path(".ronray-x1.png.tmp"), w.path("out.png")).expect("rename");
    std::fs::write(w.path("unrelated.txt"), b"x").expect("unrelated");
    let log = w.settle();
    assert_eq!(
        changes(&log),
        1,
        "output changes triggered a reload:\n{}",
        log.join("\n")
    );
}

#[test]
fn watch_passes_add_up_to_render_bit_for_bit() {
    let dir = tempfile::tempdir().expect("temp dir");
    std::fs::write(dir.path().join("tri.obj"), TRIANGLE).expect("obj");
    let path: &Path = &dir.path().join("s.ron");
    let loaded = ronray::load::load_str(path, &scene("0.8, 0.2, 0.2", 0.4, "tri.obj"), &Default::default())
        .expect("scene loads");
    let (full, _) = render_whole(&loaded.scene, &loaded.view, &RenderOptions::default());
    let mut sums = SampleSums::new(ronray::imageio::PixelRect::full(48, 48));
    for k in 0..4 {
        let plan = Plan::new(&loaded.scene, &loaded.view, Request::Pass { k }, false).expect("pass k of 4");
        let opts = RenderOptions::default();
        let (pass, _) = ronray::frame::render(
            &loaded.scene,
            &loaded.view,
            &plan,
            &opts,
            &AtomicBool::new(false),
            &|_| {},
        );
        match pass {
            Pixels::Sums(pass) => sums.add(&pass),
            Pixels::Means(_) => panic!("a watch pass keeps exact sums"),
        }
    }
    assert!(
        sums.mean(8) == full,
        "passes 1+1+2+4 differ from one 8-sample render"
    );
}

#[test]
fn watch_waits_for_a_scene_that_is_briefly_missing() {
    let w = Watch::start();
    std::fs::remove_file(w.path("scene.ron")).expect("remove");
    w.wait_until("the missing-file notice", |log| {
        log.iter().any(|l| l.contains("is missing; waiting"))
    });
    std::fs::write(w.path("scene.ron"), scene("0.2, 0.9, 0.9", 0.4, "tri.obj")).expect("recreate");
    w.wait_finals(2);
    assert_eq!(w.image(), w.reference());
}

#[cfg(unix)]
#[test]
fn watch_stops_cleanly_on_ctrl_c() {
    let mut w = Watch::start();
    let pid = w.child.id().to_string();
    let kill = Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .expect("kill runs");
    assert!(kill.success());
    let start = Instant::now();
    let status = loop {
        if let Some(s) = w.child.try_wait().expect("wait") {
            break s;
        }
        assert!(start.elapsed() < DEADLINE, "still running after Ctrl-C");
        std::thread::sleep(Duration::from_millis(10));
    };
    assert!(status.success(), "exit status {status}");
    w.wait_until("the goodbye", |log| log.last().is_some_and(|l| l == "stopped"));
}

#[test]
fn watch_prints_warnings_and_still_renders() {
    let w = Watch::start();
    let before = w.log().len();
    // Radians by habit: loads, warns, renders.
    let narrow = scene("0.8, 0.2, 0.2", 0.4, "tri.obj").replace("fov_y_degrees: 40", "fov_y_degrees: 0.7");
    std::fs::write(w.path("scene.ron"), narrow).expect("edit");
    w.wait_finals(2);
    let log = w.log();
    let new = &log[before..];
    assert!(
        new.iter()
            .any(|l| l.contains("Warning") && l.contains("field of view")),
        "the warning is shown:\n{}",
        new.join("\n")
    );
    assert!(
        new.iter().any(|l| l.contains("scene.ron:2:64")),
        "located:\n{}",
        new.join("\n")
    );
    assert_eq!(w.image(), w.reference(), "and the scene renders as written");
}

/// Hostile edits (issue 13) neither kill watch mode nor stop it rendering:
/// a syntax error beside a byte-order mark and a non-breaking space (the
/// diagnostic printer once panicked there), an instance scaled by 2e19
/// (once a panic in the BVH), and the output named as a texture the scene
/// reads (once a reload loop for ever). Each is reported and the next good
/// save renders.
#[test]
fn watch_survives_hostile_edits_and_renders_the_next_good_one() {
    let w = Watch::start();
    let good = w.image();
    let base = scene("0.8, 0.2, 0.2", 0.4, "tri.obj");
    let non_ascii = format!("\u{feff}{}", base.replace("radius: 0.4,", "radius:\u{a0}0.4 «,"));
    let huge = base.replace(
        "Mesh(file: \"tri.obj\", material: \"grey\"),",
        "Mesh(file: \"tri.obj\", material: \"grey\", transform: [Scale((2e19, 2e19, 2e19))]),",
    );
    let texture_is_output = base.replace(
        "\"grey\": Lambert(albedo: (0.6, 0.6, 0.6))",
        "\"grey\": Lambert(albedo: \"out.png\")",
    );
    assert!(huge != base && texture_is_output != base);
    for (k, edit) in [non_ascii, huge, texture_is_output].into_iter().enumerate() {
        std::fs::write(w.path("scene.ron"), edit).expect("edit");
        w.wait_until("the edit's diagnostics", |log| {
            log.iter().filter(|l| l.contains("error")).count() > k
        });
        let log = w.settle();
        assert!(
            !log.iter().any(|l| l.contains("panicked")),
            "edit {k} panicked:\n{}",
            log.join("\n")
        );
        assert_eq!(finals(&log), 1, "edit {k} rendered:\n{}", log.join("\n"));
    }
    let before = changes(&w.log());
    std::thread::sleep(SETTLE);
    assert_eq!(
        changes(&w.log()),
        before,
        "the output-as-texture edit reloads for ever"
    );
    assert_eq!(w.image(), good, "a refused edit touched the image");
    std::fs::write(w.path("scene.ron"), scene("0.2, 0.3, 0.9", 0.4, "tri.obj")).expect("fix");
    w.wait_finals(2);
    assert_eq!(w.image(), w.reference());
}
