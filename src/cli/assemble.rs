//! `ronray assemble`: pieces of a frame → one image.
use crate::farm::assemble_files;
use crate::imageio::write_image;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub(super) fn cmd_assemble(pieces: &[PathBuf], out: &Path) -> ExitCode {
    if let Some(p) = crate::farm::output_replaces_piece(pieces, out) {
        eprintln!(
            "error: -o {} would replace the piece {}; nothing was written (name another output)",
            out.display(),
            p.display()
        );
        return ExitCode::FAILURE;
    }
    let (image, meta) = match assemble_files(pieces) {
        Ok(r) => r,
        Err(e) => {
            for p in &e.problems {
                eprintln!("error: {p}");
            }
            eprintln!(
                "error: {} not assembled; nothing was written",
                if pieces.len() == 1 {
                    "the piece was"
                } else {
                    "the pieces were"
                }
            );
            return ExitCode::FAILURE;
        }
    };
    if let Err(e) = write_image(&image, out) {
        eprintln!("error: {e}");
        return ExitCode::FAILURE;
    }
    eprintln!(
        "wrote {} ({}×{}, {} spp) from {} pieces of scene {}",
        out.display(),
        meta.frame.0,
        meta.frame.1,
        meta.spp,
        pieces.len(),
        meta.scene
    );
    ExitCode::SUCCESS
}
