//! The render worker: a quick 1-sample pass first, then passes that double
//! the sample count up to the scene's, each written atomically.
//!
//! Passes add samples to running per-pixel sums (plans of `Request::Pass`), so no
//! sample is rendered twice and the last pass is byte-identical to what
//! `ronray render` writes for the same scene. A pass stops within a tile of
//! its job being cancelled; a cancelled job writes nothing more, so an
//! invalid edit leaves the last good image on disk as it was.

use super::hub::Frame;
use super::status::{PassInfo, Reporter};
use crate::frame::{Output, Pixels, Plan, RenderOptions, Request, WriteOptions, pass_targets};
use crate::imageio::{Display, Image, PixelRect, SampleSums};
use crate::scene::Scene;
use crate::view::View;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::Receiver;
use std::sync::{Arc, OnceLock};
use std::thread::JoinHandle;
use std::time::Instant;

/// Set when a newer edit makes a job pointless; remembers when, to report
/// how long stopping took, and whether the job wrote its last pass before.
#[derive(Debug, Default)]
pub struct Cancel {
    flag: AtomicBool,
    at: OnceLock<Instant>,
    finished: AtomicBool,
}

impl Cancel {
    /// Whether the job wrote its complete image (a later cancel does not
    /// undo that).
    pub fn finished(&self) -> bool {
        self.finished.load(Ordering::SeqCst)
    }

    pub fn cancel(&self) {
        let _ = self.at.set(Instant::now());
        self.flag.store(true, Ordering::SeqCst);
    }

    pub fn is_set(&self) -> bool {
        self.flag.load(Ordering::SeqCst)
    }
}

/// One successfully loaded version of the scene.
pub struct Job {
    pub scene: Scene,
    pub view: View,
    pub output: Output,
    pub cancel: Arc<Cancel>,
    pub generation: u64,
    /// The first filesystem event of the edit that produced this job.
    pub changed_at: Instant,
}

/// Renders jobs as they come, always skipping to the newest queued one.
pub fn spawn(jobs: Receiver<Job>, reporter: Arc<Reporter>, threads: Option<usize>) -> JoinHandle<()> {
    std::thread::spawn(move || {
        while let Ok(mut job) = jobs.recv() {
            while let Ok(newer) = jobs.try_recv() {
                job = newer;
            }
            if !job.cancel.is_set() {
                run(&job, &reporter, threads);
            }
        }
    })
}

fn run(job: &Job, reporter: &Reporter, threads: Option<usize>) {
    let film = job.view.film;
    let (scene, view) = (&job.scene, &job.view);
    let passes = pass_targets(film.spp).len();
    let mut sums = SampleSums::new(PixelRect::full(film.width, film.height));
    for k in 0..passes {
        let pass = k + 1;
        let stopped = || job.cancel.at.get().map(|t| t.elapsed());
        if job.cancel.is_set() {
            reporter.cancelled(pass, passes, stopped());
            return;
        }
        let plan = match Plan::new(scene, view, Request::Pass { k }, false) {
            Ok(plan) => plan,
            Err(e) => return reporter.failed(&format!("{e}; watching for the next change")),
        };
        let (done, target) = plan.samples;
        reporter.pass_started(pass, passes, done, target, film.spp);
        let opts = RenderOptions {
            threads,
            progress: false,
        };
        let (pixels, stats) = crate::frame::render(scene, view, &plan, &opts, &job.cancel.flag, &|_| {});
        // Checked again after the pass: a superseded scene writes nothing.
        if stats.cancelled || job.cancel.is_set() {
            reporter.cancelled(pass, passes, stopped());
            return;
        }
        if let Pixels::Sums(pass_sums) = &pixels {
            sums.add(pass_sums);
        }
        // The same division `render` does, on the same sums.
        let pixels = Pixels::Means(sums.mean(target));
        let written = crate::frame::write(scene, view, &plan, &job.output, &pixels, &WriteOptions::default());
        if let Err(e) = written {
            reporter.failed(&format!("{e}; watching for the next change"));
            return;
        }
        let frame = match pixels {
            Pixels::Means(image) if reporter.serving() => Some(Frame {
                png: encode_png(&image, &job.view.display),
                image,
                display: job.view.display,
            }),
            Pixels::Means(_) | Pixels::Sums(_) => None,
        };
        let info = PassInfo {
            generation: job.generation,
            pass,
            passes,
            spp: target,
            spp_total: film.spp,
            elapsed: stats.elapsed,
            since_change: job.changed_at.elapsed(),
            output: job.output.path.clone(),
            size: (film.width, film.height),
        };
        reporter.pass_written(&info, frame);
    }
    job.cancel.finished.store(true, Ordering::SeqCst);
}

/// The web page's copy of a pass: 8-bit sRGB through `display` (exposure
/// and tone map) like a PNG output file, even when the output is EXR.
pub fn encode_png(img: &Image, display: &Display) -> Vec<u8> {
    let bytes = crate::imageio::encode::to_display8(img, display);
    let mut png = Vec::new();
    let encoder = image::codecs::png::PngEncoder::new(&mut png);
    let ok = image::ImageEncoder::write_image(
        encoder,
        &bytes,
        img.width,
        img.height,
        image::ExtendedColorType::Rgb8,
    );
    if ok.is_err() {
        png.clear();
    }
    png
}
