//! Stanford PLY meshes: ASCII, binary little- and big-endian, read through
//! the `ply-rs-bw` crate (its typed parser, so a vertex is a small struct,
//! not a map of named values).
//!
//! What is read, as Mitsuba 3's and pbrt-v4's PLY readers do:
//! - `vertex`: `x y z` (any numeric type; required), `nx ny nz` (all three,
//!   or none), texture coordinates under any of their usual names (`u v`,
//!   `s t`, `texture_u texture_v`, `texture_s texture_t`), and colours
//!   `red green blue` (integer types scaled to [0, 1] by their largest
//!   value, floats as written). Colours are display colours, decoded from
//!   sRGB like an OBJ's `v x y z r g b`; `alpha` is not read.
//! - `face`: `vertex_indices` (or `vertex_index`), a list of any integer
//!   type; polygons are split into fans, faces of fewer than three corners
//!   are skipped with a warning.
//! - Other elements (`edge`, `material`, …) and properties are read past.
//!
//! The mesh has one slot (named `unnamed`, like an OBJ without groups) and
//! no materials: a scene object gives it one. Hostile files are errors, not
//! panics: the crate caps what a header's counts may reserve, every index
//! is checked against the vertex count, positions must be finite, and the
//! triangle count stays below the BVH's limit.

use super::Mesh;
use glam::{Vec2, Vec3A};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Header, Property, PropertyAccess, PropertyAccessResult, PropertyType};
use std::path::Path;

/// Most triangles a PLY may give (after polygons are split): the BVH's
/// limit ([`crate::accel::wide::MAX_PRIMS`]).
pub const MAX_PLY_TRIANGLES: usize = crate::accel::wide::MAX_PRIMS - 1;

/// One `vertex` element, as read.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    p: [f32; 3],
    n: [f32; 3],
    uv: [f32; 2],
    color: [f32; 3],
}

/// A scalar property's value, and its value scaled to [0, 1] when it is
/// an integer colour channel (by the type's largest value).
fn number(p: &Property) -> Option<(f64, f64)> {
    Some(match *p {
        Property::Char(x) => (x.into(), f64::from(x) / f64::from(i8::MAX)),
        Property::UChar(x) => (x.into(), f64::from(x) / f64::from(u8::MAX)),
        Property::Short(x) => (x.into(), f64::from(x) / f64::from(i16::MAX)),
        Property::UShort(x) => (x.into(), f64::from(x) / f64::from(u16::MAX)),
        Property::Int(x) => (x.into(), f64::from(x) / f64::from(i32::MAX)),
        Property::UInt(x) => (x.into(), f64::from(x) / f64::from(u32::MAX)),
        Property::Float(x) => (x.into(), x.into()),
        Property::Double(x) => (x, x),
        _ => return None,
    })
}

impl PropertyAccess for Vertex {
    fn new() -> Self {
        Vertex {
            p: [0.0; 3],
            n: [0.0; 3],
            uv: [0.0; 2],
            color: [1.0; 3],
        }
    }

    fn set_property(&mut self, key: &str, property: Property) -> PropertyAccessResult {
        let Some((x, unit)) = number(&property) else {
            return PropertyAccessResult::Ignored;
        };
        let x = x as f32;
        match key {
            "x" => self.p[0] = x,
            "y" => self.p[1] = x,
            "z" => self.p[2] = x,
            "nx" => self.n[0] = x,
            "ny" => self.n[1] = x,
            "nz" => self.n[2] = x,
            "u" | "s" | "texture_u" | "texture_s" => self.uv[0] = x,
            "v" | "t" | "texture_v" | "texture_t" => self.uv[1] = x,
            "red" => self.color[0] = unit as f32,
            "green" => self.color[1] = unit as f32,
            "blue" => self.color[2] = unit as f32,
            _ => return PropertyAccessResult::Ignored,
        }
        PropertyAccessResult::Set
    }
}

/// A vertex index that was negative (refused later with the face's number).
const NEGATIVE: u32 = u32::MAX;

/// One `face` element: its corners' vertex indices ([`NEGATIVE`] for a
/// negative one). A triangle's three are kept inline, so a mesh of millions
/// of triangles holds no allocation per face; longer polygons keep a list.
#[derive(Debug, Default)]
struct Face {
    len: u32,
    first: [u32; 3],
    polygon: Vec<u32>,
}

impl Face {
    fn corner(&self, i: usize) -> u32 {
        if self.polygon.is_empty() {
            self.first[i]
        } else {
            self.polygon[i]
        }
    }
}

impl PropertyAccess for Face {
    fn new() -> Self {
        Face::default()
    }

    fn set_property(&mut self, key: &str, property: Property) -> PropertyAccessResult {
        if key != "vertex_indices" && key != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        fn fill<T: Copy>(face: &mut Face, v: &[T], f: impl Fn(T) -> Option<u32>) {
            let index = |x: T| f(x).filter(|&i| i != NEGATIVE).unwrap_or(NEGATIVE);
            face.len = u32::try_from(v.len()).unwrap_or(u32::MAX);
            face.polygon.clear();
            if v.len() == 3 {
                face.first = [index(v[0]), index(v[1]), index(v[2])];
            } else if v.len() > 3 {
                face.polygon = v.iter().map(|&x| index(x)).collect();
            }
        }
        match &property {
            Property::ListChar(v) => fill(self, v, |x| u32::try_from(x).ok()),
            Property::ListUChar(v) => fill(self, v, |x| Some(x.into())),
            Property::ListShort(v) => fill(self, v, |x| u32::try_from(x).ok()),
            Property::ListUShort(v) => fill(self, v, |x| Some(x.into())),
            Property::ListInt(v) => fill(self, v, |x| u32::try_from(x).ok()),
            Property::ListUInt(v) => fill(self, v, Some),
            _ => return PropertyAccessResult::UnsupportedType,
        }
        PropertyAccessResult::Set
    }
}

/// Any other element: read past.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

/// Whether the element declares every one of `names`.
fn has(e: &ElementDef, names: &[&str]) -> bool {
    names.iter().all(|n| e.properties.contains_key(*n))
}

/// Parses PLY `bytes` (named `path` in messages) into a mesh of one slot
/// and the repairs made (one sentence each); the error is a sentence naming
/// what is wrong. (`obj.rs` wraps it as a file with one group and no
/// materials.)
pub fn parse_ply(path: &Path, bytes: &[u8]) -> Result<(Mesh, Vec<String>), String> {
    let name = path.display();
    let mut reader = Reader::new(std::io::BufReader::new(bytes));
    let header: Header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| format!("{name}: not a PLY file this reader understands ({e})"))?;
    let vertex_def = header
        .elements
        .get("vertex")
        .ok_or_else(|| format!("{name}: the PLY file has no `vertex` element"))?;
    if !has(vertex_def, &["x", "y", "z"]) {
        return Err(format!(
            "{name}: the PLY `vertex` element has no `x`, `y` and `z` properties"
        ));
    }
    // Numbers where numbers are expected, a list where a list is: a list
    // read as a coordinate would leave the vertex at 0 without a word.
    for (key, p) in &vertex_def.properties {
        let named = ["x", "y", "z", "nx", "ny", "nz", "red", "green", "blue"].contains(&key.as_str());
        if named && !matches!(p.data_type, PropertyType::Scalar(_)) {
            return Err(format!(
                "{name}: the PLY vertex property `{key}` is a list, not a number"
            ));
        }
    }
    let face_def = header.elements.get("face").ok_or_else(|| {
        format!("{name}: the PLY file has no `face` element (a point cloud is not a surface)")
    })?;
    let scalar_index = ["vertex_indices", "vertex_index"].iter().any(|k| {
        face_def
            .properties
            .get(*k)
            .is_some_and(|p| matches!(p.data_type, PropertyType::Scalar(_)))
    });
    if scalar_index {
        return Err(format!(
            "{name}: the PLY face property `vertex_indices` is a number, not a list"
        ));
    }
    if !has(face_def, &["vertex_indices"]) && !has(face_def, &["vertex_index"]) {
        return Err(format!(
            "{name}: the PLY `face` element has no `vertex_indices` (or `vertex_index`) list"
        ));
    }
    let with_normals = has(vertex_def, &["nx", "ny", "nz"]);
    let with_uvs = [
        ["u", "v"],
        ["s", "t"],
        ["texture_u", "texture_v"],
        ["texture_s", "texture_t"],
    ]
    .iter()
    .any(|pair| has(vertex_def, pair));
    let with_colors = has(vertex_def, &["red", "green", "blue"]);
    let mut vertices: Vec<Vertex> = Vec::new();
    let mut faces: Vec<Face> = Vec::new();
    let binary = !matches!(header.encoding, ply_rs_bw::ply::Encoding::Ascii);
    for (key, def) in &header.elements {
        // A binary element with no properties takes no bytes: the crate
        // would still count through all of them, and a header declaring
        // 10¹² of them hung the load. Nothing to read past.
        if binary && def.properties.is_empty() {
            continue;
        }
        let at = |e: ply_rs_bw::parser::ParseError| format!("{name}: PLY element `{key}`: {e}");
        match key.as_str() {
            "vertex" => {
                vertices = Parser::<Vertex>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(at)?
            }
            "face" => {
                faces = Parser::<Face>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(at)?
            }
            _ => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(at)?;
            }
        }
    }
    build(path, &vertices, &faces, with_normals, with_uvs, with_colors)
}

/// The mesh of the elements read.
fn build(
    path: &Path,
    vertices: &[Vertex],
    faces: &[Face],
    with_normals: bool,
    with_uvs: bool,
    with_colors: bool,
) -> Result<(Mesh, Vec<String>), String> {
    let name = path.display();
    let mut warnings = Vec::new();
    let nv = vertices.len();
    let fail = |what: &str| format!("{name}: not enough memory for the PLY's {what}");
    let mut mesh = Mesh::default();
    mesh.positions
        .try_reserve_exact(nv)
        .map_err(|_| fail("vertices"))?;
    for (k, v) in vertices.iter().enumerate() {
        if !v.p.iter().all(|x| x.is_finite()) {
            let [x, y, z] = v.p;
            return Err(format!("{name}: PLY vertex {k} is not finite: ({x}, {y}, {z})"));
        }
        mesh.positions.push(Vec3A::from_array(v.p));
    }
    if with_normals {
        let valid =
            |n: &[f32; 3]| n.iter().all(|x| x.is_finite()) && n.iter().map(|x| x * x).sum::<f32>() > 0.0;
        let bad = vertices.iter().filter(|v| !valid(&v.n)).count();
        if bad > 0 {
            warnings.push(format!(
                "{name}: {bad} PLY vertex normal{} zero or not finite; those vertices use face normals",
                if bad == 1 { " is" } else { "s are" }
            ));
        }
        mesh.normals.try_reserve_exact(nv).map_err(|_| fail("normals"))?;
        mesh.normals.extend(vertices.iter().map(|v| {
            if valid(&v.n) {
                Vec3A::from_array(v.n)
            } else {
                Vec3A::ZERO
            }
        }));
    }
    if with_uvs {
        let bad = vertices.iter().any(|v| !v.uv.iter().all(|x| x.is_finite()));
        if bad {
            warnings.push(format!(
                "{name}: PLY texture coordinates not finite; the mesh is read without them"
            ));
        } else {
            mesh.uvs
                .try_reserve_exact(nv)
                .map_err(|_| fail("texture coordinates"))?;
            mesh.uvs.extend(vertices.iter().map(|v| Vec2::from_array(v.uv)));
        }
    }
    if with_colors {
        let mut repaired = false;
        mesh.colors.try_reserve_exact(nv).map_err(|_| fail("colours"))?;
        mesh.colors.extend(vertices.iter().map(|v| {
            let (linear, ok) = super::mesh::decode_vertex_colour(v.color);
            repaired |= !ok;
            linear
        }));
        if repaired {
            warnings.push(format!(
                "{name}: PLY vertex colours outside [0, 1] or not finite; clamped (non-finite read as white)"
            ));
        }
    }
    let mut skipped = 0usize;
    for (k, f) in faces.iter().enumerate() {
        if f.len < 3 {
            skipped += 1;
            continue;
        }
        let corner = |i: usize| -> Result<u32, String> {
            match f.corner(i) {
                NEGATIVE => Err(format!(
                    "{name}: PLY face {k} uses a negative (or 4294967295) vertex index"
                )),
                c if (c as usize) < nv => Ok(c),
                c => Err(format!(
                    "{name}: PLY face {k} uses vertex {c} but the file has {nv} vertices (numbered from 0)"
                )),
            }
        };
        let first = corner(0)?;
        for i in 1..f.len as usize - 1 {
            if mesh.indices.len() >= MAX_PLY_TRIANGLES {
                return Err(format!(
                    "{name}: the PLY has more than {MAX_PLY_TRIANGLES} triangles, the most one mesh may hold"
                ));
            }
            let tri = [first, corner(i)?, corner(i + 1)?];
            mesh.indices.try_reserve(1).map_err(|_| fail("triangles"))?;
            mesh.indices.push(tri);
        }
    }
    if skipped > 0 {
        warnings.push(format!(
            "{name}: {skipped} PLY face{} fewer than three corners, skipped",
            if skipped == 1 { " has" } else { "s have" }
        ));
    }
    if mesh.indices.is_empty() {
        return Err(format!("{name} contains no faces"));
    }
    mesh.slot_count = 1;
    Ok((mesh, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<(Mesh, Vec<String>), String> {
        parse_ply(Path::new("t.ply"), text.as_bytes())
    }

    const QUAD: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
        property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\n\
        property list uchar int vertex_indices\nend_header\n\
        0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 255 255 255\n4 0 1 2 3\n";

    #[test]
    fn an_ascii_quad_with_colours_is_two_triangles() {
        let d = parse(QUAD).expect("loads");
        assert_eq!(d.0.indices, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(d.0.positions[2], Vec3A::new(1.0, 1.0, 0.0));
        assert_eq!(d.0.colors[0], Vec3A::new(1.0, 0.0, 0.0));
        assert_eq!(d.0.colors[3], Vec3A::ONE);
        assert!(d.0.normals.is_empty() && d.0.uvs.is_empty());
        assert!(d.1.is_empty(), "{:?}", d.1);
    }

    /// The same mesh written binary, both byte orders, with doubles, normals,
    /// `s t` coordinates and an `edge` element to read past.
    #[test]
    fn binary_files_of_either_byte_order_read_alike() {
        for big in [false, true] {
            let mut b = format!(
                "ply\nformat binary_{}_endian 1.0\ncomment test\nelement vertex 3\nproperty double x\n\
                 property double y\nproperty double z\nproperty float nx\nproperty float ny\nproperty float nz\n\
                 property float s\nproperty float t\nelement face 1\nproperty list uchar uint vertex_index\n\
                 element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n",
                if big { "big" } else { "little" }
            )
            .into_bytes();
            let mut put = |bytes: &[u8]| {
                if big {
                    b.extend(bytes.iter().rev())
                } else {
                    b.extend(bytes)
                }
            };
            for (p, uv) in [
                ([0.0f64, 0.0, 0.0], [0.0f32, 0.0]),
                ([2.0, 0.0, 0.0], [1.0, 0.0]),
                ([0.0, 2.0, 0.0], [0.0, 1.0]),
            ] {
                p.iter().for_each(|x| put(&x.to_le_bytes()));
                [0.0f32, 0.0, 1.0].iter().for_each(|x| put(&x.to_le_bytes()));
                uv.iter().for_each(|x| put(&x.to_le_bytes()));
            }
            put(&[3]);
            [0u32, 1, 2].iter().for_each(|x| put(&x.to_le_bytes()));
            [0i32, 1].iter().for_each(|x| put(&x.to_le_bytes()));
            let d = parse_ply(Path::new("b.ply"), &b).expect("loads");
            assert_eq!(d.0.indices, vec![[0, 1, 2]], "big endian: {big}");
            assert_eq!(d.0.positions[1], Vec3A::new(2.0, 0.0, 0.0));
            assert_eq!(d.0.normals[2], Vec3A::Z);
            assert_eq!(d.0.uvs[2], Vec2::new(0.0, 1.0));
        }
    }

    #[test]
    fn wrong_files_are_sentences_not_panics() {
        let cases = [
            ("", "not a PLY"),
            ("ply\nformat ascii 1.0\nend_header\n", "no `vertex` element"),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n",
                "no `x`, `y` and `z`",
            ),
            (
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
                "point cloud",
            ),
            (
                &QUAD.replace("4 0 1 2 3", "4 0 1 2 9"),
                "uses vertex 9 but the file has 4",
            ),
            (&QUAD.replace("4 0 1 2 3", "3 0 -1 2"), "negative"),
            (&QUAD.replace("0 1 0 255", "0 1e39 0 255"), "not finite"),
            (&QUAD.replace("0 1 0 255", "0 nan 0 255"), "PLY element `vertex`"),
            (
                &QUAD.replace("element vertex 4", "element vertex 4000000000"),
                "PLY element `vertex`",
            ),
            (&QUAD.replace("4 0 1 2 3\n", "4 0 1\n"), "PLY element `face`"),
            (&QUAD.replace("4 0 1 2 3", "2 0 1"), "contains no faces"),
            (
                &QUAD
                    .replace("property float y", "property list uchar float y")
                    .replace("0 1 0 255", "0 1 1 0 255"),
                "`y` is a list",
            ),
            (
                &QUAD.replace(
                    "property list uchar int vertex_indices",
                    "property int vertex_indices",
                ),
                "is a number, not a list",
            ),
        ];
        for (text, want) in cases {
            let e = parse(text).err().unwrap_or_else(|| panic!("{want}: loaded"));
            assert!(e.contains(want), "{want}: {e}");
        }
    }

    #[test]
    fn out_of_range_colours_and_short_faces_are_repaired_with_warnings() {
        let text = QUAD
            .replace(
                "property uchar red\nproperty uchar green\nproperty uchar blue",
                "property float red\nproperty float green\nproperty float blue",
            )
            .replace("0 0 0 255 0 0", "0 0 0 2 -1 1e39")
            .replace("element face 1", "element face 2")
            .replace("4 0 1 2 3\n", "4 0 1 2 3\n2 0 1\n");
        let d = parse(&text).expect("loads");
        assert_eq!(d.0.colors[0], Vec3A::new(1.0, 0.0, 1.0));
        assert_eq!(d.0.indices.len(), 2);
        assert_eq!(d.1.len(), 2, "{:?}", d.1);
    }
}
