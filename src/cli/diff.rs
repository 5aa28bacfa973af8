//! `ronray diff`: image metrics, heat map and threshold.

use super::print_out;
use crate::imageio::{self, Image, compare, read_image, write_image};
use std::path::Path;
use std::process::ExitCode;

pub(super) fn cmd_diff(
    a: &Path,
    b: &Path,
    heatmap: Option<&Path>,
    max_rmse: Option<f64>,
    mask: Option<&Path>,
) -> ExitCode {
    if let Some(h) = heatmap
        && [a, b].iter().any(|input| same_file(input, h))
    {
        eprintln!(
            "error: the heat map {} would overwrite an image being compared; nothing was written",
            h.display()
        );
        return ExitCode::FAILURE;
    }
    let load = |p: &Path| read_image(p).map_err(|e| eprintln!("error: {e}"));
    let (Ok(ia), Ok(ib)) = (load(a), load(b)) else {
        return ExitCode::FAILURE;
    };
    let skip: Option<Vec<bool>> = match mask.map(load) {
        Some(Ok(m)) if (m.width, m.height) == (ia.width, ia.height) => {
            Some(m.pixels.iter().map(|p| p.x >= 0.2).collect())
        }
        Some(Ok(m)) => {
            eprintln!(
                "error: mask is {}×{}, images are {}×{}",
                m.width, m.height, ia.width, ia.height
            );
            return ExitCode::FAILURE;
        }
        Some(Err(())) => return ExitCode::FAILURE,
        None => None,
    };
    let c = match compare(&ia, &ib, skip.as_deref()) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    };
    // Through `print_out`: `ronray diff … | head -1` must not panic.
    print_out(&format!(
        "rmse     {:.6}\nrel_mse  {:.6}\npsnr     {:.2} dB\nmean a   {:.6} {:.6} {:.6}\nmean b   {:.6} {:.6} {:.6}\npixels   {}\n",
        c.rmse,
        c.rel_mse,
        c.psnr,
        c.mean_a[0],
        c.mean_a[1],
        c.mean_a[2],
        c.mean_b[0],
        c.mean_b[1],
        c.mean_b[2],
        c.pixels
    ));
    if let Some(h) = heatmap {
        let img: Image = imageio::metrics::heatmap(&ia, &ib, (4.0 * c.rmse as f32).max(1e-6));
        if let Err(e) = write_image(&img, h) {
            eprintln!("error: {e}");
            return ExitCode::FAILURE;
        }
    }
    match max_rmse {
        // A NaN pixel makes the RMSE NaN, which compares below anything: a
        // gate must not pass on it.
        Some(_) if c.rmse.is_nan() => {
            eprintln!("rmse is NaN (an image has a NaN pixel): above any threshold");
            ExitCode::FAILURE
        }
        Some(t) if c.rmse > t => {
            eprintln!("rmse {:.6} is above the threshold {t}", c.rmse);
            ExitCode::FAILURE
        }
        _ => ExitCode::SUCCESS,
    }
}

/// Whether `a` and `b` name the same file (an existing one by identity, else
/// by spelling).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}
