//! Objects: the checks of each `objects` entry (shape parameters, the names
//! it refers to, its transform, its emission) and the build step that places
//! the analytic shapes, with the light of an emissive one. `Mesh` and
//! `Instance` objects are built by `mesh.rs`, `Sdf` objects by `sdf/`; the
//! transform helpers here serve all of them.

use super::build_context::BuildContext;
use super::transform::{compose, is_similarity, matrix};
use super::validate::Checker;
use crate::desc::{ColorDesc, EmissionDesc, ObjectDesc, SceneDesc, TransformDesc};
use crate::diagnostic::Problem;
use crate::geometry::{NO_LIGHT, Plane, Quad, Shape, Sphere};
use crate::lights::{Light, QuadLight, SdfLight, SphereLight};
use crate::math::Rgb;
use glam::{Vec3, Vec3A};

impl Checker {
    /// Object `path` (`objects[i]`) of `scene`: its own parameters, the
    /// materials and mesh it names, and its transform.
    pub(super) fn object(&mut self, path: &str, o: &ObjectDesc, scene: &SceneDesc) {
        self.object_refs(path, o, scene);
        self.shape(path, o);
        self.transform(path, o);
        if let Some(e) = o.emission() {
            self.emission(&format!("{path}.emission"), o, e);
        }
    }

    /// An object's `emission`: a radiance ≥ 0, on a shape that can carry it.
    fn emission(&mut self, path: &str, o: &ObjectDesc, e: &EmissionDesc) {
        if let ObjectDesc::Plane { .. } = o {
            self.push(
                path,
                "an infinite plane cannot emit: its power would be infinite",
                "use a large emissive `Rect`, or an `Environment` light for light from everywhere",
            );
            return;
        }
        let at = format!("{path}.radiance");
        self.emitted_param(&at, &e.radiance);
        if let (ObjectDesc::Sdf { .. }, ColorDesc::Texture(_)) = (o, &e.radiance) {
            self.push(
                &at,
                "an SDF has no UVs to look an emission texture up with",
                "give the SDF a constant radiance, or emit from a sphere, quad or mesh",
            );
        }
    }

    fn object_refs(&mut self, path: &str, o: &ObjectDesc, scene: &SceneDesc) {
        if let Some(name) = o.material() {
            let at = format!("{path}.material");
            self.name_ref(&at, "material", name, scene.materials.keys(), "materials");
        }
        for (key, name) in o.material_overrides().into_iter().flatten() {
            let at = format!("{path}.materials.{key}");
            self.name_ref(&at, "material", name, scene.materials.keys(), "materials");
        }
        if let ObjectDesc::Instance { mesh, .. } = o {
            let at = format!("{path}.mesh");
            self.name_ref(&at, "mesh", mesh, scene.meshes.keys(), "meshes");
        }
    }

    fn shape(&mut self, path: &str, o: &ObjectDesc) {
        match o {
            ObjectDesc::Sdf {
                shape,
                march,
                transform,
                ..
            } => (self.problems).extend(super::sdf::validate_sdf(path, shape, march, transform)),
            ObjectDesc::Sphere { center, radius, .. } => {
                self.finite(&format!("{path}.center"), center);
                if !(*radius > 0.0 && radius.is_finite()) {
                    self.push(
                        &format!("{path}.radius"),
                        format!("sphere radius {radius} must be > 0"),
                        "give a positive radius in scene units",
                    );
                }
            }
            ObjectDesc::Plane { point, normal, .. } => {
                self.finite(&format!("{path}.point"), point);
                self.nonzero(&format!("{path}.normal"), normal, "`normal`");
            }
            ObjectDesc::Quad {
                corner,
                edge_u,
                edge_v,
                ..
            } => {
                self.finite(&format!("{path}.corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
            }
            ObjectDesc::Rect {
                center,
                half_u,
                half_v,
                ..
            } => {
                self.finite(&format!("{path}.center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
            }
            ObjectDesc::Mesh { file, .. } => self.file(&format!("{path}.file"), file, "OBJ"),
            ObjectDesc::Instance { .. } => {}
            ObjectDesc::Gltf { file, .. } => self.file(&format!("{path}.file"), file, "glTF"),
        }
    }

    fn transform(&mut self, path: &str, o: &ObjectDesc) {
        self.steps(&format!("{path}.transform"), o.transform());
        if let ObjectDesc::Sphere { transform, .. } = o
            && !transform.is_empty()
            && !is_similarity(&compose(transform))
        {
            self.push(
                &format!("{path}.transform"),
                "a sphere's transform must keep it round",
                "use equal scale factors on all axes (or a Mesh for an ellipsoid)",
            );
        }
    }

    /// The placement steps at `path` (`objects[2].transform`, a key's).
    pub(super) fn steps(&mut self, path: &str, steps: &[TransformDesc]) {
        for (k, t) in steps.iter().enumerate() {
            let tp = format!("{path}[{k}]");
            match t {
                TransformDesc::Translate(v) => {
                    self.finite(&tp, v);
                }
                TransformDesc::Rotate { axis, degrees } => {
                    self.nonzero(&format!("{tp}.axis"), axis, "the rotation axis");
                    if !degrees.is_finite() {
                        self.push(
                            &format!("{tp}.degrees"),
                            "non-finite angle",
                            "use a finite angle in degrees",
                        );
                    }
                }
                TransformDesc::Scale(s) => {
                    if self.finite(&tp, s) && s.contains(&0.0) {
                        self.push(
                            &tp,
                            format!("scale {s:?} has a zero factor"),
                            "a zero scale flattens the object; use non-zero factors",
                        );
                    }
                }
                TransformDesc::Matrix(m) => {
                    let flat: Vec<f32> = m.iter().flatten().copied().collect();
                    if self.finite(&tp, &flat) && matrix(m).determinant().abs() < 1e-12 {
                        self.push(&tp, "matrix is singular", "a transform matrix must be invertible");
                    }
                }
            }
        }
    }
}

/// Adds object `i` of the scene to `ctx`: analytic shapes here, meshes,
/// instances and SDFs through their own build steps.
pub(super) fn build_object(ctx: &mut BuildContext, i: usize, o: &ObjectDesc) {
    let material = o
        .material()
        .and_then(|n| ctx.material_index.get(n))
        .copied()
        .unwrap_or(0);
    let m = compose(o.transform());
    let point = |p: &[f32; 3]| Vec3A::from(m.transform_point3(Vec3::from(*p)));
    let vector = |v: &[f32; 3]| Vec3A::from(m.transform_vector3(Vec3::from(*v)));
    let emission = o.emission();
    // The index the object's light gets, if it emits.
    let light = if emission.is_some() {
        ctx.lights.len() as u32
    } else {
        NO_LIGHT
    };
    let shape = match o {
        ObjectDesc::Sdf { shape, march, .. } => {
            let (s, bounded) = super::sdf::build_sdf(ctx, shape, march, &m, material);
            if !bounded {
                ctx.unbounded.push(s);
                return;
            }
            if let (Some(e), Shape::Sdf(k)) = (emission, s) {
                push_sdf_light(ctx, i, k, e);
            }
            s
        }
        ObjectDesc::Sphere {
            center, radius, uv, ..
        } => {
            let scale = m.transform_vector3(Vec3::X).length();
            let sphere = Sphere {
                center: point(center),
                radius: radius * scale,
                material,
                light,
                mitsuba_uv: *uv == crate::desc::SphereUvDesc::MitsubaZUp,
            };
            if let Some(e) = emission {
                let mut l = SphereLight::new(sphere.center, sphere.radius, Rgb::ZERO)
                    .with_emission(ctx.emission(&format!("objects[{i}].emission.radiance"), &e.radiance));
                l.two_sided = e.two_sided;
                l.mitsuba_uv = sphere.mitsuba_uv;
                ctx.lights.push(Light::Sphere(l));
            }
            Shape::Sphere(sphere)
        }
        ObjectDesc::Plane { point: p, normal, .. } => {
            let n = m
                .inverse()
                .transpose()
                .transform_vector3(Vec3::from(*normal))
                .normalize();
            ctx.unbounded.push(Shape::Plane(Plane {
                point: point(p),
                normal: n.into(),
                material,
            }));
            return;
        }
        ObjectDesc::Quad {
            corner,
            edge_u,
            edge_v,
            ..
        } => quad(
            ctx,
            (point(corner), vector(edge_u), vector(edge_v)),
            material,
            emission.map(|e| (e, i)),
        ),
        ObjectDesc::Rect {
            center,
            half_u,
            half_v,
            ..
        } => {
            let (u, v) = (vector(half_u), vector(half_v));
            quad(
                ctx,
                (point(center) - u - v, 2.0 * u, 2.0 * v),
                material,
                emission.map(|e| (e, i)),
            )
        }
        ObjectDesc::Mesh { .. } | ObjectDesc::Instance { .. } => return super::mesh::add(ctx, i, o, m),
        ObjectDesc::Gltf { .. } => return super::gltf::add(ctx, i, o, m),
    };
    ctx.shapes.push(shape);
}

/// A quad object `(corner, u, v)`, with its light when it emits (`e` of
/// object `i`; one-sided along `u × v` unless two-sided).
fn quad(
    ctx: &mut BuildContext,
    (c, u, v): (Vec3A, Vec3A, Vec3A),
    material: u32,
    e: Option<(&EmissionDesc, usize)>,
) -> Shape {
    let Some((e, i)) = e else {
        return Shape::Quad(Quad::new(c, u, v, material, NO_LIGHT));
    };
    let emission = ctx.emission(&format!("objects[{i}].emission.radiance"), &e.radiance);
    let mut q = QuadLight::new(c, u, v, emission.radiance).with_emission(emission);
    q.two_sided = e.two_sided;
    let id = ctx.lights.len() as u32;
    ctx.lights.push(Light::Quad(q));
    Shape::Quad(Quad::new(c, u, v, material, id))
}

/// The light of emissive SDF `k` (object `i`), sampled through its bounding
/// sphere; an unbounded SDF cannot emit (validation rejects those already).
fn push_sdf_light(ctx: &mut BuildContext, i: usize, k: u32, e: &EmissionDesc) {
    let Some(b) = ctx.geometry.sdfs[k as usize].bounds() else {
        ctx.problems.push(
            Problem::new(format!("objects[{i}].emission"), "an unbounded SDF cannot emit")
                .help("intersect it with a bounded shape"),
        );
        return;
    };
    let id = ctx.lights.len() as u32;
    ctx.geometry.sdfs[k as usize].light = id;
    ctx.lights.push(Light::Sdf(SdfLight {
        sdf: k,
        center: 0.5 * (b.min + b.max),
        radius: 0.5 * (b.max - b.min).length(),
        // Constant: the checks refuse a texture on an SDF.
        radiance: ctx.emission("", &e.radiance).radiance,
        two_sided: e.two_sided,
    }));
}
