//! An implicit surface placed in the scene: an [`Sdf`] already in world space
//! (its root is the object's `world_from_object` transform), its march
//! settings and material. [`super::Shape::Sdf`] refers to one by index.
//!
//! Sphere-tracing cost is counted in process-wide atomics ([`take_stats`]),
//! not in the integrators' per-thread counters: rays reach shapes through
//! `Scene::intersect`, which has no counters to pass, and one relaxed add per
//! march is noise next to the hundreds of distance evaluations it counts.

use super::sdf::{MarchParams, Sdf, normal, occluded, trace};
use super::{Hit, NO_LIGHT};
use crate::accel::Aabb;
use crate::math::float_error::{error_along, gamma_offset};
use crate::math::{Ray, ray_epsilon};
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// Smallest hit threshold for scene SDFs, in scene units.
///
/// Secondary rays leave a hit through `integrators::spawn`, offset along the
/// normal by the hit's `p_error`, which [`SdfObject::hit`] sets to at least
/// `4·min_eps` (1e-4 at this value) plus the rounding of the distance
/// evaluation far from the origin. The march needs that offset
/// to be at least twice its hit threshold on both ends of the ray:
/// - where the spawned ray starts (`t ≈ 0`) the threshold is `min_eps`; the
///   engine's 1e-4 would equal the offset, so a ray could "hit" at its own
///   origin. 2.5e-5 keeps the offset ≥ 4× the threshold everywhere, with
///   room for a Mandelbulb estimate that undershoots the distance by half;
/// - where the camera ray stopped, the threshold grows like a pixel's cone,
///   `1e-4·t`: 3e-4 – 1e-3 at camera distances of 3 – 10, larger than the
///   offset. A hit that far in front of the surface would send a refracted
///   ray off from outside. So hits on exact SDFs are projected onto the
///   surface ([`SdfObject::hit`]); for a distance estimate the rendered
///   surface is the level set the march stopped at, which an outward spawn
///   leaves anyway.
pub const MIN_EPS: f32 = 2.5e-5;

/// One scene SDF object: what [`super::Shape::Sdf`] indexes.
#[derive(Clone, Debug)]
pub struct SdfObject {
    /// The surface, already in world space.
    pub sdf: Sdf,
    /// How rays march it.
    pub params: MarchParams,
    /// Index into the scene's materials.
    pub material: u32,
    /// Centre of the spherical UV map: the middle of the bounds.
    pub uv_center: Vec3A,
    /// Index of the light this surface is (an emissive SDF), or [`NO_LIGHT`].
    pub light: u32,
}

impl SdfObject {
    /// An object marched with `params` and shaded with `material`; its UV centre is
    /// the middle of its bounds (the origin when unbounded).
    pub fn new(sdf: Sdf, params: MarchParams, material: u32) -> Self {
        let b = sdf.bounds();
        let c = 0.5 * (b.min + b.max);
        Self {
            uv_center: if c.is_finite() { c } else { Vec3A::ZERO },
            sdf,
            params,
            material,
            light: NO_LIGHT,
        }
    }

    /// `None` when unbounded (the BVH cannot hold it).
    pub fn bounds(&self) -> Option<Aabb> {
        let b = self.sdf.bounds();
        (b.min.is_finite() && b.max.is_finite()).then_some(b)
    }

    /// First hit in `(0, t_max)`.
    #[inline]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let r = trace(&self.sdf, ray, 0.0, t_max, &self.params);
        record(r.steps);
        r.hit.filter(|&t| t > 0.0)
    }

    /// Whether anything blocks `ray` in `(0, t_max)`: a shadow ray, marched
    /// from its far end (see [`occluded`]).
    #[inline]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        let r = occluded(&self.sdf, ray, 0.0, t_max, &self.params);
        record(r.steps);
        r.hit.is_some_and(|t| t > 0.0)
    }

    /// Hit record at `t` from [`Self::intersect`]; the normal is the SDF's
    /// gradient, sampled no finer than the hit threshold there (finer
    /// would resolve detail the march itself blurred away).
    pub fn hit(&self, ray: &Ray, mut t: f32) -> Hit {
        let mut p = ray.at(t);
        let h = self.params.eps_at(t * ray.d.length()).max(ray_epsilon(p));
        let n = normal(&self.sdf, p, h);
        if self.sdf.is_exact() {
            // The march stops up to eps_at(t) in front of the surface (see
            // MIN_EPS). Newton steps along the ray, with the gradient's
            // slope, put p on it (to 1e-6, in 1–2 steps at fair angles) and
            // keep it on the ray; a nearly tangent ray projects along the
            // normal instead, where its Newton step would be long.
            let (len, cos) = (ray.d.length(), n.dot(ray.d.normalize()));
            if cos < -0.05 {
                for _ in 0..4 {
                    let d = self.sdf.distance(ray.at(t));
                    t += d / (-cos * len);
                    if d.abs() < 0.05 * MIN_EPS {
                        break;
                    }
                }
                p = ray.at(t);
            } else {
                p -= n * self.sdf.distance(p);
            }
        }
        // Spherical coordinates about the centre, as for the analytic sphere.
        let dir = (p - self.uv_center).normalize_or(Vec3A::Y);
        let u = 0.5 + dir.z.atan2(dir.x) / (2.0 * PI);
        let v = dir.y.clamp(-1.0, 1.0).acos() / PI;
        // The bound a spawned ray's origin is moved by: four times the hit
        // threshold a march starting there uses (see MIN_EPS), plus the
        // rounding of `p` and of the distance evaluations around it, a few
        // ulps of |p| through the object's transform and the primitive.
        let p_err = Vec3A::splat(4.0 * self.params.min_eps) + gamma_offset(16) * p.abs();
        Hit {
            t,
            p,
            p_error: error_along(n, p_err),
            ng: n,
            ns: n,
            uv: Vec2::new(u, 1.0 - v),
            material: self.material,
            light: self.light,
            color: glam::Vec3A::ONE,
        }
    }
}

/// Buckets of the steps histogram: 0, 1, 2–3, 4–7, …, 2¹⁰–, so bucket `b > 0`
/// holds `[2^(b−1), 2^b)`.
pub const HISTOGRAM_BUCKETS: usize = 12;

static STEPS: AtomicU64 = AtomicU64::new(0);
static HISTOGRAM: [AtomicU64; HISTOGRAM_BUCKETS] = [const { AtomicU64::new(0) }; HISTOGRAM_BUCKETS];

/// Sphere-tracing cost since the last [`take_stats`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SdfStats {
    /// Marches (rays that reached an SDF's BVH leaf, shadow rays included).
    pub traces: u64,
    /// Distance evaluations over all marches (normals not included).
    pub steps: u64,
    /// Number of marches per step-count bucket (see [`HISTOGRAM_BUCKETS`]).
    pub histogram: [u64; HISTOGRAM_BUCKETS],
}

impl SdfStats {
    /// Mean distance evaluations per march: the cost figure to compare march settings
    /// by.
    pub fn steps_per_trace(&self) -> f64 {
        self.steps as f64 / self.traces.max(1) as f64
    }

    /// `"0:12 1:40 2-3:…"`, empty buckets left out.
    pub fn histogram_text(&self) -> String {
        let label = |b: usize| match b {
            0 | 1 => b.to_string(),
            _ if b == HISTOGRAM_BUCKETS - 1 => format!("{}+", 1u64 << (b - 1)),
            _ => format!("{}-{}", 1u64 << (b - 1), (1u64 << b) - 1),
        };
        (0..HISTOGRAM_BUCKETS)
            .filter(|&b| self.histogram[b] > 0)
            .map(|b| format!("{}:{}", label(b), self.histogram[b]))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

#[inline]
fn record(steps: u32) {
    let bucket = if steps == 0 {
        0
    } else {
        (1 + steps.ilog2() as usize).min(HISTOGRAM_BUCKETS - 1)
    };
    STEPS.fetch_add(u64::from(steps), Relaxed);
    HISTOGRAM[bucket].fetch_add(1, Relaxed);
}

/// Counts since the last call (process-wide; concurrent renders share them).
pub fn take_stats() -> SdfStats {
    let histogram = std::array::from_fn(|b| HISTOGRAM[b].swap(0, Relaxed));
    SdfStats {
        traces: histogram.iter().sum(),
        steps: STEPS.swap(0, Relaxed),
        histogram,
    }
}
