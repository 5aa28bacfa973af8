//! Regression checks: render each scene at its `test` settings and compare
//! with its golden image, `golden/<scene name>.png` beside the scene file.
//!
//! # Metric
//! Relative MSE on linear RGB, `mean((a − g)² / (g² + 0.01))` over pixels
//! and channels, computed on both images box-downsampled by
//! [`COMPARE_FACTOR`] (4×4 pixels → 1), after the new render has gone through
//! the same 8-bit sRGB encoding as the golden (so an unchanged renderer
//! scores exactly 0). Relative error weighs dark regions as much as bright
//! ones; the downsampling divides Monte Carlo noise variance by 16 while
//! keeping what a regression changes (a colour, a shadow, a highlight), so
//! a harmless change of noise pattern passes and a changed material does
//! not. The threshold is the scene's `test.tolerance` (default
//! [`DEFAULT_TOLERANCE`]).

use crate::desc::TestDesc;
use crate::imageio::{Image, compare, metrics, read_image, srgb_decode, srgb8, write_image};
use crate::load::{LoadError, Overrides, load_with};
use crate::render::{RenderOptions, render};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub use crate::desc::DEFAULT_TOLERANCE;
/// Box-downsampling factor applied before comparing.
pub const COMPARE_FACTOR: u32 = 4;

/// The documented metric: relative MSE after box downsampling.
pub fn golden_error(new: &Image, golden: &Image) -> Result<f64, String> {
    compare(
        &new.downsample(COMPARE_FACTOR),
        &golden.downsample(COMPARE_FACTOR),
        None,
    )
    .map(|c| c.rel_mse)
}

/// What checking one scene against its golden image found.
#[derive(Debug)]
pub enum Outcome {
    /// The render matches its golden image within tolerance.
    Pass {
        /// Relative MSE of the render against the golden image (see the module docs).
        error: f64,
        /// The scene's `test.tolerance`: the largest relative MSE that passes.
        tolerance: f64,
    },
    /// The render differs from its golden image by more than the tolerance.
    Fail {
        /// Relative MSE of the render against the golden image.
        error: f64,
        /// The scene's `test.tolerance`.
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
    /// Golden written by `--bless`.
    Blessed {
        /// Error against the previous golden, if there was one.
        error: Option<f64>,
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
            Outcome::Fail { .. } | Outcome::Missing { .. } | Outcome::Invalid(_)
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

/// Renders `scene` at its test settings.
pub fn render_test(scene: &Path, threads: Option<usize>) -> Result<(Image, TestDesc), LoadError> {
    let full = load_with(scene, &Overrides::default())?;
    let t = full.desc.test.clone().unwrap_or_default();
    let (fw, fh) = (full.desc.film.width as f32, full.desc.film.height as f32);
    let height = t
        .height
        .unwrap_or(((t.width as f32) * fh / fw).round().max(1.0) as u32);
    let o = Overrides {
        spp: Some(t.spp),
        size: Some((t.width, height)),
        seed: Some(t.seed),
        ..Default::default()
    };
    let loaded = load_with(scene, &o)?;
    let (img, _) = render(
        &loaded.scene,
        &loaded.view,
        &RenderOptions {
            threads,
            ..Default::default()
        },
    );
    Ok((quantise(&img), t))
}

/// Checks one scene; with `bless`, a failed or missing golden is rewritten.
pub fn check_scene(scene: &Path, bless: bool, threads: Option<usize>) -> CheckResult {
    let start = Instant::now();
    let golden = golden_path(scene);
    let sibling = |suffix: &str| golden.with_extension(format!("{suffix}.png"));
    let outcome = match render_test(scene, threads) {
        Err(e) => Outcome::Invalid(e),
        Ok((img, t)) => {
            let tolerance = t.tolerance as f64;
            let previous = read_image(&golden).ok();
            let error = previous.as_ref().and_then(|g| golden_error(&img, g).ok());
            match (error, bless) {
                (Some(e), _) if e <= tolerance => {
                    let _ = std::fs::remove_file(sibling("new"));
                    let _ = std::fs::remove_file(sibling("diff"));
                    Outcome::Pass { error: e, tolerance }
                }
                (error, true) => match write_image(&img, &golden) {
                    Ok(()) => {
                        let _ = std::fs::remove_file(sibling("new"));
                        let _ = std::fs::remove_file(sibling("diff"));
                        Outcome::Blessed { error }
                    }
                    Err(e) => Outcome::Invalid(LoadError::Io {
                        path: golden.clone(),
                        source: std::io::Error::other(e.to_string()),
                    }),
                },
                (None, false) => {
                    let new = sibling("new");
                    let _ = write_image(&img, &new);
                    Outcome::Missing { new }
                }
                (Some(error), false) => {
                    let (new, heatmap) = (sibling("new"), sibling("diff"));
                    let _ = write_image(&img, &new);
                    if let Some(g) = &previous {
                        let _ = write_image(&metrics::heatmap(&img, g, 0.1), &heatmap);
                    }
                    Outcome::Fail {
                        error,
                        tolerance,
                        new,
                        heatmap,
                    }
                }
            }
        }
    };
    CheckResult {
        scene: scene.to_path_buf(),
        outcome,
        time: start.elapsed(),
    }
}

/// The summary table printed by `ronray check`.
pub fn summary(results: &[CheckResult]) -> String {
    let mut s = format!(
        "{:<40} {:>8} {:>12} {:>10} {:>8}\n",
        "scene", "status", "relMSE", "tolerance", "time"
    );
    for r in results {
        let name = r.scene.display().to_string();
        let (status, err, tol) = match &r.outcome {
            Outcome::Pass { error, tolerance } => ("ok", format!("{error:.6}"), format!("{tolerance:.4}")),
            Outcome::Fail { error, tolerance, .. } => {
                ("FAIL", format!("{error:.6}"), format!("{tolerance:.4}"))
            }
            Outcome::Missing { .. } => ("MISSING", "-".into(), "-".into()),
            Outcome::Blessed { error } => (
                "blessed",
                error.map_or("-".into(), |e| format!("{e:.6}")),
                "-".into(),
            ),
            Outcome::Invalid(_) => ("INVALID", "-".into(), "-".into()),
        };
        s += &format!(
            "{name:<40} {status:>8} {err:>12} {tol:>10} {:>7.2}s\n",
            r.time.as_secs_f64()
        );
    }
    s
}
