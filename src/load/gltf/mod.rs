//! The `Gltf` object: a glTF 2.0 asset's meshes placed by its node tree,
//! with its materials mapped (`material.rs`) unless the scene replaces
//! them by name.
//!
//! ```text
//! Gltf(file: "helmet/FlightHelmet.gltf", materials: { "LensesMat": "my_glass" },
//!      transform: [Scale((2, 2, 2))])
//! ```
//!
//! Steps: `document.rs` reads the file and its buffers (fenced, size
//! capped), `nodes.rs` flattens the chosen scene's node tree, `primitive.rs`
//! builds each mesh used once (its primitives are the mesh's material
//! slots), `punctual.rs` converts its `KHR_lights_punctual` lights, and
//! this file places one instance per node and the lights; `camera.rs`
//! makes one of its cameras the scene's when the scene asks. What the
//! asset has and ronray does not render (cameras the scene does not take,
//! an animation not chosen) is reported in notes, never
//! silently dropped; a required extension ronray does not know is an error naming it
//! (the `gltf` crate's validation).

pub mod accessor;
pub mod animation;
pub mod camera;
pub mod document;
pub mod material;
pub mod nodes;
pub mod primitive;
pub mod punctual;
pub mod skin;

use super::build_context::BuildContext;
use super::mtl::MtlMaterials;
use crate::desc::ObjectDesc;
use crate::diagnostic::Problem;
use crate::geometry::{Instance, Mesh, NO_LIGHT, Shape};
use glam::{Affine3A, Mat4};
use material::Mapped;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// Vertices an asset's meshes may hold beyond each mesh's first build,
/// 2²⁵: a mesh is built again per skin and set of morph weights that poses
/// it, and a small file can place one large mesh under many poses (one
/// build of each mesh is bounded by the file's size).
pub const MAX_POSED_COPIES: usize = 1 << 25;

/// An asset imported into meshes and placements, before it joins a scene.
pub struct Imported {
    /// Each mesh used, with the mapped material of each of its slots.
    pub meshes: Vec<ImportedMesh>,
    /// (index into `meshes`, asset-space transform, and the transform's
    /// keys over the shutter when an animation moves it), one per placing
    /// node.
    pub placements: Vec<(usize, Mat4, Option<Keys>)>,
    /// Every file read.
    pub files: Vec<std::path::PathBuf>,
    /// The chosen scene's `KHR_lights_punctual` lights, in the pose drawn.
    pub lights: Vec<punctual::ImportedLight>,
    /// How many cameras the file holds (the scene's `camera` may take one:
    /// `camera.rs`).
    pub cameras: usize,
}

/// An asset-space transform at times in frames over the shutter, for a
/// part an animation moves rigidly while the shutter is open.
pub type Keys = Vec<(f32, Mat4)>;

/// A mesh, the mapped material of each of its slots and each slot's
/// material name in the asset.
pub type ImportedMesh = (Mesh, Vec<Mapped>, Vec<Option<String>>);

/// The pose an asset is built in: its rest pose, or one of its
/// animations at a time.
#[derive(Clone, Copy, Debug, Default)]
pub struct Pose<'a> {
    /// The animation, by name or `#k`; `None`: the rest pose.
    pub animation: Option<&'a str>,
    /// Seconds into the animation.
    pub time: f32,
    /// Wrap the time at the animation's length.
    pub repeat: bool,
    /// The shutter's opening, in frames.
    pub open: f32,
    /// Further (frames, seconds into the animation) over the open shutter
    /// the rigid parts are posed at, for motion blur; empty when the
    /// shutter is closed.
    pub blur: &'a [(f32, f32)],
}

/// Why an asset was not imported: the file (any problem reading or
/// building it) or the animation the scene names.
#[derive(Debug)]
pub enum ImportError {
    /// The file, its buffers, nodes, meshes or skins.
    File(String),
    /// The scene's `animation` names none the asset has.
    Animation(String),
}

impl From<String> for ImportError {
    fn from(e: String) -> Self {
        ImportError::File(e)
    }
}

/// Imports `path` (reading within `root` when given) in `pose`, mapping
/// materials into `mtl`.
pub(crate) fn import(
    path: &Path,
    scene: Option<u32>,
    root: Option<&Path>,
    pose: Pose,
    mtl: &mut MtlMaterials,
    notes: &mut Vec<String>,
) -> Result<Imported, ImportError> {
    import_bounded(path, scene, root, pose, mtl, notes, MAX_POSED_COPIES)
}

/// [`import`] with `max_copies` in place of [`MAX_POSED_COPIES`] (tests).
fn import_bounded(
    path: &Path,
    scene: Option<u32>,
    root: Option<&Path>,
    pose: Pose,
    mtl: &mut MtlMaterials,
    notes: &mut Vec<String>,
    max_copies: usize,
) -> Result<Imported, ImportError> {
    let asset = document::read(path, root)?;
    let document::Asset {
        doc,
        buffers,
        files: mut reader,
    } = asset;
    let label = path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    );
    report_unrendered(&doc, &label, pose.animation.is_some(), notes);
    let chosen = match pose.animation {
        Some(a) => Some(animation::find(&doc, a).map_err(ImportError::Animation)?),
        None => None,
    };
    let read = chosen
        .map(|k| animation::Animation::read(&doc, &buffers, k))
        .transpose()?;
    let posed = animation::pose(&doc, read.as_ref(), pose.time, pose.repeat)?;
    let locals = &posed.locals;
    let nodes::Walk {
        meshes: placements,
        lights: light_nodes,
        ..
    } = nodes::walk(&doc, scene, locals)?;
    let lights = punctual_lights(&doc, &light_nodes, &label, notes)?;
    let keys = motion_keys(&doc, scene, read.as_ref(), pose, &placements)?;
    // Joints may sit anywhere in the node tree: every node's world
    // transform, only when something is skinned.
    let worlds = if placements.iter().any(|p| p.skin.is_some()) {
        nodes::worlds(&doc, locals)?
    } else {
        Vec::new()
    };
    // Each mesh once per skin and per set of morph weights reshaping it:
    // (mesh, skin, weights' bits) → index in `out.meshes`.
    type Key = (usize, Option<usize>, Option<Vec<u32>>);
    let mut built: HashMap<Key, usize> = HashMap::new();
    let (mut first_build, mut copies) = (std::collections::HashSet::new(), 0usize);
    let mut out = Imported {
        meshes: Vec::new(),
        placements: Vec::new(),
        files: Vec::new(),
        lights,
        cameras: doc.cameras().count(),
    };
    let mut images = material::Images::default();
    let mut by_material: HashMap<Option<usize>, Mapped> = HashMap::new();
    for (i, p) in placements.iter().enumerate() {
        // A rigid part scaled to nothing at the opening (an animation's
        // way to hide it) and not moving is not in the picture.
        if p.skin.is_none() && keys[i].is_none() && p.world_from_mesh.determinant().abs() < 1e-30 {
            continue;
        }
        // Morph weights: the node's (posed), else the mesh's; none when
        // all are zero (the base shape).
        let weights: Option<Vec<f32>> = posed
            .weights
            .get(p.node)
            .cloned()
            .flatten()
            .or_else(|| {
                doc.meshes()
                    .nth(p.mesh)
                    .and_then(|m| m.weights())
                    .map(<[f32]>::to_vec)
            })
            .filter(|w| w.iter().any(|&x| x != 0.0));
        // A skinned mesh moves its vertices and ignores its node's
        // transform, so every node placing the same mesh with the same
        // skin (and weights) places the same triangles.
        let key = (
            p.mesh,
            p.skin,
            weights.as_ref().map(|w| w.iter().map(|x| x.to_bits()).collect()),
        );
        let placed = if p.skin.is_some() {
            Mat4::IDENTITY
        } else {
            p.world_from_mesh
        };
        if let Some(&k) = built.get(&key) {
            out.placements.push((k, placed, keys[i].clone()));
            continue;
        }
        let mut source = material::Source {
            buffers: &buffers,
            files: &mut reader,
        };
        let mut sink = material::Sink {
            mtl: &mut *mtl,
            notes: &mut *notes,
            label: &label,
        };
        let mut names = Vec::new();
        let mut mesh_notes = Vec::new();
        let mut painted = Vec::new();
        let result = {
            let mut map = |m: Option<gltf::Material>| {
                names.push(m.as_ref().and_then(|m| m.name().map(str::to_string)));
                let key = m.as_ref().and_then(gltf::Material::index);
                if let Some(done) = by_material.get(&key) {
                    return *done;
                }
                let mapped = material::map(&mut source, &mut images, &mut sink, m);
                by_material.insert(key, mapped);
                mapped
            };
            primitive::build(
                &doc,
                &buffers,
                p.mesh,
                weights.as_deref(),
                p.skin.is_some(),
                &mut map,
                &mut painted,
                &mut mesh_notes,
            )
        };
        for m in painted.drain(..) {
            sink.mtl.paint(m);
        }
        notes.extend(mesh_notes.into_iter().map(|n| format!("{label}: {n}")));
        let (mut mesh, slots, influences) = result?;
        if let (Some(s), Some(inf)) = (p.skin, influences) {
            // Into the asset's space: `placed` is the identity.
            skin::deform(&doc, &buffers, s, &worlds, &mut mesh, &inf, p.world_from_mesh)
                .map_err(|e| format!("nodes[{}]: {e}", p.node))?;
        }
        // Skins and morph weights build a mesh again per pose, which a
        // file can multiply past its own size: the copies are bounded.
        if !first_build.insert(p.mesh) {
            copies = copies.saturating_add(mesh.positions.len());
            if copies > max_copies {
                return Err(ImportError::File(format!(
                    "the asset's skins and morph weights build its meshes again past \
                     {max_copies} vertices (a mesh is built once per skin and set of \
                     weights); MAX_POSED_COPIES in src/load/gltf/mod.rs is the limit"
                )));
            }
        }
        out.meshes.push((mesh, slots, names));
        let k = out.meshes.len() - 1;
        built.insert(key, k);
        out.placements.push((k, placed, keys[i].clone()));
    }
    out.files = reader.files;
    let mut out = merge_single_placements(out);
    for (mesh, _, _) in &mut out.meshes {
        mesh.prepare();
    }
    Ok(out)
}

/// The meshes placed once each and by the same transform, with the same
/// vertex attributes, joined into one mesh (slots and their materials in
/// order, [`Mesh::append`]) under one placement: one BVH over all their
/// triangles instead of one instance each. An asset's parts overlap (the
/// FlightHelmet's six meshes share one volume), and a ray entered every
/// part's tree whose box it crossed: 12% more samples per second on the
/// helmet with one tree (docs/benchmarks.md). A mesh placed by several
/// nodes stays one shared mesh with an instance per node. Nothing is
/// transformed, so every hit is shaded exactly as before; only the order
/// in which the tree meets equally distant triangles can differ.
fn merge_single_placements(imported: Imported) -> Imported {
    let Imported {
        meshes,
        placements,
        files,
        lights,
        cameras,
    } = imported;
    let mut uses = vec![0usize; meshes.len()];
    for (k, _, _) in &placements {
        uses[*k] += 1;
    }
    let mut meshes: Vec<Option<ImportedMesh>> = meshes.into_iter().map(Some).collect();
    let mut out = Imported {
        meshes: Vec::new(),
        placements: Vec::new(),
        files,
        lights,
        cameras,
    };
    // The open group of each transform (bit for bit) and set of vertex
    // attributes: its mesh's index in `out`.
    type Key = ([u32; 16], [bool; 4]);
    let mut groups: HashMap<Key, usize> = HashMap::new();
    let mut renumbered: HashMap<usize, usize> = HashMap::new();
    for (k, world, keys) in placements {
        let Some(entry) = meshes[k].take() else {
            // Placed before: its mesh is out already.
            out.placements.push((renumbered[&k], world, keys));
            continue;
        };
        let (mesh, slots, _) = &entry;
        // A moving part keeps its own instance.
        let joinable = uses[k] == 1 && slots.len() == mesh.slot_count as usize && keys.is_none();
        let key: Key = (world.to_cols_array().map(f32::to_bits), mesh.attributes());
        // Joined while the sum stays well inside the indices' and the
        // tree's limits; past them the part opens a new group.
        let into = groups.get(&key).copied().filter(|&g| {
            let target = &out.meshes[g].0;
            joinable
                && target.positions.len() + mesh.positions.len() < u32::MAX as usize / 2
                && target.triangle_count() + mesh.triangle_count() < crate::accel::wide::MAX_PRIMS / 2
        });
        match into {
            Some(g) => {
                let (mesh, slots, names) = entry;
                let target = &mut out.meshes[g];
                target.0.append(mesh);
                target.1.extend(slots);
                target.2.extend(names);
                renumbered.insert(k, g);
            }
            None => {
                let at = out.meshes.len();
                out.meshes.push(entry);
                out.placements.push((at, world, keys));
                renumbered.insert(k, at);
                if joinable {
                    groups.insert(key, at);
                }
            }
        }
    }
    out
}

/// Sub-steps of the open shutter at which an animated asset's rigid parts
/// are posed: their motion is the keyed-instance motion through these
/// poses (`anim::TransformTrack`, linear, rotations by slerp), close to
/// the animation's own path for the turns a frame holds.
pub const BLUR_STEPS: usize = 8;

/// Per placement, its asset-space transform at the shutter's opening and
/// at each time of `pose.blur`, when an animation moves it rigidly (not
/// skinned) over the shutter and every pose is a regular transform of one
/// handedness (a key of zero scale, or a mirror between two, would pass
/// through a flat placement); else `None`, and the part holds its opening
/// pose.
fn motion_keys(
    doc: &gltf::Document,
    scene: Option<u32>,
    animation: Option<&animation::Animation>,
    pose: Pose,
    placements: &[nodes::Placement],
) -> Result<Vec<Option<Keys>>, String> {
    let mut keys = vec![None; placements.len()];
    if animation.is_none() || pose.blur.is_empty() {
        return Ok(keys);
    }
    let mut all: Vec<Keys> = placements
        .iter()
        .map(|p| vec![(pose.open, p.world_from_mesh)])
        .collect();
    for &(frame, secs) in pose.blur {
        let later = animation::pose(doc, animation, secs, pose.repeat)?;
        // The same tree, so the same placements in the same order.
        for (k, p) in nodes::flatten(doc, scene, &later.locals)?.iter().enumerate() {
            if let Some(a) = all.get_mut(k) {
                a.push((frame, p.world_from_mesh));
            }
        }
    }
    for ((slot, a), p) in keys.iter_mut().zip(all).zip(placements) {
        let det = |m: &Mat4| m.determinant();
        let regular = a.iter().all(|(_, m)| m.is_finite() && det(m).abs() >= 1e-30)
            && a.iter().all(|(_, m)| (det(m) > 0.0) == (det(&a[0].1) > 0.0));
        let moves = a.windows(2).any(|w| w[0].1 != w[1].1);
        if p.skin.is_none() && regular && moves && a.len() == pose.blur.len() + 1 {
            *slot = Some(a);
        }
    }
    Ok(keys)
}

/// Notes for what the asset carries and ronray does not render, and for
/// animations left unplayed (`posed`: the scene picked one).
/// The glTF extensions the importer reads: the `gltf` crate's features
/// enabled in Cargo.toml, and `KHR_mesh_quantization` (read by
/// `accessor.rs`). docs/gltf.md says how much of each.
const READ_EXTENSIONS: &[&str] = &[
    "KHR_texture_transform",
    "KHR_materials_ior",
    "KHR_materials_emissive_strength",
    "KHR_lights_punctual",
    "KHR_materials_transmission",
    "KHR_materials_volume",
    "KHR_mesh_quantization",
];

fn report_unrendered(doc: &gltf::Document, label: &str, posed: bool, notes: &mut Vec<String>) {
    // An extension the asset uses but does not require is one a viewer may
    // ignore: the asset renders without it, and the note says which (a
    // clear-coated car paint drawn as plain paint would otherwise be a
    // silent difference).
    let unread: Vec<&str> = doc
        .extensions_used()
        .filter(|e| !READ_EXTENSIONS.contains(e))
        .collect();
    if !unread.is_empty() {
        notes.push(format!(
            "{label}: extension{} {} not read: the asset renders without {} (docs/gltf.md lists what is read)",
            if unread.len() == 1 { "" } else { "s" },
            unread.join(", "),
            if unread.len() == 1 { "it" } else { "them" },
        ));
    }
    let animations = doc.animations().count();
    if animations > 0 && !posed {
        let first = doc
            .animations()
            .next()
            .map(|a| a.name().map_or("#0".to_string(), str::to_string))
            .unwrap_or_default();
        notes.push(format!(
            "{label}: {animations} animation(s) ({}), none played: the asset is in its rest pose; \
             pose it with `animation: \"{first}\"`",
            animation::names(doc)
        ));
    }
}

/// The lights the walk placed, converted (`punctual.rs`), with a note
/// saying how many and in what units, and one for `range`s ignored.
fn punctual_lights(
    doc: &gltf::Document,
    placed: &[nodes::LightPlacement],
    label: &str,
    notes: &mut Vec<String>,
) -> Result<Vec<punctual::ImportedLight>, String> {
    let Some(all) = doc.lights() else {
        return Ok(Vec::new());
    };
    let all: Vec<gltf::khr_lights_punctual::Light> = all.collect();
    let mut out = Vec::with_capacity(placed.len());
    let mut ranged = 0;
    for p in placed {
        let light = all.get(p.light).ok_or_else(|| {
            format!(
                "nodes[{}] names KHR_lights_punctual light {}, which does not exist",
                p.node, p.light
            )
        })?;
        ranged += usize::from(light.range().is_some());
        out.push(punctual::import(light, p.node, p.world)?);
    }
    if !out.is_empty() {
        notes.push(format!(
            "{label}: {} KHR_lights_punctual light(s) placed, their candela and lux over 683 lm/W \
             (W/sr and W/m², as Blender's importer)",
            out.len()
        ));
    }
    if ranged > 0 {
        notes.push(format!(
            "{label}: {ranged} light(s) give a `range`, not applied: light falls off with the inverse square"
        ));
    }
    Ok(out)
}

/// Adds `Gltf` object `i` to the scene.
pub(super) fn add(ctx: &mut BuildContext, i: usize, o: &ObjectDesc, world_from_object: Mat4) {
    let ObjectDesc::Gltf {
        file,
        scene,
        materials,
        animation,
        repeat,
        ..
    } = o
    else {
        return;
    };
    let at = format!("objects[{i}]");
    let path = ctx.base.join(file);
    let root = ctx.mtl.root().map(Path::to_path_buf);
    let (open, close) = super::animation::shutter(ctx.desc);
    let blur: Vec<(f32, f32)> = if animation.is_some() && close > open {
        ctx.notes.push(format!(
            "{at}: skinned and morphed parts keep the pose of the shutter's opening (no \
             deformation blur); parts the animation moves rigidly are motion-blurred"
        ));
        (1..=BLUR_STEPS)
            .map(|k| {
                let t = open + (close - open) * k as f32 / BLUR_STEPS as f32;
                (t, animation_seconds(ctx.desc, t))
            })
            .collect()
    } else {
        Vec::new()
    };
    let pose = Pose {
        animation: animation.as_deref(),
        time: animation_seconds(ctx.desc, open),
        repeat: *repeat,
        open,
        blur: &blur,
    };
    // The asset's cameras are not the scene's unless it says so.
    let taken = ctx.desc.camera.gltf.as_ref().is_some_and(|g| g.file == *file);
    let imported = match import(&path, *scene, root.as_deref(), pose, &mut ctx.mtl, &mut ctx.notes) {
        Ok(x) => x,
        Err(ImportError::File(e)) => {
            let help = "check the asset with a glTF validator; ronray reads glTF 2.0 `.gltf` and `.glb`";
            ctx.problems
                .push(Problem::new(format!("{at}.file"), e).help(help));
            return;
        }
        Err(ImportError::Animation(e)) => {
            ctx.problems.push(
                Problem::new(format!("{at}.animation"), e)
                    .help("name one of the asset's animations, or leave `animation` out for the rest pose"),
            );
            return;
        }
    };
    if imported.cameras > 0 && !taken {
        ctx.notes.push(format!(
            "{at}: the asset's {} camera(s) are not used (the scene's `camera` is); look through one \
             with `camera: (gltf: (file: {file:?}))`",
            imported.cameras
        ));
    }
    ctx.mtl_files.extend(imported.files.iter().cloned());
    let known: Vec<&str> = imported
        .meshes
        .iter()
        .flat_map(|(_, _, names)| names.iter().flatten().map(String::as_str))
        .collect();
    check_overrides(ctx, &at, materials, &known);
    let first_mesh = ctx.geometry.meshes.len();
    let mut slot_materials = Vec::new();
    for (mesh, slots, names) in imported.meshes {
        let resolved: Vec<(u32, Option<(crate::lights::Emission, bool)>)> = slots
            .iter()
            .zip(&names)
            .map(|(mapped, name)| {
                let chosen = name
                    .as_deref()
                    .and_then(|n| materials.get(n))
                    .or(o.material().map(str::to_string).as_ref())
                    .and_then(|n| ctx.material_index.get(n.as_str()).copied());
                match chosen {
                    Some(m) => (m, None),
                    None => (
                        mapped.index,
                        mapped.emission.map(|e| {
                            let emission = match mapped.emission_map {
                                Some(look) => ctx.mtl.emission_lookup(look, e),
                                None => crate::lights::Emission::constant(e),
                            };
                            (emission, mapped.double_sided)
                        }),
                    ),
                }
            })
            .collect();
        ctx.geometry.meshes.push(mesh);
        slot_materials.push(resolved);
    }
    for (k, asset_from_mesh, keys) in imported.placements {
        let world = world_from_object * asset_from_mesh;
        let mesh = (first_mesh + k) as u32;
        let slots = &slot_materials[k];
        let mut instance = Instance::new(
            mesh,
            Affine3A::from_mat4(world),
            slots.iter().map(|s| s.0).collect(),
        );
        if let Some(keys) = keys {
            // Moving while the shutter is open, as a keyed `Instance`.
            let keys: Keys = keys.iter().map(|&(t, m)| (t, world_from_object * m)).collect();
            let track = crate::anim::TransformTrack::new(&keys, crate::anim::Interpolation::Linear);
            if track.moves_between(open, close) {
                instance =
                    instance.with_motion(crate::geometry::moving::InstanceMotion::new(track, (open, close)));
            }
        }
        if slots.iter().any(|s| s.1.is_some()) {
            instance.lights = slots
                .iter()
                .enumerate()
                .map(|(slot, s)| {
                    s.1.as_ref().map_or(NO_LIGHT, |(emission, two_sided)| {
                        super::mesh::mesh_light(ctx, &instance, slot, emission.clone(), *two_sided)
                    })
                })
                .collect();
        }
        ctx.triangles += ctx.geometry.meshes[mesh as usize].triangle_count();
        let id = ctx.geometry.instances.len() as u32;
        ctx.geometry.instances.push(instance);
        ctx.shapes.push(Shape::Instance(id));
    }
    for light in &imported.lights {
        place_light(ctx, &at, light, world_from_object);
    }
}

/// Adds an asset's light, placed by its node and the object's transform,
/// to the scene's lights (at the shutter's opening: lights are not
/// motion-blurred). A spot or directional light whose node is scaled to
/// nothing has no direction and is left out, with a note.
fn place_light(ctx: &mut BuildContext, at: &str, light: &punctual::ImportedLight, world_from_object: Mat4) {
    use crate::lights::{DirectionalLight, Light, PointLight, SpotLight};
    use punctual::PunctualKind;
    let (p, d) = light.placed(world_from_object);
    let emitted = crate::math::Rgb::from(light.emitted);
    let built = match (light.kind, d) {
        (PunctualKind::Point, _) => Light::Point(PointLight {
            position: p,
            intensity: emitted,
        }),
        (
            PunctualKind::Spot {
                cone_degrees,
                falloff_degrees,
            },
            Some(d),
        ) => Light::Spot(SpotLight::new(p, d, emitted, cone_degrees, falloff_degrees)),
        (PunctualKind::Directional, Some(d)) => Light::Directional(DirectionalLight::new(d, emitted)),
        (PunctualKind::Spot { .. } | PunctualKind::Directional, None) => {
            ctx.notes.push(format!(
                "{at}: the light of nodes[{}] has no direction (its node is scaled to nothing): left out",
                light.node
            ));
            return;
        }
    };
    // As the scene's own positions (`validate::MAX_COORD`): beyond it,
    // squared distances overflow f32.
    let limit = super::validate::MAX_COORD;
    if !(p.is_finite() && p.abs().max_element() <= limit) {
        ctx.notes.push(format!(
            "{at}: the light of nodes[{}] is placed at {p}, beyond ±{limit:e} (the scene's coordinate \
             limit): left out",
            light.node
        ));
        return;
    }
    ctx.lights.push(built);
}

/// Seconds into a glTF animation at time `t` (frames): the scene's first
/// frame is the animation's start and each frame `1/fps` s later. The
/// asset is posed at the shutter's opening (`frame + shutter.0`), the time
/// keyed instances are built at. A scene without `animation` counts from
/// frame 0 at 24 frames per second.
pub(super) fn animation_seconds(desc: &crate::desc::SceneDesc, t: f32) -> f32 {
    let (first, fps) = desc.animation.as_ref().map_or((0, 24.0), |a| (a.frames.0, a.fps));
    let fps = if fps > 0.0 && fps.is_finite() { fps } else { 24.0 };
    (t - first as f32) / fps
}

/// Every key of `materials` must name a material of the asset.
fn check_overrides(ctx: &mut BuildContext, at: &str, materials: &BTreeMap<String, String>, known: &[&str]) {
    for key in materials.keys() {
        if !known.contains(&key.as_str()) {
            let mut names: Vec<&str> = known.to_vec();
            names.sort_unstable();
            names.dedup();
            ctx.problems.push(
                Problem::new(
                    format!("{at}.materials.{key}"),
                    format!("the asset has no material named `{key}`"),
                )
                .help(format!("its materials are: {}", names.join(", "))),
            );
        }
    }
}

/// The scene through whose camera [`fuzz_import`] looks at its asset.
const FUZZ_LOOKING: &str = r##"Scene(camera: (gltf: (file: "fuzz.glb"), shutter: (0, 0.5)),
    objects: [Gltf(file: "fuzz.glb", animation: "#0", repeat: true)])"##;

fn fuzz_scene() -> Result<crate::desc::SceneDesc, ron::error::SpannedError> {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(FUZZ_LOOKING)
}

/// The fuzz target's entry: `data` as a `.glb` or `.gltf` file in a
/// temporary folder, its first camera taken as a scene's, and imported
/// with every check, posed by its first animation (0.37 s in, wrapped)
/// when it has one, else at rest; never panics.
pub fn fuzz_import(data: &[u8]) -> bool {
    let Ok(dir) = tempfile::tempdir() else {
        return false;
    };
    let path = dir.path().join("fuzz.glb");
    if std::fs::write(&path, data).is_err() {
        return false;
    }
    let mut mtl = MtlMaterials::new(0, 0, Some(dir.path()));
    let mut notes = Vec::new();
    // Half a frame of shutter at 24 fps: the motion keys too.
    let blur: Vec<(f32, f32)> = (1..=2)
        .map(|k| (k as f32 * 0.25, 0.37 + k as f32 * 0.25 / 24.0))
        .collect();
    let posed = Pose {
        animation: Some("#0"),
        time: 0.37,
        repeat: true,
        open: 0.0,
        blur: &blur,
    };
    // Its first camera as a scene's, animated over an open shutter.
    if let Ok(desc) = fuzz_scene() {
        let _ = camera::resolve(&desc, dir.path(), Some(dir.path()), &mut notes);
    }
    match import(&path, None, Some(dir.path()), posed, &mut mtl, &mut notes) {
        Err(ImportError::Animation(_)) => import(
            &path,
            None,
            Some(dir.path()),
            Pose::default(),
            &mut mtl,
            &mut notes,
        )
        .is_ok(),
        r => r.is_ok(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fuzz entry's scene reads, so the camera step does run.
    #[test]
    fn the_fuzz_entry_looks_through_the_asset_camera() {
        let desc = fuzz_scene().expect("reads");
        assert!(desc.camera.gltf.is_some() && desc.camera.shutter.is_some());
    }

    /// A triangle with one morph target placed by three nodes, each with
    /// its own weight: three builds, two of them copies of six vertices in
    /// all. Within a limit of six they import; past five they are refused
    /// with the limit's name, not allocated.
    #[test]
    fn posed_copies_are_bounded() {
        let floats: Vec<u8> = [
            0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
        let b64 = |d: &[u8]| -> String {
            const T: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
            d.chunks(3)
                .flat_map(|c| {
                    let n = c
                        .iter()
                        .enumerate()
                        .fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
                    (0..4).map(move |k| {
                        if k <= c.len() {
                            T[(n >> (18 - 6 * k)) as usize & 63] as char
                        } else {
                            '='
                        }
                    })
                })
                .collect()
        };
        let doc = format!(
            r#"{{"asset": {{"version": "2.0"}},
               "buffers": [{{"byteLength": 72, "uri": "data:application/octet-stream;base64,{}"}}],
               "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 36}}],
               "accessors": [
                 {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                 {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [0, 0, 1]}}],
               "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "targets": [{{"POSITION": 1}}]}}]}}],
               "nodes": [{{"mesh": 0, "weights": [0.1]}}, {{"mesh": 0, "weights": [0.2]}}, {{"mesh": 0, "weights": [0.3]}}],
               "scenes": [{{"nodes": [0, 1, 2]}}]}}"#,
            b64(&floats)
        );
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("a.gltf");
        std::fs::write(&path, doc).expect("write");
        let run = |limit| {
            let mut mtl = MtlMaterials::new(0, 0, Some(dir.path()));
            import_bounded(
                &path,
                None,
                Some(dir.path()),
                Pose::default(),
                &mut mtl,
                &mut Vec::new(),
                limit,
            )
        };
        let ok = run(6).unwrap_or_else(|e| panic!("within the limit: {e:?}"));
        // One build per weight (then joined: same transform, same attributes).
        let triangles: usize = ok.meshes.iter().map(|m| m.0.triangle_count()).sum();
        assert_eq!(triangles, 3, "one triangle per weight");
        match run(5) {
            Err(ImportError::File(e)) => assert!(e.contains("MAX_POSED_COPIES"), "{e}"),
            other => panic!("expected the limit, got {:?}", other.map(|i| i.meshes.len())),
        }
    }
}
