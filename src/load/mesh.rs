//! The mesh part of `build`: OBJ files loaded (each `meshes` entry once),
//! `Mesh` objects baked into world space, `Instance`s placed by transform,
//! and every OBJ group given a scene material.
//!
//! A group's material is, first match wins: `materials: { "group or MTL
//! name": "scene material" }`, then the object's `material`, then the group's
//! MTL material (see `mtl.rs`), then a grey default (with a note).
//!
//! A group emits the object's `emission` if it has one, else the `Ke` of its
//! MTL material when the group keeps that material (a scene material that
//! replaces it replaces its emission too). Each emitting group of each
//! placed mesh is one [`MeshLight`] with its own world-space copy of the
//! group's triangles; a moving instance's light keeps them in the mesh's
//! space with the instance's motion.
//!
//! The check step only makes sure each OBJ file exists (`Checker::file`);
//! parsing the file is the build's work, and its problems are reported at
//! the object or `meshes` entry that names it.

use super::build_context::BuildContext;
use super::mesh_keys::{Key, key_problem, parts_list, twice_defined};
use super::mesh_state::LoadedMesh;
use super::validate::Checker;
use crate::desc::{MeshDesc, ObjectDesc};
use crate::diagnostic::Problem;
use crate::geometry::flat_shade::FlatShade;
use crate::geometry::mesh_quad::pairing;
use crate::geometry::mesh_triangle::FLATTEN_MAX;
use crate::geometry::obj::ObjData;
use crate::geometry::{Instance, MeshQuad, MeshTriangle, NO_LIGHT, Shape};
use crate::lights::{Emission, Light, MeshLight};
use crate::materials::{ColorTex, LambertMaterial, Material};
use crate::math::Rgb;
use glam::{Affine3A, Mat4, Vec2, Vec3};
use std::collections::BTreeMap;

impl Checker {
    /// An entry of the scene's `meshes` section.
    pub(super) fn mesh_entry(&mut self, path: &str, m: &MeshDesc) {
        self.file(&format!("{path}.file"), &m.file, "OBJ");
    }
}

/// Adds object `i` (a `Mesh` or an `Instance`) as one [`Shape::Instance`],
/// or, for a small baked mesh, as its triangles (see `mesh_triangle.rs`).
pub(super) fn add(ctx: &mut BuildContext, i: usize, o: &ObjectDesc, world_from_object: Mat4) {
    let path = format!("objects[{i}]");
    let mut flatten = false;
    let (loaded, transform) = match o {
        ObjectDesc::Mesh { file, smooth, .. } => {
            let Some(mut data) = load(ctx, file, *smooth, &format!("{path}.file")) else {
                return;
            };
            // Baked: the mesh is this object's alone.
            bake(&mut data, world_from_object);
            flatten = data.mesh.triangle_count() <= FLATTEN_MAX;
            data.mesh.prepare();
            (
                push_mesh(ctx, data, file, &format!("{path}.file")),
                Affine3A::IDENTITY,
            )
        }
        ObjectDesc::Instance { mesh, .. } => {
            let Some(l) = shared(ctx, mesh) else {
                return;
            };
            (l, Affine3A::from_mat4(world_from_object))
        }
        _ => return,
    };
    let overrides = o.material_overrides().cloned().unwrap_or_default();
    // An index-matched medium boundary (a medium and no material) is never
    // shaded: its grey slots are placeholders, not worth a note.
    let (interior, exterior) = o.media();
    let null = (interior.is_some() || exterior.is_some()) && o.material().is_none() && overrides.is_empty();
    let materials = resolve(ctx, &path, &loaded, o.material(), &overrides, null);
    let emission = slot_emission(ctx, o, &path, &loaded, &materials);
    let id = ctx.geometry.instances.len() as u32;
    let mut instance = Instance::new(loaded.mesh, transform, materials.into_boxed_slice());
    if let Some(track) = super::animation::instance_track(o) {
        // Keyed: placed at the shutter's opening, and moving while it is open.
        let shutter = super::animation::shutter(ctx.desc);
        let placed = Affine3A::from_mat4(track.at(shutter.0));
        instance = Instance::new(loaded.mesh, placed, instance.materials);
        if track.moves_between(shutter.0, shutter.1) {
            instance = instance.with_motion(crate::geometry::moving::InstanceMotion::new(track, shutter));
        }
    }
    if emission.iter().any(Option::is_some) {
        instance.lights = emission
            .iter()
            .enumerate()
            .map(|(slot, e)| {
                e.clone().map_or(NO_LIGHT, |(emission, two_sided)| {
                    mesh_light(ctx, &instance, slot, emission, two_sided)
                })
            })
            .collect();
    }
    ctx.geometry.instances.push(instance);
    let mesh = &ctx.geometry.meshes[loaded.mesh as usize];
    ctx.triangles += mesh.triangle_count();
    if flatten {
        // Triangles that make a quad go in as one entry (`mesh_quad.rs`),
        // the others one by one. Greedy over all pairs: the mesh's BVH
        // build has reordered the triangles, and flattened meshes are
        // small (at most FLATTEN_MAX triangles).
        let n = mesh.triangle_count() as u32;
        let corners = |tri: u32| {
            let (a, b, c) = mesh.corners(tri);
            [a, b, c]
        };
        // Flat-shaded and untextured: each triangle's record is fixed here
        // (`geometry/flat_shade.rs`) instead of read through the instance.
        let instance = &ctx.geometry.instances[id as usize];
        let plain = mesh.normals.is_empty() && mesh.uvs.is_empty() && instance.is_identity();
        let flat = |tri: u32| {
            let slot = mesh.slot(tri) as usize;
            FlatShade::new(
                corners(tri),
                instance.materials.get(slot).copied().unwrap_or(0),
                instance.lights.get(slot).copied().unwrap_or(NO_LIGHT),
            )
        };
        let mut taken = vec![false; n as usize];
        for tri in 0..n {
            if taken[tri as usize] {
                continue;
            }
            taken[tri as usize] = true;
            let pair = (tri + 1..n).filter(|&o| !taken[o as usize]).find_map(|o| {
                let (v, rot) = pairing(corners(tri), corners(o))?;
                Some((o, MeshQuad::new(v, id, [tri, o], rot)?))
            });
            match pair {
                Some((o, q)) => {
                    taken[o as usize] = true;
                    let q = if plain {
                        q.with_flat([flat(tri), flat(o)])
                    } else {
                        q
                    };
                    ctx.shapes.push(Shape::MeshQuad(q));
                }
                None => {
                    let t = MeshTriangle::new(corners(tri), id, tri);
                    let t = if plain { t.with_flat(flat(tri)) } else { t };
                    ctx.shapes.push(Shape::Triangle(t));
                }
            }
        }
    } else {
        ctx.shapes.push(Shape::Instance(id));
    }
}

/// What each slot (OBJ group) emits, as radiance and two-sidedness: the
/// object's `emission` for every slot, else the `Ke` of each slot that kept
/// its MTL material.
fn slot_emission(
    ctx: &BuildContext,
    o: &ObjectDesc,
    path: &str,
    l: &LoadedMesh,
    materials: &[u32],
) -> Vec<Option<(Emission, bool)>> {
    if let Some(e) = o.emission() {
        let emission = ctx.emission(&format!("{path}.emission.radiance"), &e.radiance);
        return vec![Some((emission, e.two_sided)); materials.len()];
    }
    l.groups
        .iter()
        .zip(materials)
        .map(|(g, &m)| {
            let mtl = g.material.map(|k| l.mtl[k]).filter(|&k| k == m)?;
            ctx.mtl.emission(mtl).map(|ke| (ke.clone(), false))
        })
        .collect()
}

/// The light of the triangles of `slot` in `instance` (not yet pushed), or
/// `NO_LIGHT` when they have no area.
pub(super) fn mesh_light(
    ctx: &mut BuildContext,
    instance: &Instance,
    slot: usize,
    emission: Emission,
    two_sided: bool,
) -> u32 {
    let mesh = &ctx.geometry.meshes[instance.mesh as usize];
    let in_slot = || (0..mesh.triangle_count() as u32).filter(|&t| mesh.slot(t) as usize == slot);
    // A moving instance's light keeps the triangles in the mesh's space
    // and places them at each time (`lights/mesh.rs`).
    let tris: Vec<_> = in_slot()
        .map(|t| match instance.motion() {
            None => instance.world_triangle(t, &ctx.geometry.meshes),
            Some(_) => {
                let (a, b, c) = mesh.corners(t);
                [a, b, c]
            }
        })
        .collect();
    // Corner UVs as a hit interpolates them (`Mesh::hit`: barycentric
    // (0, 0), (1, 0), (0, 1) without UVs), in `world_triangle`'s order,
    // which swaps two corners under a mirroring transform.
    let mirrored = instance.motion().is_none() && instance.world_from_object.matrix3.determinant() < 0.0;
    let uvs: Vec<[Vec2; 3]> = if emission.is_textured() {
        in_slot()
            .map(|t| {
                let [a, b, c] = if mesh.uvs.is_empty() {
                    [Vec2::ZERO, Vec2::X, Vec2::Y]
                } else {
                    mesh.indices[t as usize].map(|k| mesh.uvs[k as usize])
                };
                if mirrored { [a, c, b] } else { [a, b, c] }
            })
            .collect()
    } else {
        Vec::new()
    };
    let light = MeshLight::new(tris, emission.radiance, two_sided).map(|l| l.with_emission(emission, uvs));
    match light.map(|l| match instance.motion() {
        Some(m) => l.with_motion(m.clone()),
        None => l,
    }) {
        Some(light) => {
            ctx.lights.push(match light.as_parallelogram() {
                Some(quad) => Light::Quad(quad),
                None => Light::Mesh(light),
            });
            ctx.lights.len() as u32 - 1
        }
        None => NO_LIGHT,
    }
}

/// The `meshes` entry `name`, loaded on first use.
fn shared(ctx: &mut BuildContext, name: &str) -> Option<LoadedMesh> {
    if !ctx.mesh_state.shared.contains_key(name) {
        let entry = ctx.desc.meshes.get(name).and_then(|m| {
            let mut data = load(ctx, &m.file, m.smooth, &format!("meshes.{name}.file"))?;
            data.mesh.prepare();
            Some(push_mesh(ctx, data, &m.file, &format!("meshes.{name}.file")))
        });
        ctx.mesh_state.shared.insert(name.to_string(), entry);
    }
    ctx.mesh_state.shared.get(name).cloned().flatten()
}

fn load(ctx: &mut BuildContext, file: &str, smooth: bool, at: &str) -> Option<ObjData> {
    let path = ctx.base.join(file);
    match (ctx.load_obj)(&path) {
        Ok(mut data) => {
            ctx.notes.append(&mut data.warnings);
            if smooth {
                data.mesh.compute_smooth_normals();
            }
            if ctx.normal_maps || data.materials.iter().any(super::mtl::wants_tangents) {
                crate::geometry::tangents::generate(&mut data.mesh);
            }
            Some(data)
        }
        Err(msg) => {
            let help = if path.exists() && crate::geometry::obj::is_ply(&path) {
                "check that the file is a PLY mesh with a `vertex` element (x, y, z) and a `face` element (vertex_indices)"
                    .to_string()
            } else if path.exists() {
                "check that the file is a Wavefront OBJ with `v` and `f` lines".to_string()
            } else {
                format!(
                    "no file at {} (paths are relative to the scene file's folder)",
                    path.display()
                )
            };
            ctx.problems.push(Problem::new(at, msg).help(help));
            None
        }
    }
}

fn push_mesh(ctx: &mut BuildContext, data: ObjData, file: &str, at: &str) -> LoadedMesh {
    let obj = ctx.base.join(file);
    let dir = obj.parent().unwrap_or(ctx.base);
    // The MTL's notes say which object's OBJ they come from.
    let mut notes = Vec::new();
    let painted = !data.mesh.colors.is_empty();
    let mtl = data
        .materials
        .iter()
        .map(|m| ctx.mtl.add(m, dir, painted, &mut notes))
        .collect();
    ctx.notes
        .extend(notes.into_iter().map(|n| format!("{at} ({file}): {n}")));
    for why in std::mem::take(&mut ctx.mtl.refused) {
        let help = "an untrusted scene may read only files inside --root";
        ctx.problems.push(Problem::new(at, why).help(help));
    }
    ctx.problems.extend(twice_defined(&data, at));
    ctx.obj_parts.push((obj.clone(), parts_list(&data)));
    ctx.mtl_files.extend(data.mtl_files);
    ctx.geometry.meshes.push(data.mesh);
    LoadedMesh {
        mesh: ctx.geometry.meshes.len() as u32 - 1,
        groups: data.groups,
        mtl,
        painted,
    }
}

/// Scene material of each slot; unknown and two-sided override keys are
/// problems.
fn resolve(
    ctx: &mut BuildContext,
    path: &str,
    l: &LoadedMesh,
    material: Option<&str>,
    overrides: &BTreeMap<String, String>,
    null: bool,
) -> Vec<u32> {
    let mtl_names: Vec<Option<String>> = l
        .groups
        .iter()
        .map(|g| g.material.and_then(|m| ctx.mtl.name(l.mtl[m])))
        .collect();
    let parts: Vec<(&str, Option<&str>)> = l
        .groups
        .iter()
        .zip(&mtl_names)
        .map(|(g, m)| (g.name.as_str(), m.as_deref()))
        .collect();
    for key in overrides.keys() {
        if let Some(p) = key_problem(&format!("{path}.materials.{key}"), key, &parts) {
            ctx.problems.push(p);
        }
    }
    let mut keys: Vec<(Key, &String)> = overrides.iter().map(|(k, m)| (Key::of(k), m)).collect();
    keys.sort_by_key(|(k, _)| k.rank());
    l.groups
        .iter()
        .zip(&mtl_names)
        .map(|(g, mtl_name)| {
            let scene = |n: &str| ctx.material_index.get(n).copied();
            let by_name = keys
                .iter()
                .find(|(k, _)| k.selects(&g.name, mtl_name.as_deref()))
                .map(|(_, m)| m.as_str());
            if let Some(m) = by_name.and_then(&scene).or_else(|| material.and_then(&scene)) {
                return m;
            }
            if let Some(m) = g.material {
                return l.mtl[m];
            }
            grey(ctx, path, &g.name, null, l.painted)
        })
        .collect()
}

/// The grey default for a group that has no material from anywhere, with
/// a note the first time a shaded (not `null`) group takes it; on a mesh
/// with vertex colours, a Lambert of those colours (a scan or a painted
/// model shows as it was painted), without a note.
fn grey(ctx: &mut BuildContext, path: &str, group: &str, null: bool, painted: bool) -> u32 {
    if painted {
        if let Some(g) = ctx.mesh_state.painted {
            return g;
        }
        let g = ctx.mtl.push(Material::Lambert(LambertMaterial {
            albedo: ColorTex::Vertex {
                channel: crate::materials::Channel::All,
                factor: Rgb::ONE,
            },
        }));
        ctx.mesh_state.painted = Some(g);
        return g;
    }
    if !null && !ctx.mesh_state.grey_noted {
        ctx.mesh_state.grey_noted = true;
        ctx.notes.push(format!(
            "{path}: OBJ group `{group}` has no material and the scene gives none; using grey Lambert (0.5)"
        ));
    }
    if let Some(g) = ctx.mesh_state.grey {
        return g;
    }
    let g = ctx.mtl.push(Material::Lambert(LambertMaterial {
        albedo: ColorTex::Const(Rgb::splat(0.5)),
    }));
    ctx.mesh_state.grey = Some(g);
    g
}

/// Transforms positions and normals of `data` into world space. A mirroring
/// transform reverses the winding, so it is reversed back: the
/// counter-clockwise front (where an emissive mesh emits) stays outside.
fn bake(data: &mut ObjData, m: Mat4) {
    if m.determinant() < 0.0 {
        for t in &mut data.mesh.indices {
            t.swap(1, 2);
        }
    }
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
    // Tangents lie in the surface: carried as vectors; a mirror turns
    // their handedness (see `Instance::tangent`).
    let w = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
    for t in &mut data.mesh.tangents {
        *t = m.transform_vector3(t.truncate()).extend(w * t.w);
    }
}
