//! Wavefront OBJ loading through tobj: polygons triangulated (fans), one
//! index per vertex, every object/group of the file merged into one mesh
//! whose triangles remember their group as a material slot.
//!
//! Real files are messy (see `tests/fixtures/obj-corpus/SOURCES.md`), so the
//! loader repairs what it can and says so in `warnings`: normals that are
//! missing, dangling (a `vn` index with no `vn` line comes back as a zero
//! normal) or not finite are dropped for that group, and the shading falls
//! back to the geometric normal; a missing MTL file leaves the groups without
//! material. What it cannot repair (no faces, a vertex index out of range, a
//! non-finite vertex) is an error naming the file, group and face.

use super::Mesh;
use glam::{Vec2, Vec3A};
use std::path::Path;

/// One OBJ object/group (tobj model): a material slot of the mesh.
#[derive(Clone, Debug)]
pub struct ObjGroup {
    /// The OBJ object/group name, which `materials: { ... }` keys of a scene object
    /// may name.
    pub name: String,
    /// Index into [`ObjData::materials`].
    pub material: Option<usize>,
}

/// A loaded OBJ: the mesh (slot `k` = `groups[k]`) and its MTL materials.
#[derive(Clone, Debug)]
pub struct ObjData {
    /// All groups merged into one triangle mesh, in the file's coordinates.
    pub mesh: Mesh,
    /// The file's objects/groups, in slot order.
    pub groups: Vec<ObjGroup>,
    /// The MTL materials the file refers to (empty if it has no MTL file or the file
    /// is missing).
    pub materials: Vec<tobj::Material>,
    /// Repairs made, one sentence each.
    pub warnings: Vec<String>,
    /// The MTL files the OBJ names (`mtllib`), resolved against its folder,
    /// whether or not they could be read: what the materials depend on.
    pub mtl_files: Vec<std::path::PathBuf>,
}

/// Loads `path` as one mesh, ignoring materials.
pub fn load_obj(path: &Path) -> Result<Mesh, String> {
    load_obj_data(path).map(|d| d.mesh)
}

/// Largest OBJ file read: 1 GiB (about 20 million triangles). Raise it
/// here; the mesh's own arrays are reserved fallibly, so a file that fits
/// but does not fit in memory is an error, not an abort.
pub const MAX_OBJ_FILE_BYTES: u64 = 1 << 30;
/// Largest MTL file read (hand-written material lists are kilobytes).
pub const MAX_MTL_FILE_BYTES: u64 = 64 << 20;

/// How an MTL refused by `--root` is told apart from a missing one (which
/// is only a warning).
const OUTSIDE_ROOT: &str = "refused: ";

/// Loads `path` with its groups and MTL materials; the error is a sentence
/// naming what is wrong and where.
pub fn load_obj_data(path: &Path) -> Result<ObjData, String> {
    load_obj_data_in(path, None)
}

/// As [`load_obj_data`], refusing an MTL file outside `root` (`--root`).
/// The OBJ and its MTL files must be regular files below their size limits:
/// a FIFO would block, `/dev/zero` would never end.
/// A file whose name ends in `.ply` (any case) is read as a Stanford PLY
/// mesh ([`super::ply`]), under the same size limit.
pub fn load_obj_data_in(path: &Path, root: Option<&Path>) -> Result<ObjData, String> {
    let ply = is_ply(path);
    let kind = if ply { "PLY" } else { "OBJ" };
    let bytes = crate::files::read_regular(path, MAX_OBJ_FILE_BYTES).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => format!("cannot open {kind} file {}", path.display()),
        _ => format!("cannot read {kind} file {}: {e}", path.display()),
    })?;
    if ply {
        let (mesh, warnings) = super::ply::parse_ply(path, &bytes)?;
        return Ok(ObjData {
            mesh,
            groups: vec![ObjGroup {
                name: "unnamed".to_string(),
                material: None,
            }],
            materials: Vec::new(),
            warnings,
            mtl_files: Vec::new(),
        });
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    let mtl = |name: &Path| -> Result<Vec<u8>, String> {
        let full = dir.join(name);
        if let Some(why) = root.and_then(|r| crate::files::outside_root(r, &full)) {
            return Err(format!("{}{why}", OUTSIDE_ROOT));
        }
        crate::files::read_regular(&full, MAX_MTL_FILE_BYTES).map_err(|e| format!("{}: {e}", full.display()))
    };
    parse_obj_data(path, &bytes, &mtl)
}

/// Whether `path` names a PLY mesh (by its extension, any case).
pub fn is_ply(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ply"))
}

/// Refuses a face (or line) index tobj 4.0.5 would overflow on: a relative
/// index `-k` past the `k` elements read so far (tobj resolves it against
/// the count so far and multiplies the wrapped result unchecked: `f 1/-356/1`
/// after 109 `vt` lines, found by the `obj` fuzz target; caught by
/// `catch_unwind`, but a panic all the same), or an absolute one past
/// `u32::MAX` (no mesh has that many elements). Other indices past the end
/// are tobj's to refuse, and texture and normal indices in a file with no
/// `vt` or `vn` line at all stay ignored, as tobj ignores them: no file tobj
/// reads is refused here (words split at ASCII whitespace, where tobj also
/// splits at Unicode's). One pass over the bytes, parsing only the index
/// components that could overflow (a `-` or ten digits or more): on a
/// 1M-triangle OBJ a full parse of every index cost 10–20% of the load.
fn check_face_indices(bytes: &[u8]) -> Result<(), String> {
    const KINDS: [&str; 3] = ["position", "texture coordinate", "normal"];
    let has_kind = |k: usize| {
        let tag: &[u8] = if k == 1 { b"vt" } else { b"vn" };
        bytes.split(|&b| b == b'\n').any(|l| {
            let l = l.trim_ascii_start();
            l.starts_with(tag) && l.get(2).is_none_or(u8::is_ascii_whitespace)
        })
    };
    let mut so_far = [0u64; 3];
    for (n, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let l = line.trim_ascii_start();
        let blank_at = |i: usize| l.get(i).is_none_or(u8::is_ascii_whitespace);
        match l {
            [b'v', b't', ..] if blank_at(2) => so_far[1] += 1,
            [b'v', b'n', ..] if blank_at(2) => so_far[2] += 1,
            [b'v', ..] if blank_at(1) => so_far[0] += 1,
            [b'f' | b'l', rest @ ..] if blank_at(1) && could_overflow(rest) => {
                let words = rest.split(u8::is_ascii_whitespace).filter(|w| !w.is_empty());
                for vertex in words {
                    for (k, index) in vertex.split(|&b| b == b'/').enumerate().take(3) {
                        let Some(x) = std::str::from_utf8(index)
                            .ok()
                            .and_then(|s| s.parse::<i64>().ok())
                        else {
                            continue; // empty (`v//vn`) or not a number: tobj's to refuse
                        };
                        let past = if x < 0 {
                            x.unsigned_abs() > so_far[k]
                        } else {
                            x > i64::from(u32::MAX)
                        };
                        if past && (k == 0 || has_kind(k)) {
                            return Err(if x < 0 {
                                format!(
                                    "line {}: the face names {} {x}, but only {} were read before it",
                                    n + 1,
                                    KINDS[k],
                                    so_far[k]
                                )
                            } else {
                                format!(
                                    "line {}: the face names {} {x}, past the {} elements a mesh may have",
                                    n + 1,
                                    KINDS[k],
                                    u32::MAX
                                )
                            });
                        }
                    }
                }
            }
            _ => {}
        }
    }
    Ok(())
}

/// Whether a face line holds an index that could overflow tobj: a `-` or a
/// run of ten digits or more (`u32::MAX` has ten). Most lines have neither
/// and are not parsed at all.
fn could_overflow(line: &[u8]) -> bool {
    let mut run = 0;
    for &b in line {
        if b == b'-' {
            return true;
        }
        run = if b.is_ascii_digit() { run + 1 } else { 0 };
        if run >= 10 {
            return true;
        }
    }
    false
}

/// Parses OBJ text (`bytes`, named `path` in messages), reading each MTL
/// file it names through `mtl`. The one OBJ parser of ronray: files,
/// watch mode's cache and the fuzz target all come through here.
pub fn parse_obj_data(
    path: &Path,
    bytes: &[u8],
    mtl: &dyn Fn(&Path) -> Result<Vec<u8>, String>,
) -> Result<ObjData, String> {
    check_face_indices(bytes).map_err(|e| format!("invalid OBJ file {}: {e}", path.display()))?;
    let opts = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mtl_errors = std::cell::RefCell::new(Vec::new());
    let mtl_files = std::cell::RefCell::new(Vec::new());
    let dir = path.parent().unwrap_or(Path::new("."));
    let material_loader = |name: &Path| {
        mtl_files.borrow_mut().push(dir.join(name));
        match mtl(name) {
            Ok(b) => tobj::load_mtl_buf(&mut std::io::Cursor::new(complete_colours(&b))),
            Err(e) => {
                mtl_errors.borrow_mut().push(e);
                Err(tobj::LoadError::OpenFileFailed)
            }
        }
    };
    // tobj is not ours: a panic on some input we did not foresee becomes an
    // error rather than taking the renderer down.
    let loaded = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &opts, material_loader)
    }))
    .map_err(|_| format!("invalid OBJ file {}: the OBJ parser gave up", path.display()))?;
    let (models, mtl) = loaded.map_err(|e| match e {
        tobj::LoadError::ReadError => format!("cannot read OBJ file {}", path.display()),
        tobj::LoadError::FaceColorOutOfBounds => format!(
            "invalid OBJ file {}: some vertices have a colour (`v x y z r g b`) and others not; \
             give every vertex a colour, or none",
            path.display()
        ),
        other => format!("invalid OBJ file {}: {other}", path.display()),
    })?;
    if let Some(why) = mtl_errors.borrow().iter().find(|e| e.contains(OUTSIDE_ROOT)) {
        return Err(format!("{}: its MTL file {why}", path.display()));
    }
    let mtl = mtl.map_err(|e| match mtl_errors.borrow().last() {
        Some(why) => why.clone(),
        None => e.to_string(),
    });
    let mut warnings = Vec::new();
    let materials = mtl.unwrap_or_else(|e| {
        warnings.push(format!("{}: its MTL file was not loaded ({e})", path.display()));
        Vec::new()
    });
    let mut mesh = Mesh::default();
    let mut groups = Vec::new();
    let (mut any_normals, mut any_uvs) = (false, false);
    for (slot, m) in models.iter().enumerate() {
        let mm = &m.mesh;
        let base = mesh.positions.len() as u32;
        let nv = mm.positions.len() / 3;
        let name = if m.name.is_empty() { "unnamed" } else { &m.name };
        for (k, p) in mm.positions.chunks_exact(3).enumerate() {
            if !p.iter().all(|x| x.is_finite()) {
                return Err(format!(
                    "{}: vertex {} of object `{name}` is not finite: ({}, {}, {})",
                    path.display(),
                    k + 1,
                    p[0],
                    p[1],
                    p[2]
                ));
            }
        }
        reserve(&mut mesh, nv, mm.indices.len() / 3).map_err(|e| format!("{}: {e}", path.display()))?;
        mesh.positions
            .extend(mm.positions.chunks_exact(3).map(|p| Vec3A::new(p[0], p[1], p[2])));
        let normals_ok = mm.normals.len() == mm.positions.len()
            && mm
                .normals
                .chunks_exact(3)
                .all(|n| n.iter().all(|x| x.is_finite()) && n.iter().map(|x| x * x).sum::<f32>() > 0.0);
        if normals_ok {
            any_normals = true;
            mesh.normals
                .extend(mm.normals.chunks_exact(3).map(|n| Vec3A::new(n[0], n[1], n[2])));
        } else {
            if !mm.normals.is_empty() {
                warnings.push(format!(
                    "{}: object `{name}` has missing or invalid normals (dangling `vn` indices?); using face normals",
                    path.display()
                ));
            }
            mesh.normals.resize(mesh.positions.len(), Vec3A::ZERO);
        }
        // Vertex colours (`v x y z r g b`, MeshLab's and ZBrush's
        // extension): display colours, so sRGB-encoded like `Kd` in
        // practice, decoded to linear; out of range clamped to [0, 1] and
        // non-finite read as white, with a warning.
        if mm.vertex_color.len() == mm.positions.len() && nv > 0 {
            if mesh.colors.is_empty() {
                mesh.colors.resize(base as usize, Vec3A::ONE);
            }
            let mut repaired = false;
            mesh.colors.extend(mm.vertex_color.chunks_exact(3).map(|c| {
                let (linear, ok) = super::mesh::decode_vertex_colour([c[0], c[1], c[2]]);
                repaired |= !ok;
                linear
            }));
            if repaired {
                warnings.push(format!(
                    "{}: object `{name}` has vertex colours outside [0, 1] or not finite; clamped (non-finite read as white)",
                    path.display()
                ));
            }
        } else if !mesh.colors.is_empty() {
            mesh.colors.resize(mesh.positions.len(), Vec3A::ONE);
        }
        if mm.texcoords.len() == 2 * nv && mm.texcoords.iter().all(|x| x.is_finite()) {
            any_uvs = true;
            mesh.uvs
                .extend(mm.texcoords.chunks_exact(2).map(|t| Vec2::new(t[0], t[1])));
        } else {
            mesh.uvs.resize(mesh.positions.len(), Vec2::ZERO);
        }
        for (k, tri) in mm.indices.chunks_exact(3).enumerate() {
            if let Some(&bad) = tri.iter().find(|&&i| i as usize >= nv) {
                return Err(format!(
                    "{}: face {} of object `{name}` uses vertex index {} but the object has {nv} vertices",
                    path.display(),
                    k + 1,
                    bad as usize + 1
                ));
            }
            mesh.indices.push([base + tri[0], base + tri[1], base + tri[2]]);
            mesh.slots.push(slot as u32);
        }
        groups.push(ObjGroup {
            name: name.to_string(),
            material: mm.material_id.filter(|&i| i < materials.len()),
        });
    }
    if !any_normals {
        mesh.normals.clear();
    }
    if !any_uvs {
        mesh.uvs.clear();
    }
    if mesh.indices.is_empty() {
        return Err(format!("{} contains no faces", path.display()));
    }
    mesh.slot_count = groups.len().max(1) as u32;
    Ok(ObjData {
        mesh,
        groups,
        materials,
        warnings,
        mtl_files: mtl_files.into_inner(),
    })
}

/// MTL text with every colour line (`Ka`, `Kd`, `Ks`, `Ke`) given three
/// values: the format lets `g b` default to `r`, and tobj panics on fewer
/// than three (found by the `obj` fuzz target). A colour line with no value
/// is dropped, so the material keeps its default.
fn complete_colours(mtl: &[u8]) -> Vec<u8> {
    let text = String::from_utf8_lossy(mtl);
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        if !matches!(key, "Ka" | "Kd" | "Ks" | "Ke") {
            out.push_str(line);
            continue;
        }
        let values: Vec<&str> = words.collect();
        match values.len() {
            0 => {}
            1 | 2 => {
                let r = values[0];
                let g = values.get(1).copied().unwrap_or(r);
                out.push_str(&format!("{key} {r} {g} {r}\n"));
            }
            _ => out.push_str(line),
        }
    }
    out.into_bytes()
}

/// Room for `vertices` more vertices and `triangles` more triangles, or an
/// error instead of an abort when memory runs out.
fn reserve(mesh: &mut Mesh, vertices: usize, triangles: usize) -> Result<(), String> {
    let fail = |_| format!("not enough memory for {vertices} more vertices and {triangles} more triangles");
    mesh.positions.try_reserve(vertices).map_err(fail)?;
    mesh.normals.try_reserve(vertices).map_err(fail)?;
    mesh.uvs.try_reserve(vertices).map_err(fail)?;
    mesh.indices.try_reserve(triangles).map_err(fail)?;
    mesh.slots.try_reserve(triangles).map_err(fail)
}

/// The image file of a `map_Kd` value, skipping MTL texture options
/// (`-o 0.1 0 0 file.jpg`, `-clamp on file.png`, `file.png -bm 1`).
pub fn texture_file(spec: &str) -> Option<&str> {
    let mut words = spec.split_whitespace().peekable();
    while let Some(w) = words.next() {
        if w.starts_with('-') && w.parse::<f32>().is_err() {
            // An option: skip its numeric / on-off arguments (one for `-type`
            // and `-imfchan`, which take a word).
            if matches!(w, "-type" | "-imfchan") {
                words.next();
            }
            while words
                .peek()
                .is_some_and(|a| a.parse::<f32>().is_ok() || *a == "on" || *a == "off")
            {
                words.next();
            }
        } else {
            return Some(w);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::{check_face_indices, texture_file};

    /// Face indices naming nothing are refused with their line before tobj
    /// sees them (it overflowed on a relative one); every index tobj reads
    /// without overflow is still left to it.
    #[test]
    fn face_indices_that_name_nothing_are_refused_with_their_line() {
        let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
        let refused = |face: &str| check_face_indices(format!("{head}{face}\n").as_bytes()).err();
        let e = refused("f 1/-356/1 2/1/1 3/1/1").expect("relative texcoord past the start");
        assert!(
            e.contains("line 6") && e.contains("texture coordinate -356") && e.contains("only 1"),
            "{e}"
        );
        let e = refused("f -4 -2 -1").expect("relative position past the start");
        assert!(e.contains("position -4"), "{e}");
        let e = refused("f 1//9223372036854775807 2//1 3//1").expect("absolute normal past u32");
        assert!(
            e.contains("normal 9223372036854775807") && e.contains("past the 4294967295"),
            "{e}"
        );
        // Past the end but no overflow: tobj refuses it itself.
        assert_eq!(refused("f 1/1/1 2/1/1 9/1/1"), None);
        for fine in [
            "f 1/1/1 2/1/1 3/1/1",
            "f -3/-1/-1 -2/-1/-1 -1/-1/-1",
            "f 1//1 2//1 3//1",
            "l 1 2",
        ] {
            assert_eq!(refused(fine), None, "{fine}");
        }
        // Without any `vt`, tobj ignores texture indices: so does the check.
        assert_eq!(
            check_face_indices(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/-9 2/7 3/1\n").err(),
            None
        );
    }

    /// Running out of memory for a mesh is an error, not an abort (here a
    /// request no machine can meet).
    #[test]
    fn a_mesh_too_large_for_memory_is_an_error() {
        let mut mesh = super::Mesh::default();
        let e = super::reserve(&mut mesh, usize::MAX / 64, 1).expect_err("cannot fit");
        assert!(e.contains("not enough memory"), "{e}");
        assert!(super::reserve(&mut mesh, 3, 1).is_ok());
    }

    #[test]
    fn obj_texture_file_skips_options() {
        assert_eq!(texture_file("a.png"), Some("a.png"));
        assert_eq!(
            texture_file("-o 0.1 0 0 -clamp on diffuse.jpg"),
            Some("diffuse.jpg")
        );
        assert_eq!(texture_file("-type sphere d.jpg -bm 1"), Some("d.jpg"));
        assert_eq!(texture_file("-s 1"), None);
    }
}
