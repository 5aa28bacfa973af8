//! Render farms: a frame cut into pieces that machines render on their own,
//! and put back together bit for bit.
//!
//! Any scheduler can run the pieces (Slurm job arrays, Kubernetes indexed
//! Jobs, GNU parallel): `ronray render --tile auto/N` takes its index from
//! the scheduler, writes an EXR piece ([`piece`]) that carries the scene
//! content hash ([`scene_hash`]) and its sample range, and `ronray assemble`
//! ([`assemble()`]) refuses pieces that do not make one frame and otherwise
//! writes exactly the image one machine would have rendered: the renderer's
//! per-(pixel, sample, seed) random numbers and exact per-pixel sums
//! ([`crate::math::ExactSum`]) make a pixel's value independent of who
//! rendered which of its samples.
//!
//! - `split.rs`: `--crop`, `--pixels`, `--tile`, `--samples` → a [`PieceSpec`].
//! - `hash.rs`: the scene content hash two machines agree on.
//! - `piece.rs`: the piece file format (EXR windows, exact sums, metadata).
//! - `assemble.rs`: checks (scenes, versions, overlaps, gaps) and merging.

pub mod assemble;
pub mod frames;
pub mod hash;
pub mod piece;
pub mod split;

pub use assemble::{AssembleError, assemble, assemble_files, output_replaces_piece};
pub use hash::scene_hash;
pub use piece::{Piece, PieceMeta, read_piece, read_piece_meta, write_piece};
pub use split::{PieceSpec, Region, TileIndex, resolve};

use crate::load::Loaded;
use std::path::{Path, PathBuf};

/// A piece file that cannot be read or written.
#[derive(Debug, thiserror::Error)]
#[error("{}: {reason}", path.display())]
pub struct PieceError {
    /// The piece file.
    pub path: PathBuf,
    /// What is wrong with it, as a sentence.
    pub reason: String,
}

/// The metadata of the piece `spec` of a loaded scene; `spread` is the
/// first pass's samples per pixel when the plan spreads samples by noise.
pub fn piece_meta(loaded: &Loaded, spec: &PieceSpec, spread: Option<u32>) -> Result<PieceMeta, String> {
    let f = loaded.view.film;
    // The frame drawn is recorded apart, so that pieces of two frames of
    // one scene are told apart as frames, not as scenes.
    let mut desc = loaded.desc.clone();
    let animation_frame = desc.animation.as_mut().map(|a| {
        let f = a.current();
        a.frame = None;
        f
    });
    Ok(PieceMeta {
        version: env!("CARGO_PKG_VERSION").to_string(),
        scene: scene_hash(&desc, &loaded.files)?,
        animation_frame,
        seed: f.seed,
        spp: f.spp,
        samples: spec.samples,
        tile: spec.tile,
        frame: (f.width, f.height),
        rect: spec.rect,
        spread,
    })
}

/// What `--resume` finds at a piece's output path.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Existing {
    /// Nothing there.
    Absent,
    /// The same piece of the same scene: nothing to do.
    Done,
    /// Something else (another scene, other pixels, not a piece), and why.
    Different(String),
}

/// Whether `path` already holds the piece `meta` describes.
pub fn existing_piece(path: &Path, meta: &PieceMeta) -> Existing {
    if !path.exists() {
        return Existing::Absent;
    }
    // The whole piece is read, not only its header: a truncated or corrupt
    // piece (a job killed mid-copy) is rendered again, not skipped.
    match read_piece(path).map(|p| p.meta) {
        Ok(m) if m.same_work(meta) => Existing::Done,
        Ok(m) if m.scene != meta.scene => Existing::Different(format!(
            "it holds scene {}, and this scene is {}",
            m.scene, meta.scene
        )),
        Ok(m) if m.version != meta.version => {
            Existing::Different(format!("it was rendered by ronray {}", m.version))
        }
        Ok(m) => Existing::Different(format!(
            "it holds samples {}..{} of pixels {}",
            m.samples.0, m.samples.1, m.rect
        )),
        Err(e) => Existing::Different(e.reason),
    }
}
