//! The runtime scene the renderer sees: glam types, u32 indices, no names,
//! no options, no serde. Built once by `build`, never mutated while rendering.

use crate::accel::Bvh;
use crate::camera::Camera;
use crate::geometry::{Hit, Mesh, SdfObject, Shape};
use crate::integrators::Integrator;
use crate::lights::{Light, LightPicker};
use crate::materials::{Material, Texture};
use crate::math::Ray;
use crate::sampler::SamplerKind;
use std::path::PathBuf;

/// Image size and sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    pub width: u32,
    pub height: u32,
    pub spp: u32,
    pub seed: u64,
    pub sampler: SamplerKind,
}

pub struct Scene {
    pub camera: Camera,
    pub film: Film,
    /// Where `render` writes when no `-o` is given (resolved against the
    /// scene file's folder).
    pub output: PathBuf,
    pub integrator: Integrator,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub lights: Vec<Light>,
    /// Chooses the light for next-event estimation.
    pub light_picker: LightPicker,
    /// Bounded shapes first (`..bounded`, in the BVH), then unbounded ones
    /// (planes), which every ray tests.
    pub shapes: Vec<Shape>,
    pub bounded: u32,
    pub meshes: Vec<Mesh>,
    pub bvh: Bvh,
    /// Implicit surfaces, referred to by [`Shape::Sdf`].
    pub sdfs: Vec<SdfObject>,
}

impl Scene {
    /// Closest hit in `(0, t_max)`.
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let (meshes, sdfs) = (&self.meshes, &self.sdfs);
        let shapes = &self.shapes;
        let mut best = self.bvh.intersect(ray, t_max, |i, r, tm| {
            shapes[i as usize].intersect_t(r, tm, meshes, sdfs)
        });
        let mut t_best = best.map_or(t_max, |(_, t)| t);
        for i in self.bounded..self.shapes.len() as u32 {
            if let Some(t) = shapes[i as usize].intersect_t(ray, t_best, meshes, sdfs) {
                t_best = t;
                best = Some((i, t));
            }
        }
        best.map(|(i, t)| shapes[i as usize].hit(ray, t, meshes, sdfs))
    }

    /// Whether anything blocks `ray` before `t_max` (shadow rays).
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let (meshes, sdfs) = (&self.meshes, &self.sdfs);
        let shapes = &self.shapes;
        (self.bounded..self.shapes.len() as u32)
            .any(|i| shapes[i as usize].intersect_t(ray, t_max, meshes, sdfs).is_some())
            || self.bvh.occluded(ray, t_max, |i, r, tm| {
                shapes[i as usize].intersect_t(r, tm, meshes, sdfs).is_some()
            })
    }
}
