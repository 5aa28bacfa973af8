//! The time of the camera sample this thread is tracing, read by whatever
//! moves during the shutter (moving instances).
//!
//! pbrt-v4 carries the time in its `Ray`. Here it travels beside the ray,
//! on the thread: a camera sample and every ray of its path are traced on
//! one thread, and `Ray` stays two vectors (32 bytes) so that static
//! scenes, which never read the clock, trace exactly as before. The view
//! sets it in `View::camera_ray` when the scene has motion during the
//! shutter; nothing else writes it.

use std::cell::Cell;

thread_local! {
    static NOW: Cell<f32> = const { Cell::new(0.0) };
}

/// Sets the time, in frames, of the camera sample this thread traces next.
#[inline]
pub fn set(time: f32) {
    NOW.with(|c| c.set(time));
}

/// The time, in frames, of the camera sample this thread is tracing; 0
/// before any was set.
#[inline]
pub fn now() -> f32 {
    NOW.with(Cell::get)
}
