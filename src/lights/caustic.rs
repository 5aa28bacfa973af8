//! Where the caustic light tracer (`crate::integrators::caustic`) emits
//! from and aims at: the rectangle and sphere lights, chosen by power, and
//! the bounding spheres of the perfect mirrors and smooth glass.

use super::{Light, sphere_cone};
use crate::accel::Aabb;
use crate::geometry::{Geometry, Shape};
use crate::math::trig::sin_cos_turns;
use crate::math::{Frame, luminance};
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
}

impl CausticEmitters {
    /// The emitters of a scene, or `None` when the light tracer cannot
    /// matter: no surface is a perfect mirror or smooth glass (`targets` is
    /// empty), or no light is one this module emits from. `targets` is
    /// `None` when a specular surface is unbounded ([`specular_targets`]).
    pub fn new(lights: &[Light], targets: Option<Vec<(Vec3A, f32)>>) -> Option<Self> {
        let targets = match targets {
            Some(t) if t.is_empty() => return None,
            Some(t) => t,
            None => Vec::new(),
        };
        let mut pmf: Vec<f32> = lights
            .iter()
            // Each light says whether it is traced from (`LightModel::emits_caustics`).
            .map(|l| {
                if l.emits_caustics() {
                    luminance(l.power()).max(0.0)
                } else {
                    0.0
                }
            })
            .map(|p| if p.is_finite() { p } else { 0.0 })
            .collect();
        let total: f32 = pmf.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return None;
        }
        pmf.iter_mut().for_each(|p| *p /= total);
        let indices: Vec<u32> = (0..lights.len() as u32)
            .filter(|&i| pmf[i as usize] > 0.0)
            .collect();
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
        Some(Self {
            lights: indices,
            cdf,
            pmf,
            targets,
        })
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
