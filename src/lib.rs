//! ronray: a physically based renderer driven by hand-written RON scene files.
//!
//! The pipeline is read → parse → validate → build → render; each stage is
//! its own module under [`scene`], and the renderer only ever sees the runtime
//! scene.

pub mod accel;
pub mod geometry;
pub mod materials;
pub mod math;
pub mod scene;
