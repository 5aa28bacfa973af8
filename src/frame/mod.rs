//! One frame, from request to file: the frame wing.
//!
//! - `plan.rs`: a [`Plan`] made once from the view and a [`Request`] (the
//!   whole frame, a piece of rect × sample range, watch pass k of n): the
//!   sample range, the sampling policy ([`Sampling`]: even, adaptive, spread
//!   by noise), the caustic light-tracing pass, the layers and denoising.
//! - `output.rs`: [`Output`], where the frame goes and whether it may go
//!   there (the format carries what the plan produces, no input is
//!   overwritten, the film fits in memory), over the format table
//!   [`crate::imageio::OutputFormat`].
//! - `tiles.rs`: the one tile loop, over the policy the plan chose.
//! - `caustics.rs`: the light-tracing pass a whole frame may add.
//! - `render.rs`: [`render`], the entry point, and [`render_whole`];
//!   `options.rs` and `stats.rs`: how to render and what it cost.
//! - `write.rs`: the one writer, for beauty, layers, denoised copies,
//!   pieces and passes.
//!
//! The CLI, watch mode and the farm make a plan, check an output, render
//! and write; they print what these answer and decide nothing again.
//! `film/` keeps the film's data and per-pixel rules (filter, adaptive
//! stopping, allocation by noise); the loader never imports this wing.

mod caustics;
mod options;
pub mod output;
pub mod plan;
mod render;
mod stats;
mod tiles;
pub mod write;

pub use options::RenderOptions;
pub use output::{Output, OutputError};
pub use plan::{LightTrace, Plan, PlanError, Request, Sampling, pass_targets};
pub use render::{Pixels, render, render_whole};
pub use stats::{RenderStats, TileDone};
pub use write::{WriteError, WriteOptions, noisy_path, write};
