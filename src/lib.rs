#![warn(missing_docs)]
//! ronray: a physically based renderer driven by hand-written RON scene files.
//!
//! The pipeline is read → parse ([`desc`]) → check → build ([`load`]) →
//! render ([`frame`]: plan, tiles, write). The loader returns the runtime [`scene::Scene`] (what
//! rays query) and the [`view::View`] beside it (camera, film, integrator);
//! the renderer sees only those two. [`farm`] cuts a frame into pieces that
//! render farms run on many machines, and assembles them bit for bit.

pub mod accel;
pub mod anim;
pub mod aov;
pub mod camera;
pub mod check;
pub mod cli;
pub mod cpu;
pub mod denoise;
pub mod desc;
pub mod diagnostic;
pub mod farm;
pub mod files;
pub mod film;
pub mod frame;
pub mod fuzzing;
pub mod geometry;
pub mod huge_pages;
pub mod imageio;
pub mod integrators;
pub mod lights;
pub mod load;
pub mod lsp;
pub mod materials;
pub mod math;
pub mod media;
pub mod memory;
pub mod migrate;

pub mod sampler;
pub mod scene;
pub mod schema;
pub mod syntax;
pub mod view;
pub mod watch;
