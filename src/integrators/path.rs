//! Unidirectional path tracing with next-event estimation and multiple
//! importance sampling (Veach 1997, ch. 9, power heuristic), as Mitsuba 3's
//! `path` integrator does, so renders converge to its references.
//!
//! Depth follows Mitsuba: `max_depth` counts path **segments** from the
//! camera — 1 shows emitters only, 2 is direct lighting, 3 adds one indirect
//! bounce; −1 is unlimited (Russian roulette ends paths). Russian roulette
//! starts once the path has `rr_depth` segments, continuing with probability
//! min(0.95, max(β)·η²) (η² undoes the radiance scaling of refraction so
//! roulette acts on flux).
//!
//! Emitters reached by a BSDF sample after a non-delta vertex are weighted
//! against light sampling; after a delta vertex (or from the camera) they
//! count fully, since light sampling cannot produce those paths. Each path
//! therefore counts every emitter exactly once. The environment is an
//! emitter like the others: a BSDF sample that escapes the scene is weighted
//! against the environment's own density (its luminance distribution, or
//! the cosine about the previous vertex's normal for a constant sky), and
//! next-event estimation picks it like any light (by the light tree, which
//! weighs it by its irradiance at the point). A camera ray that
//! escapes sees the environment, or its background when it is not
//! `visible`.
//!
//! Path splitting (`splits` > 1) shares a camera sample's first hit and its
//! light sample among several continuations ([`Path::trace`]). It lowers
//! the error per camera sample by more than it adds instructions on rooms
//! lit indirectly, but at equal error its wall time was within 4% of one
//! path per sample on the reference scenes and worse on one lit mostly
//! directly (`docs/integrators.md`), so one path is the default.

use super::caustic::max_chain;
use super::interior::Interior;
use super::{Counters, emitted, escaped, shadow_ray, spawn};
use crate::geometry::{Hit, NO_LIGHT};
use crate::lights::LightPicker;
use crate::lights::tree::Top;
use crate::materials::{BsdfSample, Bxdf};
use crate::math::sampling::power_heuristic;
use crate::math::{Frame, Ray, Rgb};
use crate::sampler::{Draw, Sampler};
use crate::scene::Scene;
use glam::Vec3A;

/// Path-tracing estimator with next-event estimation and MIS; the module docs pin
/// down its depth convention.
#[derive(Clone, Copy, Debug)]
pub struct Path {
    /// Segments from the camera; `u32::MAX` when unlimited.
    pub max_depth: u32,
    /// Segments a path has before Russian roulette may end it.
    pub rr_depth: u32,
    /// Whether caustics seen directly are light-traced ([`super::caustic`])
    /// when the render can: the scene's wish.
    pub light_trace_caustics: bool,
    /// Set by the renderer for a render whose light-tracing pass runs: the
    /// paths that pass counts are dropped here (see [`super::caustic`]).
    pub split_caustics: bool,
    /// Continuations of each camera sample at its first non-delta vertex
    /// (path splitting); 1 traces one path per camera sample, as Mitsuba.
    pub splits: u32,
}

/// Where a path stands between two vertices: what the loop of
/// [`Path::trace`] carries from one vertex to the next, so that the
/// continuations of a split path can each start from a copy.
#[derive(Clone, Copy, Debug)]
struct State {
    /// The ray leaving the last vertex (the camera ray at first).
    ray: Ray,
    /// Path throughput up to `ray`'s origin.
    beta: Rgb,
    /// Product of η² over the refractions so far: roulette acts on flux.
    eta_scale: f32,
    /// Density of the last BSDF sample, and whether it was a delta lobe
    /// (the camera ray counts as one: emitters it sees count fully).
    prev_pdf: f32,
    prev_delta: bool,
    /// The vertex the ray left from: light densities for MIS are seen from it.
    prev_p: Vec3A,
    /// Its shading normal: a light tree's probabilities depend on both.
    prev_n: Vec3A,
    /// The side of it light samples came from (`Bsdf::light_side`): the
    /// environment's density depends on it.
    prev_side: Vec3A,
    /// Segments traced so far.
    segments: u32,
    /// The split with the caustic light tracer (`super::caustic`): whether
    /// the path since its last non-delta vertex is one the tracer counts
    /// (that vertex seen straight from the camera and left by a non-delta
    /// sample), and the perfect-specular vertices since.
    traced: bool,
    chain: u32,
    /// The absorbing solid `ray` travels in (coloured glass), if any.
    inside: Interior,
}

impl Path {
    /// Radiance in W/(m²·sr) arriving along camera `ray`: one camera
    /// sample's estimate (the mean of its continuations when paths split);
    /// unbiased for unlimited depth.
    pub fn li(&self, scene: &Scene, ray: &Ray, sampler: &mut Sampler, counters: &mut Counters) -> Rgb {
        if let Some(media) = &scene.media {
            return super::vol_path::li(self, scene, media, ray, sampler, counters);
        }
        self.li_from(scene, ray, None, sampler, counters)
    }

    /// [`Path::li`] in a scene without media, with the camera ray's first
    /// hit found by the caller (`first`: whether it hits, and the record
    /// when it does): the frame loop finds two camera samples' first hits
    /// back to back, so the processor overlaps their two latency-bound
    /// searches. The same numbers in the same order, the same image.
    pub fn li_first_found(
        &self,
        scene: &Scene,
        ray: &Ray,
        first: (bool, &Hit),
        sampler: &mut Sampler,
        counters: &mut Counters,
    ) -> Rgb {
        debug_assert!(scene.media.is_none(), "media take `vol_path`");
        self.li_from(scene, ray, Some(first), sampler, counters)
    }

    #[inline(always)]
    fn li_from(
        &self,
        scene: &Scene,
        ray: &Ray,
        first: Option<(bool, &Hit)>,
        sampler: &mut Sampler,
        counters: &mut Counters,
    ) -> Rgb {
        let start = State {
            ray: *ray,
            beta: Rgb::ONE,
            eta_scale: 1.0,
            prev_pdf: 0.0,
            prev_delta: true,
            prev_p: ray.o,
            prev_n: Vec3A::ZERO,
            prev_side: Vec3A::ZERO,
            segments: 0,
            traced: false,
            chain: 0,
            inside: Interior::OUTSIDE,
        };
        // Two copies of the loop: scenes without coloured glass run one
        // with no absorption bookkeeping at all, the loop they ran before
        // (one loop with run-time tests cost `cornell` 1.5% more
        // instructions, by changing what LLVM inlined: docs/benchmarks.md).
        let l = if scene.absorption.is_empty() {
            self.trace::<false>(scene, start, self.splits, None, first, sampler, counters)
        } else {
            self.trace::<true>(scene, start, self.splits, None, first, sampler, counters)
        };
        debug_assert!(l.is_finite(), "non-finite radiance {l}");
        l
    }

    /// Radiance the path in `st` gathers from its next vertex on; `prev_top`
    /// is the light tree's first step at the vertex `st.ray` left (as its
    /// light sample was picked; `None` when it was not), which the density
    /// of an emitter the ray reaches starts from (`LightTree::top`: made
    /// once a vertex, not again for that density). With
    /// `splits > 1` the path splits at its first non-delta vertex: after
    /// the one light sample there, it goes on `splits` times, each
    /// continuation along its own BSDF sample (its numbers from
    /// [`Sampler::split`]) with weight 1/`splits`; continuations do not
    /// split again. `first`: the camera ray's first hit when the caller
    /// found it ([`Path::li_first_found`]). `ABSORBING`: whether any
    /// material absorbs inside (coloured glass); only then does the path
    /// track the solid it is in.
    #[allow(clippy::too_many_arguments)] // each is a different piece of the path's state
    fn trace<const ABSORBING: bool>(
        &self,
        scene: &Scene,
        mut st: State,
        splits: u32,
        mut prev_top: Option<Top>,
        mut first: Option<(bool, &Hit)>,
        sampler: &mut Sampler,
        counters: &mut Counters,
    ) -> Rgb {
        let picker: &LightPicker = &scene.light_picker;
        let mut l = Rgb::ZERO;
        let split = self.split_caustics && scene.caustics.is_some();
        let max_chain = max_chain(self.max_depth);
        let mut hit = Hit::default();
        // Whether the next ray hits, when the previous vertex found it
        // already (see the end of the loop).
        let mut found_ahead: Option<bool> = None;
        loop {
            counters.rays += 1;
            let found = match (first.take(), found_ahead.take()) {
                (Some((found, h)), _) => {
                    if found {
                        hit = *h;
                    }
                    found
                }
                (None, Some(found)) => found,
                (None, None) => scene.intersect_into(&st.ray, f32::INFINITY, &mut hit),
            };
            if !found {
                if ABSORBING {
                    // Out of the scene from inside a solid: an open mesh.
                    st.beta *= st.inside.over(scene, f32::INFINITY);
                }
                // The environment, reached by the previous BSDF sample.
                // After a non-delta vertex (never the camera ray) the radiance
                // and the MIS density share one mapping of the direction.
                match scene.environment() {
                    Some((i, env)) if !st.prev_delta => {
                        let (le, env_pdf) = env.le_and_pdf(st.ray.d, st.prev_side);
                        if le != Rgb::ZERO {
                            let w = power_heuristic(
                                st.prev_pdf,
                                picker.pmf_from(prev_top.as_ref(), st.prev_p, st.prev_n, i as usize)
                                    * env_pdf,
                            );
                            l += st.beta * le * w;
                        }
                    }
                    Some((i, _)) if self.theirs(scene, &st, split, max_chain, i) => {}
                    _ => {
                        let le = escaped(scene, st.ray.d, st.segments == 0);
                        if le != Rgb::ZERO {
                            l += st.beta * le;
                        }
                    }
                }
                break;
            }
            st.segments += 1;
            if ABSORBING {
                st.beta *= st.inside.to_hit(scene, &hit, st.ray.d);
            }

            // Emission reached by the previous BSDF sample.
            if hit.light != NO_LIGHT {
                let le = emitted(scene, &hit, st.ray.d);
                if le != Rgb::ZERO {
                    let w = if st.prev_delta {
                        if self.theirs(scene, &st, split, max_chain, hit.light) {
                            0.0
                        } else {
                            1.0
                        }
                    } else {
                        let light = &scene.lights[hit.light as usize];
                        let light_pdf =
                            picker.pmf_from(prev_top.as_ref(), st.prev_p, st.prev_n, hit.light as usize)
                                * light.pdf(st.prev_p, st.ray.d, &hit);
                        power_heuristic(st.prev_pdf, light_pdf)
                    };
                    l += st.beta * le * w;
                }
            }
            if st.segments >= self.max_depth {
                break;
            }

            let bsdf = scene.materials[hit.material as usize]
                .bsdf(&crate::materials::TexPoint::at(&hit), &scene.textures);
            let frame = Frame::from_normal(hit.ns);
            let wo = frame.to_local(-st.ray.d);

            // The numbers are drawn in a fixed order (light pick, light
            // point, BSDF lobe and direction), but the BSDF is sampled
            // before the shadow ray is traced: its direction does not depend
            // on the light, so its latency-bound chain (a division, a sine
            // polynomial, a square root) runs while the shadow ray
            // traverses instead of after it. Same numbers, same image.
            let delta = bsdf.is_delta();
            // Only the sky's sampling and density read the side: scenes
            // without one skip it (0.9% of the Cornell box's instructions).
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
            // A sky map's table entry for these numbers is fetched while
            // the BSDF is sampled (the sky may not be the light picked).
            if !delta && let Some((_, env)) = scene.environment() {
                env.prefetch(u_light, draw);
            }
            let mark = sampler.draws();
            let bs = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2());

            // Next-event estimation: one light, picked as the scene says (by
            // the light tree unless told otherwise).
            let top = if delta { None } else { picker.top(hit.p, hit.ns) };
            // The light sample's shadow ray, traced once the next ray is
            // (below), and what it brings if nothing blocks it.
            let mut shadow = None;
            if !delta && let Some((li, pmf)) = picker.pick_from(top.as_ref(), hit.p, hit.ns, u_pick) {
                let light = &scene.lights[li];
                if let Some(ls) = light.sample(hit.p, side, u_light, draw, &scene.geometry) {
                    let wi = frame.to_local(ls.wi);
                    let f = bsdf.eval(wo, wi) * wi.z.abs();
                    if f != Rgb::ZERO {
                        counters.rays += 1;
                        let mut contribution = st.beta * f * ls.li;
                        if ABSORBING {
                            contribution *= st.inside.beyond(scene, &hit, ls.wi).over(scene, ls.dist);
                        }
                        shadow = Some((shadow_ray(&hit, &ls), contribution, pmf * ls.pdf, ls.delta, wi));
                    }
                }
            }
            // Adds the light sample's radiance when its shadow ray is clear.
            let light_sample = |l: &mut Rgb| {
                if let Some(((ray, extent), contribution, light_pdf, light_delta, wi)) = shadow
                    && !scene.occluded(&ray, extent)
                {
                    let w = if light_delta {
                        1.0
                    } else {
                        power_heuristic(light_pdf, bsdf.pdf(wo, wi))
                    };
                    *l += contribution * (w / light_pdf);
                }
            };

            if splits > 1 && !delta {
                light_sample(&mut l);
                // Path splitting: the first continuation along the sample
                // drawn above, the others along their own.
                let mut sum = Rgb::ZERO;
                let mut bs = bs;
                for k in 0..splits {
                    if k > 0 {
                        sampler.split(k, mark);
                        bs = bsdf.sample(wo, sampler.next_f32(), sampler.next_vec2());
                    }
                    let mut next = st;
                    if let Some(bs) = bs
                        && self.advance(&mut next, &bs, &hit, &frame, (delta, side), split, sampler)
                    {
                        if ABSORBING {
                            next.inside = next.inside.beyond(scene, &hit, next.ray.d);
                        }
                        sum += self.trace::<ABSORBING>(scene, next, 1, top, None, sampler, counters);
                    }
                }
                return l + sum * (1.0 / splits as f32);
            }

            // Continue the path along the BSDF sample. Its ray is traced
            // before the shadow ray, back to back: the two searches do not
            // depend on each other, and the processor overlaps them.
            let go_on = match bs {
                Some(bs) => self.advance(&mut st, &bs, &hit, &frame, (delta, side), split, sampler),
                None => false,
            };
            if go_on {
                if ABSORBING {
                    st.inside = st.inside.beyond(scene, &hit, st.ray.d);
                }
                found_ahead = Some(scene.intersect_into(&st.ray, f32::INFINITY, &mut hit));
            }
            light_sample(&mut l);
            if !go_on {
                break;
            }
            prev_top = top;
        }
        l
    }

    /// Whether light `light`, reached by `st`'s last ray after a delta
    /// vertex, is the caustic light tracer's to count (`super::caustic`):
    /// the path's last non-delta vertex was seen from the camera and left by
    /// a non-delta sample, one to `max_chain` perfect-specular vertices
    /// since, and the tracer emits from that light.
    #[inline]
    fn theirs(&self, scene: &Scene, st: &State, split: bool, max_chain: u32, light: u32) -> bool {
        split
            && st.traced
            && (1..=max_chain).contains(&st.chain)
            && scene.caustics.as_ref().is_some_and(|c| c.covers(light))
    }

    /// Moves `st` across the vertex at `hit` along `bs` (throughput, MIS
    /// memory, the next ray), then plays Russian roulette once the path has
    /// `rr_depth` segments. `delta_side`: whether the vertex's BSDF is a
    /// delta, and the side its light samples came from. False when the path
    /// ends there.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn advance(
        &self,
        st: &mut State,
        bs: &BsdfSample,
        hit: &Hit,
        frame: &Frame,
        (delta, side): (bool, Vec3A),
        split: bool,
        sampler: &mut Sampler,
    ) -> bool {
        if split {
            if delta {
                st.chain += 1;
            } else {
                st.chain = 0;
                st.traced = st.segments == 1 && !bs.delta;
            }
        }
        st.beta *= bs.weight;
        if st.beta == Rgb::ZERO {
            return false;
        }
        st.eta_scale *= bs.eta * bs.eta;
        st.prev_pdf = bs.pdf;
        st.prev_delta = bs.delta;
        st.prev_p = hit.p;
        st.prev_n = hit.ns;
        st.prev_side = side;
        st.ray = spawn(hit, frame.to_world(bs.wi));

        if st.segments >= self.rr_depth {
            let q = (st.beta.max_element() * st.eta_scale).min(0.95);
            if sampler.next_f32() >= q {
                return false;
            }
            st.beta /= q;
        }
        true
    }
}
