//! The path tracer's volumetric branch: unidirectional path tracing
//! through participating media with next-event estimation and MIS, as
//! Mitsuba 3's `volpath`, so renders converge to its references.
//!
//! [`super::Path`] takes this branch for scenes that declare media (and
//! only those: a surface-only scene runs the plain loop, instruction for
//! instruction). One integrator rather than a separate `VolPath` keeps one
//! set of settings (`max_depth`, `rr_depth`) and one convention, and adding
//! fog to a scene needs no other change.
//!
//! # One path
//! Along each segment the current medium samples a free-flight distance
//! (`media::Medium::sample`): closed form in homogeneous media, delta
//! tracking in grids. A collision before the surface ahead is a scattering
//! vertex: one light is sampled (next-event estimation, weighted by the
//! phase function and the transmittance of the shadow ray), then the phase
//! function picks the next direction. Otherwise the path reaches the
//! surface and goes on as in `path.rs`, its shadow rays attenuated by the
//! media they cross. Emitters reached by a phase or BSDF sample are
//! weighted against light sampling with the power heuristic (light
//! densities seen from the last real vertex).
//!
//! # Path length (Mitsuba's `volpath` convention)
//! `max_depth` counts segments, and a scattering event in a medium is a
//! vertex exactly as a surface hit: 1 shows emitters seen directly
//! (attenuated), 2 adds single scattering and direct light on surfaces.
//! Crossing an index-matched (null) boundary is not a vertex, nor are the
//! fictitious collisions of delta tracking. Russian roulette as in
//! `path.rs`, once a path has `rr_depth` segments.
//!
//! # Shadow rays
//! The transmittance of a shadow ray is exact in homogeneous media and
//! ratio-tracked in grids; index-matched boundaries on the way change the
//! medium and let it through, any other surface blocks it. Paths split by
//! `splits` and the caustic light tracer are surface-only features: with
//! media each camera sample traces one path (the loader drops the
//! caustic emitters).

use super::interior::Interior;
use super::{Counters, Path, emitted, escaped, light_point_error, offset_origin};
use crate::geometry::{Hit, NO_LIGHT};
use crate::lights::{LightPicker, LightSample};
use crate::materials::Bxdf;
use crate::math::sampling::power_heuristic;
use crate::math::{Frame, Ray, Rgb};
use crate::media::{Media, Medium};
use crate::sampler::{Draw, Sampler};
use crate::scene::Scene;
use glam::{Vec2, Vec3A};

/// Most index-matched boundaries a path or a shadow ray crosses: past
/// this it ends (dark), so nested null shapes cannot loop a ray forever.
pub const MAX_NULL_CROSSINGS: u32 = 256;

/// The last real vertex, for MIS of the emitters the next sample reaches.
#[derive(Clone, Copy)]
struct Prev {
    pdf: f32,
    delta: bool,
    p: Vec3A,
    /// Shading normal (zero at a medium vertex: light selection then
    /// judges every direction alike).
    n: Vec3A,
    side: Vec3A,
}

/// Radiance in W/(m²·sr) arriving along camera `ray` through the scene's
/// `media`: one sample of `path`'s estimator with media.
pub(super) fn li(
    path: &Path,
    scene: &Scene,
    media: &Media,
    ray: &Ray,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Rgb {
    let picker: &LightPicker = &scene.light_picker;
    let (mut ray, mut beta, mut l) = (*ray, Rgb::ONE, Rgb::ZERO);
    let mut medium = media.camera;
    // The absorbing solid the ray is in (coloured glass, `super::interior`),
    // on top of the medium.
    let mut inside = Interior::OUTSIDE;
    let mut prev = Prev {
        pdf: 0.0,
        delta: true,
        p: ray.o,
        n: Vec3A::ZERO,
        side: Vec3A::ZERO,
    };
    let (mut segments, mut crossings, mut eta_scale) = (0u32, 0u32, 1.0f32);
    let mut hit = Hit::default();
    loop {
        counters.rays += 1;
        let current = media.get(medium);
        // In a homogeneous medium the free-flight distance is drawn first
        // (the same two numbers `Medium::sample` draws after the hit) and
        // the surface looked for only up to it: a collision then costs a
        // shorter traversal and no surface record. The same vertices and
        // weights as drawing it after the hit
        // (`media::homogeneous::tests::free_flight_is_where_sample_collides`).
        let drawn = match current {
            Some(Medium::Homogeneous(h)) => Some((
                h,
                h.free_flight(Vec2::new(sampler.next_f32(), sampler.next_f32())),
            )),
            _ => None,
        };
        let reach = drawn.map_or(f32::INFINITY, |(_, reach)| reach);
        // Written in place (`Scene::intersect_into` says why).
        let found = scene.intersect_object_into(&ray, reach, &mut hit);
        let t_hit = if found.is_some() { hit.t } else { f32::INFINITY };
        let collision = match (drawn, current) {
            (Some((h, reach)), _) => Some(h.collision(reach, t_hit)),
            (None, Some(m)) => Some(m.sample(&ray, t_hit, &mut || sampler.next_f32())),
            (None, None) => None,
        };

        // The medium along the segment: a scattering vertex, or on to the surface.
        if let (Some(m), Some(c)) = (current, collision) {
            beta *= c.weight;
            if beta == Rgb::ZERO || !beta.is_finite() {
                break;
            }
            if let Some(t) = c.t {
                beta *= inside.over(scene, t);
                segments += 1;
                if segments >= path.max_depth {
                    break;
                }
                let p = ray.at(t);
                let phase = m.phase();
                let u_pick = sampler.next_f32();
                let (u_light, draw) = sampler.next_vec2_draw();
                let u_phase = sampler.next_vec2();
                if let Some((i, pmf)) = picker.pick(p, Vec3A::ZERO, u_pick)
                    && let Some(ls) = scene.lights[i].sample(p, Vec3A::ZERO, u_light, draw, &scene.geometry)
                {
                    let f = phase.eval(ray.d, ls.wi);
                    if f > 0.0 {
                        let (shadow, extent) = shadow_from_point(p, &ls);
                        let tr = transmittance(scene, media, medium, shadow, extent, sampler, counters)
                            * inside.over(scene, ls.dist);
                        if tr != Rgb::ZERO {
                            let light_pdf = pmf * ls.pdf;
                            let w = if ls.delta {
                                1.0
                            } else {
                                power_heuristic(light_pdf, f)
                            };
                            l += beta * tr * ls.li * (f * w / light_pdf);
                        }
                    }
                }
                let (wi, pdf) = phase.sample(ray.d, u_phase);
                prev = Prev {
                    pdf,
                    delta: false,
                    p,
                    n: Vec3A::ZERO,
                    side: Vec3A::ZERO,
                };
                ray = Ray::new(p, wi);
                if !roulette(path, segments, &mut beta, eta_scale, sampler) {
                    break;
                }
                continue;
            }
        }

        let Some(object) = found else {
            beta *= inside.over(scene, f32::INFINITY);
            // Out of the scene: the environment, as in `path.rs`.
            match scene.environment() {
                Some((i, env)) if !prev.delta => {
                    let (le, env_pdf) = env.le_and_pdf(ray.d, prev.side);
                    if le != Rgb::ZERO {
                        let w = power_heuristic(prev.pdf, picker.pmf(prev.p, prev.n, i as usize) * env_pdf);
                        l += beta * le * w;
                    }
                }
                _ => l += beta * escaped(scene, ray.d, segments == 0),
            }
            break;
        };
        beta *= inside.to_hit(scene, &hit, ray.d);
        let boundary = media.boundary(object);
        if let Some(b) = boundary
            && b.null
        {
            // An index-matched boundary: on along the same line, in the medium beyond.
            crossings += 1;
            if crossings > MAX_NULL_CROSSINGS {
                break;
            }
            medium = b.toward(ray.d, hit.ng);
            ray = Ray::new(offset_origin(hit.p, hit.ng, hit.p_error, ray.d), ray.d);
            continue;
        }
        segments += 1;

        // Emission reached by the previous phase or BSDF sample.
        if hit.light != NO_LIGHT {
            let le = emitted(scene, &hit, ray.d);
            if le != Rgb::ZERO {
                let w = if prev.delta {
                    1.0
                } else {
                    let light = &scene.lights[hit.light as usize];
                    let light_pdf =
                        picker.pmf(prev.p, prev.n, hit.light as usize) * light.pdf(prev.p, ray.d, &hit);
                    power_heuristic(prev.pdf, light_pdf)
                };
                l += beta * le * w;
            }
        }
        if segments >= path.max_depth {
            break;
        }

        let bsdf = scene.materials[hit.material as usize]
            .bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
        let frame = Frame::from_normal(hit.ns);
        let wo = frame.to_local(-ray.d);
        let delta = bsdf.is_delta();
        let side = if scene.environment.is_some() {
            bsdf.light_side(hit.ns, wo.z)
        } else {
            Vec3A::ZERO
        };
        let (u_pick, (u_light, draw)) = if delta {
            (0.0, (glam::Vec2::ZERO, Draw::Independent))
        } else {
            (sampler.next_f32(), sampler.next_vec2_draw())
        };
        let bs = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2());
        // The medium on the side a direction leaves into.
        let beyond = |w: Vec3A| boundary.map_or(medium, |b| b.toward(w, hit.ng));

        if !delta
            && let Some((i, pmf)) = picker.pick(hit.p, hit.ns, u_pick)
            && let Some(ls) = scene.lights[i].sample(hit.p, side, u_light, draw, &scene.geometry)
        {
            let wi = frame.to_local(ls.wi);
            let f = bsdf.eval(wo, wi) * wi.z.abs();
            if f != Rgb::ZERO {
                let (shadow, extent) = super::shadow_ray(&hit, &ls);
                let tr = transmittance(scene, media, beyond(ls.wi), shadow, extent, sampler, counters)
                    * inside.beyond(scene, &hit, ls.wi).over(scene, ls.dist);
                if tr != Rgb::ZERO {
                    let light_pdf = pmf * ls.pdf;
                    let w = if ls.delta {
                        1.0
                    } else {
                        power_heuristic(light_pdf, bsdf.pdf(wo, wi))
                    };
                    l += beta * tr * f * ls.li * (w / light_pdf);
                }
            }
        }

        let Some(bs) = bs else {
            break;
        };
        beta *= bs.weight;
        if beta == Rgb::ZERO {
            break;
        }
        eta_scale *= bs.eta * bs.eta;
        let wi = frame.to_world(bs.wi);
        prev = Prev {
            pdf: bs.pdf,
            delta: bs.delta,
            p: hit.p,
            n: hit.ns,
            side,
        };
        medium = beyond(wi);
        inside = inside.beyond(scene, &hit, wi);
        ray = super::spawn(&hit, wi);
        if !roulette(path, segments, &mut beta, eta_scale, sampler) {
            break;
        }
    }
    debug_assert!(l.is_finite(), "non-finite radiance {l}");
    l
}

/// Russian roulette as `path.rs` plays it: false when the path ends.
#[inline]
fn roulette(path: &Path, segments: u32, beta: &mut Rgb, eta_scale: f32, sampler: &mut Sampler) -> bool {
    if segments < path.rr_depth {
        return true;
    }
    let q = (beta.max_element() * eta_scale).min(0.95);
    if sampler.next_f32() >= q {
        return false;
    }
    *beta /= q;
    true
}

/// The shadow ray from a medium point `p` (no surface to step off) to the
/// light sample `ls`, and its extent; as [`super::shadow_ray`] otherwise.
fn shadow_from_point(p: Vec3A, ls: &LightSample) -> (Ray, f32) {
    if ls.dist == f32::INFINITY {
        return (Ray::new(p, ls.wi), f32::INFINITY);
    }
    let target = if ls.n == Vec3A::ZERO {
        ls.p
    } else {
        offset_origin(ls.p, ls.n, light_point_error(ls.p, ls.n), p - ls.p)
    };
    let d = target - p;
    let len = d.length();
    if !(len > 0.0 && len.is_finite()) {
        return (Ray::new(p, ls.wi), 0.0);
    }
    (Ray::new(p, d / len), len * (1.0 - 1e-4))
}

/// Transmittance along a shadow ray over `(0, extent)` starting in
/// `medium`: zero when an opaque surface blocks it; index-matched
/// boundaries change the medium and let it through.
fn transmittance(
    scene: &Scene,
    media: &Media,
    mut medium: u32,
    mut ray: Ray,
    mut extent: f32,
    sampler: &mut Sampler,
    counters: &mut Counters,
) -> Rgb {
    let mut tr = Rgb::ONE;
    let mut hit = Hit::default();
    if !media.any_null {
        counters.rays += 1;
        if scene.occluded(&ray, extent) {
            return Rgb::ZERO;
        }
        if let Some(m) = media.get(medium) {
            tr = m.transmittance(&ray, extent, &mut || sampler.next_f32());
        }
        return tr;
    }
    for _ in 0..=MAX_NULL_CROSSINGS {
        counters.rays += 1;
        let found = scene.intersect_object_into(&ray, extent, &mut hit);
        let t = if found.is_some() { hit.t } else { extent };
        if let Some(m) = media.get(medium) {
            tr *= m.transmittance(&ray, t, &mut || sampler.next_f32());
            if tr == Rgb::ZERO {
                return tr;
            }
        }
        let Some(object) = found else {
            return tr;
        };
        match media.boundary(object) {
            Some(b) if b.null => {
                medium = b.toward(ray.d, hit.ng);
                let o = offset_origin(hit.p, hit.ng, hit.p_error, ray.d);
                extent -= (o - ray.o).dot(ray.d);
                ray = Ray::new(o, ray.d);
                if extent <= 0.0 {
                    return tr;
                }
            }
            Some(_) | None => return Rgb::ZERO,
        }
    }
    Rgb::ZERO
}
