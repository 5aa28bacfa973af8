//! Which files a reload depends on, which folders to watch for them, and
//! which filesystem events matter.
//!
//! Folders are watched rather than files: editors save by writing a temporary
//! file and renaming it over the original (vim, IDEs) or by truncating and
//! rewriting, and a watch on the file itself dies with the old inode. Events
//! in a watched folder are matched by path against the files of the last
//! load, so the image written beside the scene never triggers a reload.

use notify::EventKind;
use notify::event::{AccessKind, AccessMode};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// The files a scene depends on, as event paths will name them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WatchSet {
    files: BTreeSet<PathBuf>,
    dirs: BTreeSet<PathBuf>,
}

impl WatchSet {
    pub fn new<'a>(files: impl IntoIterator<Item = &'a PathBuf>) -> Self {
        let mut set = WatchSet::default();
        for f in files {
            set.add(f);
        }
        set
    }

    /// Adds `file` under its canonical folder (the folder must exist to be
    /// watched; the file need not). A symlinked file is also watched where
    /// it points, since edits happen there.
    fn add(&mut self, file: &Path) {
        let Some(key) = canonical_key(file) else {
            return;
        };
        if let Ok(target) = std::fs::canonicalize(file)
            && target != key
            && let Some(dir) = target.parent()
        {
            self.dirs.insert(dir.to_path_buf());
            self.files.insert(target.clone());
        }
        if let Some(dir) = key.parent() {
            self.dirs.insert(dir.to_path_buf());
        }
        self.files.insert(key);
    }

    pub fn union(&self, other: &WatchSet) -> WatchSet {
        WatchSet {
            files: self.files.union(&other.files).cloned().collect(),
            dirs: self.dirs.union(&other.dirs).cloned().collect(),
        }
    }

    pub fn dirs(&self) -> impl Iterator<Item = &PathBuf> {
        self.dirs.iter()
    }

    pub fn has_dir(&self, dir: &Path) -> bool {
        self.dirs.contains(dir)
    }

    pub fn file_count(&self) -> usize {
        self.files.len()
    }

    /// Whether an event may have changed what the scene loads to.
    pub fn matters(&self, kind: &EventKind, paths: &[PathBuf]) -> bool {
        changes_content(kind) && paths.iter().any(|p| !is_own_temp(p) && self.files.contains(p))
    }
}

/// Opening or reading a file (ours included: every reload opens the scene)
/// changes nothing; closing a file opened for writing ends a save.
fn changes_content(kind: &EventKind) -> bool {
    match kind {
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        EventKind::Access(_) => false,
        _ => true,
    }
}

/// The temporary files `write_image` renames over the output.
fn is_own_temp(path: &Path) -> bool {
    path.file_name()
        .and_then(|n| n.to_str())
        .is_some_and(|n| n.starts_with(".ronray-") && n.ends_with(".tmp"))
}

/// `folder/name` with the folder canonicalised, as the watcher reports paths
/// under a folder it was given in canonical form.
fn canonical_key(file: &Path) -> Option<PathBuf> {
    let name = file.file_name()?;
    let dir = match file.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    Some(std::fs::canonicalize(dir).ok()?.join(name))
}

#[cfg(test)]
mod tests {
    use super::*;
    use notify::event::{CreateKind, ModifyKind, RenameMode};

    fn set_in(dir: &Path) -> WatchSet {
        WatchSet::new(&[dir.join("scene.ron"), dir.join("mesh.obj")])
    }

    #[test]
    fn watch_set_matches_renames_and_writes_of_its_files_only() {
        let tmp = tempfile::tempdir().expect("temp dir");
        let dir = std::fs::canonicalize(tmp.path()).expect("canonical");
        let set = set_in(&dir);
        let scene = vec![dir.join("scene.ron")];
        let rename = EventKind::Modify(ModifyKind::Name(RenameMode::To));
        assert!(set.matters(&rename, &scene));
        assert!(set.matters(&EventKind::Create(CreateKind::File), &[dir.join("mesh.obj")]));
        assert!(set.matters(&EventKind::Access(AccessKind::Close(AccessMode::Write)), &scene));
        assert!(!set.matters(&EventKind::Access(AccessKind::Open(AccessMode::Any)), &scene));
        assert!(!set.matters(&rename, &[dir.join("scene.png")]));
        assert!(!set.matters(&rename, &[dir.join(".ronray-abc.png.tmp")]));
        assert_eq!(set.dirs().collect::<Vec<_>>(), vec![&dir]);
    }

    #[test]
    fn watch_set_names_files_through_a_canonical_folder() {
        let tmp = tempfile::tempdir().expect("temp dir");
        std::fs::create_dir(tmp.path().join("sub")).expect("mkdir");
        let dotted = tmp.path().join("sub/../scene.ron");
        let set = WatchSet::new(&[dotted]);
        let key = std::fs::canonicalize(tmp.path())
            .expect("canonical")
            .join("scene.ron");
        assert!(set.matters(&EventKind::Any, &[key]));
    }
}
