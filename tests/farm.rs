//! Pieces of a frame, rendered by separate `ronray render` runs and put back
//! together by `ronray assemble`: tiles and crops byte for byte, sample
//! splits exactly, and every mismatch refused with the pieces and pixels
//! named.

use crate::common;

use common::{ronray_in, ronray_within_memory, root};
use std::path::{Path, PathBuf};
use std::process::Output;
use std::time::Duration;

/// A named edit of the files in a scene's folder.
type Edit<'a> = (&'a str, &'a dyn Fn(&Path));

/// A 64×64, 4-spp Cornell box: a few hundred milliseconds per render.
const SIZE: &str = "64x64";
const SPP: &str = "4";

fn scene() -> String {
    root().join("scenes/cornell.ron").display().to_string()
}

/// `ronray render` of the test scene in `dir` with `extra` arguments; must
/// succeed.
fn render(dir: &Path, extra: &[&str]) -> Output {
    render_spp(dir, SPP, extra)
}

/// [`render`] at `spp` samples per pixel.
fn render_spp(dir: &Path, spp: &str, extra: &[&str]) -> Output {
    let s = scene();
    let mut args = vec!["render", s.as_str(), "--size", SIZE, "--spp", spp];
    args.extend_from_slice(extra);
    let o = ronray_in(dir, &args);
    assert!(
        o.status.success(),
        "ronray {} failed: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn assemble(dir: &Path, pieces: &[String], out: &str) -> Output {
    let mut args = vec!["assemble"];
    args.extend(pieces.iter().map(String::as_str));
    args.extend(["-o", out]);
    ronray_in(dir, &args)
}

fn read(p: PathBuf) -> Vec<u8> {
    std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// Renders the whole frame as EXR and PNG, assembles `pieces` into both, and
/// requires equal bytes.
fn assert_reassembles(dir: &Path, pieces: &[String]) {
    render(dir, &["-o", "whole.exr"]);
    render(dir, &["-o", "whole.png"]);
    for ext in ["exr", "png"] {
        let out = format!("assembled.{ext}");
        let o = assemble(dir, pieces, &out);
        assert!(
            o.status.success(),
            "assemble failed: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert!(
            read(dir.join(&out)) == read(dir.join(format!("whole.{ext}"))),
            "{} assembled from {pieces:?} differs from the whole render",
            out
        );
    }
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn four_crop_tiles_reassemble_byte_for_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    let crops = ["0,0.5,0,0.5", "0.5,1,0,0.5", "0,0.5,0.5,1", "0.5,1,0.5,1"];
    let mut pieces = Vec::new();
    for (i, c) in crops.iter().enumerate() {
        let out = format!("crop{i}.exr");
        let threads = if i % 2 == 0 { "1" } else { "2" };
        render(dir.path(), &["--crop", c, "-o", &out, "--threads", threads]);
        pieces.push(out);
    }
    assert_reassembles(dir.path(), &pieces);
}

#[test]
fn seven_uneven_tiles_reassemble_byte_for_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut pieces = Vec::new();
    // 64 rows in 7 bands of 9 or 10 rows, none aligned with the renderer's
    // 16-pixel tiles; given in scrambled order.
    for i in [3, 0, 6, 1, 5, 2, 4] {
        let tile = format!("{i}/7");
        let threads = if i % 2 == 0 { "2" } else { "1" };
        render(
            dir.path(),
            &["--tile", &tile, "-o", "tile-{tile}.exr", "--threads", threads],
        );
        pieces.push(format!("tile-{i}.exr"));
    }
    assert_reassembles(dir.path(), &pieces);
}

/// Samples 0..1, 1..3 and 3..4 of every pixel on three "machines". Per-pixel
/// sums are exact (fixed point), so the merge is exact: the largest
/// difference from the whole render is 0, in every channel of every pixel.
/// It also holds the frame loop's two ways of running a sample to each
/// other: the whole render runs samples 0–1 and 2–3 as pairs (first hits
/// found back to back), the pieces run 0 and 3 alone and 1–2 as a pair.
#[test]
fn three_way_sample_split_merges_to_the_whole_render_exactly() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut pieces = Vec::new();
    for (range, threads) in [("3..4", "1"), ("0..1", "2"), ("1..3", "1")] {
        let out = format!("samples-{range}.exr");
        render(
            dir.path(),
            &["--samples", range, "-o", &out, "--threads", threads],
        );
        pieces.push(out);
    }
    assert_reassembles(dir.path(), &pieces);
    let whole = ronray::imageio::read_image(&dir.path().join("whole.exr")).expect("whole");
    let merged = ronray::imageio::read_image(&dir.path().join("assembled.exr")).expect("merged");
    let largest = whole
        .pixels
        .iter()
        .zip(&merged.pixels)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .fold(0.0f32, f32::max);
    assert_eq!(
        largest, 0.0,
        "merged samples differ from the whole render by up to {largest}"
    );
    // What exact sums buy: the sample-weighted mean of the pieces' own f32
    // means (their RGB channels), the merge a renderer without exact sums
    // could do, is off by a few float roundings.
    let means: Vec<(u32, ronray::imageio::Image)> = pieces
        .iter()
        .map(|p| {
            let piece = ronray::farm::read_piece(&dir.path().join(p)).expect("piece");
            let n = piece.meta.samples.1 - piece.meta.samples.0;
            (n, piece.sums.mean(n))
        })
        .collect();
    let (mut abs, mut rel) = (0.0f32, 0.0f32);
    for (i, w) in whole.pixels.iter().enumerate() {
        let m = means
            .iter()
            .map(|(n, img)| img.pixels[i] * *n as f32)
            .sum::<glam::Vec3A>()
            / 4.0;
        let d = (m - *w).abs().max_element();
        abs = abs.max(d);
        rel = rel.max(d / w.max_element().max(1e-6));
    }
    common::report(&format!(
        "three_way_sample_split: exact sums differ from the whole render by 0; merging the pieces' f32 means would differ by up to {abs:.2e} ({rel:.2e} relative)"
    ));
}

/// 32 spp: enough for the default `allocation: ByNoise` to spread samples
/// (below 32 every pixel takes `spp`, and pieces would pass trivially).
const SPREAD_SPP: &str = "32";

/// Renders the whole frame and the pieces with `--spp 32` and the scene's
/// own allocation (`ByNoise`), and requires the assembled EXR and PNG to be
/// the whole render's bytes.
fn assert_spread_pieces_reassemble(pieces: &[&[&str]]) {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut names = Vec::new();
    for (i, extra) in pieces.iter().enumerate() {
        let out = format!("piece-{i}.exr");
        let threads = if i % 2 == 0 { "1" } else { "2" };
        let mut args = extra.to_vec();
        args.extend(["-o", &out, "--threads", threads]);
        let o = render_spp(dir.path(), SPREAD_SPP, &args);
        assert!(
            stderr(&o).contains("first renders the whole frame's first pass") || extra.contains(&"--samples"),
            "a tile of a frame spread by noise says what it costs: {}",
            stderr(&o)
        );
        let piece = ronray::farm::read_piece(&dir.path().join(&out)).expect("piece");
        assert_eq!(piece.meta.spread, Some(16), "{out} is spread by noise");
        names.push(out);
    }
    for ext in ["exr", "png"] {
        render_spp(dir.path(), SPREAD_SPP, &["-o", &format!("whole.{ext}")]);
        let out = format!("assembled.{ext}");
        let o = assemble(dir.path(), &names, &out);
        assert!(o.status.success(), "assemble failed: {}", stderr(&o));
        assert!(
            read(dir.path().join(&out)) == read(dir.path().join(format!("whole.{ext}"))),
            "{out} assembled from {pieces:?} differs from the whole render spread by noise"
        );
    }
    // The pixels really took different counts: the test is not an even render.
    let whole = ronray::imageio::read_image(&dir.path().join("whole.exr")).expect("whole");
    let even = {
        render_spp(
            dir.path(),
            SPREAD_SPP,
            &["--set", "film.allocation=Even", "-o", "even.exr"],
        );
        ronray::imageio::read_image(&dir.path().join("even.exr")).expect("even")
    };
    assert!(whole.pixels != even.pixels, "ByNoise rendered what Even renders");
}

#[test]
fn tiles_of_a_frame_spread_by_noise_reassemble_byte_for_byte() {
    assert_spread_pieces_reassemble(&[&["--tile", "0/3"], &["--tile", "2/3"], &["--tile", "1/3"]]);
}

#[test]
fn sample_splits_of_a_frame_spread_by_noise_reassemble_byte_for_byte() {
    assert_spread_pieces_reassemble(&[&["--samples", "13..32"], &["--samples", "0..13"]]);
}

#[test]
fn crops_and_sample_splits_of_a_frame_spread_by_noise_mix() {
    assert_spread_pieces_reassemble(&[
        &["--pixels", "0,0,64,20"],
        &["--pixels", "0,20,64,64", "--samples", "0..7"],
        &["--pixels", "0,20,64,64", "--samples", "7..32"],
    ]);
}

#[test]
fn a_piece_holds_the_whole_renders_values_and_windows() {
    let dir = tempfile::tempdir().expect("temp dir");
    render(dir.path(), &["--pixels", "5,7,40,30", "-o", "piece.exr"]);
    render(dir.path(), &["-o", "whole.exr"]);
    let piece = ronray::farm::read_piece(&dir.path().join("piece.exr")).expect("piece reads");
    let m = &piece.meta;
    assert_eq!((m.frame, m.samples, m.spp, m.tile), ((64, 64), (0, 4), 4, None));
    assert_eq!((m.rect.x0, m.rect.y0, m.rect.x1, m.rect.y1), (5, 7, 40, 30));
    assert_eq!(m.version, env!("CARGO_PKG_VERSION"));
    assert!(m.scene.starts_with("sha256:"), "scene hash {}", m.scene);
    // The EXR windows, as any EXR reader sees them.
    let exr = exr::meta::MetaData::read_from_file(dir.path().join("piece.exr"), false).expect("header");
    let h = &exr.headers[0];
    assert_eq!(h.shared_attributes.display_window.size, exr::math::Vec2(64, 64));
    assert_eq!(h.own_attributes.layer_position, exr::math::Vec2(5, 7));
    assert_eq!(h.layer_size, exr::math::Vec2(35, 23));
    // Its RGB are the whole render's values at those pixels, bit for bit.
    let whole = ronray::imageio::read_image(&dir.path().join("whole.exr")).expect("whole");
    let mean = piece.sums.mean(4);
    for y in 7..30 {
        for x in 5..40 {
            let (a, b) = (mean.get(x - 5, y - 7), whole.get(x, y));
            assert!(
                a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits),
                "pixel ({x}, {y}): {a} vs {b}"
            );
        }
    }
}

#[test]
fn pieces_of_two_scenes_are_refused_naming_them() {
    let dir = tempfile::tempdir().expect("temp dir");
    render(dir.path(), &["--tile", "0/2", "-o", "a-0.exr", "--seed", "0"]);
    // Another scene file at the same size, samples and seed: only the scene
    // differs.
    let other = root().join("scenes/materials.ron").display().to_string();
    let b = ronray_in(
        dir.path(),
        &[
            "render", &other, "--size", SIZE, "--spp", SPP, "--seed", "0", "--tile", "1/2", "-o", "b-1.exr",
        ],
    );
    assert!(b.status.success(), "{}", stderr(&b));
    let o = assemble(dir.path(), &["a-0.exr".into(), "b-1.exr".into()], "out.png");
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("different scenes")
            && e.contains("a-0.exr has scene sha256:")
            && e.contains("b-1.exr has scene sha256:"),
        "expected both pieces named with their scene hashes, got:\n{e}"
    );
    assert!(
        !dir.path().join("out.png").exists(),
        "a refused assembly wrote its output"
    );
}

#[test]
fn overlapping_pieces_are_refused_naming_them_and_the_pixels() {
    let dir = tempfile::tempdir().expect("temp dir");
    render(dir.path(), &["--pixels", "0,0,64,40", "-o", "top.exr"]);
    render(dir.path(), &["--pixels", "0,32,64,64", "-o", "bottom.exr"]);
    let o = assemble(dir.path(), &["top.exr".into(), "bottom.exr".into()], "out.exr");
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("pieces top.exr and bottom.exr overlap: both hold samples 0..4 of pixels x 0..64, y 32..40 (512 pixels)"),
        "expected the overlap named, got:\n{e}"
    );
}

#[test]
fn a_missing_tile_is_refused_naming_the_tile_and_its_pixels() {
    let dir = tempfile::tempdir().expect("temp dir");
    let mut pieces = Vec::new();
    for i in [0, 1, 3] {
        render(dir.path(), &["--tile", &format!("{i}/4"), "-o", "t{tile}.exr"]);
        pieces.push(format!("t{i}.exr"));
    }
    let o = assemble(dir.path(), &pieces, "out.exr");
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    assert!(
        e.contains("missing tile 2/4: no piece holds samples 0..4 of pixels x 0..64, y 32..48 (1024 pixels)"),
        "expected the missing tile named, got:\n{e}"
    );
}

#[test]
fn png_pieces_are_refused_with_the_reason() {
    let dir = tempfile::tempdir().expect("temp dir");
    let s = scene();
    let o = ronray_in(
        dir.path(),
        &["render", &s, "--size", SIZE, "--tile", "0/2", "-o", "piece.png"],
    );
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{e}");
    assert!(
        e.contains("PNG pieces are 8-bit and cannot be merged exactly"),
        "{e}"
    );
    assert!(!dir.path().join("piece.png").exists());
}

#[test]
fn resume_skips_a_finished_piece_and_redoes_a_different_one() {
    let dir = tempfile::tempdir().expect("temp dir");
    render(dir.path(), &["--tile", "1/3", "-o", "t.exr", "--resume"]);
    let again = render(dir.path(), &["--tile", "1/3", "-o", "t.exr", "--resume"]);
    assert!(
        stderr(&again).contains("skipped t.exr: it already holds this piece"),
        "{}",
        stderr(&again)
    );
    let other = render(
        dir.path(),
        &["--tile", "1/3", "-o", "t.exr", "--resume", "--seed", "9"],
    );
    assert!(
        stderr(&other).contains("re-rendering t.exr: it holds scene"),
        "{}",
        stderr(&other)
    );
}

#[test]
fn progress_json_prints_one_line_per_tile() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = render(
        dir.path(),
        &["--tile", "0/2", "-o", "t.exr", "--progress", "json"],
    );
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&o.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("`{l}` is not JSON: {e}")))
        .collect();
    let events: Vec<&str> = lines.iter().map(|v| v["event"].as_str().unwrap_or("?")).collect();
    // 64×32 pixels are 4×2 tiles of 16.
    let mut expected = vec!["start"];
    expected.extend(["tile"; 8]);
    expected.push("done");
    assert_eq!(events, expected);
    assert_eq!(lines[8]["total"], 8);
}

#[test]
fn tile_auto_reads_the_schedulers_index_or_says_which_variables_it_reads() {
    let dir = tempfile::tempdir().expect("temp dir");
    let s = scene();
    let run = |var: Option<(&str, &str)>| {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_ronray"));
        c.args([
            "render",
            &s,
            "--size",
            SIZE,
            "--spp",
            "1",
            "--tile",
            "auto/4",
            "-o",
            "a{tile}.exr",
        ])
        .current_dir(dir.path());
        for v in ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX", "PARALLEL_SEQ"] {
            c.env_remove(v);
        }
        if let Some((k, v)) = var {
            c.env(k, v);
        }
        c.output().expect("ronray runs")
    };
    assert!(run(Some(("SLURM_ARRAY_TASK_ID", "2"))).status.success());
    assert!(run(Some(("JOB_COMPLETION_INDEX", "0"))).status.success());
    assert!(
        run(Some(("PARALLEL_SEQ", "2"))).status.success(),
        "GNU parallel's 2 is tile 1"
    );
    for i in 0..3 {
        assert!(
            dir.path().join(format!("a{i}.exr")).exists(),
            "tile {i} not written"
        );
    }
    let none = run(None);
    assert_eq!(none.status.code(), Some(2));
    assert!(stderr(&none).contains("SLURM_ARRAY_TASK_ID"), "{}", stderr(&none));
}

/// Long enough for any run of these tests on a loaded machine; a run that
/// takes longer hangs (a FIFO opened for reading waits for ever).
const HANG: Duration = Duration::from_secs(120);

/// `ronray render` of an 8×8, 1-spp Cornell box tile `tile` with `extra`
/// arguments, killed and failed if it hangs, in 4 GiB of address space
/// (`--resume` reads what is at the output first); its output.
fn render_small(dir: &Path, tile: &str, extra: &[&str]) -> Output {
    let s = scene();
    let mut args = vec![
        "render",
        s.as_str(),
        "--size",
        "8x8",
        "--spp",
        "1",
        "--tile",
        tile,
    ];
    args.extend_from_slice(extra);
    ronray_within_memory(dir, &args, HANG, 4)
}

/// `ronray assemble pieces -o out`, killed and failed if it hangs, in 4
/// GiB of address space (a few hundred MB is what it needs here; a
/// regression to allocating what a header claims aborts instead of taking
/// the machine's memory).
fn assemble_within(dir: &Path, pieces: &[&str], out: &str) -> Output {
    let mut args = vec!["assemble"];
    args.extend_from_slice(pieces);
    args.extend(["-o", out]);
    ronray_within_memory(dir, &args, HANG, 4)
}

/// The process ended by itself with `code` (not on a signal: an abort on
/// a failed allocation is SIGABRT).
fn assert_code(o: &Output, code: i32, what: &str) {
    assert!(
        o.status.code() == Some(code),
        "{what}: expected exit code {code}, got {} (a signal is an abort or a crash)\n{}",
        o.status,
        stderr(o)
    );
}

fn mkfifo(p: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(p)
        .status()
        .expect("mkfifo");
    assert!(ok.success(), "mkfifo {}", p.display());
}

/// `--resume` reads the whole piece: a truncated one is rendered again, not
/// reported done; a FIFO named as a piece (`assemble`) or as `--resume`'s
/// output is refused as not a regular file instead of hanging (issue 39:
/// both waited for ever on a writer that never came). Every run is bounded
/// by [`HANG`], so a regression fails instead of stopping the test run.
#[test]
fn resume_redoes_a_truncated_piece_and_fifos_do_not_hang() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = render_small(dir.path(), "0/2", &["-o", "t.exr"]);
    assert_code(&o, 0, "the first render");
    let good = read(dir.path().join("t.exr"));
    std::fs::write(dir.path().join("t.exr"), &good[..good.len() / 2]).expect("truncate");
    let o = render_small(dir.path(), "0/2", &["-o", "t.exr", "--resume"]);
    assert_code(&o, 0, "--resume over a truncated piece");
    assert!(!stderr(&o).contains("skipped"), "{}", stderr(&o));
    assert!(
        read(dir.path().join("t.exr")) == good,
        "the truncated piece was not repaired"
    );
    mkfifo(&dir.path().join("pipe.exr"));
    let o = assemble_within(dir.path(), &["t.exr", "pipe.exr"], "frame.exr");
    assert_code(&o, 1, "assemble with a FIFO as a piece");
    assert!(
        stderr(&o).contains("pipe.exr") && stderr(&o).contains("not a regular file"),
        "{}",
        stderr(&o)
    );
    let o = render_small(dir.path(), "1/2", &["-o", "pipe.exr", "--resume"]);
    assert_code(&o, 0, "--resume with a FIFO as the output");
    assert!(stderr(&o).contains("re-rendering"), "{}", stderr(&o));
    assert!(
        std::fs::metadata(dir.path().join("pipe.exr")).is_ok_and(|m| m.is_file()),
        "the piece did not replace the FIFO"
    );
}

/// `bytes` (an EXR file) with its `box2i` attribute `name` set to
/// `[x_min, y_min, x_max, y_max]` (inclusive, as EXR stores a window).
fn set_window(bytes: &mut [u8], name: &str, b: [i32; 4]) {
    let at = window_at(bytes, name);
    for (i, v) in b.iter().enumerate() {
        bytes[at + 4 * i..at + 4 * i + 4].copy_from_slice(&v.to_le_bytes());
    }
}

/// Where the value of the `box2i` attribute `name` starts in an EXR file
/// (after its name, type and 4-byte size).
fn window_at(bytes: &[u8], name: &str) -> usize {
    let key = format!("{name}\0box2i\0");
    bytes
        .windows(key.len())
        .position(|w| w == key.as_bytes())
        .unwrap_or_else(|| panic!("no `{name}` attribute"))
        + key.len()
        + 4
}

/// The `box2i` attribute `name` of an EXR file.
fn window(bytes: &[u8], name: &str) -> [i32; 4] {
    let at = window_at(bytes, name);
    std::array::from_fn(|i| {
        i32::from_le_bytes(bytes[at + 4 * i..at + 4 * i + 4].try_into().unwrap_or_default())
    })
}

/// Issue 39: piece headers sized allocations. A piece of about a kilobyte
/// whose data window starts at x = −(2³⁰ − 2) (the widest window EXR
/// allows, two billion pixels a row) made the decoder ask for 32 GB a
/// channel, and one claiming a 100,000² display window made `assemble`
/// allocate a frame of 10¹⁰ pixels: both aborted (SIGABRT). Now both are
/// refused by `assemble`, naming the piece, and `--resume` renders such a
/// piece again instead of trusting it.
#[test]
fn piece_headers_that_lie_about_their_size_are_refused_before_allocating() {
    let dir = tempfile::tempdir().expect("temp dir");
    let o = render_small(dir.path(), "0/2", &["-o", "good.exr"]);
    assert_code(&o, 0, "the first render");
    let good = read(dir.path().join("good.exr"));
    assert!(good.len() < 4096, "the small piece is {} bytes", good.len());
    let data = window(&good, "dataWindow");

    let mut wide = good.clone();
    set_window(
        &mut wide,
        "dataWindow",
        [-(1 << 30) + 2, data[1], (1 << 30) - 3, data[3]],
    );
    std::fs::write(dir.path().join("wide.exr"), &wide).expect("write");
    let mut huge = good.clone();
    set_window(&mut huge, "displayWindow", [0, 0, 99_999, 99_999]);
    std::fs::write(dir.path().join("huge.exr"), &huge).expect("write");

    let o = assemble_within(dir.path(), &["wide.exr"], "frame.exr");
    assert_code(&o, 1, "assemble of a piece with a negative data window");
    assert!(
        stderr(&o).contains("wide.exr") && stderr(&o).contains("truncated or corrupt"),
        "{}",
        stderr(&o)
    );
    let o = assemble_within(dir.path(), &["huge.exr"], "frame.exr");
    assert_code(&o, 1, "assemble of a piece claiming a 100000² frame");
    assert!(
        stderr(&o).contains("huge.exr") && stderr(&o).contains("100000×100000, above the limit of 16384"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.path().join("frame.exr").exists(), "a frame was written");

    for bad in ["wide.exr", "huge.exr"] {
        let o = render_small(dir.path(), "0/2", &["-o", bad, "--resume"]);
        assert_code(&o, 0, &format!("--resume over {bad}"));
        assert!(stderr(&o).contains("re-rendering"), "{bad}: {}", stderr(&o));
        assert!(read(dir.path().join(bad)) == good, "{bad} was not rendered again");
    }
}

/// A folder with a textured quad whose look comes from its MTL file
/// (`Kd`, `map_Kd tex.png`) under a sky map, in a grey fog grid, beside a
/// textured sphere: each kind of file a scene reads indirectly.
fn textured_folder(kd: &str, texel: u8) -> tempfile::TempDir {
    // `texel` differs from `wall.png`'s 200, so that swapping them matters.
    let dir = tempfile::tempdir().expect("temp dir");
    let p = |f: &str| dir.path().join(f);
    std::fs::write(
        p("scene.ron"),
        r#"Scene(
    camera: (eye: (0, 0, 3), target: (0, 0, 0), fov_y_degrees: 40),
    integrator: Path(max_depth: 4),
    materials: { "wall": Lambert(albedo: Image(file: "wall.png")) },
    media: { "fog": Grid(file: "fog.vol", min: (-3, -3, -3), max: (3, 3, 3), scale: 0.01) },
    medium: "fog",
    lights: [Environment(map: "sky.exr")],
    objects: [
        Mesh(file: "quad.obj"),
        Sphere(center: (0.7, 0.7, 0), radius: 0.2, material: "wall"),
    ],
)
"#,
    )
    .expect("write");
    std::fs::write(
        p("quad.obj"),
        "mtllib look.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl paint\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n",
    )
    .expect("write");
    std::fs::write(p("look.mtl"), format!("newmtl paint\nKd {kd}\nmap_Kd tex.png\n")).expect("write");
    let png = |name: &str, v: u8| {
        image::RgbImage::from_raw(2, 2, vec![v; 12])
            .expect("2 × 2")
            .save(p(name))
            .expect("write png")
    };
    png("tex.png", texel);
    png("wall.png", 200);
    sky(&p("sky.exr"), 0.5);
    let vol = ronray::media::vol::write_vol([2, 2, 2], &[1.0; 8], [-3.0; 3], [3.0; 3]);
    std::fs::write(p("fog.vol"), vol).expect("write");
    dir
}

/// A 2 × 2 sky map of radiance `v`.
fn sky(path: &Path, v: f32) {
    image::Rgb32FImage::from_raw(2, 2, vec![v; 12])
        .expect("2 × 2")
        .save(path)
        .expect("write exr")
}

/// One tile of `dir/scene.ron` to `out`.
fn render_tile(dir: &Path, tile: &str, out: &str) {
    let o = ronray_in(
        dir,
        &[
            "render",
            "scene.ron",
            "--size",
            "16x16",
            "--spp",
            "1",
            "--tile",
            tile,
            "-o",
            out,
        ],
    );
    assert!(o.status.success(), "render --tile {tile}: {}", stderr(&o));
}

/// Pieces rendered while a file the scene reads indirectly differed are
/// two scenes: `assemble` refuses them. A different MTL file or MTL
/// texture was already refused; a `.vol` grid was not in the hash, and two
/// textures with their contents swapped left the sorted digests alike:
/// both were merged into a frame that matched neither, exit 0.
#[test]
fn pieces_rendered_with_different_indirect_files_are_refused() {
    let swap = |d: &Path| {
        std::fs::copy(d.join("wall.png"), d.join("tmp.png")).expect("copy");
        std::fs::copy(d.join("tex.png"), d.join("wall.png")).expect("copy");
        std::fs::copy(d.join("tmp.png"), d.join("tex.png")).expect("copy");
    };
    let cases: [Edit; 4] = [
        ("MTL file", &|d| {
            std::fs::write(
                d.join("look.mtl"),
                "newmtl paint\nKd 0.2 0.9 0.2\nmap_Kd tex.png\n",
            )
            .expect("write")
        }),
        ("MTL's texture", &|d| {
            image::RgbImage::from_raw(2, 2, vec![40; 12])
                .expect("2 × 2")
                .save(d.join("tex.png"))
                .expect("write png")
        }),
        ("textures swapped", &swap),
        ("density grid", &|d| {
            let v = ronray::media::vol::write_vol([2, 2, 2], &[50.0; 8], [-3.0; 3], [3.0; 3]);
            std::fs::write(d.join("fog.vol"), v).expect("write")
        }),
    ];
    for (what, change) in cases {
        let dir = textured_folder("0.8 0.8 0.8", 255);
        render_tile(dir.path(), "0/2", "a-0.exr");
        change(dir.path());
        render_tile(dir.path(), "1/2", "a-1.exr");
        let o = assemble(dir.path(), &["a-0.exr".into(), "a-1.exr".into()], "out.exr");
        let e = stderr(&o);
        assert_eq!(
            o.status.code(),
            Some(1),
            "pieces with a different {what} were merged: {e}"
        );
        assert!(e.contains("different scenes"), "{what}: {e}");
        assert!(
            !dir.path().join("out.exr").exists(),
            "{what}: a refused assembly wrote"
        );
    }
}

/// Every file the scene reads indirectly is in its hash: changing any one
/// of them (the scene's texture, the sky map, the grid, the MTL file, the
/// texture it names) changes the hash; swapping two files' contents does
/// too; moving the folder does not.
#[test]
fn scene_hash_covers_every_file_the_scene_reads() {
    let hash = |dir: &Path| {
        let l = ronray::load::load(&dir.join("scene.ron")).unwrap_or_else(|e| panic!("{e}"));
        ronray::farm::scene_hash(&l.desc, &l.files).expect("hash")
    };
    let dir = textured_folder("0.8 0.8 0.8", 255);
    let base = hash(dir.path());
    let moved = textured_folder("0.8 0.8 0.8", 255);
    assert_eq!(hash(moved.path()), base, "another folder, same files");
    let changes: [Edit; 6] = [
        ("wall.png", &|d| {
            std::fs::copy(d.join("tex.png"), d.join("wall.png"))
                .map(drop)
                .expect("copy")
        }),
        ("sky.exr", &|d| sky(&d.join("sky.exr"), 2.0)),
        ("fog.vol", &|d| {
            let v = ronray::media::vol::write_vol([2, 2, 2], &[2.0; 8], [-3.0; 3], [3.0; 3]);
            std::fs::write(d.join("fog.vol"), v).expect("write")
        }),
        ("look.mtl", &|d| {
            std::fs::write(
                d.join("look.mtl"),
                "newmtl paint\nKd 0.1 0.1 0.1\nmap_Kd tex.png\n",
            )
            .expect("write")
        }),
        ("tex.png", &|d| {
            std::fs::copy(d.join("wall.png"), d.join("tex.png"))
                .map(drop)
                .expect("copy")
        }),
        ("wall.png and tex.png swapped", &|d| {
            std::fs::copy(d.join("wall.png"), d.join("tmp.png")).expect("copy");
            std::fs::copy(d.join("tex.png"), d.join("wall.png")).expect("copy");
            std::fs::copy(d.join("tmp.png"), d.join("tex.png")).expect("copy");
        }),
    ];
    for (what, change) in changes {
        let d = textured_folder("0.8 0.8 0.8", 255);
        change(d.path());
        assert_ne!(hash(d.path()), base, "{what} changed and the hash did not");
    }
}
