//! `ronray watch`: edit the scene, see the image, never lose the last good
//! picture.
//!
//! The main thread owns the filesystem watcher: a change cancels the render
//! in flight at once, then, once the files have been quiet for a moment
//! (`debounce`), reloads and validates. A valid scene goes to the render
//! worker (`progressive`), which writes a quick pass and then refines it;
//! an invalid one prints its diagnostics and leaves the image on disk alone.
//! Folders are watched rather than files (`watched`), and the set is
//! re-derived after every reload, so adding or renaming an OBJ re-arms it.

mod debounce;
mod hub;
pub mod mesh_cache;
mod progressive;
mod server;
mod status;
mod watched;

use crate::desc::ObjectDesc;
use crate::frame::{Output, OutputError, Plan, Request};
use crate::load::pipeline::{load_str_with_meshes, read};
use crate::load::{LoadError, Overrides};
use debounce::Debounce;
use mesh_cache::MeshCache;
use notify::{RecommendedWatcher, RecursiveMode, Watcher};
use progressive::{Cancel, Job};
use status::Reporter;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::time::Instant;
use watched::WatchSet;

/// What `ronray watch` was asked to do.
#[derive(Clone, Debug)]
pub struct WatchArgs {
    /// The scene file to watch.
    pub scene: PathBuf,
    /// `-o`: where each pass is written (default as for `render`).
    pub output: Option<PathBuf>,
    /// Overrides from the command line (`--spp`, `--set`, …).
    pub overrides: Overrides,
    /// Worker threads; `None` uses every core.
    pub threads: Option<usize>,
    /// `Some("")` serves on the default address.
    pub serve: Option<String>,
    /// `--max-memory` in bytes (default: what the machine has available).
    pub max_memory: Option<u64>,
}

enum Msg {
    Fs(notify::Result<notify::Event>),
    Quit,
}

/// Watches and re-renders until interrupted (Ctrl-C).
pub fn run(args: WatchArgs) -> ExitCode {
    let hub = args.serve.is_some().then(|| Arc::new(hub::Hub::default()));
    let reporter = Arc::new(Reporter::new(std::io::stderr().is_terminal(), hub.clone()));
    if let (Some(addr), Some(hub)) = (&args.serve, hub) {
        match server::start(addr, hub) {
            Ok(a) => eprintln!("serving http://{a}/"),
            Err(e) => {
                let shown = if addr.is_empty() {
                    "the default port"
                } else {
                    addr.as_str()
                };
                eprintln!("error: cannot serve on {shown}: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    if !args.scene.is_file() {
        eprintln!("error: cannot read scene file {}", args.scene.display());
        return ExitCode::FAILURE;
    }
    let (tx, rx) = mpsc::channel();
    let quit = tx.clone();
    if let Err(e) = ctrlc::set_handler(move || {
        let _ = quit.send(Msg::Quit);
    }) {
        eprintln!("warning: Ctrl-C will not stop cleanly: {e}");
    }
    let watcher = match notify::recommended_watcher(move |r| {
        let _ = tx.send(Msg::Fs(r));
    }) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("error: cannot watch files: {e}");
            return ExitCode::FAILURE;
        }
    };
    eprintln!("watching {} (Ctrl-C to stop)", args.scene.display());
    let (jobs, queue) = mpsc::channel();
    let worker = progressive::spawn(queue, reporter.clone(), args.threads);
    let mut session = Session {
        overrides: args.overrides,
        scene: args.scene,
        output: args.output,
        max_memory: args.max_memory,
        reporter: reporter.clone(),
        watcher,
        set: WatchSet::default(),
        cache: MeshCache::default(),
        cancel: Arc::new(Cancel::default()),
        generation: 0,
        jobs,
        rendered: None,
    };
    // Watch before the first load, so an edit during it is not missed.
    session.rearm(WatchSet::new([&session.scene]));
    session.reload(Instant::now());
    session.event_loop(&rx);
    session.cancel.cancel();
    drop(session);
    let _ = worker.join();
    reporter.finish("stopped");
    ExitCode::SUCCESS
}

/// The watcher side: what is watched, the last load, the job in flight.
struct Session {
    scene: PathBuf,
    output: Option<PathBuf>,
    overrides: Overrides,
    max_memory: Option<u64>,
    reporter: Arc<Reporter>,
    watcher: RecommendedWatcher,
    set: WatchSet,
    cache: MeshCache,
    cancel: Arc<Cancel>,
    generation: u64,
    jobs: Sender<Job>,
    /// What the last job was rendered from, to tell a save that changed
    /// nothing (editors write twice, a checkout of the same text); `None`
    /// after a reload that sent no job.
    rendered: Option<Inputs>,
}

/// The scene's text, and of every file the load read: the text of scene
/// files (the scene, its includes; small), the size and modification time of
/// the others (meshes and images can be large).
#[derive(PartialEq)]
struct Inputs {
    text: String,
    files: Vec<(PathBuf, Stamp)>,
}

#[derive(PartialEq)]
enum Stamp {
    Text(String),
    Modified(u64, std::time::SystemTime),
    Unreadable,
}

impl Inputs {
    fn of(text: String, files: &[PathBuf]) -> Self {
        let stamp = |p: &PathBuf| {
            let is_scene = p
                .extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("ron") || e.eq_ignore_ascii_case("json"));
            let read = || -> Option<Stamp> {
                if is_scene {
                    return std::fs::read_to_string(p).ok().map(Stamp::Text);
                }
                let m = std::fs::metadata(p).ok()?;
                Some(Stamp::Modified(m.len(), m.modified().ok()?))
            };
            read().unwrap_or(Stamp::Unreadable)
        };
        Inputs {
            text,
            files: files.iter().map(|p| (p.clone(), stamp(p))).collect(),
        }
    }
}

impl Session {
    fn event_loop(&mut self, rx: &Receiver<Msg>) {
        let mut debounce = Debounce::default();
        loop {
            if let Some(first) = debounce.take_due(Instant::now()) {
                self.reload(first);
            }
            let msg = match debounce.deadline() {
                Some(d) => rx.recv_timeout(d.saturating_duration_since(Instant::now())),
                None => rx.recv().map_err(|_| RecvTimeoutError::Disconnected),
            };
            match msg {
                Ok(Msg::Quit) | Err(RecvTimeoutError::Disconnected) => return,
                Err(RecvTimeoutError::Timeout) => {}
                Ok(Msg::Fs(Ok(ev))) => {
                    if ev.need_rescan() || self.set.matters(&ev.kind, &ev.paths) {
                        // The render in flight is stale already: stop it now,
                        // not after the debounce.
                        self.cancel.cancel();
                        debounce.note(Instant::now());
                    }
                }
                Ok(Msg::Fs(Err(e))) => self.reporter.line(&format!("warning: file watcher: {e}")),
            }
        }
    }

    /// Loads the scene as it is now and hands it to the worker, or reports
    /// why it cannot be rendered.
    fn reload(&mut self, changed_at: Instant) {
        self.generation += 1;
        let generation = self.generation;
        self.cancel.cancel();
        let t0 = Instant::now();
        let text = match std::fs::read_to_string(&self.scene) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                let msg = format!("{} is missing; waiting for it", self.scene.display());
                return self.reporter.problem(generation, &msg);
            }
            Err(source) => {
                let path = self.scene.clone();
                return self.reporter.invalid(generation, &LoadError::Io { path, source });
            }
        };
        let cache = &self.cache;
        let loaded = load_str_with_meshes(&self.scene, &text, &self.overrides, &|p| cache.load(p));
        let inputs = loaded.as_ref().ok().map(|l| Inputs::of(text.clone(), &l.files));
        if inputs.is_some() && inputs == self.rendered && self.cancel.finished() {
            // Nothing changed since the complete image on screen.
            return;
        }
        // Set again only once a job is on its way: a scene refused below
        // (its output, the memory it needs) is checked again on any save.
        self.rendered = None;
        let loaded = match loaded {
            Ok(l) => l,
            Err(e) => {
                self.reporter.invalid(generation, &e);
                // Watch what the broken scene names too: creating the OBJ
                // it is missing should fix it.
                let next = self
                    .set
                    .union(&WatchSet::new(&referenced_files(&self.scene, &text)));
                return self.rearm(next);
            }
        };
        let (load_time, reused) = (t0.elapsed(), self.cache.take_hits());
        self.cache.retain(&loaded.files);
        self.rearm(WatchSet::new(&loaded.files));
        // The first pass's plan answers for every pass: same pixels, same
        // output rule (format, not an input, fits in memory).
        let output = Plan::new(&loaded.scene, &loaded.view, Request::Pass { k: 0 }, false)
            .map_err(|e| e.to_string())
            .and_then(|plan| {
                let path = Output::path(&loaded.view, &self.scene, self.output.clone(), None);
                Output::new(path, &plan, &loaded.files, self.max_memory)
                    .and_then(|o| {
                        o.confine_scene_output(&loaded.view, &self.scene, self.output.is_some(), None)
                    })
                    .map_err(|e| match e {
                        // Writing it would overwrite an input and trigger this
                        // reload again, for ever.
                        OutputError::IsInput { .. } => format!("{e}; keeping the last good image"),
                        _ => e.to_string(),
                    })
            });
        let output = match output {
            Ok(o) => o,
            Err(msg) => return self.reporter.problem(generation, &format!("error: {msg}")),
        };
        self.reporter.warnings(&loaded.warnings);
        let name = self.scene.display().to_string();
        let watched = self.set.file_count();
        self.reporter
            .loaded(generation, &name, load_time, reused, watched);
        self.rendered = inputs;
        self.cancel = Arc::new(Cancel::default());
        let job = Job {
            scene: loaded.scene,
            view: loaded.view,
            output,
            cancel: self.cancel.clone(),
            generation,
            changed_at,
        };
        let _ = self.jobs.send(job);
    }

    /// Watches the folders of `next` and stops watching the others.
    fn rearm(&mut self, next: WatchSet) {
        for dir in next.dirs().filter(|d| !self.set.has_dir(d)) {
            if let Err(e) = self.watcher.watch(dir, RecursiveMode::NonRecursive) {
                self.reporter
                    .line(&format!("warning: cannot watch {}: {e}", dir.display()));
            }
        }
        for dir in self.set.dirs().filter(|d| !next.has_dir(d)) {
            let _ = self.watcher.unwatch(dir);
        }
        self.set = next;
    }
}

/// The files a scene that failed to load names, as far as it parses (every
/// entry that parses on its own counts).
fn referenced_files(scene: &Path, text: &str) -> Vec<PathBuf> {
    let base = scene.parent().unwrap_or(Path::new("."));
    let mut files = vec![scene.to_path_buf()];
    if let Ok(parsed) = read::<crate::desc::SceneDesc>(scene, text) {
        for o in &parsed.desc.objects {
            if let ObjectDesc::Mesh { file, .. } = o {
                files.push(base.join(file));
            }
        }
    }
    files
}
