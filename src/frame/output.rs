//! The output rule, written once: where a frame goes and whether it may go
//! there. The format table itself ([`OutputFormat`]: what each extension is
//! and can carry) lives in `imageio/format.rs`, where the loader reads it
//! too; this file applies it to one [`Plan`]: a piece needs a format that
//! carries exact sums, layers one that carries layers, the file must not be
//! an input of the scene, and the film must fit in memory. The CLI, watch
//! mode and the farm call [`Output::new`] and print its error.

use super::plan::{Plan, Request};
use crate::imageio::OutputFormat;
use crate::memory::MemoryError;
use crate::view::View;
use std::path::{Path, PathBuf};

/// Where a frame is written, checked against its plan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Output {
    /// The file.
    pub path: PathBuf,
    /// Its format, by extension.
    pub format: OutputFormat,
}

/// Why a frame cannot be written where asked. The library never prints:
/// commands add "nothing was written" or "keeping the last good image".
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// A piece asked of a format that cannot hold exact sums.
    #[error(
        "a piece of a frame is written as EXR, and {} is not .exr: PNG pieces are 8-bit and cannot be merged exactly (assemble the EXR pieces into a PNG instead)",
        path.display()
    )]
    PieceNeedsSums {
        /// The output asked for.
        path: PathBuf,
    },
    /// An extension no format has.
    #[error("output {} must end in {}", path.display(), OutputFormat::choices())]
    Extension {
        /// The output asked for.
        path: PathBuf,
    },
    /// The output is a file the scene reads: writing it would destroy an
    /// input (and, in watch mode, trigger the next render for ever).
    #[error("output {} is {}, which the scene reads", path.display(), input.display())]
    IsInput {
        /// The output asked for.
        path: PathBuf,
        /// The input it would overwrite.
        input: PathBuf,
    },
    /// Layers asked of a format that cannot hold them.
    #[error(
        "`film.aovs` adds layers to EXR files, and {} is not .exr; pass `-o NAME.exr` or remove `aovs`",
        path.display()
    )]
    LayersNeedExr {
        /// The output asked for.
        path: PathBuf,
    },
    /// The film would not fit in memory.
    #[error(transparent)]
    Memory(#[from] MemoryError),
    /// The scene's own `film.output` is (or passes through) a symlink
    /// leading out of the scene's folder (and `--root`): a scene from
    /// someone else's repository would replace a file the user never named.
    #[error(
        "the scene's film.output: {why}; a scene writes only inside its own folder (pass `-o PATH` to write elsewhere)"
    )]
    OutsideFolder {
        /// Where and why, as a sentence.
        why: String,
    },
}

impl OutputError {
    /// Whether the command line asked for something contradictory (exit
    /// code 2) rather than something the files or machine refuse (1).
    pub fn is_usage(&self) -> bool {
        match self {
            OutputError::PieceNeedsSums { .. } | OutputError::LayersNeedExr { .. } => true,
            OutputError::Extension { .. }
            | OutputError::IsInput { .. }
            | OutputError::Memory(_)
            | OutputError::OutsideFolder { .. } => false,
        }
    }
}

impl Output {
    /// Where a render of the scene at `scene_path` goes: `cli` (`-o`), else
    /// the scene's `film.output`, else `<scene stem>.png` in the current
    /// folder; `{tile}` becomes the piece's tile index.
    pub fn path(view: &View, scene_path: &Path, cli: Option<PathBuf>, tile: Option<u32>) -> PathBuf {
        let out = cli
            .or_else(|| (!view.output.as_os_str().is_empty()).then(|| view.output.clone()))
            .unwrap_or_else(|| {
                let stem = scene_path
                    .file_stem()
                    .and_then(|s| s.to_str())
                    .unwrap_or("render");
                PathBuf::from(format!("{stem}.png"))
            });
        match tile {
            Some(i) => PathBuf::from(out.to_string_lossy().replace("{tile}", &i.to_string())),
            None => out,
        }
    }

    /// Refuses an output the scene chose itself (`film.output`, no `-o`)
    /// that lands outside `fences` (the scene's folder and `--root`) once
    /// links are followed. What `-o` names is the user's own choice.
    pub fn confine(self, fences: &[&Path]) -> Result<Output, OutputError> {
        match crate::files::write_outside(fences, &self.path) {
            None => Ok(self),
            Some(why) => Err(OutputError::OutsideFolder { why }),
        }
    }

    /// [`Output::confine`] when the scene at `scene_path` chose this output
    /// (`cli_given` false, `film.output` set): its folder and `root` fence
    /// it. Render and watch mode both call it.
    pub fn confine_scene_output(
        self,
        view: &View,
        scene_path: &Path,
        cli_given: bool,
        root: Option<&Path>,
    ) -> Result<Output, OutputError> {
        if cli_given || view.output.as_os_str().is_empty() {
            return Ok(self);
        }
        let folder = crate::files::resolved(scene_path.parent().unwrap_or(Path::new("")));
        let fences: Vec<&Path> = std::iter::once(folder.as_path()).chain(root).collect();
        self.confine(&fences)
    }

    /// Checks `path` for `plan`: its format carries what the plan produces,
    /// it is none of the scene's `inputs`, and the film fits in
    /// `max_memory` bytes (default: what the machine has).
    pub fn new(
        path: PathBuf,
        plan: &Plan,
        inputs: &[PathBuf],
        max_memory: Option<u64>,
    ) -> Result<Output, OutputError> {
        let format = OutputFormat::of_path(&path);
        let piece = match plan.request {
            Request::Piece { .. } => true,
            Request::Whole | Request::Pass { .. } => false,
        };
        if piece && !format.is_some_and(OutputFormat::carries_pieces) {
            return Err(OutputError::PieceNeedsSums { path });
        }
        let Some(format) = format else {
            return Err(OutputError::Extension { path });
        };
        if let Some(input) = input_at(inputs, &path) {
            let input = input.to_path_buf();
            return Err(OutputError::IsInput { path, input });
        }
        if !plan.layers.is_empty() && !format.carries_layers() {
            return Err(OutputError::LayersNeedExr { path });
        }
        // Refused before anything is allocated: pieces and passes keep exact
        // sums per pixel.
        // A piece spread by noise renders the whole frame's first pass.
        let rect = match plan.sampling {
            super::Sampling::Spread(_) => plan.frame,
            super::Sampling::Even { .. } | super::Sampling::Adaptive(_) => plan.rect,
        };
        crate::memory::check_film(rect.width(), rect.height(), plan.keeps_sums(), max_memory)?;
        Ok(Output { path, format })
    }
}

/// The input (the scene file, an include, an OBJ, a texture) that writing
/// to `out` would overwrite, if any; symlinks followed.
fn input_at<'a>(inputs: &'a [PathBuf], out: &Path) -> Option<&'a Path> {
    let out = crate::files::write_target(out);
    inputs
        .iter()
        .map(PathBuf::as_path)
        .find(|f| crate::files::resolved(f) == out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_output_is_never_an_input() {
        let dir = std::env::temp_dir();
        let scene = dir.join("ronray_output_rule_scene.ron");
        let inputs = vec![scene.clone()];
        assert_eq!(input_at(&inputs, &scene), Some(scene.as_path()));
        assert_eq!(input_at(&inputs, &dir.join("other.png")), None);
    }
}
