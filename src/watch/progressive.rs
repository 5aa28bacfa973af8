//! The render worker: a quick 1-sample pass first, then passes that double
//! the sample count up to the scene's, each written atomically.
//!
//! Passes add samples to running per-pixel sums (`render_accumulate`), so no
//! sample is rendered twice and the last pass is byte-identical to what
//! `ronray render` writes for the same scene. A pass stops within a tile of
//! its job being cancelled; a cancelled job writes nothing more, so an
//! invalid edit leaves the last good image on disk as it was.

use super::hub::Frame;
use super::status::{PassInfo, Reporter};
use crate::imageio::{Display, Image, PixelRect, write_image_with};
use crate::render::{RenderOptions, SampleSums, render_accumulate};
use crate::scene::Scene;
use crate::view::View;
use std::path::PathBuf;
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
    pub output: PathBuf,
    pub cancel: Arc<Cancel>,
    pub generation: u64,
    /// The first filesystem event of the edit that produced this job.
    pub changed_at: Instant,
}

/// Cumulative sample counts after each pass: 1, 2, 4, … and finally `spp`.
pub fn schedule(spp: u32) -> Vec<u32> {
    let mut targets: Vec<u32> = std::iter::successors(Some(1u32), |&n| n.checked_mul(2))
        .take_while(|&n| n < spp)
        .collect();
    targets.push(spp.max(1));
    targets
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
    let targets = schedule(film.spp);
    let passes = targets.len();
    let mut sums = SampleSums::new(PixelRect::full(film.width, film.height));
    let mut done = 0;
    for (k, &target) in targets.iter().enumerate() {
        let pass = k + 1;
        let stopped = || job.cancel.at.get().map(|t| t.elapsed());
        if job.cancel.is_set() {
            reporter.cancelled(pass, passes, stopped());
            return;
        }
        reporter.pass_started(pass, passes, done, target, film.spp);
        let opts = RenderOptions {
            threads,
            progress: false,
            sample_range: Some((done, target - done)),
        };
        let stats = render_accumulate(&job.scene, &job.view, &opts, &job.cancel.flag, &mut sums);
        // Checked again after the pass: a superseded scene writes nothing.
        if stats.cancelled || job.cancel.is_set() {
            reporter.cancelled(pass, passes, stopped());
            return;
        }
        done = target;
        // The same division `render` does, on the same sums.
        let image = sums.mean(done);
        if let Err(e) = write_image_with(&image, &job.output, &job.view.display) {
            reporter.failed(&format!("{e}; watching for the next change"));
            return;
        }
        let frame = reporter.serving().then(|| Frame {
            png: encode_png(&image, &job.view.display),
            image,
            display: job.view.display,
        });
        let info = PassInfo {
            generation: job.generation,
            pass,
            passes,
            spp: done,
            spp_total: film.spp,
            elapsed: stats.elapsed,
            since_change: job.changed_at.elapsed(),
            output: job.output.clone(),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedule_doubles_up_to_the_scene_spp() {
        assert_eq!(schedule(1), vec![1]);
        assert_eq!(schedule(8), vec![1, 2, 4, 8]);
        assert_eq!(schedule(64), vec![1, 2, 4, 8, 16, 32, 64]);
        assert_eq!(schedule(100), vec![1, 2, 4, 8, 16, 32, 64, 100]);
        assert_eq!(schedule(u32::MAX).last(), Some(&u32::MAX));
    }
}
