//! Caustics seen directly, light-traced: light reaching a diffuse or glossy
//! surface through perfect mirrors and smooth glass, found from the light's
//! side and joined to the camera.
//!
//! A unidirectional path tracer finds a caustic path `E y S…S L` (y a
//! non-delta surface the camera sees, S perfect mirrors or smooth glass, L
//! an area light) only when the BSDF sample at y happens to leave through
//! the specular chain onto the light: next-event estimation cannot see a
//! light through glass. Those rare, bright samples are a large part of a
//! glass scene's noise: on `cornell_specular` (128 spp, two seeds) caustics
//! seen directly are 37% of the image's variance, caustics reached after
//! another diffuse bounce 14%, and caustics seen in the mirror or through
//! the glass sphere (specular–diffuse–specular paths, which no connection
//! of a light path can sample better) 39%.
//!
//! So a whole-frame render also traces light paths (`frame::caustics`;
//! pbrt-v4's `LightPathIntegrator` and Mitsuba's `ptracer`, kept to the
//! paths a camera ray finds badly): a light chosen by power, a point on it uniformly,
//! a direction toward the bounding spheres of the perfect-specular objects
//! (uniform in the cone of one, chosen by solid angle; cosine-weighted when
//! the point is inside one or a specular surface is unbounded), through
//! perfect-specular surfaces only, to the first surface that is not one, y.
//! y is joined to the pinhole by a shadow ray and its contribution is added
//! to the pixel it projects to (a *splat*).
//!
//! The two estimators split path space instead of weighting each other by
//! MIS: a path whose first vertex y (seen from the camera) is left by a
//! non-delta BSDF sample through one to [`max_chain`] perfect-specular
//! vertices onto a light this module emits from belongs to the light tracer
//! alone; the path tracer drops it when its BSDF sample happens to reach it
//! (`Path::split_caustics`), the light tracer adds it. Every other path is
//! the path tracer's, as before, so each path is counted once and the image
//! stays unbiased.
//!
//! Density of a light path: (L, ω_L) is drawn with density `pmf · 1/A ·
//! p_ω`; along a perfect-specular chain étendue is conserved (`cos θ dA dω`
//! times η²), so the density of (y, ω_y) is that times `|cos θ_y| / cos
//! θ_L`, and the refraction scalings cancel against the radiance's: the
//! path's weight is its flux `Φ = L_e cos θ_L / (pmf · p_A · p_ω)` times each
//! specular vertex's reflectance or transmittance (`BsdfSample::weight ·
//! η²`). A pixel is the mean radiance over its footprint on the image plane
//! at distance 1 (area `A_pix`, box filter), `dA = dω / cos³θ`, so one
//! light path adds `Φ · f_y · |cos_s y|_chain / |cos_g y|_chain · |cos_g
//! y|_camera / d² / (A_pix cos³θ)` to its pixel, and the pixel's estimate
//! is the sum over all light paths over their number.
//!
//! Light from a point, spot or directional light does not stop at y: the
//! caustic lights other surfaces in turn (a glass ball's bright spot on the
//! floor brightens a ball beside it), and the path tracer cannot find those
//! paths either (from each later surface, the way to the light still ends
//! in a delta light seen through a specular chain). So a light path from a
//! delta light goes on from y ([`bounce`]: a BSDF sample in its direction
//! of travel, through any perfect-specular surfaces, to the next surface
//! that is not one) and every such surface is splatted like y, within the
//! path tracer's depth and by Russian roulette on the flux (as Mitsuba's
//! `ptracer` joins every vertex of its light paths to the camera). A path
//! from an area light or the sky stops at y: the path tracer finds what
//! follows by BSDF sampling.
//!
//! Not done, measured: joining every non-delta camera-path vertex to the
//! light path's end (bidirectional connections, for the caustics reached
//! after another diffuse bounce) had 50 times less variance than the path
//! tracer on those paths, but they are only 14% of the variance and the
//! shadow rays cost 30–60% more time, so it lost overall.
//!
//! Emitted from: rectangles and parallelograms (one- or two-sided),
//! one-sided emissive spheres, a sky with an image (a parallel beam
//! through a specular object's bounding sphere: `lights/caustic.rs`),
//! directional lights (the same beam, one direction), and point and spot
//! lights. A point, spot or directional light's caustics are found by
//! nothing else: a BSDF sample never reaches a point, so without the light
//! tracer a glass ball under a point light casts a black shadow (as in
//! pbrt-v4's and Mitsuba 3's path tracers). Caustics of other lights
//! (meshes, SDFs, a constant sky) stay with the path tracer, as before.

use super::interior::Interior;
use super::{Counters, light_point_error, offset_origin, spawn};
use crate::camera::Camera;
use crate::geometry::Hit;
use crate::lights::{CausticEmitters, LightOrigin};
use crate::materials::Bxdf;
use crate::math::sampling::{UNIFORM_SPHERE_PDF, cosine_hemisphere, uniform_sphere};
use crate::math::{Frame, Ray, Rgb};
use crate::sampler::Sampler;
use crate::scene::Scene;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;

/// Longest specular chain a light path follows (perfect-specular vertices
/// between the light and y) whatever the depth; longer caustic chains stay
/// with the path tracer.
pub const MAX_CHAIN: u32 = 16;

/// The longest chain the light tracer takes for a path tracer of
/// `max_depth` segments: the camera segment, the chain's segments and the
/// one onto y fit within it. The path tracer's drop rule uses the same
/// bound, so the two agree on which paths are whose.
#[inline]
pub fn max_chain(max_depth: u32) -> u32 {
    MAX_CHAIN.min(max_depth.saturating_sub(2))
}

/// The end y of a light path: a non-delta surface lit through at least one
/// perfect-specular vertex.
#[derive(Clone, Copy, Debug)]
pub struct LightVertex {
    /// The surface point, normals, material and texture coordinates.
    hit: Hit,
    /// Unit direction from y back along the arriving ray (toward the chain).
    wi: Vec3A,
    /// Flux weight of the path (see the module docs).
    flux: Rgb,
    /// Specular vertices between the light and y (≥ 1).
    pub chain: u32,
    /// Segments from the light to this vertex.
    segments: u32,
    /// Whether the light is a point, spot or directional light: the path
    /// goes on past y ([`bounce`]).
    from_delta: bool,
    /// The absorbing solid (coloured glass) the path reached y in.
    inside: Interior,
}

/// Most segments a light path from a delta light takes (Russian roulette
/// ends nearly all long before; this bounds a path between mirrors that
/// reflect everything).
pub const MAX_SEGMENTS: u32 = 64;

/// Traces one light path: `None` unless it leaves the light, meets one to
/// `max_chain` perfect-specular surfaces and lands on a non-delta one.
pub fn trace(
    scene: &Scene,
    em: &CausticEmitters,
    max_chain: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Option<LightVertex> {
    let (li, pmf) = em.pick(sampler.next_f32());
    trace_from(scene, em, li, pmf, max_chain, sampler, counters)
}

/// [`trace`] from light `li`, picked with probability `pmf`.
pub(super) fn trace_from(
    scene: &Scene,
    em: &CausticEmitters,
    li: u32,
    pmf: f32,
    max_chain: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Option<LightVertex> {
    let u_point = sampler.next_vec2();
    let u_dir = sampler.next_vec2();
    let u_cone = sampler.next_f32();
    let light = &scene.lights[li as usize];
    let delta = light.is_delta();
    // Through one to `max_chain` specular surfaces to y, marked with
    // whether the path goes on past it.
    let to_y = |ray: Ray, flux: Rgb, sampler: &mut Sampler, counters: &mut Counters| {
        follow(scene, ray, flux, max_chain, sampler, counters).map(|mut y| {
            y.from_delta = delta;
            y
        })
    };
    if let Some(env) = light.as_environment().filter(|_| em.is_sky(li)) {
        // From the sky: a parallel beam through a target's disk.
        let (o, d, flux) = em.sky_start(env, pmf, u_dir, u_cone, u_point)?;
        return to_y(Ray::new(o, d), flux, sampler, counters);
    }
    if let Some(sun) = light.as_directional() {
        // From a directional light: its parallel beam through a target's disk.
        let (o, d, flux) = em.sun_start(sun, pmf, u_cone, u_point, u_dir)?;
        return to_y(Ray::new(o, d), flux, sampler, counters);
    }
    if let Some(p) = light.point_source() {
        // A point or spot light: a direction toward the targets (over the
        // sphere when they cannot be aimed at), flux I(ω) / (pmf · p(ω)).
        let (d, pdf) = em
            .aim(p, u_cone, u_dir)
            .unwrap_or_else(|| (uniform_sphere(u_dir), UNIFORM_SPHERE_PDF));
        let flux = light.intensity_toward(d) / (pmf * pdf);
        return to_y(Ray::new(p, d), flux, sampler, counters);
    }
    // A point, its emitting normal, L_e / (pmf · p_A), and whether the back
    // emits too.
    let LightOrigin { p, n, le, two_sided } = light.caustic_origin(u_point, pmf)?;
    // A direction and its density: toward the specular objects' bounding
    // spheres when they can be aimed at from here, else cosine-weighted.
    let (d, pdf) = match em.aim(p, u_cone, u_dir) {
        Some(dp) => dp,
        None => {
            let local = cosine_hemisphere(u_dir);
            let (side, half) = if two_sided && u_cone < 0.5 {
                (-n, 0.5)
            } else {
                (n, if two_sided { 0.5 } else { 1.0 })
            };
            (Frame::from_normal(side).to_world(local), half * local.z / PI)
        }
    };
    let cos_l = if two_sided { d.dot(n).abs() } else { d.dot(n) };
    if !(cos_l > 0.0 && pdf > 0.0) {
        return None;
    }
    let flux = le * (cos_l / pdf);
    let side = if d.dot(n) >= 0.0 { n } else { -n };
    let ray = Ray::new(offset_origin(p, side, light_point_error(p, side), d), d);
    to_y(ray, flux, sampler, counters)
}

/// Follows a light path leaving the light along `ray` with flux weight
/// `flux` through perfect-specular surfaces: its end y when one to
/// `max_chain` of them lead to a surface that is not one. The vertex is not
/// marked `from_delta`.
fn follow(
    scene: &Scene,
    mut ray: Ray,
    mut flux: Rgb,
    max_chain: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Option<LightVertex> {
    let mut inside = Interior::OUTSIDE;
    follow_from(
        scene,
        (&mut ray, &mut inside),
        &mut flux,
        (1, max_chain),
        0,
        sampler,
        counters,
    )
}

/// The next surface that is not perfectly specular along `ray`, when
/// `chain.0` to `chain.1` specular surfaces lead to it, for a path that has
/// `segments` segments where `ray` leaves; `ray`, the absorbing solid it
/// travels in and `flux` are carried through the chain.
fn follow_from(
    scene: &Scene,
    (ray, inside): (&mut Ray, &mut Interior),
    flux: &mut Rgb,
    (min_chain, max_chain): (u32, u32),
    segments: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Option<LightVertex> {
    if !flux.is_finite() || *flux == Rgb::ZERO {
        return None;
    }
    let mut chain = 0u32;
    loop {
        counters.rays += 1;
        let hit = scene.intersect(ray, f32::INFINITY)?;
        *flux *= inside.to_hit(scene, &hit, ray.d);
        if *flux == Rgb::ZERO {
            return None;
        }
        let bsdf = scene.materials[hit.material as usize]
            .bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
        if !bsdf.is_delta() {
            return (chain >= min_chain).then_some(LightVertex {
                hit,
                wi: -ray.d,
                flux: *flux,
                chain,
                segments: segments + chain + 1,
                from_delta: false,
                inside: *inside,
            });
        }
        chain += 1;
        if chain > max_chain {
            return None;
        }
        let frame = Frame::from_normal(hit.ns);
        let bs = bsdf.sample(frame.to_local(-ray.d), sampler.next_f32(), Vec2::ZERO)?;
        // The flux part of the weight: the radiance scaling of a refraction
        // is undone by the étendue's (module docs).
        *flux *= bs.weight * (bs.eta * bs.eta);
        if *flux == Rgb::ZERO || !flux.is_finite() {
            return None;
        }
        *ray = spawn(&hit, frame.to_world(bs.wi));
        *inside = inside.beyond(scene, &hit, ray.d);
    }
}

/// The next surface that is not perfectly specular, lit by the light path
/// that reached `v` (module docs: only a path from a point, spot or
/// directional light goes on): a BSDF sample at `v` along the light's
/// direction of travel, then any perfect-specular chain. `None` when the
/// path ends: from another light, past `max_depth` (the path tracer's:
/// the camera's segment counts), by Russian roulette on the flux, or
/// escaping.
pub fn bounce(
    scene: &Scene,
    v: &LightVertex,
    max_depth: u32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Option<LightVertex> {
    // The camera's segment and at least one more must fit.
    let room = max_depth.min(MAX_SEGMENTS).saturating_sub(v.segments + 1);
    if !v.from_delta || room == 0 {
        return None;
    }
    let bsdf = scene.materials[v.hit.material as usize]
        .bsdf(&crate::materials::TexPoint::at(&v.hit), &scene.textures);
    let frame = Frame::from_normal(v.hit.ns);
    let wo = frame.to_local(v.wi);
    let bs = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2())?;
    let u_rr = sampler.next_f32();
    let d = frame.to_world(bs.wi);
    // Flux through the geometric surface: the shading normal's cosines
    // traded for the geometric ones on both sides (Veach 1997, §5.3), and
    // a refraction's radiance scaling undone, as along a chain.
    let (cos_in_s, cos_in_g) = (wo.z.abs(), v.hit.ng.dot(v.wi).abs());
    let (cos_out_s, cos_out_g) = (bs.wi.z.abs(), v.hit.ng.dot(d).abs());
    if cos_in_g == 0.0 || cos_out_s == 0.0 {
        return None;
    }
    let scale = bs.weight * (bs.eta * bs.eta) * (cos_in_s * cos_out_g / (cos_in_g * cos_out_s));
    // Roulette on what the bounce keeps of the flux.
    let q = scale.max_element().min(0.95);
    if !(q > 0.0 && u_rr < q) {
        return None;
    }
    let mut flux = v.flux * (scale / q);
    let mut ray = spawn(&v.hit, d);
    let mut inside = v.inside.beyond(scene, &v.hit, d);
    // A specular chain after this bounce takes what depth is left.
    let mut next = follow_from(
        scene,
        (&mut ray, &mut inside),
        &mut flux,
        (0, room - 1),
        v.segments,
        sampler,
        counters,
    )?;
    next.from_delta = true;
    Some(next)
}

/// Where light vertex `y` lands on the film of a pinhole `camera` (`w` × `h`
/// pixels), and what it adds there per light path (module docs): `None`
/// when it is behind the camera, off the film or hidden from the eye.
pub fn splat(
    scene: &Scene,
    camera: &Camera,
    w: u32,
    h: u32,
    y: &LightVertex,
    counters: &mut Counters,
) -> Option<(u32, Rgb)> {
    let (pixel, cos_cam) = project(camera, w, h, y.hit.p)?;
    let v = camera.eye - y.hit.p;
    let d2 = v.length_squared();
    let to_eye = v / d2.sqrt();
    let th = camera.tan_half_fov;
    let aspect = w as f32 / h as f32;
    let bsdf = scene.materials[y.hit.material as usize]
        .bsdf(&crate::materials::TexPoint::at(&y.hit), &scene.textures);
    let frame = Frame::from_normal(y.hit.ns);
    let wi = frame.to_local(y.wi);
    let cos_chain = y.hit.ng.dot(y.wi).abs();
    if cos_chain == 0.0 {
        return None;
    }
    let f = bsdf.eval(frame.to_local(to_eye), wi) * (wi.z.abs() / cos_chain);
    if f == Rgb::ZERO {
        return None;
    }
    // 1/(A_pix cos³θ) · |cos_g y| / d², A_pix the pixel's area on the image
    // plane at distance 1.
    let a_pix = (2.0 * th * aspect / w as f32) * (2.0 * th / h as f32);
    let c = y.flux * f * (y.hit.ng.dot(to_eye).abs() / (d2 * a_pix * cos_cam * cos_cam * cos_cam));
    if !c.is_finite() || c == Rgb::ZERO {
        return None;
    }
    let o = offset_origin(y.hit.p, y.hit.ng, y.hit.p_error, to_eye);
    let seg = camera.eye - o;
    let len = seg.length();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    // Absorbed on the way when y and the eye are inside coloured glass.
    let c = c * y.inside.beyond(scene, &y.hit, to_eye).over(scene, len);
    counters.rays += 1;
    if scene.occluded(&Ray::new(o, seg / len), len * (1.0 - 1e-4)) {
        return None;
    }
    Some((pixel, c))
}

/// The pixel (row-major index) of a `w` × `h` film of pinhole `camera`
/// whose camera rays pass through `p`, and the cosine between that
/// direction and the view direction: the inverse of `perspective::ray`.
/// `None` behind the camera or off the film.
#[inline]
pub fn project(camera: &Camera, w: u32, h: u32, p: Vec3A) -> Option<(u32, f32)> {
    let d = p - camera.eye;
    let z = d.dot(camera.forward);
    let len = d.length();
    if !(z > 0.0 && len.is_finite()) || w == 0 || h == 0 {
        return None;
    }
    let (th, aspect) = (camera.tan_half_fov, w as f32 / h as f32);
    let fx = 0.5 * (1.0 + d.dot(camera.right) / (z * th * aspect));
    let fy = 0.5 * (1.0 - d.dot(camera.up) / (z * th));
    if !((0.0..1.0).contains(&fx) && (0.0..1.0).contains(&fy)) {
        return None;
    }
    let (px, py) = (
        ((fx * w as f32) as u32).min(w - 1),
        ((fy * h as f32) as u32).min(h - 1),
    );
    Some((py * w + px, z / len))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;

    #[test]
    fn a_point_projects_to_the_pixel_whose_camera_rays_pass_through_it() {
        let cam = Camera::look_at(
            Vec3A::new(0.3, -0.2, 3.9),
            Vec3A::new(0.1, 0.0, 0.0),
            Vec3A::Y,
            37.5,
        );
        let (w, h) = (40u32, 24u32);
        let mut rng = Pcg32::new(3, 5);
        for _ in 0..2000 {
            let (x, y) = (rng.next_f32() * w as f32, rng.next_f32() * h as f32);
            let ray = cam.ray(
                Vec2::new(x / w as f32, y / h as f32),
                w as f32 / h as f32,
                Vec2::ZERO,
            );
            let p = ray.at(0.5 + 4.0 * rng.next_f32());
            let Some((pixel, cos)) = project(&cam, w, h, p) else {
                panic!("({x}, {y}) not projected");
            };
            // Off by one only within rounding of a pixel edge.
            let (px, py) = (pixel % w, pixel / w);
            let near_edge = |v: f32| (v - v.round()).abs() < 1e-3;
            assert!(
                (px == x as u32 || near_edge(x)) && (py == y as u32 || near_edge(y)),
                "({x}, {y}) -> ({px}, {py})"
            );
            assert!((cos - ray.d.dot(cam.forward)).abs() < 1e-4);
        }
        // Behind the camera, and beside the film.
        assert!(project(&cam, w, h, cam.eye - cam.forward).is_none());
        assert!(project(&cam, w, h, cam.eye + cam.forward + 10.0 * cam.right).is_none());
    }
}
