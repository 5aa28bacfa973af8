//! Desc → runtime: names become indices, defaults are filled, meshes are
//! loaded and transformed, the BVH is built. Problems found here (a missing
//! OBJ) are reported like validation problems.

use super::build_mesh::MeshBuilder;
use super::build_mtl::MtlMaterials;
use crate::accel::{Aabb, Leaves, WideBvh};
use crate::camera::Camera;
use crate::desc::{
    IntegratorDesc, LightDesc, LightSelectionDesc, ObjectDesc, SamplerDesc, SceneDesc, TransformDesc,
};
use crate::diagnostic::Problem;
use crate::geometry::obj::ObjData;
use crate::geometry::{NO_LIGHT, Plane, Quad, Shape, Sphere};
use crate::integrators::{Direct, Integrator, Path as PathTracer, Whitted};
use crate::lights::{Light, LightPicker, PointLight, QuadLight, SpotLight};
use crate::materials::Material;
use crate::sampler::SamplerKind;
use crate::scene::Scene;
use crate::view::{Film, View};
use glam::{Mat4, Vec3, Vec3A};
use std::path::Path;
use std::time::{Duration, Instant};

/// What building cost, for `--stats` and the render summary.
#[derive(Clone, Debug, Default)]
pub struct BuildStats {
    pub bvh_time: Duration,
    pub load_time: Duration,
    /// Triangles over all placed meshes (instances counted each time).
    pub triangles: usize,
    /// Texture files read while building (watch mode re-reads on change).
    pub texture_files: Vec<std::path::PathBuf>,
    /// Distinct meshes held in memory, and their placements.
    pub meshes: usize,
    pub instances: usize,
    /// Bytes of the meshes' BVHs and inline triangles (each mesh once).
    pub mesh_accel_bytes: usize,
}

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
    let t0 = Instant::now();
    let mut problems = Vec::new();
    let super::build_material::Materials {
        mut materials,
        mut textures,
        index,
        files: texture_files,
    } = super::build_material::build_materials(&desc.materials, base)?;
    let emitter = materials.len() as u32;
    materials.push(Material::Emitter);

    let mut lights = Vec::new();
    let mut shapes = Vec::new();
    let mut unbounded = Vec::new();
    for l in &desc.lights {
        // An area light's surface is black unless the scene gives it a material.
        let surface = |m: &Option<String>| m.as_ref().and_then(|n| index.get(n).copied()).unwrap_or(emitter);
        match l {
            LightDesc::Point { position, intensity } => lights.push(Light::Point(PointLight {
                position: (*position).into(),
                intensity: (*intensity).into(),
            })),
            LightDesc::Spot {
                position,
                direction,
                intensity,
                cone_degrees,
                falloff_degrees,
            } => lights.push(Light::Spot(SpotLight::new(
                (*position).into(),
                (*direction).into(),
                (*intensity).into(),
                *cone_degrees,
                *falloff_degrees,
            ))),
            LightDesc::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
                material,
            } => {
                let q = QuadLight::new(
                    (*corner).into(),
                    (*edge_u).into(),
                    (*edge_v).into(),
                    (*radiance).into(),
                );
                push_quad_light(&mut lights, &mut shapes, surface(material), q);
            }
            LightDesc::Rect {
                center,
                half_u,
                half_v,
                radiance,
                material,
            } => {
                let (c, u, v) = (Vec3A::from(*center), Vec3A::from(*half_u), Vec3A::from(*half_v));
                let q = QuadLight::new(c - u - v, 2.0 * u, 2.0 * v, (*radiance).into());
                push_quad_light(&mut lights, &mut shapes, surface(material), q);
            }
        }
    }

    let index_by_str: std::collections::HashMap<&str, u32> =
        index.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    let mut mesh_builder = MeshBuilder::new(desc, base, load_obj);
    let mut mtl = MtlMaterials::new(materials.len() as u32, textures.len() as u32);
    let mut sdfs = Vec::new();
    for (i, o) in desc.objects.iter().enumerate() {
        let material = o.material().and_then(|n| index.get(n)).copied().unwrap_or(0);
        let m = compose(o.transform());
        let point = |p: &[f32; 3]| Vec3A::from(m.transform_point3(Vec3::from(*p)));
        let vector = |v: &[f32; 3]| Vec3A::from(m.transform_vector3(Vec3::from(*v)));
        match o {
            ObjectDesc::Sdf { shape, march, .. } => {
                let (s, bounded) = super::build_sdf::build_sdf(desc, shape, march, &m, material, &mut sdfs);
                if bounded { &mut shapes } else { &mut unbounded }.push(s);
            }
            ObjectDesc::Sphere { center, radius, .. } => {
                let scale = m.transform_vector3(Vec3::X).length();
                shapes.push(Shape::Sphere(Sphere {
                    center: point(center),
                    radius: radius * scale,
                    material,
                }));
            }
            ObjectDesc::Plane { point: p, normal, .. } => {
                let n = m
                    .inverse()
                    .transpose()
                    .transform_vector3(Vec3::from(*normal))
                    .normalize();
                unbounded.push(Shape::Plane(Plane {
                    point: point(p),
                    normal: n.into(),
                    material,
                }));
            }
            ObjectDesc::Quad {
                corner,
                edge_u,
                edge_v,
                ..
            } => {
                shapes.push(Shape::Quad(Quad::new(
                    point(corner),
                    vector(edge_u),
                    vector(edge_v),
                    material,
                    NO_LIGHT,
                )));
            }
            ObjectDesc::Rect {
                center,
                half_u,
                half_v,
                ..
            } => {
                let (u, v) = (vector(half_u), vector(half_v));
                shapes.push(Shape::Quad(Quad::new(
                    point(center) - u - v,
                    2.0 * u,
                    2.0 * v,
                    material,
                    NO_LIGHT,
                )));
            }
            ObjectDesc::Mesh { .. } | ObjectDesc::Instance { .. } => {
                mesh_builder.add(i, o, m, &index_by_str, &mut mtl, &mut shapes, &mut problems)
            }
        }
    }
    let (mut geometry, triangles, notes) = mesh_builder.finish();
    geometry.sdfs = sdfs;
    notes.iter().for_each(|n| eprintln!("note: {n}"));
    materials.extend(mtl.materials);
    textures.extend(mtl.textures);
    if !problems.is_empty() {
        return Err(problems);
    }
    let load_time = t0.elapsed();

    let t1 = Instant::now();
    let bounds: Vec<_> = shapes
        .iter()
        .map(|s| s.bounds(&geometry).unwrap_or(Aabb::EMPTY))
        .collect();
    let bvh = WideBvh::build_with(&bounds, Leaves::Single);
    // Shapes in leaf order, so a leaf is a contiguous run of them; shapes
    // with empty bounds (never hit) drop out here.
    let mut shapes: Vec<Shape> = bvh.order().iter().map(|&i| shapes[i as usize]).collect();
    let bvh_time = t1.elapsed();
    let bounded = shapes.len() as u32;
    shapes.extend(unbounded);

    let c = &desc.camera;
    let mut camera = Camera::look_at(c.eye.into(), c.target.into(), c.up.into(), c.fov_y_degrees);
    camera.aperture_radius = c.aperture_radius;
    if let Some(f) = c.focus_distance {
        camera.focus_distance = f;
    }
    let integrator = match desc.integrator {
        IntegratorDesc::Direct { light_samples } => Integrator::Direct(Direct { light_samples }),
        IntegratorDesc::Whitted {
            max_depth,
            light_samples,
        } => Integrator::Whitted(Whitted {
            max_depth,
            light_samples,
        }),
        IntegratorDesc::Path {
            max_depth, rr_depth, ..
        } => Integrator::Path(PathTracer {
            max_depth: u32::try_from(max_depth).unwrap_or(u32::MAX),
            rr_depth,
        }),
    };
    let f = &desc.film;
    let view = View {
        camera,
        film: Film {
            width: f.width,
            height: f.height,
            spp: f.spp,
            seed: f.seed,
            sampler: match f.sampler {
                SamplerDesc::Independent => SamplerKind::Independent,
                SamplerDesc::Stratified => SamplerKind::Stratified,
                SamplerDesc::Sobol => SamplerKind::Sobol,
            },
        },
        output: f.output.as_ref().map(|o| base.join(o)).unwrap_or_default(),
        integrator,
    };
    let scene = Scene {
        light_picker: LightPicker::new(
            &lights,
            matches!(
                desc.integrator,
                IntegratorDesc::Path {
                    light_selection: LightSelectionDesc::Uniform,
                    ..
                }
            ),
        ),
        materials,
        textures,
        lights,
        shapes,
        bounded,
        geometry,
        bvh,
    };
    let stats = BuildStats {
        bvh_time,
        load_time,
        triangles,
        texture_files,
        meshes: scene.geometry.meshes.len(),
        instances: scene.geometry.instances.len(),
        mesh_accel_bytes: scene.geometry.meshes.iter().map(|m| m.accel_bytes()).sum(),
    };
    Ok((scene, view, stats))
}

fn push_quad_light(lights: &mut Vec<Light>, shapes: &mut Vec<Shape>, material: u32, q: QuadLight) {
    let id = lights.len() as u32;
    shapes.push(Shape::Quad(Quad::new(q.corner, q.u, q.v, material, id)));
    lights.push(Light::Quad(q));
}

/// A 4×4 matrix written as rows.
pub fn matrix(rows: &[[f32; 4]; 4]) -> Mat4 {
    Mat4::from_cols_array_2d(rows).transpose()
}

/// The steps in written order: the first is applied to the object first.
pub fn compose(steps: &[TransformDesc]) -> Mat4 {
    steps.iter().fold(Mat4::IDENTITY, |acc, t| {
        let step = match t {
            TransformDesc::Translate(v) => Mat4::from_translation(Vec3::from(*v)),
            TransformDesc::Rotate { axis, degrees } => {
                Mat4::from_axis_angle(Vec3::from(*axis).normalize(), degrees.to_radians())
            }
            TransformDesc::Scale(s) => Mat4::from_scale(Vec3::from(*s)),
            TransformDesc::Matrix(m) => matrix(m),
        };
        step * acc
    })
}

/// Rotation, uniform scale and translation only (keeps spheres spheres).
pub fn is_similarity(m: &Mat4) -> bool {
    let (x, y, z) = (
        m.transform_vector3(Vec3::X),
        m.transform_vector3(Vec3::Y),
        m.transform_vector3(Vec3::Z),
    );
    let s = x.length();
    let tol = 1e-4 * s.max(1e-12);
    (y.length() - s).abs() < tol
        && (z.length() - s).abs() < tol
        && x.dot(y).abs() < tol * s
        && y.dot(z).abs() < tol * s
        && x.dot(z).abs() < tol * s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compose_applies_steps_in_written_order() {
        let m = compose(&[
            TransformDesc::Scale([2.0, 2.0, 2.0]),
            TransformDesc::Translate([1.0, 0.0, 0.0]),
        ]);
        // scale first, then translate: (1,0,0) → (2,0,0) → (3,0,0)
        assert!((m.transform_point3(Vec3::X) - Vec3::new(3.0, 0.0, 0.0)).length() < 1e-6);
        let r = compose(&[TransformDesc::Rotate {
            axis: [0.0, 1.0, 0.0],
            degrees: 90.0,
        }]);
        assert!(
            (r.transform_vector3(Vec3::X) - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6,
            "right-handed about y"
        );
        assert!(is_similarity(&r) && !is_similarity(&compose(&[TransformDesc::Scale([1.0, 2.0, 1.0])])));
    }
}
