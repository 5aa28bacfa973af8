//! Desc → runtime: names become indices, defaults are filled, meshes are
//! loaded and transformed, the BVH is built. Each kind of thing builds itself
//! in its own file (`material.rs`, `light.rs`, `object.rs`, `mesh.rs`,
//! `sdf/`, `view.rs`) into one `BuildContext`; this file runs them in
//! order and assembles the [`Scene`]. Problems found here (an OBJ that does
//! not parse) are reported like validation problems.

use super::build_context::BuildContext;
use super::mesh_state::MeshState;
use super::mtl::MtlMaterials;
use super::validate::{MAX_COORD, MAX_RADIANCE, RADIANCE_HELP};
use crate::accel::{Aabb, Leaves, WideBvh};
use crate::desc::{ColorDesc, IntegratorDesc, LightDesc, LightSelectionDesc, SceneDesc};
use crate::diagnostic::Problem;
use crate::geometry::obj::ObjData;
use crate::geometry::shape_lanes::ShapeLanes;
use crate::geometry::{Geometry, Shape};
use crate::lights::caustic::{self, CausticEmitters};
use crate::lights::{Emission, Light, LightPicker, Selection};
use crate::materials::Bxdf as _;
use crate::materials::{Emitter, Material};
use crate::scene::Scene;
use crate::view::View;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// What building cost, for `--stats` and the render summary.
#[derive(Clone, Debug, Default)]
pub struct BuildStats {
    /// Time to build the top-level (scene) BVH.
    pub bvh_time: Duration,
    /// Time for everything before it: materials and textures, lights, objects, OBJ
    /// files read and each mesh's own BVH built.
    pub load_time: Duration,
    /// Triangles over all placed meshes (instances counted each time).
    pub triangles: usize,
    /// Texture files and environment maps read while building (watch mode
    /// re-reads on change).
    pub texture_files: Vec<PathBuf>,
    /// What OBJ files read beside themselves: their MTL files and the
    /// textures those name (watch mode re-reads on change; `validate -v`
    /// lists them).
    pub mesh_inputs: Vec<PathBuf>,
    /// Each OBJ file read, with its groups and the MTL material each wears
    /// (`validate -v`).
    pub obj_parts: Vec<(PathBuf, String)>,
    /// Distinct meshes held in memory.
    pub meshes: usize,
    /// Placements of those meshes (`Mesh` and `Instance` objects).
    pub instances: usize,
    /// Bytes of the meshes' BVHs and inline triangles (each mesh once).
    pub mesh_accel_bytes: usize,
    /// Time to read the environment map (zero without one).
    pub env_read_time: Duration,
    /// Time to build the environment's sampling tables.
    pub env_table_time: Duration,
    /// What the build repaired or defaulted (an OBJ group without a
    /// material, an MTL feature not supported), for the commands to show.
    pub notes: Vec<String>,
    /// Notes at a scene path (an image whose texels were repaired, at the
    /// parameter that read it), located in the files like warnings.
    pub located_notes: Vec<Problem>,
    /// The scene's camera as a glTF asset's camera filled it in
    /// (`camera.gltf`); `None` when the scene describes its own.
    pub camera: Option<crate::desc::CameraDesc>,
}

/// Most directional lights a scene may hold, its own and its glTF assets'
/// together: light selection weighs every one at every shading point (the
/// light tree holds lights with a position), so ten thousand would make a
/// render crawl. Real scenes have one to three.
pub const MAX_DIRECTIONAL_LIGHTS: usize = 64;

/// Builds a scene that has passed [`super::validate::validate`]. `base` is
/// the folder relative paths resolve against.
pub fn build(desc: &SceneDesc, base: &Path) -> Result<(Scene, View, BuildStats), Vec<Problem>> {
    build_with(desc, base, &crate::geometry::obj::load_obj_data)
}

/// As [`build`], reading OBJ files through `load_obj`, so that watch mode
/// can reuse meshes whose files did not change between reloads.
pub fn build_with(
    desc: &SceneDesc,
    base: &Path,
    load_obj: &dyn Fn(&Path) -> Result<ObjData, String>,
) -> Result<(Scene, View, BuildStats), Vec<Problem>> {
    build_in(desc, base, load_obj, None)
}

/// As [`build_with`], refusing the textures MTL files name outside `root`
/// (`--root`; the scene's own files were fenced by validation).
pub fn build_in(
    desc: &SceneDesc,
    base: &Path,
    load_obj: &dyn Fn(&Path) -> Result<ObjData, String>,
    root: Option<&Path>,
) -> Result<(Scene, View, BuildStats), Vec<Problem>> {
    let t0 = Instant::now();
    // A glTF asset's camera, read first: SDFs take their precision from it.
    let mut camera_notes = Vec::new();
    let (camera, camera_problem) = match super::gltf::camera::resolve(desc, base, root, &mut camera_notes) {
        Ok(c) => (c, None),
        Err(p) => (None, Some(p)),
    };
    let with_camera;
    let desc = match &camera {
        Some(c) => {
            with_camera = SceneDesc {
                camera: c.clone(),
                ..desc.clone()
            };
            &with_camera
        }
        None => desc,
    };
    let super::material::Materials {
        mut materials,
        mut surfaces,
        mut textures,
        index,
        files: texture_files,
        emissions,
        notes: located_notes,
    } = super::material::build_materials(&desc.materials, &textured_emissions(desc), base)?;
    let too_bright: Vec<Problem> = emissions
        .iter()
        .filter_map(|(path, tex)| too_bright(path, tex, &textures))
        .collect();
    if !too_bright.is_empty() {
        return Err(too_bright);
    }
    let emissions = emissions
        .into_iter()
        .map(|(path, tex)| (path, Emission::new(&tex, &textures)))
        .collect();
    let (media, media_index) = super::medium::build_media(desc, base)?;
    let emitter = materials.len() as u32;
    materials.push(Material::Emitter(Emitter));
    let mut ctx = BuildContext {
        desc,
        base,
        load_obj,
        material_index: index,
        emissions,
        emitter,
        mtl: MtlMaterials::new(materials.len() as u32, textures.len() as u32, root),
        lights: Vec::new(),
        environment: None,
        shapes: Vec::new(),
        unbounded: Vec::new(),
        object_ids: (Vec::new(), Vec::new()),
        geometry: Geometry::default(),
        mesh_state: MeshState::default(),
        normal_maps: surfaces.iter().any(|s| {
            matches!(
                s.normal,
                Some(crate::materials::surface::Perturb::NormalMap { .. })
            )
        }),
        triangles: 0,
        problems: camera_problem.into_iter().collect(),
        notes: camera_notes,
        env_times: Default::default(),
        light_files: Vec::new(),
        mtl_files: Vec::new(),
        obj_parts: Vec::new(),
    };
    // Object ids: 1 + i for `objects[i]`, then the area lights after them
    // (0 is "no surface" in the object-index layer).
    let first_light_id = desc.objects.len() as u32 + 1;
    for (i, l) in desc.lights.iter().enumerate() {
        super::light::build_light(&mut ctx, i, l);
        tag_object(&mut ctx, first_light_id.saturating_add(i as u32));
    }
    for (i, o) in desc.objects.iter().enumerate() {
        let (shapes, unbounded) = (ctx.shapes.len(), ctx.unbounded.len());
        super::object::build_object(&mut ctx, i, o);
        check_extent(&mut ctx, i, shapes, unbounded);
        tag_object(&mut ctx, i as u32 + 1);
    }
    let suns = ctx.lights.iter().filter(|l| l.as_directional().is_some()).count();
    if suns > MAX_DIRECTIONAL_LIGHTS {
        ctx.problems.push(
            Problem::new(
                "lights",
                format!(
                    "{suns} directional lights (the scene's and its glTF assets'), more than the limit of \
                     {MAX_DIRECTIONAL_LIGHTS}: every shading point weighs each one"
                ),
            )
            .help(
                "merge suns that shine the same way into one (their irradiances add); \
                 MAX_DIRECTIONAL_LIGHTS in src/load/build.rs is the limit",
            ),
        );
    }
    if !ctx.problems.is_empty() {
        return Err(ctx.problems);
    }
    // The emitter's surface, then the MTL materials' (cut-outs from `map_d`).
    surfaces.push(crate::materials::Surface::default());
    surfaces.extend(std::mem::take(&mut ctx.mtl.surfaces));
    let mut mesh_inputs = std::mem::take(&mut ctx.mtl_files);
    let mut mtl_textures: Vec<PathBuf> = ctx.mtl.files().cloned().collect();
    mtl_textures.sort();
    mesh_inputs.extend(mtl_textures);
    materials.extend(std::mem::take(&mut ctx.mtl.materials));
    textures.extend(std::mem::take(&mut ctx.mtl.textures));
    let load_time = t0.elapsed();

    let t1 = Instant::now();
    let (shapes, objects, bounded, bvh) = bvh_and_leaf_order(
        (ctx.shapes, ctx.object_ids.0),
        (ctx.unbounded, ctx.object_ids.1),
        &ctx.geometry,
    );
    let bvh_time = t1.elapsed();
    // The environment's power (for light selection) is its flux through the
    // scene's bounding disk.
    // So is a directional light's.
    let b = bvh.bounds();
    let r = 0.5 * (b.max - b.min).length();
    let scene_radius = if r.is_finite() && r > 0.0 { r } else { 1.0 };
    if let Some(Light::Environment(env)) = ctx.environment.map(|i| &mut ctx.lights[i as usize]) {
        env.scene_radius = scene_radius;
    }
    for l in &mut ctx.lights {
        if let Light::Directional(d) = l {
            d.scene_radius = scene_radius;
        }
    }

    let stats = BuildStats {
        bvh_time,
        load_time,
        triangles: ctx.triangles,
        texture_files: texture_files.into_iter().chain(ctx.light_files).collect(),
        mesh_inputs,
        obj_parts: ctx.obj_parts,
        meshes: ctx.geometry.meshes.len(),
        instances: ctx.geometry.instances.len(),
        mesh_accel_bytes: ctx.geometry.meshes.iter().map(|m| m.accel_bytes()).sum(),
        notes: ctx.notes,
        located_notes,
        env_read_time: ctx.env_times.0,
        env_table_time: ctx.env_times.1,
        camera,
    };
    let selection = match desc.integrator {
        IntegratorDesc::Path { light_selection, .. } => match light_selection {
            LightSelectionDesc::Power => Selection::Power,
            LightSelectionDesc::Uniform => Selection::Uniform,
            LightSelectionDesc::Tree => Selection::Tree,
        },
        _ => Selection::Power,
    };
    // The caustic light tracer matters where a perfect mirror or smooth glass
    // can focus a light (a material's delta-ness does not depend on its
    // textures).
    let delta: Vec<bool> = materials
        .iter()
        .map(|m| {
            m.bsdf(&crate::materials::TexPoint::uv(glam::Vec2::ZERO), &textures)
                .is_delta()
        })
        .collect();
    let is_delta = |m: u32| {
        through_blends(&surfaces, m, 0, &|m| {
            delta.get(m as usize).copied().unwrap_or(false)
        })
    };
    let targets = caustic::specular_targets(&shapes, &objects, &ctx.geometry, |s| {
        any_material(s, &ctx.geometry, is_delta)
    });
    let caustics = CausticEmitters::new(&ctx.lights, targets, bvh.bounds());
    // A hit fills in its vertex colour only for the materials that read it:
    // each surface says so for itself (a blend for its weight, each of its
    // two materials for their own parameters, met after the pick).
    debug_assert_eq!(surfaces.len(), materials.len());
    for (s, m) in surfaces.iter_mut().zip(&materials) {
        s.vertex_color = m.reads_vertex_color() || s.reads_vertex_color();
    }
    // Only scenes with a normal map, bump map, cut-out, blend or vertex
    // colours pay for them.
    if surfaces.iter().all(crate::materials::Surface::is_plain) {
        surfaces.clear();
    }
    // Which shapes a shadow ray may pass through; none in most scenes.
    let has_cutout = |m: u32| {
        through_blends(&surfaces, m, 0, &|m| {
            surfaces.get(m as usize).is_some_and(|s| s.cutout.is_some())
        })
    };
    let cut: Vec<bool> = if surfaces.iter().any(|s| s.cutout.is_some()) {
        shapes
            .iter()
            .map(|s| any_material(s, &ctx.geometry, has_cutout))
            .collect()
    } else {
        Vec::new()
    };
    let lanes = ShapeLanes::new(&shapes[..bounded as usize]);
    let absorption: Vec<Option<crate::math::Rgb>> = if materials
        .iter()
        .any(|m| m.interior().is_some_and(|s| s != crate::math::Rgb::ZERO))
    {
        materials.iter().map(Material::interior).collect()
    } else {
        Vec::new()
    };
    let mut scene = Scene {
        absorption,
        caustics,
        light_picker: LightPicker::new(&ctx.lights, selection),
        materials,
        surfaces,
        black: emitter,
        textures,
        lights: ctx.lights,
        environment: ctx.environment,
        shapes,
        objects,
        bounded,
        lanes,
        cut,
        geometry: ctx.geometry,
        bvh,
        media: None,
    };
    let ids = 1 + desc.objects.len() + desc.lights.len();
    scene.media = super::medium::scene_media(desc, media, &media_index, ids);
    if scene.media.is_some() {
        // The caustic light tracer knows nothing of media (see
        // `integrators::vol_path`).
        scene.caustics = None;
    }
    let view = super::view::build_view(desc, base);
    // Lights whose light paths would almost never reach the film leave
    // their caustics to the path tracer (a few hundred paths each).
    if let crate::integrators::Integrator::Path(p) = &view.integrator
        && p.light_trace_caustics
    {
        let film = (view.film.width, view.film.height);
        let chain = crate::integrators::caustic::max_chain(p.max_depth);
        crate::integrators::caustic_reach::keep_lights_that_reach(&mut scene, &view.camera, film, chain);
    }
    // What share of the sky the surfaces the camera sees are lit by
    // (light selection's weight for the sky; a few thousand rays).
    let aspect = view.film.width as f32 / view.film.height.max(1) as f32;
    let v = crate::integrators::sky_visibility::sky_visibility(&scene, &view.camera, aspect);
    scene.light_picker.set_sky_visibility(v);
    Ok((scene, view, stats))
}

/// Gives the shapes built since the last call the object id `id`.
fn tag_object(ctx: &mut BuildContext, id: u32) {
    let (bounded, unbounded) = &mut ctx.object_ids;
    bounded.resize(ctx.shapes.len(), id);
    unbounded.resize(ctx.unbounded.len(), id);
}

/// Object `i` (its shapes from `shapes` and `unbounded` on) must lie within
/// ±[`MAX_COORD`] once placed: a mesh scaled by 1e37 validates (its file is
/// not read by the checks) but its squared distances would overflow.
fn check_extent(ctx: &mut BuildContext, i: usize, shapes: usize, unbounded: usize) {
    let far = ctx.shapes[shapes..]
        .iter()
        .chain(&ctx.unbounded[unbounded..])
        .filter_map(|s| s.bounds(&ctx.geometry))
        .map(|b| b.min.abs().max(b.max.abs()).max_element())
        .find(|m| m.is_nan() || *m > MAX_COORD);
    if let Some(m) = far {
        ctx.problems.push(
            Problem::new(
                format!("objects[{i}]"),
                format!("the placed object reaches {m:e}, beyond ±{MAX_COORD:e}"),
            )
            .help("scene coordinates are 32-bit floats; scale the object or the scene down"),
        );
    }
}

/// Whether `pred` holds for material `m` or, if it is a blend, for either
/// material a hit on it may be shaded with (blends nest at most
/// `MAX_BLEND_DEPTH` deep; deeper is refused at load).
fn through_blends(
    surfaces: &[crate::materials::Surface],
    m: u32,
    depth: u32,
    pred: &impl Fn(u32) -> bool,
) -> bool {
    match surfaces.get(m as usize).and_then(|s| s.blend.as_ref()) {
        Some(b) if depth <= super::material::MAX_BLEND_DEPTH => {
            through_blends(surfaces, b.a, depth + 1, pred) || through_blends(surfaces, b.b, depth + 1, pred)
        }
        _ => pred(m),
    }
}

/// Whether `pred` holds for a material shape `s` is drawn with (any of a
/// mesh's, whose triangles take their materials from its instance).
fn any_material(s: &Shape, geometry: &Geometry, pred: impl Fn(u32) -> bool) -> bool {
    let instance = |i: u32| {
        geometry
            .instances
            .get(i as usize)
            .is_some_and(|x| x.materials.iter().any(|&m| pred(m)))
    };
    match s {
        Shape::Sphere(x) => pred(x.material),
        Shape::Quad(x) => pred(x.material),
        Shape::Plane(x) => pred(x.material),
        Shape::Sdf(i) => geometry.sdfs.get(*i as usize).is_some_and(|x| pred(x.material)),
        Shape::Instance(i) => instance(*i),
        Shape::Triangle(t) => instance(t.instance),
        Shape::MeshQuad(q) => instance(q.instance),
    }
}

/// The scene BVH over the bounded shapes, and every shape in the order the
/// scene keeps them: bounded ones in the BVH's leaf order (a leaf is a
/// contiguous run; shapes with empty bounds, never hit, drop out), then the
/// unbounded ones.
/// Each shape's object id travels with it.
fn bvh_and_leaf_order(
    (shapes, ids): (Vec<Shape>, Vec<u32>),
    (unbounded, unbounded_ids): (Vec<Shape>, Vec<u32>),
    geometry: &Geometry,
) -> (Vec<Shape>, Vec<u32>, u32, WideBvh) {
    let bounds: Vec<_> = shapes
        .iter()
        .map(|s| s.bounds(geometry).unwrap_or(Aabb::EMPTY))
        .collect();
    let bvh = WideBvh::build_with(&bounds, Leaves::Single);
    let mut ordered: Vec<Shape> = bvh.order().iter().map(|&i| shapes[i as usize]).collect();
    let mut objects: Vec<u32> = bvh.order().iter().map(|&i| ids[i as usize]).collect();
    let bounded = ordered.len() as u32;
    ordered.extend(unbounded);
    objects.extend(unbounded_ids);
    (ordered, objects, bounded, bvh)
}

/// An emission image whose brightest texel, times the lookup's scale and
/// plus its offset, is above [`MAX_RADIANCE`] (an EXR texel of 1e38 is a
/// finite number, so neither the texel repair nor validation saw it), as a
/// problem at `path`.
fn too_bright(
    path: &str,
    tex: &crate::materials::ColorTex,
    textures: &[crate::materials::Texture],
) -> Option<Problem> {
    let crate::materials::Tex::Image(l) = tex else {
        return None;
    };
    let t = textures.get(l.index as usize)?;
    let texel = t.texels.iter().fold(0.0f32, |m, c| m.max(c.max_element()));
    let brightest = texel * l.scale.abs() + l.offset.abs();
    (brightest.is_nan() || brightest > MAX_RADIANCE).then(|| {
        Problem::new(
            format!("{path}.file"),
            format!(
                "the emission image's brightest texel is {texel:e}; times its scale, {brightest:e} W/(m²·sr), \
                 above the limit of {MAX_RADIANCE:e}"
            ),
        )
        .help(RADIANCE_HELP)
    })
}

/// The textured `radiance` of every light and emitting object, by scene path
/// (`lights[i].radiance`, `objects[i].emission.radiance`): built with the
/// materials' textures.
fn textured_emissions(desc: &SceneDesc) -> Vec<(String, &ColorDesc)> {
    let lights = desc.lights.iter().enumerate().filter_map(|(i, l)| match l {
        LightDesc::Quad { radiance, .. } | LightDesc::Rect { radiance, .. } => {
            Some((format!("lights[{i}].radiance"), radiance))
        }
        LightDesc::Point { .. }
        | LightDesc::Spot { .. }
        | LightDesc::Directional { .. }
        | LightDesc::Environment { .. } => None,
    });
    let objects = desc.objects.iter().enumerate().filter_map(|(i, o)| {
        o.emission()
            .map(|e| (format!("objects[{i}].emission.radiance"), &e.radiance))
    });
    lights
        .chain(objects)
        .filter(|(_, c)| matches!(c, ColorDesc::Texture(_)))
        .collect()
}
