//! Where the caustic light tracer (`crate::integrators::caustic`) emits
//! from and aims at: the rectangle and sphere lights and a sky map, chosen
//! by power, and the bounding spheres of the perfect mirrors and smooth
//! glass.
//!
//! # The sky
//! A sky map's sun focused by a glass ball onto the ground is the same
//! caustic as a lamp's, and as rare for the path tracer (a floor's BSDF
//! sample must leave through the glass onto a sun a few pixels wide). A
//! light path from the sky ([`CausticEmitters::sky_start`]) takes a direction
//! by the sky's own importance sampling, density `p(ω)`, then a point of the
//! plane across it: uniform on the disk, across `ω`, of one target's bounding
//! sphere, the sphere chosen in proportion to its disk's area, so that the
//! point's density is `n / (π Σ r²)` with `n` the disks that hold it. The
//! ray starts there, moved back toward the sky to outside the scene's
//! bounds, and travels along `−ω`: every ray from the sky that can meet a
//! perfect-specular object is drawn (it crosses that object's bounding
//! sphere, so its point lies in that sphere's disk). Its flux weight is
//! `L(ω) / (pmf · p(ω) · p(x))` (a parallel beam: `dΦ = L dA⊥ dω`). Only a
//! sky with an image is traced from: a constant sky's caustics are as soft
//! as the sky and the path tracer finds them well.
//!
//! # Directional lights
//! A sun given as a `Directional` light is the same beam with its one
//! direction ([`CausticEmitters::sun_start`]): a point on the targets'
//! disks across it, flux weight `E / (pmf · p(x))`. Its caustics are found
//! by nothing else (no BSDF sample reaches a delta direction), so its
//! weight among the emitters is what it sends through the disks, `π Σ r²
//! E`.

use super::{DirectionalLight, EnvironmentLight, Light, sphere_cone};
use crate::accel::Aabb;
use crate::geometry::{Geometry, Shape};
use crate::math::trig::sin_cos_turns;
use crate::math::{Frame, Rgb, luminance};
use crate::sampler::Draw;
use glam::{Vec2, Vec3A};
use std::collections::HashMap;
use std::f32::consts::PI;

/// The lights the caustic light tracer emits from, chosen by power, and
/// where it aims.
#[derive(Clone, Debug)]
pub struct CausticEmitters {
    /// Indices in `Scene::lights`.
    lights: Vec<u32>,
    /// Running sum of the selection probabilities; last entry 1.
    cdf: Vec<f32>,
    /// Selection probability of every scene light (0 for lights not emitted from).
    pmf: Vec<f32>,
    /// Bounding spheres (centre, radius) of the perfect-specular objects,
    /// at most [`MAX_CONES`]; empty when one is unbounded (a mirror plane):
    /// then emission is cosine-weighted.
    targets: Vec<(Vec3A, f32)>,
    /// The sky when it is emitted from (module docs): its light index, and
    /// a box around every bounded shape (its light paths start outside it).
    sky: Option<(u32, Aabb)>,
    /// That box when beams can be traced (targets bounded, the box
    /// finite): the sky's and the directional lights' paths start outside it.
    beam_bounds: Option<Aabb>,
}

impl CausticEmitters {
    /// The emitters of a scene, or `None` when the light tracer cannot
    /// matter: no surface is a perfect mirror or smooth glass (`targets` is
    /// empty), or no light is one this module emits from. `targets` is
    /// `None` when a specular surface is unbounded ([`specular_targets`]).
    /// `bounds` holds every bounded shape: the sky's light paths start
    /// outside it (the sky is emitted from only when it has an image, the
    /// bounds are finite and the targets bounded).
    pub fn new(lights: &[Light], targets: Option<Vec<(Vec3A, f32)>>, bounds: Aabb) -> Option<Self> {
        let targets = match targets {
            Some(t) if t.is_empty() => return None,
            Some(t) => t,
            None => Vec::new(),
        };
        // What the sky sends through the targets' disks, π Σ r² ∫L dω: its
        // power as the light tracer sees it.
        let disks: f32 = targets.iter().map(|(_, r)| PI * r * r).sum();
        let finite = bounds.min.is_finite()
            && bounds.max.is_finite()
            && (bounds.max - bounds.min).length().is_finite();
        let sky_traced = !targets.is_empty() && finite && disks.is_finite();
        let beam_bounds = sky_traced.then_some(bounds);
        let mut sky = None;
        let pmf: Vec<f32> = lights
            .iter()
            .enumerate()
            // Each light says whether it is traced from
            // (`LightModel::emits_caustics`); the first sky with an image
            // is, through the targets.
            .map(|(i, l)| match l.as_environment() {
                Some(e) if sky_traced && sky.is_none() && e.map().is_some() => {
                    sky = Some((i as u32, bounds));
                    disks * luminance(e.radiance_integral()).max(0.0)
                }
                _ if l.as_directional().is_some() => match (l.as_directional(), sky_traced) {
                    (Some(d), true) => disks * luminance(d.irradiance).max(0.0),
                    _ => 0.0,
                },
                _ if l.emits_caustics() => luminance(l.power()).max(0.0),
                _ => 0.0,
            })
            .map(|p| if p.is_finite() { p } else { 0.0 })
            .collect();
        Self::by_power(pmf, targets, sky, beam_bounds)
    }

    /// The emitters of lights weighted `pmf` (one entry per scene light; 0:
    /// not emitted from), normalised; `None` when none has weight.
    fn by_power(
        mut pmf: Vec<f32>,
        targets: Vec<Target>,
        sky: Option<(u32, Aabb)>,
        beam_bounds: Option<Aabb>,
    ) -> Option<Self> {
        let total: f32 = pmf.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        pmf.iter_mut().for_each(|p| *p /= total);
        let indices: Vec<u32> = (0..pmf.len() as u32).filter(|&i| pmf[i as usize] > 0.0).collect();
        let mut acc = 0.0;
        let mut cdf: Vec<f32> = indices
            .iter()
            .map(|&i| {
                acc += pmf[i as usize];
                acc
            })
            .collect();
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let sky = sky.filter(|s| pmf[s.0 as usize] > 0.0);
        Some(Self {
            lights: indices,
            cdf,
            pmf,
            targets,
            sky,
            beam_bounds,
        })
    }

    /// The lights emitted from (indices in the scene's lights).
    pub fn emitters(&self) -> &[u32] {
        &self.lights
    }

    /// These emitters without the lights in `drop`, the others chosen in
    /// the same proportions; `None` when none is left. The path tracer then
    /// keeps the caustic paths of the dropped lights
    /// (`crate::integrators::caustic_reach`).
    pub fn without(&self, drop: &[u32]) -> Option<Self> {
        let mut pmf = self.pmf.clone();
        for &i in drop {
            if let Some(p) = pmf.get_mut(i as usize) {
                *p = 0.0;
            }
        }
        Self::by_power(pmf, self.targets.clone(), self.sky, self.beam_bounds)
    }

    /// Whether a point, spot or directional light of `lights` (the scene's,
    /// these emitters were built from) is emitted from: its caustics are
    /// found by nothing but the light tracer.
    pub fn from_points(&self, lights: &[Light]) -> bool {
        self.lights
            .iter()
            .any(|&i| lights.get(i as usize).is_some_and(Light::is_delta))
    }

    /// Whether light `i` is the sky, emitted from ([`Self::sky_start`]).
    #[inline]
    pub fn is_sky(&self, i: u32) -> bool {
        self.sky.is_some_and(|s| s.0 == i)
    }

    /// The start of a light path from the sky `env` (picked with
    /// probability `pmf`; module docs): the ray's origin outside the scene,
    /// its direction of travel, and its flux weight `L(ω) / (pmf · p(ω) ·
    /// p(x))`. `u_dir` draws the direction, `u_disk` the point, `u_pick`
    /// the target. `None` where the sky sends nothing that way.
    pub fn sky_start(
        &self,
        env: &EnvironmentLight,
        pmf: f32,
        u_dir: Vec2,
        u_pick: f32,
        u_disk: Vec2,
    ) -> Option<(Vec3A, Vec3A, Rgb)> {
        let (_, bounds) = self.sky?;
        let s = env.sample(bounds.centroid(), Vec3A::ZERO, u_dir, Draw::Independent)?;
        if !(s.pdf > 0.0 && s.li != Rgb::ZERO) {
            return None;
        }
        self.beam_start(s.wi, s.li / (pmf * s.pdf), u_pick, u_disk)
    }

    /// The start of a light path from the directional light `sun` (picked
    /// with probability `pmf`; module docs), as [`Self::sky_start`]'s.
    /// `u_dir` picks the beam's direction in a sun's disk (unused by a hard
    /// sun).
    pub fn sun_start(
        &self,
        sun: &DirectionalLight,
        pmf: f32,
        u_pick: f32,
        u_disk: Vec2,
        u_dir: Vec2,
    ) -> Option<(Vec3A, Vec3A, Rgb)> {
        if sun.irradiance == Rgb::ZERO {
            return None;
        }
        let (toward, weight) = sun.toward(u_dir);
        self.beam_start(toward, weight / pmf, u_pick, u_disk)
    }

    /// A ray of the parallel beam arriving from unit direction `w` (toward
    /// the light), `weight` its radiance or irradiance over the densities
    /// drawn so far: a point on one target's disk across `w`, moved back to
    /// outside the scene's box; its origin, direction of travel and flux
    /// weight `weight / p(x)`.
    fn beam_start(&self, w: Vec3A, weight: Rgb, u_pick: f32, u_disk: Vec2) -> Option<(Vec3A, Vec3A, Rgb)> {
        let bounds = self.beam_bounds?;
        if self.targets.is_empty() || !w.is_finite() {
            return None;
        }
        // A target by its disk's area, then a point uniform on the disk.
        let total: f32 = self.targets.iter().map(|(_, r)| r * r).sum();
        let mut acc = 0.0;
        let k = self
            .targets
            .iter()
            .position(|(_, r)| {
                acc += r * r;
                acc > u_pick * total
            })
            .unwrap_or(self.targets.len() - 1);
        let (c, r) = self.targets[k];
        let frame = Frame::from_normal(w);
        let (sin_p, cos_p) = sin_cos_turns(u_disk.y);
        let q = c + frame.to_world(Vec3A::new(cos_p, sin_p, 0.0) * (r * u_disk.x.sqrt()));
        // The disks that hold the ray: its distance to each centre's line
        // along ω within that radius.
        let holds = |(c, r): &(Vec3A, f32)| {
            let v = *c - q;
            (v - v.dot(w) * w).length_squared() <= r * r * (1.0 + 1e-5)
        };
        let n = self.targets.iter().filter(|t| holds(t)).count().max(1);
        let p_x = n as f32 / (PI * total);
        // Just past where the line leaves the scene's box toward the sky, not
        // farther: an origin twice the scene's size away would blur the
        // caustic of a small ball on a large floor (f32 positions).
        let mut t_exit = f32::INFINITY;
        for a in 0..3 {
            if w[a].abs() > 1e-12 {
                let (t0, t1) = ((bounds.min[a] - q[a]) / w[a], (bounds.max[a] - q[a]) / w[a]);
                t_exit = t_exit.min(t0.max(t1));
            }
        }
        let margin = 1e-4 * (1.0 + (bounds.max - bounds.min).length());
        let o = q + (t_exit.max(0.0) * (1.0 + 1e-4) + margin) * w;
        let flux = weight / p_x;
        (o.is_finite() && flux.is_finite()).then_some((o, -w, flux))
    }

    /// Whether light `i` is emitted from (its caustic paths seen directly
    /// are the light tracer's).
    #[inline]
    pub fn covers(&self, i: u32) -> bool {
        self.pmf.get(i as usize).is_some_and(|&p| p > 0.0)
    }

    /// A direction from `p` toward the specular objects ([`aim`]) and its
    /// solid-angle density; `None` when they cannot be aimed at from `p`
    /// (inside one's bounding sphere, or one is unbounded).
    #[inline]
    pub fn aim(&self, p: Vec3A, u_cone: f32, u: Vec2) -> Option<(Vec3A, f32)> {
        aim(&self.targets, p, u_cone, u)
    }

    /// A light by power: its index and probability.
    pub fn pick(&self, u: f32) -> (u32, f32) {
        let k = self.cdf.partition_point(|&c| c <= u).min(self.cdf.len() - 1);
        let i = self.lights[k];
        (i, self.pmf[i as usize])
    }
}

/// A bounding sphere emission aims at: centre and radius.
type Target = (Vec3A, f32);

/// Most bounding spheres emission aims at; more specular objects are
/// bounded by one sphere around them all.
pub const MAX_CONES: usize = 32;

/// The bounding spheres of a scene's perfect-specular objects (`object[i]`
/// is shape `i`'s object; `is_delta(shape)` says whether it is a perfect
/// mirror or smooth glass): one per object, or one around them all beyond
/// [`MAX_CONES`]. `Some(empty)` when there is none; `None` when one is
/// unbounded, so directions cannot be aimed.
pub fn specular_targets(
    shapes: &[Shape],
    objects: &[u32],
    geo: &Geometry,
    mut is_delta: impl FnMut(&Shape) -> bool,
) -> Option<Vec<(Vec3A, f32)>> {
    // Per object: its box, and its sphere while it is a single sphere (a
    // sphere's box's bounding sphere would hold three times its cone).
    let mut boxes: Vec<(u32, Aabb, Option<Target>)> = Vec::new();
    // Object id → its entry in `boxes` (a scene may hold many objects).
    let mut index: HashMap<u32, usize> = HashMap::new();
    for (i, s) in shapes.iter().enumerate() {
        if !is_delta(s) {
            continue;
        }
        let b = s.bounds(geo)?;
        let exact = match s {
            Shape::Sphere(sp) => Some((sp.center, sp.radius)),
            _ => None,
        };
        let id = objects.get(i).copied().unwrap_or(u32::MAX);
        match index.get(&id) {
            Some(&k) => {
                let (_, ob, ex) = &mut boxes[k];
                *ob = ob.union(b);
                *ex = None;
            }
            None => {
                index.insert(id, boxes.len());
                boxes.push((id, b, exact));
            }
        }
    }
    if boxes.len() > MAX_CONES {
        let all = boxes.iter().skip(1).fold(boxes[0].1, |a, (_, b, _)| a.union(*b));
        boxes = vec![(0, all, None)];
    }
    let spheres: Vec<(Vec3A, f32)> = boxes
        .iter()
        .map(|(_, b, ex)| ex.unwrap_or((0.5 * (b.min + b.max), 0.5 * (b.max - b.min).length())))
        .collect();
    spheres
        .iter()
        .all(|(c, r)| c.is_finite() && r.is_finite())
        .then_some(spheres)
}

/// A direction from `p` uniform in the cone of one of `targets` (chosen in
/// proportion to its solid angle), and its density: the number of cones
/// holding it over their total solid angle. `None` when there are no
/// targets or `p` is inside one (no cone to aim at).
fn aim(targets: &[Target], p: Vec3A, u_cone: f32, u: Vec2) -> Option<(Vec3A, f32)> {
    if targets.is_empty() {
        return None;
    }
    let mut cones = [(Vec3A::ZERO, 0.0f32, 0.0f32); MAX_CONES];
    let mut total = 0.0f32;
    for (k, (c, r)) in targets.iter().enumerate() {
        let (_, one_minus_cos) = sphere_cone(*c, *r, p, 1.0 + 1e-5)?;
        let axis = (*c - p).normalize();
        cones[k] = (axis, 1.0 - one_minus_cos, 2.0 * PI * one_minus_cos);
        total += cones[k].2;
    }
    let cones = &cones[..targets.len()];
    if !(total > 0.0 && total.is_finite()) {
        return None;
    }
    // The cone: first whose running solid angle passes u_cone · total.
    let mut acc = 0.0;
    let target = u_cone * total;
    let k = cones
        .iter()
        .position(|c| {
            acc += c.2;
            acc > target
        })
        .unwrap_or(cones.len() - 1);
    let (axis, cos_max, _) = cones[k];
    let cos_t = 1.0 - u.x * (1.0 - cos_max);
    let sin_t = (1.0 - cos_t * cos_t).max(0.0).sqrt();
    let (sin_p, cos_p) = sin_cos_turns(u.y);
    let d = Frame::from_normal(axis)
        .to_world(Vec3A::new(sin_t * cos_p, sin_t * sin_p, cos_t))
        .normalize();
    let inside = cones.iter().filter(|c| d.dot(c.0) >= c.1).count().max(1);
    Some((d, inside as f32 / total))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Pcg32;
    use crate::math::sampling::uniform_sphere;

    #[test]
    fn aimed_directions_stay_in_their_cones_with_the_union_density() {
        // Two overlapping spheres seen from the origin: each direction lies
        // in a cone, and 1/pdf averages to the union's solid angle.
        let targets = [
            (Vec3A::new(0.0, 0.0, -3.0), 1.0),
            (Vec3A::new(0.8, 0.0, -3.0), 1.0),
        ];
        let cone = |(c, r): (Vec3A, f32), d: Vec3A| {
            d.dot((c).normalize()) >= (1.0 - (r * r) / c.length_squared()).sqrt() - 1e-5
        };
        let mut rng = Pcg32::new(9, 1);
        let n = 200_000;
        let mut inv_pdf = 0.0f64;
        for _ in 0..n {
            let u = Vec2::new(rng.next_f32(), rng.next_f32());
            let (d, pdf) = aim(&targets, Vec3A::ZERO, rng.next_f32(), u).expect("outside both");
            assert!(cone(targets[0], d) || cone(targets[1], d), "{d}");
            inv_pdf += 1.0 / pdf as f64;
        }
        // The union's solid angle by uniform sphere sampling.
        let mut hits = 0u64;
        let m = 2_000_000;
        for _ in 0..m {
            let d = uniform_sphere(Vec2::new(rng.next_f32(), rng.next_f32()));
            if cone(targets[0], d) || cone(targets[1], d) {
                hits += 1;
            }
        }
        let union = 4.0 * std::f64::consts::PI * hits as f64 / m as f64;
        let est = inv_pdf / n as f64;
        assert!(
            (est - union).abs() < 0.02 * union,
            "E[1/pdf] {est} vs union {union}"
        );
        // From inside a target there is no cone: emission is cosine-weighted.
        assert!(aim(&targets, Vec3A::new(0.0, 0.0, -3.0), 0.5, Vec2::splat(0.5)).is_none());
    }

    /// A 64 × 32 sky: a dim gradient and a bright 3 × 2-pixel sun.
    fn sky() -> EnvironmentLight {
        let (w, h) = (64u32, 32u32);
        let mut rgb = Vec::new();
        for j in 0..h {
            for i in 0..w {
                let sun = (20..23).contains(&i) && (9..11).contains(&j);
                let l = if sun {
                    400.0
                } else {
                    0.2 + 0.8 * j as f32 / h as f32
                };
                rgb.extend_from_slice(&[l, 0.7 * l, 0.4 * l]);
            }
        }
        EnvironmentLight::from_map(crate::lights::EnvMap::from_rgb(w, h, &rgb), 1.5, 30.0)
    }

    #[test]
    fn sky_beams_carry_what_the_sky_sends_through_the_targets() {
        // E[flux] of `sky_start` is ∫ L(ω) A(ω) dω, A(ω) the area of the
        // union of the targets' disks across ω. One sphere: π r² ∫L dω.
        // Two concentric spheres: the larger's disk is the union, so the
        // smaller's points, which both disks hold, must count twice in the
        // density (and a point counted once too often would bias it).
        let env = sky();
        let lights = [Light::Environment(Box::new(env.clone()))];
        let bounds = Aabb::from_points(&[Vec3A::splat(-3.0), Vec3A::splat(3.0)]);
        let c = Vec3A::new(0.3, -0.2, 0.5);
        for (targets, area) in [(vec![(c, 0.7)], PI * 0.49), (vec![(c, 0.4), (c, 0.9)], PI * 0.81)] {
            let em = CausticEmitters::new(&lights, Some(targets.clone()), bounds).expect("a sky to trace");
            assert!(em.is_sky(0));
            let mut rng = Pcg32::new(5, 3);
            let n = 200_000;
            let mut sum = [0.0f64; 3];
            for _ in 0..n {
                let mut u = || rng.next_f32();
                let (u_dir, u_pick, u_disk) = (Vec2::new(u(), u()), u(), Vec2::new(u(), u()));
                let Some((o, d, flux)) = em.sky_start(&env, 1.0, u_dir, u_pick, u_disk) else {
                    continue;
                };
                // The beam starts outside the scene and crosses a target.
                let inside = o.cmpge(bounds.min).all() && o.cmple(bounds.max).all();
                assert!(!inside, "origin {o} inside the scene");
                assert!(targets.iter().any(|(tc, r)| {
                    let v = *tc - o;
                    (v - v.dot(d) * d).length() <= r * 1.0001
                }));
                for (s, f) in sum.iter_mut().zip(flux.to_array()) {
                    *s += f as f64;
                }
            }
            let want = env.radiance_integral() * area;
            for (s, w) in sum.iter().zip(want.to_array()) {
                let got = s / n as f64;
                assert!((got - w as f64).abs() < 0.02 * w as f64, "flux {got} vs {w}");
            }
        }
        // No sky image (a constant sky) or no bounded target: no sky beams.
        let constant = [Light::Environment(Box::new(EnvironmentLight::constant(Rgb::ONE)))];
        assert!(CausticEmitters::new(&constant, Some(vec![(c, 0.5)]), bounds).is_none());
        assert!(CausticEmitters::new(&lights, None, bounds).is_none());
    }

    #[test]
    fn without_leaves_the_dropped_lights_to_the_path_tracer() {
        // The sky and a point light, both emitted from; dropping the sky
        // leaves the point light alone (probability 1, the sky no longer
        // covered or traced), dropping both leaves nothing.
        let lights = [
            Light::Environment(Box::new(sky())),
            Light::Point(super::super::PointLight {
                position: Vec3A::new(0.0, 2.0, 0.0),
                intensity: Rgb::splat(3.0),
            }),
        ];
        let bounds = Aabb::from_points(&[Vec3A::splat(-3.0), Vec3A::splat(3.0)]);
        let em = CausticEmitters::new(&lights, Some(vec![(Vec3A::ZERO, 0.5)]), bounds).expect("emitters");
        assert_eq!(em.emitters(), &[0, 1]);
        assert!(em.is_sky(0) && em.covers(0) && em.covers(1));
        let point = em.without(&[0]).expect("the point light is left");
        assert_eq!(point.emitters(), &[1]);
        assert!(!point.is_sky(0) && !point.covers(0) && point.covers(1));
        assert_eq!(point.pick(0.3), (1, 1.0));
        assert!(em.without(&[0, 1]).is_none());
        // Dropping a light that is not emitted from changes nothing.
        assert_eq!(em.without(&[7]).expect("unchanged").emitters(), &[0, 1]);
    }

    #[test]
    fn targets_are_one_sphere_per_object_and_one_around_many() {
        use crate::geometry::{NO_LIGHT, Sphere};
        let sphere = |x: f32| {
            Shape::Sphere(Sphere {
                center: Vec3A::new(x, 0.0, 0.0),
                radius: 0.5,
                material: 0,
                light: NO_LIGHT,
                mitsuba_uv: false,
            })
        };
        let geo = Geometry::default();
        // Two objects: each its own sphere, exactly.
        let shapes = [sphere(0.0), sphere(3.0)];
        let t = specular_targets(&shapes, &[1, 2], &geo, |_| true).expect("bounded");
        assert_eq!(t, vec![(Vec3A::ZERO, 0.5), (Vec3A::new(3.0, 0.0, 0.0), 0.5)]);
        // Nothing specular: no targets (and no emitters).
        assert_eq!(
            specular_targets(&shapes, &[1, 2], &geo, |_| false),
            Some(Vec::new())
        );
        // A mirror plane cannot be aimed at.
        let plane = Shape::Plane(crate::geometry::Plane {
            point: Vec3A::ZERO,
            normal: Vec3A::Y,
            material: 0,
        });
        assert_eq!(
            specular_targets(&[sphere(0.0), plane], &[1, 2], &geo, |_| true),
            None
        );
        // A hundred thousand specular objects: one sphere around them all,
        // found in linear time.
        let many: Vec<Shape> = (0..100_000).map(|i| sphere(i as f32)).collect();
        let ids: Vec<u32> = (0..100_000).collect();
        let t = specular_targets(&many, &ids, &geo, |_| true).expect("bounded");
        assert_eq!(t.len(), 1);
        assert!((t[0].0.x - 49_999.5).abs() < 1.0 && t[0].1 >= 50_000.0, "{t:?}");
    }
}
