//! The farm examples run by real schedulers: `examples/slurm-tiles.sbatch`
//! as a 4-task Slurm job array on the one-node cluster `.ci/slurm-up.sh`
//! starts, and `examples/parallel-tiles.sh` through GNU parallel. Each
//! assembles the tiles and compares them with a plain render byte for byte.
//!
//! Where Slurm or GNU parallel is missing, or no cluster answers, the test
//! says so and skips; `.ci/run` sets `RONRAY_REQUIRE_TOOLS=1`, which turns
//! the skip into a failure.

use crate::common;

use common::{report, ronray_in, root, skip_or_fail, tool_or_skip};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const SIZE: &str = "64x64";
const SPP: &str = "8";

/// Runs `cmd` to the end, or kills it after `limit` and panics.
fn run_for(cmd: &mut Command, limit: Duration, on_timeout: impl FnOnce()) -> Output {
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("cannot start {cmd:?}: {e}"));
    let start = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            on_timeout();
            panic!("{cmd:?} did not finish in {} s", limit.as_secs());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    child.wait_with_output().expect("output")
}

/// A plain render of the test scene to `whole.exr`, and how long it took.
fn plain_render(dir: &Path) -> Duration {
    let scene = root().join("scenes/cornell.ron").display().to_string();
    let t = Instant::now();
    let o = ronray_in(
        dir,
        &["render", &scene, "--size", SIZE, "--spp", SPP, "-o", "whole.exr"],
    );
    assert!(
        o.status.success(),
        "plain render: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    t.elapsed()
}

/// Assembles `dir/tiles/tile-*.exr` (four of them) and compares with
/// `dir/whole.exr`.
fn assert_tiles_make_the_plain_render(dir: &Path) {
    let tiles: Vec<String> = (0..4).map(|i| format!("tiles/tile-{i}.exr")).collect();
    let mut args = vec!["assemble"];
    args.extend(tiles.iter().map(String::as_str));
    args.extend(["-o", "assembled.exr"]);
    let o = ronray_in(dir, &args);
    assert!(
        o.status.success(),
        "assemble: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let read = |p: &str| std::fs::read(dir.join(p)).unwrap_or_else(|e| panic!("{p}: {e}"));
    assert!(
        read("assembled.exr") == read("whole.exr"),
        "the assembled tiles differ from the plain render"
    );
}

/// Whether a Slurm controller answers (with a node up), within 10 s.
fn slurm_cluster(test: &str) -> bool {
    let o = run_for(
        Command::new("sinfo").args(["-h", "-o", "%t"]),
        Duration::from_secs(10),
        || {},
    );
    let state = String::from_utf8_lossy(&o.stdout).trim().to_string();
    if o.status.success()
        && (state.starts_with("idle") || state.starts_with("mix") || state.starts_with("alloc"))
    {
        return true;
    }
    skip_or_fail(
        test,
        &format!(
            "no Slurm cluster answers (sinfo: {})",
            String::from_utf8_lossy(&o.stderr)
                .lines()
                .last()
                .unwrap_or(&state)
                .trim()
        ),
        "start one with `eval \"$(.ci/slurm-up.sh /tmp/ronray-slurm)\"` (as root; stop it with .ci/slurm-down.sh)",
    );
    false
}

#[test]
fn slurm_job_array_of_four_tiles_reassembles_to_the_plain_render() {
    let test = "slurm_job_array_of_four_tiles_reassembles_to_the_plain_render";
    let install = "apt-get install slurm-wlm munge";
    if tool_or_skip("sbatch", test, install).is_none() || !slurm_cluster(test) {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let plain = plain_render(dir.path());
    let scene = root().join("scenes/cornell.ron").display().to_string();
    let script = root().join("examples/slurm-tiles.sbatch");
    let name = format!("ronray-test-{}", std::process::id());
    let t = Instant::now();
    let o = run_for(
        Command::new("sbatch")
            .args(["--wait", "--array=0-3", "--time=5", "-J", &name, "-o"])
            .arg(dir.path().join("slurm-%a.out"))
            .arg("--chdir")
            .arg(dir.path())
            .arg(&script)
            .args(["4", &scene, "tiles", "--size", SIZE, "--spp", SPP])
            .env("RONRAY", env!("CARGO_BIN_EXE_ronray")),
        Duration::from_secs(180),
        || {
            let _ = Command::new("scancel").args(["-n", &name]).status();
        },
    );
    let slurm = t.elapsed();
    let logs: String = (0..4)
        .map(|i| std::fs::read_to_string(dir.path().join(format!("slurm-{i}.out"))).unwrap_or_default())
        .collect();
    assert!(
        o.status.success(),
        "sbatch --wait failed: {}{}\ntask logs:\n{logs}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(
        logs.matches("\"event\":\"done\"").count(),
        4,
        "every array task ends with a JSON `done` line:\n{logs}"
    );
    assert_tiles_make_the_plain_render(dir.path());
    report(&format!(
        "{test}: 4-task Slurm array {:.2} s (submission to completion), plain render {:.2} s",
        slurm.as_secs_f64(),
        plain.as_secs_f64()
    ));
}

#[test]
fn gnu_parallel_renders_four_tiles_that_reassemble_to_the_plain_render() {
    let test = "gnu_parallel_renders_four_tiles_that_reassemble_to_the_plain_render";
    if tool_or_skip("parallel", test, "apt-get install parallel").is_none() {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let plain = plain_render(dir.path());
    let scene = root().join("scenes/cornell.ron").display().to_string();
    let t = Instant::now();
    let o = run_for(
        Command::new("bash")
            .arg(root().join("examples/parallel-tiles.sh"))
            .args(["4", &scene, "tiles", "--size", SIZE, "--spp", SPP])
            .current_dir(dir.path())
            .env("RONRAY", env!("CARGO_BIN_EXE_ronray"))
            // Each job's index must come from PARALLEL_SEQ alone.
            .env_remove("SLURM_ARRAY_TASK_ID")
            .env_remove("JOB_COMPLETION_INDEX"),
        Duration::from_secs(120),
        || {},
    );
    let elapsed = t.elapsed();
    assert!(
        o.status.success(),
        "parallel-tiles.sh failed: {}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert_tiles_make_the_plain_render(dir.path());
    let frame = std::fs::read(dir.path().join("tiles/frame.exr")).expect("the script assembles");
    assert!(frame == std::fs::read(dir.path().join("whole.exr")).expect("whole"));
    report(&format!(
        "{test}: GNU parallel, 4 tiles {:.2} s, plain render {:.2} s",
        elapsed.as_secs_f64(),
        plain.as_secs_f64()
    ));
}

#[test]
fn slurm_job_array_over_frames_writes_what_frames_range_writes() {
    let test = "slurm_job_array_over_frames_writes_what_frames_range_writes";
    let install = "apt-get install slurm-wlm munge";
    if tool_or_skip("sbatch", test, install).is_none() || !slurm_cluster(test) {
        return;
    }
    let dir = tempfile::tempdir().expect("temp dir");
    let scene = root().join("tests/fixtures/anim/turntable.ron");
    let bin = env!("CARGO_BIN_EXE_ronray");
    let range = Command::new(bin)
        .arg("render")
        .arg(&scene)
        .args(["--frames", "3..5", "--progress", "none", "-o"])
        .arg(dir.path().join("range_{frame}.exr"))
        .output()
        .expect("ronray runs");
    assert!(
        range.status.success(),
        "{}",
        String::from_utf8_lossy(&range.stderr)
    );
    // Array task k draws frame 3 + k: the scene's first frame plus the index.
    let wrap = format!(
        "{bin} render {} --frame auto --threads 1 --progress none -o {}",
        scene.display(),
        dir.path().join("slurm_{frame}.exr").display()
    );
    let name = format!("ronray-frames-{}", std::process::id());
    let o = run_for(
        Command::new("sbatch")
            .args(["--wait", "--array=0-2", "--time=5", "-J", &name, "-o"])
            .arg(dir.path().join("slurm-%a.out"))
            .arg("--chdir")
            .arg(dir.path())
            .args(["--wrap", &wrap]),
        Duration::from_secs(180),
        || {
            let _ = Command::new("scancel").args(["-n", &name]).status();
        },
    );
    let logs: String = (0..3)
        .map(|i| std::fs::read_to_string(dir.path().join(format!("slurm-{i}.out"))).unwrap_or_default())
        .collect();
    assert!(
        o.status.success(),
        "sbatch --wait failed: {}\n{logs}",
        String::from_utf8_lossy(&o.stderr)
    );
    for f in 3..=5 {
        let a = std::fs::read(dir.path().join(format!("range_{f}.exr"))).expect("range frame");
        let b = std::fs::read(dir.path().join(format!("slurm_{f}.exr"))).unwrap_or_default();
        assert!(
            a == b,
            "frame {f} from the Slurm array differs from --frames 3..5\n{logs}"
        );
    }
}
