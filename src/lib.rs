//! ronray: a physically based renderer driven by hand-written RON scene files.
//!
//! The pipeline is read → parse → validate → build → render; each stage is
//! its own module under [`scene`], and the renderer only ever sees the runtime
//! [`scene::Scene`].

pub mod accel;
pub mod bench;
pub mod camera;
pub mod check;
pub mod cli;
pub mod diagnostic;
pub mod geometry;
pub mod imageio;
pub mod integrators;
pub mod lights;
pub mod materials;
pub mod math;
pub mod render;
pub mod sampler;
pub mod scene;
pub mod schema;
pub mod watch;
