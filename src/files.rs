//! Reading the files a scene names, safely: regular files only (a FIFO or a
//! device would block or never end), a size cap checked before reading, and
//! the `--root` fence for untrusted scenes. The bottom layer beside
//! [`crate::diagnostic`]: it imports nothing, so the loader, the OBJ reader
//! and the image readers share one rule.

use std::io::{Error, ErrorKind, Read};
use std::path::{Path, PathBuf};

/// Opens `path` for reading if it is a regular file of at most `limit`
/// bytes. `metadata` does not open the file, so asking cannot block on a
/// FIFO.
pub fn open_regular(path: &Path, limit: u64) -> std::io::Result<std::io::Take<std::fs::File>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    if meta.len() > limit {
        return Err(too_large(limit));
    }
    // The file may grow between the check and the read: read one byte past
    // the limit at most, so a growing file is caught below.
    Ok(std::fs::File::open(path)?.take(limit + 1))
}

/// Reads a regular file of at most `limit` bytes (see [`open_regular`]).
pub fn read_regular(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    let mut bytes = Vec::new();
    open_regular(path, limit)?.read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(limit));
    }
    Ok(bytes)
}

fn too_large(limit: u64) -> Error {
    let size = if limit >= 1 << 20 {
        format!("{} MiB", limit >> 20)
    } else {
        format!("{limit} bytes")
    };
    Error::new(ErrorKind::InvalidData, format!("larger than {size}"))
}

/// `path` with symlinks and `..` resolved; a path that does not exist yet
/// is resolved through its nearest existing ancestor.
pub fn resolved(path: &Path) -> PathBuf {
    // `Path::new("")` is the parent of a bare file name: the current folder.
    let path = if path.as_os_str().is_empty() {
        Path::new(".")
    } else {
        path
    };
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut tail = Vec::new();
    let mut at = abs.as_path();
    while let Some(parent) = at.parent() {
        tail.push(at.file_name().map(|n| n.to_os_string()).unwrap_or_default());
        if let Ok(p) = std::fs::canonicalize(parent) {
            return tail.iter().rev().fold(p, |acc, n| acc.join(n));
        }
        at = parent;
    }
    abs
}

/// Where writing `path` really lands: a symlink at `path` is followed to
/// its target, however many links deep (at most 40, as the kernel does),
/// even when the target does not exist yet (a dangling link is written
/// through too). Folders on the way are followed by [`resolved`].
pub fn follow_links(path: &Path) -> PathBuf {
    let mut at = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::read_link(&at) {
            Ok(target) => {
                at = match at.parent() {
                    Some(dir) => dir.join(target),
                    None => target,
                }
            }
            Err(_) => break,
        }
    }
    at
}

/// The file a write to `path` replaces, with every link on the way
/// followed: the key to compare outputs with inputs and fences.
pub fn write_target(path: &Path) -> PathBuf {
    resolved(&follow_links(path))
}

/// `None` when a write to `path` (links followed, dangling ones too) lands
/// inside one of `fences`; else the sentence saying where it would land.
/// What a scene names for writing (its `film.output`, its goldens) must
/// stay in its folder, or under `--root`.
pub fn write_outside(fences: &[&Path], path: &Path) -> Option<String> {
    let real = write_target(path);
    if fences.iter().any(|f| real.starts_with(resolved(f))) {
        return None;
    }
    let names: Vec<String> = fences.iter().map(|f| resolved(f).display().to_string()).collect();
    Some(format!(
        "{} would write {}, outside {}",
        path.display(),
        real.display(),
        names.join(" and ")
    ))
}

/// `None` when `path`, resolved (symlinks followed), lies inside `root`;
/// else the sentence saying where it really is. Used for every input of a
/// scene when `--root DIR` is given.
pub fn outside_root(root: &Path, path: &Path) -> Option<String> {
    let root = resolved(root);
    let real = resolved(path);
    if real.starts_with(&root) {
        return None;
    }
    Some(format!(
        "{} is outside --root {} (it resolves to {})",
        path.display(),
        root.display(),
        real.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symlink_out_of_the_root_is_outside_it() {
        let dir = tempfile::tempdir().expect("tempdir");
        let root = dir.path().join("root");
        std::fs::create_dir(&root).expect("mkdir");
        std::fs::write(dir.path().join("secret.ron"), "x").expect("write");
        std::fs::write(root.join("ok.ron"), "x").expect("write");
        std::os::unix::fs::symlink(dir.path().join("secret.ron"), root.join("link.ron")).expect("link");
        assert!(outside_root(&root, &root.join("ok.ron")).is_none());
        assert!(outside_root(&root, &root.join("link.ron")).is_some());
        assert!(outside_root(&root, &root.join("../secret.ron")).is_some());
        assert!(outside_root(&root, &root.join("not-yet/new.ron")).is_none());
        // The parent of a bare file name is "": the current folder, not
        // a prefix of everything.
        assert!(outside_root(Path::new(""), Path::new("/etc/passwd")).is_some());
    }

    #[test]
    fn a_write_through_a_link_out_of_the_folder_is_outside_it() {
        let dir = tempfile::tempdir().expect("tempdir");
        let scene = dir.path().join("scene");
        std::fs::create_dir_all(scene.join("sub")).expect("mkdir");
        std::fs::write(dir.path().join("notes.txt"), "x").expect("write");
        let link = |target: &str, name: &str| {
            std::os::unix::fs::symlink(target, scene.join(name)).expect("link");
            scene.join(name)
        };
        let fence = [scene.as_path()];
        assert!(write_outside(&fence, &scene.join("out.png")).is_none());
        assert!(write_outside(&fence, &scene.join("new/out.png")).is_none());
        assert!(write_outside(&fence, &link("sub/x.png", "inside.png")).is_none());
        let out = link("../notes.txt", "out.png");
        let why = write_outside(&fence, &out).expect("outside");
        assert!(why.contains("notes.txt"), "{why}");
        // A dangling link is written through as well.
        assert!(write_outside(&fence, &link("../made-up.png", "dangling.png")).is_some());
        // A folder on the way that is a link.
        assert!(write_outside(&fence, &link("..", "up").join("x.png")).is_some());
        // Two links deep.
        link("out.png", "twice.png");
        assert!(write_outside(&fence, &scene.join("twice.png")).is_some());
    }

    #[test]
    fn reading_refuses_what_is_not_a_small_regular_file() {
        let dir = tempfile::tempdir().expect("tempdir");
        let f = dir.path().join("f");
        std::fs::write(&f, "12345").expect("write");
        assert_eq!(read_regular(&f, 5).expect("fits"), b"12345");
        assert!(read_regular(&f, 4).is_err(), "above the limit");
        assert!(read_regular(dir.path(), 100).is_err(), "a folder");
        assert!(read_regular(Path::new("/dev/zero"), 100).is_err(), "a device");
    }
}
