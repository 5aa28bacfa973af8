//! `ronray new NAME`: a commented starter scene, for the first five minutes.
use std::io::Write;
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
    let written = create(&path, force, |f| std::io::Write::write_all(f, text.as_bytes()));
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

/// Creates the scene file at `path` with what `write` puts in it, or
/// leaves nothing behind: without `force` the file is created exclusively
/// (never replacing someone's scene) and removed again if `write` fails (a
/// full disk left an empty scene before); with `force` it is written to a
/// temporary file beside it and renamed over the old one, which survives a
/// failed write.
fn create(
    path: &Path,
    force: bool,
    write: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let finish = |f: &mut std::fs::File| -> std::io::Result<()> {
        write(f)?;
        f.flush()?;
        f.sync_all()
    };
    if force {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let mut tmp = tempfile::Builder::new().prefix(".ronray-new").tempfile_in(dir)?;
        finish(tmp.as_file_mut())?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            tmp.as_file()
                .set_permissions(std::fs::Permissions::from_mode(0o644))?;
        }
        return tmp.persist(path).map(drop).map_err(|e| e.error);
    }
    let mut f = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)?;
    finish(&mut f).inspect_err(|_| {
        drop(std::fs::remove_file(path));
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn full_disk(_: &mut std::fs::File) -> std::io::Result<()> {
        Err(std::io::Error::from_raw_os_error(28)) // ENOSPC
    }

    #[test]
    fn a_failed_write_leaves_nothing_behind() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("scene.ron");
        assert!(create(&path, false, full_disk).is_err());
        assert!(!path.exists(), "an empty scene was left behind");
        // With --force the old scene survives a failed write.
        std::fs::write(&path, "old").expect("write");
        assert!(create(&path, true, full_disk).is_err());
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "old");
        let left: Vec<_> = std::fs::read_dir(dir.path()).expect("list").flatten().collect();
        assert_eq!(left.len(), 1, "temporary files left: {left:?}");
        create(&path, true, |f| f.write_all(b"new")).expect("write");
        assert_eq!(std::fs::read_to_string(&path).expect("read"), "new");
    }
}
