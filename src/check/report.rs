//! A static HTML page for each failed check: the new render, the golden and
//! their difference side by side (as Blender's render tests show them),
//! written as `golden/<name>.html` beside the images it shows, so the page
//! works from a file browser, a CI artefact or a plain `file://` link.

use super::{CheckResult, Outcome, golden_path};
use std::path::{Path, PathBuf};

/// Writes the page of every failed result; returns each page's path or why
/// it could not be written.
pub fn write_all(results: &[CheckResult]) -> Vec<Result<PathBuf, String>> {
    results
        .iter()
        .filter_map(|r| match &r.outcome {
            Outcome::Fail { score, tolerance, .. } => Some(write_page(&r.scene, score, *tolerance)),
            _ => None,
        })
        .collect()
}

fn write_page(scene: &Path, score: &super::Score, tolerance: f64) -> Result<PathBuf, String> {
    let golden = golden_path(scene);
    let page = golden.with_extension("html");
    let name = |p: &Path| p.file_name().and_then(|n| n.to_str()).unwrap_or("").to_string();
    let html = page_html(
        &scene.display().to_string(),
        [
            ("new render", name(&golden.with_extension("new.png"))),
            ("golden", name(&golden)),
            (
                "difference (white = 0.1 or more)",
                name(&golden.with_extension("diff.png")),
            ),
        ],
        score,
        tolerance,
    );
    std::fs::write(&page, html).map_err(|e| format!("{}: {e}", page.display()))?;
    Ok(page)
}

/// The page itself; image paths are relative to it.
pub fn page_html(scene: &str, images: [(&str, String); 3], score: &super::Score, tolerance: f64) -> String {
    let figures: String = images
        .iter()
        .map(|(caption, src)| {
            format!(
                "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                escape(src),
                escape(caption),
                escape(caption)
            )
        })
        .collect();
    let (x, y) = score.at;
    let side = super::WINDOW * super::COMPARE_FACTOR;
    format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n\
         <title>ronray check: {title} failed</title>\n<style>\n\
         body {{ font: 15px system-ui, sans-serif; margin: 2em; background: #222; color: #eee; }}\n\
         .row {{ display: flex; gap: 1.5em; flex-wrap: wrap; }}\n\
         figure {{ margin: 0; }}\n\
         img {{ width: 384px; image-rendering: pixelated; border: 1px solid #555; }}\n\
         code {{ color: #fc6; }}\n</style></head>\n<body>\n\
         <h1>{title}: regression</h1>\n\
         <p>Worst {side}×{side}-pixel window at ({x}, {y}): score <code>{worst:.3}</code> \
         (mean squared z-score of the difference against the noise), \
         over the tolerance <code>{tolerance:.4}</code> (whole-image relative MSE: <code>{whole:.6}</code>).</p>\n\
         <div class=\"row\">\n{figures}</div>\n\
         <p>Accept the new image on purpose with <code>ronray check --bless {title}</code>.</p>\n\
         </body></html>\n",
        title = escape(scene),
        worst = score.worst,
        whole = score.whole,
    )
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
