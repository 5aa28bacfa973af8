//! Wavefront OBJ loading through tobj: polygons triangulated, one index per
//! vertex, every model of the file merged into one mesh.

use super::Mesh;
use glam::{Vec2, Vec3A};
use std::path::Path;

/// Loads `path`; the error is a sentence naming what is wrong.
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, _materials) = tobj::load_obj(path, &opts).map_err(|e| match e {
        tobj::LoadError::OpenFileFailed => format!("cannot open OBJ file {}", path.display()),
        tobj::LoadError::ReadError => format!("cannot read OBJ file {}", path.display()),
        other => format!("invalid OBJ file {}: {other}", path.display()),
    })?;
    let mut mesh = Mesh::default();
    let mut any_normals = true;
    let mut any_uvs = true;
    for m in &models {
        let mm = &m.mesh;
        let base = mesh.positions.len() as u32;
        let nv = mm.positions.len() / 3;
        mesh.positions
            .extend(mm.positions.chunks_exact(3).map(|p| Vec3A::new(p[0], p[1], p[2])));
        any_normals &= mm.normals.len() == mm.positions.len();
        any_uvs &= mm.texcoords.len() / 2 == nv;
        mesh.normals
            .extend(mm.normals.chunks_exact(3).map(|n| Vec3A::new(n[0], n[1], n[2])));
        mesh.uvs
            .extend(mm.texcoords.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])));
        for (k, tri) in mm.indices.chunks_exact(3).enumerate() {
            if let Some(&bad) = tri.iter().find(|&&i| i as usize >= nv) {
                return Err(format!(
                    "{}: face {} of object `{}` uses vertex index {} but the object has {nv} vertices",
                    path.display(),
                    k + 1,
                    m.name,
                    bad as usize + 1
                ));
            }
            mesh.indices.push([base + tri[0], base + tri[1], base + tri[2]]);
        }
    }
    if !any_normals {
        mesh.normals.clear();
    }
    if !any_uvs {
        mesh.uvs.clear();
    }
    if let Some(p) = mesh.positions.iter().find(|p| !p.is_finite()) {
        return Err(format!("{}: vertex {p} is not finite", path.display()));
    }
    if mesh.indices.is_empty() {
        return Err(format!("{} contains no faces", path.display()));
    }
    Ok(mesh)
}
