//! Regression checks: render each scene at its `test` settings and compare
//! with its golden image, `golden/<scene name>.png` beside the scene file.
//!
//! The metric ([`metric`]) judges each region against the noise of the
//! sampling: the largest mean over 8×8-pixel windows of the squared z-scores
//! of 4×4-cell differences, the noise measured by rendering the scene with
//! other seeds and kept beside the golden as a per-pixel variance image
//! (`golden/<scene name>.var.exr`, written by `--bless`; measured again at
//! check time when it is missing). The new render goes through the same
//! 8-bit sRGB encoding as the golden, so an unchanged renderer scores
//! exactly 0. The threshold is the scene's `test.tolerance` (default [`DEFAULT_TOLERANCE`]) unless the
//! command line gives one. A failure leaves the new render and a heat map
//! beside the golden, and an HTML page showing the three side by side
//! ([`report`]).

pub mod metric;
pub mod report;

use crate::desc::TestDesc;
use crate::frame::{RenderOptions, render_whole};
use crate::imageio::{Image, metrics, read_image, srgb_decode, srgb8, write_image};
use crate::load::{LoadError, Overrides, load_with};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub use crate::desc::DEFAULT_TOLERANCE;
pub use metric::{COMPARE_FACTOR, Score, WINDOW, score, variance_of};

/// The judged figure of [`score`]: the worst window's mean squared z-score.
pub fn golden_error(new: &Image, golden: &Image, variance: &Image) -> Result<f64, String> {
    score(new, golden, variance).map(|s| s.worst)
}

/// What the seed of the second render, the one that measures noise, differs
/// by: far from any seed a user would write in `test.seed`.
const NOISE_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// How many renders beside the golden's measure its noise (at `--bless`, or
/// at check time when the variance image is missing): the variance of each
/// pixel then has this many degrees of freedom.
const NOISE_RENDERS: u64 = 3;

/// The per-pixel variance image kept beside a golden:
/// `golden/<name>.var.exr` (linear, one render's variance per channel).
pub fn variance_path(golden: &Path) -> PathBuf {
    golden.with_extension("var.exr")
}

/// What `ronray check` was asked, beside the scenes.
#[derive(Clone, Debug, Default)]
pub struct CheckOptions {
    /// Rewrite the goldens that fail or are missing.
    pub bless: bool,
    /// Worker threads (default: all cores); the image does not depend on it.
    pub threads: Option<usize>,
    /// `--set path=value` overrides, applied before the test settings are
    /// read (`--set test.seed=7` re-seeds the check).
    pub sets: Vec<String>,
    /// Replaces every scene's `test.tolerance`.
    pub tolerance: Option<f64>,
    /// With `bless`, also replace a golden that is corrupt or of another
    /// size ([`Outcome::BadGolden`]); without it such a golden is kept, since
    /// it may be a file someone put there by mistake or a size change that
    /// deserves a look.
    pub force: bool,
    /// `--root`: inputs outside it are refused (see [`Overrides::root`]).
    pub root: Option<PathBuf>,
}

/// What checking one scene against its golden image found.
#[derive(Debug)]
pub enum Outcome {
    /// The render matches its golden image within tolerance.
    Pass {
        /// The render's score against the golden image (see [`metric`]).
        score: Score,
        /// The largest score that passes (`test.tolerance` or `--tolerance`).
        tolerance: f64,
    },
    /// The render differs from its golden image by more than the tolerance.
    Fail {
        /// The render's score against the golden image.
        score: Score,
        /// The largest score that passes.
        tolerance: f64,
        /// Where the new render was written (`golden/<name>.new.png`), for review.
        new: PathBuf,
        /// Where the per-pixel error image was written (`golden/<name>.diff.png`).
        heatmap: PathBuf,
    },
    /// No golden yet (run with `--bless` to create it).
    Missing {
        /// Where the new render was written (`golden/<name>.new.png`); bless it to
        /// make it the golden.
        new: PathBuf,
    },
    /// A golden file that is there but cannot serve: it does not decode
    /// (`corrupt golden: …`) or its size is not the render's (`golden is
    /// 64×48, render is 64×64`). A failure; `--bless` replaces it only with
    /// `--force`.
    BadGolden {
        /// What is wrong with it, one sentence.
        reason: String,
        /// Where the new render was written (`golden/<name>.new.png`).
        new: PathBuf,
    },
    /// Golden written by `--bless`.
    Blessed {
        /// Score against the previous golden, if there was one.
        score: Option<Score>,
    },
    /// The scene did not load (I/O error or invalid scene); nothing was rendered.
    Invalid(LoadError),
}

/// The result of checking one scene, one row of [`summary`].
#[derive(Debug)]
pub struct CheckResult {
    /// The scene file checked.
    pub scene: PathBuf,
    /// What the comparison found.
    pub outcome: Outcome,
    /// Wall-clock time to load, render and compare the scene.
    pub time: Duration,
}

impl CheckResult {
    /// True if the scene needs attention: a failed comparison, a missing golden or a
    /// scene that does not load. What `ronray check` turns into its exit status.
    pub fn failed(&self) -> bool {
        matches!(
            self.outcome,
            Outcome::Fail { .. } | Outcome::Missing { .. } | Outcome::BadGolden { .. } | Outcome::Invalid(_)
        )
    }
}

/// Scene files named directly, and every `*.ron` / `*.json` scene in the
/// folders named (not recursive), in name order.
pub fn collect(paths: &[PathBuf]) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            let mut v: Vec<PathBuf> = std::fs::read_dir(p)?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|f| f.is_file() && f.extension().is_some_and(|e| e == "ron" || e == "json"))
                .collect();
            v.sort();
            out.extend(v);
        } else {
            out.push(p.clone());
        }
    }
    Ok(out)
}

/// The golden image of `scene`: `golden/<scene file stem>.png` beside the scene file.
pub fn golden_path(scene: &Path) -> PathBuf {
    let stem = scene.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    scene
        .parent()
        .unwrap_or(Path::new("."))
        .join("golden")
        .join(format!("{stem}.png"))
}

/// Quantises like an 8-bit sRGB PNG round trip.
fn quantise(img: &Image) -> Image {
    let mut out = img.clone();
    for p in &mut out.pixels {
        *p = p.to_array().map(|c| srgb_decode(srgb8(c) as f32 / 255.0)).into();
    }
    out
}

/// Renders `scene` at its test settings (after `sets`), 8-bit quantised.
/// `sets` whose path starts with `test` change those settings even when the
/// scene has no `test` entry (`--set test.seed=7` re-seeds the check).
pub fn render_test(
    scene: &Path,
    threads: Option<usize>,
    sets: &[String],
) -> Result<(Image, TestDesc), LoadError> {
    render_test_in(scene, threads, sets, None)
}

/// As [`render_test`], refusing inputs outside `root` (`--root`).
pub fn render_test_in(
    scene: &Path,
    threads: Option<usize>,
    sets: &[String],
    root: Option<&Path>,
) -> Result<(Image, TestDesc), LoadError> {
    let (o, t) = test_overrides(scene, sets, root)?;
    Ok((render_with(scene, &o, threads)?, t))
}

/// The per-pixel variance of `scene`'s test render after `sets`
/// ([`variance_of`] of renders with different seeds).
pub fn test_variance(
    scene: &Path,
    threads: Option<usize>,
    sets: &[String],
    root: Option<&Path>,
) -> Result<Image, LoadError> {
    let (o, _) = test_overrides(scene, sets, root)?;
    let first = render_with(scene, &o, threads)?;
    noise_of(scene, &o, threads, &first)
}

/// [`variance_of`] `first` (rendered with `o`) and [`NOISE_RENDERS`]
/// renders with other seeds.
fn noise_of(scene: &Path, o: &Overrides, threads: Option<usize>, first: &Image) -> Result<Image, LoadError> {
    let mut renders = vec![first.clone()];
    for i in 0..NOISE_RENDERS {
        let other = Overrides {
            seed: Some((o.seed.unwrap_or_default() ^ NOISE_SEED).wrapping_add(i)),
            ..o.clone()
        };
        renders.push(render_with(scene, &other, threads)?);
    }
    variance_of(&renders).map_err(|e| LoadError::Io {
        path: scene.to_path_buf(),
        source: std::io::Error::other(e),
    })
}

/// The overrides that turn `scene` into its test render (size, samples and
/// seed from `test`, after `sets`), and the test settings.
fn test_overrides(
    scene: &Path,
    sets: &[String],
    root: Option<&Path>,
) -> Result<(Overrides, TestDesc), LoadError> {
    let (test_sets, scene_sets): (Vec<String>, Vec<String>) = sets
        .iter()
        .cloned()
        .partition(|s| s.trim_start().starts_with("test"));
    let with_sets = Overrides {
        sets: scene_sets,
        root: root.map(Path::to_path_buf),
        ..Default::default()
    };
    let full = load_with(scene, &with_sets)?;
    let mut desc = full.desc.clone();
    desc.test = Some(desc.test.unwrap_or_default());
    crate::load::set::apply_sets(&mut desc, &test_sets)
        .map_err(|problems| LoadError::Invalid(crate::load::source::command_line(&problems)))?;
    let t = desc.test.unwrap_or_default();
    let (fw, fh) = (full.desc.film.width as f32, full.desc.film.height as f32);
    let height = t
        .height
        .unwrap_or(((t.width as f32) * fh / fw).round().max(1.0) as u32);
    let o = Overrides {
        spp: Some(t.spp),
        size: Some((t.width, height)),
        seed: Some(t.seed),
        ..with_sets
    };
    Ok((o, t))
}

/// `scene` loaded with `o`, rendered and 8-bit quantised.
fn render_with(scene: &Path, o: &Overrides, threads: Option<usize>) -> Result<Image, LoadError> {
    let loaded = load_with(scene, o)?;
    let (img, _) = render_whole(
        &loaded.scene,
        &loaded.view,
        &RenderOptions {
            threads,
            ..Default::default()
        },
    );
    Ok(quantise(&img))
}

/// The stored variance of `golden` when it is there and fits `img`.
fn stored_variance(golden: &Path, img: &Image) -> Option<Image> {
    read_image(&variance_path(golden))
        .ok()
        .filter(|v| (v.width, v.height) == (img.width, img.height))
}

/// The by-products of a failed check beside the golden: `<name>.new.png`,
/// `<name>.diff.png` and `<name>.html`.
fn by_product(golden: &Path, suffix: &str) -> PathBuf {
    golden.with_extension(suffix)
}

/// Refuses to judge a scene whose golden or by-products are (or pass
/// through) links leading out of the scene's folder and `root`: a scene
/// repository shipping `golden/x.png -> ../../notes.txt` would otherwise
/// have `--bless` (or a failed check) replace a file the user never named.
fn fenced(scene: &Path, golden: &Path, root: Option<&Path>) -> Result<(), LoadError> {
    let folder = crate::files::resolved(scene.parent().unwrap_or(Path::new("")));
    let fences: Vec<&Path> = std::iter::once(folder.as_path()).chain(root).collect();
    let writes = [
        golden.to_path_buf(),
        variance_path(golden),
        by_product(golden, "new.png"),
        by_product(golden, "diff.png"),
    ];
    match writes
        .iter()
        .find_map(|w| crate::files::write_outside(&fences, w))
    {
        None => Ok(()),
        Some(why) => Err(io_error(
            golden,
            format!("{why}; a scene's golden images are written only inside its folder"),
        )),
    }
}

fn remove_by_products(golden: &Path) {
    for s in ["new.png", "diff.png", "html"] {
        let _ = std::fs::remove_file(by_product(golden, s));
    }
}

/// What is at a scene's golden path.
enum Golden {
    /// Nothing: the golden is missing.
    Absent,
    /// A golden of the render's size.
    Usable(Image),
    /// A file that does not decode or has another size: why.
    Bad(String),
}

fn golden_state(golden: &Path, img: &Image) -> Golden {
    if std::fs::symlink_metadata(golden).is_err() {
        return Golden::Absent;
    }
    match read_image(golden) {
        Err(e) => Golden::Bad(format!("corrupt golden: {e}")),
        Ok(g) if (g.width, g.height) != (img.width, img.height) => Golden::Bad(format!(
            "golden is {}×{}, render is {}×{}",
            g.width, g.height, img.width, img.height
        )),
        Ok(g) => Golden::Usable(g),
    }
}

/// Checks one scene; with `bless`, a failed or missing golden is rewritten
/// (a corrupt or wrong-size one only with `force`), with its variance image.
pub fn check_scene(scene: &Path, opts: &CheckOptions) -> CheckResult {
    let start = Instant::now();
    let outcome = judge(scene, opts).unwrap_or_else(Outcome::Invalid);
    CheckResult {
        scene: scene.to_path_buf(),
        outcome,
        time: start.elapsed(),
    }
}

fn judge(scene: &Path, opts: &CheckOptions) -> Result<Outcome, LoadError> {
    let golden = golden_path(scene);
    fenced(scene, &golden, opts.root.as_deref())?;
    let (o, t) = test_overrides(scene, &opts.sets, opts.root.as_deref())?;
    let img = render_with(scene, &o, opts.threads)?;
    let tolerance = opts.tolerance.unwrap_or(t.tolerance as f64);
    let previous = match golden_state(&golden, &img) {
        Golden::Usable(g) => Some(g),
        Golden::Absent => None,
        Golden::Bad(_) if opts.bless && opts.force => None,
        Golden::Bad(reason) => {
            let new = by_product(&golden, "new.png");
            let _ = write_image(&img, &new);
            return Ok(Outcome::BadGolden { reason, new });
        }
    };
    // The noise: kept beside the golden, or measured now.
    let stored = stored_variance(&golden, &img);
    let mut fresh = None;
    let score = match (&previous, &stored) {
        (None, _) => None,
        (Some(g), Some(v)) => score(&img, g, v).ok(),
        (Some(g), None) => {
            let v = noise_of(scene, &o, opts.threads, &img)?;
            let s = score(&img, g, &v).ok();
            fresh = Some(v);
            s
        }
    };
    Ok(match (score, opts.bless) {
        (Some(s), _) if s.worst <= tolerance => {
            remove_by_products(&golden);
            if let (true, None, Some(v)) = (opts.bless, &stored, &fresh) {
                // A golden from before variance images gets one.
                write_image(v, &variance_path(&golden)).map_err(|e| io_error(&golden, e))?;
            }
            Outcome::Pass { score: s, tolerance }
        }
        (score, true) => {
            let v = match fresh {
                Some(v) => v,
                None => noise_of(scene, &o, opts.threads, &img)?,
            };
            write_image(&img, &golden).map_err(|e| io_error(&golden, e))?;
            write_image(&v, &variance_path(&golden)).map_err(|e| io_error(&golden, e))?;
            remove_by_products(&golden);
            Outcome::Blessed { score }
        }
        (None, false) => {
            let new = by_product(&golden, "new.png");
            let _ = write_image(&img, &new);
            Outcome::Missing { new }
        }
        (Some(score), false) => {
            let (new, heatmap) = (by_product(&golden, "new.png"), by_product(&golden, "diff.png"));
            let _ = write_image(&img, &new);
            if let Some(g) = &previous {
                let _ = write_image(&metrics::heatmap(&img, g, 0.1), &heatmap);
            }
            Outcome::Fail {
                score,
                tolerance,
                new,
                heatmap,
            }
        }
    })
}

fn io_error(path: &Path, e: impl std::fmt::Display) -> LoadError {
    LoadError::Io {
        path: path.to_path_buf(),
        source: std::io::Error::other(e.to_string()),
    }
}

/// The summary table printed by `ronray check`: the judged score (worst
/// window) beside the whole-image figure.
pub fn summary(results: &[CheckResult]) -> String {
    let mut s = format!(
        "{:<40} {:>8} {:>12} {:>12} {:>10} {:>8}\n",
        "scene", "status", "score", "whole relMSE", "tolerance", "time"
    );
    let figures = |sc: &Score| (format!("{:.3}", sc.worst), format!("{:.6}", sc.whole));
    for r in results {
        let name = r.scene.display().to_string();
        let dash = || ("-".to_string(), "-".to_string());
        let (status, (worst, whole), tol) = match &r.outcome {
            Outcome::Pass { score, tolerance } => ("ok", figures(score), format!("{tolerance:.4}")),
            Outcome::Fail { score, tolerance, .. } => ("FAIL", figures(score), format!("{tolerance:.4}")),
            Outcome::Missing { .. } => ("MISSING", dash(), "-".into()),
            Outcome::BadGolden { .. } => ("BAD", dash(), "-".into()),
            Outcome::Blessed { score } => ("blessed", score.as_ref().map_or_else(dash, figures), "-".into()),
            Outcome::Invalid(_) => ("INVALID", dash(), "-".into()),
        };
        s += &format!(
            "{name:<40} {status:>8} {worst:>12} {whole:>12} {tol:>10} {:>7.2}s\n",
            r.time.as_secs_f64()
        );
    }
    s
}
