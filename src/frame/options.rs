//! How a frame is rendered, as opposed to what: threads and progress.

/// How to render (threads, progress); the plan says what.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderOptions {
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    /// Draw a progress bar on stderr (only shown on a terminal).
    pub progress: bool,
}
