//! The mesh part of `build`: OBJ files loaded (each `meshes` entry once),
//! `Mesh` objects baked into world space, `Instance`s placed by transform,
//! and every OBJ group given a scene material.
//!
//! A group's material is, first match wins: `materials: { "group or MTL
//! name": "scene material" }`, then the object's `material`, then the group's
//! MTL material (see `build_mtl.rs`), then a grey default (with a note).

use super::build_mtl::MtlMaterials;
use crate::desc::{ObjectDesc, SceneDesc};
use crate::diagnostic::{Problem, suggest};
use crate::geometry::mesh_triangle::FLATTEN_MAX;
use crate::geometry::obj::{ObjData, ObjGroup};
use crate::geometry::{Geometry, Instance, MeshTriangle, Shape};
use crate::materials::{ColorTex, Material};
use crate::math::Rgb;
use glam::{Affine3A, Mat4, Vec3};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// A mesh in `Geometry::meshes` with what material resolution needs.
struct Loaded {
    mesh: u32,
    groups: Vec<ObjGroup>,
    /// Scene material of each MTL material of the file.
    mtl: Vec<u32>,
}

pub(super) struct MeshBuilder<'a> {
    desc: &'a SceneDesc,
    base: &'a Path,
    /// Reads an OBJ file (watch mode passes a cache of unchanged files).
    load_obj: &'a dyn Fn(&Path) -> Result<ObjData, String>,
    pub geo: Geometry,
    /// `meshes` entries already loaded, by name.
    shared: HashMap<String, Option<Loaded>>,
    grey: Option<u32>,
    pub triangles: usize,
    pub notes: Vec<String>,
}

impl<'a> MeshBuilder<'a> {
    pub fn new(
        desc: &'a SceneDesc,
        base: &'a Path,
        load_obj: &'a dyn Fn(&Path) -> Result<ObjData, String>,
    ) -> Self {
        Self {
            desc,
            base,
            load_obj,
            geo: Geometry::default(),
            shared: HashMap::new(),
            grey: None,
            triangles: 0,
            notes: Vec::new(),
        }
    }

    /// Adds object `i` (a `Mesh` or an `Instance`) as one [`Shape::Instance`],
    /// or, for a small baked mesh, as its triangles (see `mesh_triangle.rs`).
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        i: usize,
        o: &ObjectDesc,
        world_from_object: Mat4,
        index: &HashMap<&str, u32>,
        mats: &mut MtlMaterials,
        shapes: &mut Vec<Shape>,
        problems: &mut Vec<Problem>,
    ) {
        let path = format!("objects[{i}]");
        let mut flatten = false;
        let (loaded, transform) = match o {
            ObjectDesc::Mesh { file, smooth, .. } => {
                let Some(mut data) = self.load(file, *smooth, &format!("{path}.file"), problems) else {
                    return;
                };
                // Baked: the mesh is this object's alone.
                bake(&mut data, world_from_object);
                flatten = data.mesh.triangle_count() <= FLATTEN_MAX;
                data.mesh.prepare();
                (self.push_mesh(data, file, mats), Affine3A::IDENTITY)
            }
            ObjectDesc::Instance { mesh, .. } => {
                if !self.shared.contains_key(mesh) {
                    let entry = self.desc.meshes.get(mesh).and_then(|m| {
                        let mut data =
                            self.load(&m.file, m.smooth, &format!("meshes.{mesh}.file"), problems)?;
                        data.mesh.prepare();
                        Some(self.push_mesh(data, &m.file, mats))
                    });
                    self.shared.insert(mesh.clone(), entry);
                }
                let Some(Some(l)) = self.shared.get(mesh) else {
                    return;
                };
                let l = Loaded {
                    mesh: l.mesh,
                    groups: l.groups.clone(),
                    mtl: l.mtl.clone(),
                };
                (l, Affine3A::from_mat4(world_from_object))
            }
            _ => return,
        };
        let overrides = o.material_overrides().cloned().unwrap_or_default();
        let materials = self.resolve(&path, &loaded, o.material(), &overrides, index, mats, problems);
        let id = self.geo.instances.len() as u32;
        self.geo.instances.push(Instance::new(
            loaded.mesh,
            transform,
            materials.into_boxed_slice(),
        ));
        let mesh = &self.geo.meshes[loaded.mesh as usize];
        self.triangles += mesh.triangle_count();
        if flatten {
            shapes.extend((0..mesh.triangle_count() as u32).map(|tri| {
                let (a, b, c) = mesh.corners(tri);
                Shape::Triangle(MeshTriangle {
                    p: [a.into(), b.into(), c.into()],
                    instance: id,
                    tri,
                })
            }));
        } else {
            shapes.push(Shape::Instance(id));
        }
    }

    fn load(&mut self, file: &str, smooth: bool, at: &str, problems: &mut Vec<Problem>) -> Option<ObjData> {
        let path = self.base.join(file);
        match (self.load_obj)(&path) {
            Ok(mut data) => {
                self.notes.append(&mut data.warnings);
                if smooth {
                    data.mesh.compute_smooth_normals();
                }
                Some(data)
            }
            Err(msg) => {
                let help = if path.exists() {
                    "check that the file is a Wavefront OBJ with `v` and `f` lines".to_string()
                } else {
                    format!(
                        "no file at {} (paths are relative to the scene file's folder)",
                        path.display()
                    )
                };
                problems.push(Problem::new(at, msg).help(help));
                None
            }
        }
    }

    fn push_mesh(&mut self, data: ObjData, file: &str, mats: &mut MtlMaterials) -> Loaded {
        let obj = self.base.join(file);
        let dir = obj.parent().unwrap_or(self.base);
        let mtl = data
            .materials
            .iter()
            .map(|m| mats.add(m, dir, &mut self.notes))
            .collect();
        self.geo.meshes.push(data.mesh);
        Loaded {
            mesh: self.geo.meshes.len() as u32 - 1,
            groups: data.groups,
            mtl,
        }
    }

    /// Scene material of each slot; unknown override keys are problems.
    #[allow(clippy::too_many_arguments)]
    fn resolve(
        &mut self,
        path: &str,
        l: &Loaded,
        material: Option<&str>,
        overrides: &BTreeMap<String, String>,
        index: &HashMap<&str, u32>,
        mats: &mut MtlMaterials,
        problems: &mut Vec<Problem>,
    ) -> Vec<u32> {
        let mtl_names: Vec<Option<String>> = l
            .groups
            .iter()
            .map(|g| g.material.and_then(|m| mats.name(l.mtl[m])))
            .collect();
        let names: Vec<String> = l
            .groups
            .iter()
            .zip(&mtl_names)
            .flat_map(|(g, m)| std::iter::once(g.name.clone()).chain(m.clone()))
            .collect();
        for key in overrides.keys().filter(|k| !names.contains(k)) {
            let mut p = Problem::new(
                format!("{path}.materials.{key}"),
                format!("the OBJ has no group or material `{key}`"),
            );
            p = match suggest(key, names.iter().map(String::as_str)) {
                Some(s) => p.help(format!("did you mean `{s}`?")),
                None => p.help(format!("its groups and materials are: {}", quoted(&names))),
            };
            problems.push(p);
        }
        let scene = |n: &str| index.get(n).copied();
        l.groups
            .iter()
            .zip(&mtl_names)
            .map(|(g, mtl_name)| {
                let by_name = overrides
                    .get(&g.name)
                    .or_else(|| mtl_name.as_ref().and_then(|m| overrides.get(m)));
                if let Some(m) = by_name.and_then(|n| scene(n)).or_else(|| material.and_then(scene)) {
                    return m;
                }
                if let Some(m) = g.material {
                    return l.mtl[m];
                }
                *self.grey.get_or_insert_with(|| {
                    self.notes.push(format!(
                        "{path}: OBJ group `{}` has no material and the scene gives none; using grey Lambert (0.5)",
                        g.name
                    ));
                    mats.push(Material::Lambert {
                        albedo: ColorTex::Const(Rgb::splat(0.5)),
                    })
                })
            })
            .collect()
    }

    /// Hands over the geometry, the triangle count over all instances and
    /// the notes (repairs and defaults).
    pub fn finish(self) -> (Geometry, usize, Vec<String>) {
        (self.geo, self.triangles, self.notes)
    }
}

fn quoted(names: &[String]) -> String {
    names
        .iter()
        .map(|n| format!("`{n}`"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Transforms positions and normals of `data` into world space.
fn bake(data: &mut ObjData, m: Mat4) {
    let normal_m = m.inverse().transpose();
    for p in &mut data.mesh.positions {
        *p = m.transform_point3(Vec3::from(*p)).into();
    }
    for n in &mut data.mesh.normals {
        *n = normal_m
            .transform_vector3(Vec3::from(*n))
            .normalize_or_zero()
            .into();
    }
}
