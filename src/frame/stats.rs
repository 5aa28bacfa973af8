//! What a render reports: its cost ([`RenderStats`]) and each finished
//! tile ([`TileDone`]), for summaries, progress lines and benchmarks.

use crate::imageio::PixelRect;
use std::time::Duration;

/// What a render cost, for the summary line and benchmarks.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderStats {
    /// Wall-clock time of the render.
    pub elapsed: Duration,
    /// Camera samples taken (pixels × samples per pixel, fewer if cancelled).
    pub samples: u64,
    /// Rays traced, camera, bounce and shadow rays together.
    pub rays: u64,
    /// True if the render stopped early because it was cancelled.
    pub cancelled: bool,
}

impl RenderStats {
    /// One line for the terminal: seconds, millions of samples and of rays per
    /// second.
    pub fn summary(&self) -> String {
        let s = self.elapsed.as_secs_f64().max(1e-9);
        format!(
            "{:.2} s, {:.2} M samples/s, {:.2} M rays/s",
            s,
            self.samples as f64 / s / 1e6,
            self.rays as f64 / s / 1e6
        )
    }
}

/// A finished tile, for progress reports.
#[derive(Clone, Copy, Debug)]
pub struct TileDone {
    /// The tile's pixels.
    pub rect: PixelRect,
    /// Tiles finished so far, this one included.
    pub done: usize,
    /// Tiles in the render.
    pub total: usize,
    /// Since the render started.
    pub elapsed: Duration,
}
