//! What a watch session tells the user: one status line rewritten in place
//! on a terminal (a scrolling log of passes would bury the diagnostics), one
//! line per event otherwise (for scripts and tests), and the same news as
//! JSON for the web page.

use super::hub::{Frame, Hub, Kind, json_str};
use crate::diagnostic::Report;
use crate::load::LoadError;
use std::io::Write;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

/// A pass that finished and was written.
#[derive(Clone, Debug)]
pub struct PassInfo {
    pub generation: u64,
    pub pass: usize,
    pub passes: usize,
    /// Samples per pixel in the image so far, and the scene's target.
    pub spp: u32,
    pub spp_total: u32,
    pub elapsed: Duration,
    pub since_change: Duration,
    pub output: PathBuf,
    pub size: (u32, u32),
}

pub struct Reporter {
    tty: bool,
    hub: Option<Arc<Hub>>,
    /// Serialises output so lines from the worker and the watcher never mix.
    out: Mutex<()>,
    /// Passes written so far: the page's image URL changes with each.
    version: AtomicU64,
}

impl Reporter {
    pub fn new(tty: bool, hub: Option<Arc<Hub>>) -> Self {
        Reporter {
            tty,
            hub,
            out: Mutex::new(()),
            version: AtomicU64::new(0),
        }
    }

    pub fn serving(&self) -> bool {
        self.hub.is_some()
    }

    /// The status line: replaces the previous one on a terminal.
    pub fn line(&self, text: &str) {
        let _guard = self.out.lock().unwrap_or_else(PoisonError::into_inner);
        let mut err = std::io::stderr().lock();
        let _ = if self.tty {
            write!(err, "\r\x1b[2K{text}")
        } else {
            writeln!(err, "{text}")
        };
        let _ = err.flush();
    }

    /// Text that must stay on screen (diagnostics), above the status line.
    fn block(&self, text: &str) {
        let _guard = self.out.lock().unwrap_or_else(PoisonError::into_inner);
        let mut err = std::io::stderr().lock();
        let clear = if self.tty { "\r\x1b[2K" } else { "" };
        let _ = write!(err, "{clear}{text}");
        let _ = err.flush();
    }

    fn publish(&self, kind: Kind, json: String, frame: Option<Frame>) {
        if let Some(hub) = &self.hub {
            hub.publish(kind, json, frame);
        }
    }

    fn progress(&self, state: &str, pass: usize, passes: usize, spp_done: u32, spp_total: u32) {
        self.publish(
            Kind::Progress,
            format!(
                r#"{{"state":"{state}","pass":{pass},"passes":{passes},"spp_done":{spp_done},"spp_total":{spp_total}}}"#
            ),
            None,
        );
    }

    pub fn loaded(&self, generation: u64, scene: &str, load: Duration, reused: usize, watched: usize) {
        self.publish(Kind::Diagnostics, r#"{"message":null}"#.into(), None);
        self.progress("loaded", 0, 0, 0, 0);
        self.line(&format!(
            "change {generation}: loaded {scene} in {:.1} ms ({reused} meshes reused, {watched} files watched)",
            load.as_secs_f64() * 1e3
        ));
    }

    /// Warnings of a scene that loaded (it renders anyway): kept on screen
    /// above the status line, like errors. The page is not told: it shows
    /// only errors, as a reason the image is stale.
    pub fn warnings(&self, warnings: &Report) {
        if !warnings.diagnostics.is_empty() {
            self.block(&warnings.render(self.tty));
        }
    }

    /// An edit that does not load: every diagnostic, and the old image stays.
    pub fn invalid(&self, generation: u64, e: &LoadError) {
        let plain = match e.report() {
            Some(r) => {
                self.block(&r.render(self.tty));
                r.render(false)
            }
            None => e.to_string(),
        };
        self.publish(
            Kind::Diagnostics,
            format!(r#"{{"message":{}}}"#, json_str(&plain)),
            None,
        );
        self.progress("invalid", 0, 0, 0, 0);
        self.line(&format!(
            "change {generation}: error: {e}; keeping the last good image"
        ));
    }

    /// A problem that is not the scene's (an output path, a missing file).
    pub fn problem(&self, generation: u64, message: &str) {
        self.publish(
            Kind::Diagnostics,
            format!(r#"{{"message":{}}}"#, json_str(message)),
            None,
        );
        self.progress("invalid", 0, 0, 0, 0);
        self.line(&format!("change {generation}: {message}"));
    }

    pub fn pass_started(&self, pass: usize, passes: usize, spp_done: u32, spp_target: u32, spp_total: u32) {
        self.progress("rendering", pass, passes, spp_done, spp_total);
        if self.tty {
            self.line(&format!("pass {pass}/{passes}: rendering {spp_target} spp…"));
        }
    }

    pub fn pass_written(&self, p: &PassInfo, frame: Option<Frame>) {
        let version = self.version.fetch_add(1, Ordering::Relaxed) + 1;
        let json = format!(
            r#"{{"version":{version},"generation":{},"pass":{},"passes":{},"spp":{},"spp_total":{},"seconds":{:.3},"width":{},"height":{},"output":{}}}"#,
            p.generation,
            p.pass,
            p.passes,
            p.spp,
            p.spp_total,
            p.elapsed.as_secs_f64(),
            p.size.0,
            p.size.1,
            json_str(&p.output.display().to_string())
        );
        self.publish(Kind::Pass, json, frame);
        let state = if p.pass == p.passes { "done" } else { "rendering" };
        self.progress(state, p.pass, p.passes, p.spp, p.spp_total);
        self.line(&format!(
            "pass {}/{}: {} spp written to {} ({:.2} s, {:.2} s after the change)",
            p.pass,
            p.passes,
            p.spp,
            p.output.display(),
            p.elapsed.as_secs_f64(),
            p.since_change.as_secs_f64()
        ));
    }

    pub fn cancelled(&self, pass: usize, passes: usize, stopped_after: Option<Duration>) {
        self.progress("cancelled", pass, passes, 0, 0);
        let after = stopped_after
            .map(|d| format!(" ({:.1} ms after the change)", d.as_secs_f64() * 1e3))
            .unwrap_or_default();
        self.line(&format!("pass {pass}/{passes}: cancelled{after}"));
    }

    pub fn failed(&self, message: &str) {
        self.progress("failed", 0, 0, 0, 0);
        self.line(&format!("error: {message}"));
    }

    /// Leaves the terminal on a fresh line.
    pub fn finish(&self, message: &str) {
        self.block(&format!("{message}\n"));
    }
}
