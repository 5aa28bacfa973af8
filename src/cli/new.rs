//! `ronray new NAME`: a commented starter scene, for the first five minutes.
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The starter scene (`src/cli/starter.ron`; `tests/cli.rs` validates and
/// renders it).
pub const STARTER: &str = include_str!("starter.ron");

pub(super) fn cmd_new(name: &Path, force: bool) -> ExitCode {
    let path: PathBuf = if name.extension().is_some_and(|e| e == "ron") {
        name.to_path_buf()
    } else {
        let mut s = name.as_os_str().to_owned();
        s.push(".ron");
        s.into()
    };
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("scene");
    let text = STARTER.replace("NAME", stem);
    let written = if force {
        std::fs::write(&path, text)
    } else {
        // Never replace someone's scene: create the file or fail.
        std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .and_then(|mut f| std::io::Write::write_all(&mut f, text.as_bytes()))
    };
    match written {
        Ok(()) => {
            eprintln!(
                "wrote {}; render it with `ronray render {}`",
                path.display(),
                path.display()
            );
            ExitCode::SUCCESS
        }
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {
            eprintln!("error: {} exists; pass --force to replace it", path.display());
            ExitCode::FAILURE
        }
        Err(e) => {
            eprintln!("error: cannot write {}: {e}", path.display());
            ExitCode::FAILURE
        }
    }
}
