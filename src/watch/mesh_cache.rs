//! Meshes kept between reloads, so a camera, material or light edit does not
//! re-read and re-triangulate OBJ files.
//!
//! A mesh is reused while its file's (path, modification time, size) is
//! unchanged, and so are those of the MTL files it names: the cached value
//! holds the MTL materials too, so an MTL edit must read the OBJ again. The cached mesh is the file's content in object space; the
//! scene's transform is applied to a copy by `build`, and the BVH is rebuilt
//! (milliseconds for thousands of triangles).

use crate::geometry::obj::{self, ObjData};
use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

type Stamp = (Option<SystemTime>, u64);

/// A cached OBJ: its stamp, its MTL files' stamps (`None`: missing), the data.
type Entry = (Stamp, Vec<Option<Stamp>>, ObjData);

/// Parsed OBJ files by path, reused while the file and its MTL files are
/// unchanged.
#[derive(Default)]
pub struct MeshCache {
    entries: RefCell<HashMap<PathBuf, Entry>>,
    hits: RefCell<usize>,
}

fn stamp(path: &Path) -> Option<Stamp> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok(), m.len()))
}

impl MeshCache {
    /// A drop-in for [`obj::load_obj_data`].
    pub fn load(&self, path: &Path) -> Result<ObjData, String> {
        let before = stamp(path);
        if let Some(s) = before
            && let Some((cached, mtl, mesh)) = self.entries.borrow().get(path)
            && *cached == s
            && mesh.mtl_files.iter().map(|m| stamp(m)).eq(mtl.iter().copied())
        {
            *self.hits.borrow_mut() += 1;
            return Ok(mesh.clone());
        }
        let mesh = obj::load_obj_data(path)?;
        // A file rewritten while it was read is not cached: the next event
        // reloads it. (An MTL file rewritten between its read and the stamp
        // below is kept stale until its next change: the window is the
        // parse of the OBJ.)
        let mtl = mesh.mtl_files.iter().map(|m| stamp(m)).collect();
        match before {
            Some(s) if stamp(path) == before => {
                self.entries
                    .borrow_mut()
                    .insert(path.to_path_buf(), (s, mtl, mesh.clone()));
            }
            _ => {
                self.entries.borrow_mut().remove(path);
            }
        }
        Ok(mesh)
    }

    /// Forgets meshes the scene no longer uses.
    pub fn retain(&self, files: &[PathBuf]) {
        self.entries.borrow_mut().retain(|p, _| files.contains(p));
    }

    /// Meshes served from the cache since the last call.
    pub fn take_hits(&self) -> usize {
        std::mem::take(&mut *self.hits.borrow_mut())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_cache_reuses_until_the_file_changes() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("t.obj");
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").expect("write");
        let cache = MeshCache::default();
        assert_eq!(cache.load(&path).map(|m| m.mesh.triangle_count()), Ok(1));
        assert_eq!(cache.load(&path).map(|m| m.mesh.triangle_count()), Ok(1));
        assert_eq!(cache.take_hits(), 1);
        std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n").expect("write");
        assert_eq!(cache.load(&path).map(|m| m.mesh.triangle_count()), Ok(2));
        assert_eq!(cache.take_hits(), 0, "a changed file is read again");
        cache.retain(&[]);
        assert!(cache.entries.borrow().is_empty());
    }

    #[test]
    fn mesh_cache_reads_again_when_its_mtl_changes() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("t.obj");
        let obj = "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
        std::fs::write(&path, obj).expect("write");
        std::fs::write(dir.path().join("t.mtl"), "newmtl red\nKd 0.8 0.1 0.1\n").expect("write");
        let kd = |c: &MeshCache| c.load(&path).map(|m| m.materials[0].diffuse);
        let cache = MeshCache::default();
        assert_eq!(kd(&cache), Ok(Some([0.8, 0.1, 0.1])));
        std::fs::write(dir.path().join("t.mtl"), "newmtl red\nKd 0.1 0.8 0.15\n").expect("write");
        assert_eq!(kd(&cache), Ok(Some([0.1, 0.8, 0.15])), "the MTL edit is seen");
        assert_eq!(cache.take_hits(), 0);
        assert_eq!(kd(&cache), Ok(Some([0.1, 0.8, 0.15])));
        assert_eq!(cache.take_hits(), 1, "unchanged files are reused");
    }
}
