//! The first-hit pass that fills [`AovLayers`].

use super::{AovLayers, AovSet, first_hit_albedo};
use crate::integrators::{emitted, escaped};
use crate::math::Rgb;
use crate::sampler::PixelSampler;
use crate::scene::Scene;
use crate::view::View;
use glam::{DVec3, Vec3A};
use rayon::prelude::*;

/// One pixel's layer values.
#[derive(Clone, Copy)]
struct Pixel {
    albedo: Rgb,
    normal: Vec3A,
    depth: f32,
    position: Vec3A,
    material_id: u32,
    object_id: u32,
    emission: Rgb,
}

/// Traces the camera rays of every (pixel, sample) of `view`'s film to their
/// first hit and reduces them per pixel; `written` is recorded as the layers
/// to write. The camera sample is drawn exactly as the tile loop (`crate::frame`) draws it
/// (same sampler stream, same two dimensions), so the layers see what the
/// beauty pass sees. `threads` as in [`crate::frame::RenderOptions`]; the
/// result does not depend on it.
pub fn render_aovs(scene: &Scene, view: &View, written: AovSet, threads: Option<usize>) -> AovLayers {
    let film = view.film;
    let (w, h) = (film.width, film.height);
    let rows = |y: u32| -> Vec<Pixel> {
        let mut samples = PixelSampler::new(film.sampler, film.spp, film.seed);
        (0..w).map(|x| pixel(scene, view, &mut samples, x, y)).collect()
    };
    let all = || -> Vec<Vec<Pixel>> { (0..h).into_par_iter().map(rows).collect() };
    let rows = match rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
    {
        Ok(pool) => pool.install(all),
        Err(_) => all(),
    };
    let px: Vec<Pixel> = rows.into_iter().flatten().collect();
    AovLayers {
        width: w,
        height: h,
        written,
        albedo: px.iter().map(|p| p.albedo).collect(),
        normal: px.iter().map(|p| p.normal).collect(),
        depth: px.iter().map(|p| p.depth).collect(),
        position: px.iter().map(|p| p.position).collect(),
        material_id: px.iter().map(|p| p.material_id).collect(),
        object_id: px.iter().map(|p| p.object_id).collect(),
        emission: px.iter().map(|p| p.emission).collect(),
        aux_noise_free: view.camera.aperture_radius <= 0.0,
    }
}

/// The layers of pixel (x, y): sums in sample order in `f64` on one thread,
/// so the same on any thread count.
fn pixel(scene: &Scene, view: &View, samples: &mut PixelSampler, x: u32, y: u32) -> Pixel {
    let film = view.film;
    let (mut albedo, mut normal, mut position) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
    let mut emission = DVec3::ZERO;
    let (mut depth, mut hits) = (0.0f64, 0u32);
    // (id, votes), few entries: a pixel straddles a handful of materials
    // and objects.
    let (mut material_votes, mut object_votes) = (Votes::default(), Votes::default());
    samples.set_pixel(x, y, 0..film.spp);
    for s in 0..film.spp {
        let mut sampler = samples.sample(s);
        // The layers average unweighted (a Mitchell lobe's sign means
        // nothing for a normal or an id); emission is weighted as the beauty
        // pass weights it.
        let (ray, weight) = view.camera_ray(x, y, &mut sampler);
        let hit = scene.intersect_object(&ray, f32::INFINITY);
        let le = match &hit {
            Some((hit, _)) => emitted(scene, hit, ray.d),
            None => escaped(scene, ray.d, true),
        };
        if le.is_finite() {
            emission += (le * weight).as_dvec3();
        }
        let (material, object) = match hit {
            Some((hit, object)) => {
                let m = &scene.materials[hit.material as usize];
                albedo +=
                    first_hit_albedo(m, &crate::materials::TexPoint::at(&hit), &scene.textures).as_dvec3();
                // Facing the camera, so both sides of a sheet read alike.
                let n = if hit.ns.dot(ray.d) > 0.0 { -hit.ns } else { hit.ns };
                normal += n.as_dvec3();
                position += hit.p.as_dvec3();
                depth += f64::from(hit.t) * f64::from(ray.d.length());
                hits += 1;
                (hit.material + 1, object)
            }
            None => (0, 0),
        };
        material_votes.add(material);
        object_votes.add(object);
    }
    let n = f64::from(film.spp.max(1));
    let per_hit = f64::from(hits.max(1));
    Pixel {
        albedo: (albedo / n).as_vec3a(),
        normal: (normal / n).as_vec3a(),
        depth: if hits == 0 {
            f32::INFINITY
        } else {
            (depth / per_hit) as f32
        },
        position: (position / per_hit).as_vec3a(),
        emission: (emission / n).as_vec3a(),
        material_id: material_votes.winner(),
        object_id: object_votes.winner(),
    }
}

/// Per-id sample counts of one pixel: an id layer keeps the id most samples
/// hit, since averaging ids would make ids that exist nowhere.
#[derive(Default)]
struct Votes(Vec<(u32, u32)>);

impl Votes {
    fn add(&mut self, id: u32) {
        match self.0.iter_mut().find(|(v, _)| *v == id) {
            Some((_, n)) => *n += 1,
            None => self.0.push((id, 1)),
        }
    }

    /// The id with the most votes; among equals the smaller id; 0 if none.
    fn winner(&self) -> u32 {
        self.0
            .iter()
            .max_by(|a, b| a.1.cmp(&b.1).then(b.0.cmp(&a.0)))
            .map_or(0, |v| v.0)
    }
}
