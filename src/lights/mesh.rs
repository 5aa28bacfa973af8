//! Emissive triangles: the emitting part of a placed mesh (one material slot
//! of one `Mesh` or `Instance` object), sampled uniformly by area — a
//! triangle by an alias table over the areas, then a uniform point on it.
//!
//! **A moving emitter** (an emissive instance with `keys`) keeps its
//! triangles in the mesh's own space, its rest frame, and the instance's
//! motion ([`InstanceMotion`]). A sample is drawn there as for a still
//! light, then placed — point and normal — by the instance's placement at
//! the time of the path being traced, the placement the instance's hits
//! use, so the light is sampled where the rays find it. The placement may
//! scale: a triangle's area grows by `J = |det M|·|M⁻ᵀn|` (Nanson's
//! formula), and an affine map keeps a uniform point uniform, so the
//! density by world area of a point on triangle `k` is
//! `(Aₖ/A) / (Aₖ·Jₖ) = 1 / (A·Jₖ)`, `A` the rest area. [`MeshLight::pdf`]
//! recovers `Jₖ` from the hit's world normal at the same time
//! ([`Placement::area_scale`]), so MIS sees the density the sample had.

use super::QuadLight;
use super::alias::AliasTable;
use super::emission::{Emission, EmissionTexture};
use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::accel::Aabb;
use crate::geometry::moving::{InstanceMotion, Placement};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;
use std::sync::Arc;

/// Triangles emitting uniform radiance from their front (the side their
/// counter-clockwise winding faces), or both sides when `two_sided`; in world
/// space, copied from the placed mesh (48 bytes per triangle for its corners,
/// 16 for its normal and 12 for the alias table), or in the mesh's space
/// for a moving emitter (see the module docs).
#[derive(Clone, Debug)]
pub struct MeshLight {
    /// Corners, wound so that `(b − a) × (c − a)` is the emitting side: in
    /// world space, or in the mesh's space when `motion` is set.
    tris: Vec<[Vec3A; 3]>,
    /// Unit normal of each triangle's emitting side (zero when degenerate),
    /// kept rather than made from the corners at every sample.
    normals: Vec<Vec3A>,
    /// Picks a triangle in proportion to its area.
    alias: AliasTable,
    /// Total area in m² (in the mesh's space when `motion` is set).
    area: f32,
    /// The instance's keys, when it moves while the shutter is open.
    motion: Option<Box<InstanceMotion>>,
    /// Area placed at the shutter's opening, what [`MeshLight::power`]
    /// reports; `area` for a still light.
    power_area: f32,
    /// Emitted radiance, W/(m²·sr); a texture's average when `texture` is set.
    pub radiance: Rgb,
    /// The radiance over the mesh's UVs, when it varies.
    pub texture: Option<Arc<EmissionTexture>>,
    /// Each triangle's corner UVs, in the order of `tris` (empty unless
    /// `texture` is set).
    uvs: Vec<[Vec2; 3]>,
    /// Whether the back of each triangle emits too.
    pub two_sided: bool,
}

impl MeshLight {
    /// The light of `tris` (world space, front = counter-clockwise); degenerate
    /// triangles get probability 0. `None` when their total area is 0.
    pub fn new(tris: Vec<[Vec3A; 3]>, radiance: Rgb, two_sided: bool) -> Option<Self> {
        let areas: Vec<f32> = tris
            .iter()
            .map(|[a, b, c]| 0.5 * (*b - *a).cross(*c - *a).length())
            .map(|x| if x.is_finite() { x } else { 0.0 })
            .collect();
        let area: f32 = areas.iter().map(|&a| a as f64).sum::<f64>() as f32;
        (area > 0.0).then(|| Self {
            alias: AliasTable::new(&areas),
            normals: tris
                .iter()
                .map(|[a, b, c]| (*b - *a).cross(*c - *a).normalize_or_zero())
                .collect(),
            tris,
            area,
            motion: None,
            power_area: area,
            radiance,
            texture: None,
            uvs: Vec::new(),
            two_sided,
        })
    }

    /// This light emitting `e` over the corner UVs `uvs` (one triple per
    /// triangle, in the order given to [`MeshLight::new`]); stays constant
    /// when the counts differ.
    pub fn with_emission(mut self, e: Emission, uvs: Vec<[Vec2; 3]>) -> Self {
        if e.texture.is_some() && uvs.len() != self.tris.len() {
            debug_assert!(
                false,
                "{} UV triples for {} triangles",
                uvs.len(),
                self.tris.len()
            );
            return self;
        }
        self.radiance = e.radiance;
        self.texture = e.texture;
        self.uvs = uvs;
        self
    }

    /// This light carried by `motion`: the triangles given to
    /// [`MeshLight::new`] were in the mesh's space, and are placed at each
    /// time by the motion's placement then.
    pub fn with_motion(mut self, motion: InstanceMotion) -> Self {
        let opening = motion.placement_at(motion.shutter.0);
        self.power_area = self
            .tris
            .iter()
            .zip(&self.normals)
            .map(|([a, b, c], n)| {
                let rest = 0.5 * (*b - *a).cross(*c - *a).length();
                let scale = if *n == Vec3A::ZERO {
                    0.0
                } else {
                    opening.normal_and_area_scale(*n).1
                };
                f64::from(rest * scale)
            })
            .sum::<f64>() as f32;
        self.motion = Some(Box::new(motion));
        self
    }

    /// Whether the light moves while the shutter is open.
    pub fn moves(&self) -> bool {
        self.motion.is_some()
    }

    /// The same light as one parallelogram, when it is one: two untextured
    /// triangles sharing an edge, coplanar, wound alike, whose unshared
    /// corners sum to the shared ones (the rectangle an OBJ file writes for
    /// an area lamp), and still. A [`QuadLight`] samples the same uniform-by-area
    /// density without the alias table and the triangle's square root, and
    /// a rectangle near a shading point by solid angle instead; the OBJ
    /// Cornell box spent 10% of its time in [`MeshLight::sample`] against
    /// 2.4% for the analytic box's quad light.
    pub fn as_parallelogram(&self) -> Option<QuadLight> {
        let ([t0, t1], [n0, n1]) = (self.tris.as_slice(), self.normals.as_slice()) else {
            return None;
        };
        if self.texture.is_some() || self.motion.is_some() || n0.dot(*n1) < 1.0 - 1e-6 {
            return None;
        }
        // The corner of t0 that t1 lacks, and the corner of t1 that t0 lacks.
        let lone = |a: &[Vec3A; 3], b: &[Vec3A; 3]| {
            let mut out = a.iter().filter(|p| !b.contains(p));
            match (out.next(), out.next()) {
                (Some(&p), None) => Some(p),
                _ => None,
            }
        };
        let (x, y) = (lone(t0, t1)?, lone(t1, t0)?);
        let mut shared = t0.iter().filter(|p| **p != x);
        let (&s0, &s1) = (shared.next()?, shared.next()?);
        let (mut u, mut v) = (s0 - x, s1 - x);
        let gap = ((x + y) - (s0 + s1)).length();
        // A NaN gap (corners at infinity) is no parallelogram either.
        if gap.is_nan() || gap > 1e-5 * (u.length() + v.length()) {
            return None;
        }
        if u.cross(v).dot(*n0) < 0.0 {
            std::mem::swap(&mut u, &mut v);
        }
        let mut quad = QuadLight::new(x, u, v, self.radiance);
        quad.two_sided = self.two_sided;
        Some(quad)
    }

    /// Radiance leaving a point of geometric normal `n` (the triangle's front)
    /// and texture coordinates `uv` toward `w`.
    #[inline]
    pub fn emitted(&self, n: Vec3A, uv: Vec2, w: Vec3A) -> Rgb {
        if !(self.two_sided || n.dot(w) > 0.0) {
            return Rgb::ZERO;
        }
        match &self.texture {
            None => self.radiance,
            Some(t) => t.eval(uv),
        }
    }

    /// Uniform by area over all triangles, converted to solid angle:
    /// pdf = d² / (|cos θl| · A), with `A·Jₖ` for a moving light (see the
    /// module docs).
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        let (k, _, ux) = self.alias.sample(u.x);
        let [a, b, c] = self.tris[k];
        // Uniform on the triangle (square-root parametrisation).
        let su = ux.sqrt();
        let (b1, b2) = (1.0 - su, u.y * su);
        let q = a * b1 + b * b2 + c * (1.0 - b1 - b2);
        let n = self.normals[k];
        // A moving light: the point and normal placed at the path's time.
        let (q, n, area) = match &self.motion {
            None => (q, n, self.area),
            Some(m) => placed(m, q, n, self.area),
        };
        let d = q - p;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        if dist.is_nan() || dist <= 0.0 {
            return None;
        }
        let wi = d / dist;
        let cos_l = -wi.dot(n);
        let cos_l = if self.two_sided { cos_l.abs() } else { cos_l };
        if cos_l.is_nan() || cos_l <= 0.0 {
            return None;
        }
        Some(LightSample {
            wi,
            dist,
            p: q,
            n,
            li: match &self.texture {
                None => self.radiance,
                Some(t) => {
                    let [ua, ub, uc] = self.uvs[k];
                    t.eval(ua * b1 + ub * b2 + uc * (1.0 - b1 - b2))
                }
            },
            pdf: dist2 / (cos_l * area),
            delta: false,
        })
    }

    /// Solid-angle density of [`Self::sample`] for a ray that reached the mesh
    /// along unit `wi` at distance `dist`, where its geometric normal is `n`
    /// (a moving light's at the time traced, as the hit was).
    #[inline]
    pub fn pdf(&self, wi: Vec3A, dist: f32, n: Vec3A) -> f32 {
        let cos_l = wi.dot(n).abs();
        let area = match &self.motion {
            None => self.area,
            Some(m) => moving_area(m, self.area, n),
        };
        if cos_l > 0.0 {
            dist * dist / (cos_l * area)
        } else {
            0.0
        }
    }

    /// Total area in m² (in the mesh's space for a moving light).
    pub fn area(&self) -> f32 {
        self.area
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// World-space bounds of the triangles, and a cone (axis, cos half-angle)
    /// holding every triangle's emitting normal, for the light tree: around
    /// the area-weighted mean normal, or all directions when they cancel.
    /// A moving light is bounded over the whole shutter, so that the tree
    /// never gives it less than it may send at some time: the box its rest
    /// bounds sweep ([`crate::anim::TransformTrack::bounds`], as the
    /// instance's box in the scene BVH), and every direction for its
    /// normals, which the motion may turn anywhere.
    pub fn bounds_and_normal_cone(&self) -> (Aabb, Vec3A, f32) {
        let bounds = self
            .tris
            .iter()
            .fold(Aabb::EMPTY, |acc, t| acc.union(Aabb::from_points(t)));
        if let Some(m) = &self.motion {
            let (lo, hi) = m
                .track
                .bounds(bounds.min.into(), bounds.max.into(), m.shutter.0, m.shutter.1);
            let swept = Aabb::EMPTY.grow_point(lo.into()).grow_point(hi.into());
            return (swept, Vec3A::Z, -1.0);
        }
        let (w, cos_o) = self.rest_normal_cone();
        (bounds, w, cos_o)
    }

    /// The cone (axis, cos half-angle) around the triangles' area-weighted
    /// mean normal holding all of them as they are stored (all directions
    /// when they cancel).
    fn rest_normal_cone(&self) -> (Vec3A, f32) {
        let normals = || self.tris.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a));
        let w = normals().sum::<Vec3A>().normalize_or_zero();
        if w == Vec3A::ZERO {
            return (Vec3A::Z, -1.0);
        }
        let cos_o = normals()
            .filter_map(|n| n.try_normalize())
            .map(|n| n.dot(w))
            .fold(1.0f32, f32::min);
        // A little wider than the tightest: rounding must not leave a
        // normal outside (a wider cone is still a bound).
        (w, (cos_o - 1e-4).max(-1.0))
    }

    /// Φ = π·A·L, twice that when two-sided; for a moving light, with its
    /// area at the shutter's opening (light selection only weighs it).
    pub fn power(&self) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * self.power_area * self.radiance
    }
}

/// A rest-frame sample point `q` with unit normal `n` on a light of rest
/// area `area`, placed by `m` at the path's time: the world point, its unit
/// normal, and the area its density is over (`area · J`, see the module
/// docs). Out of line, as [`moving_area`], so that still lights compile as
/// before.
#[cold]
#[inline(never)]
fn placed(m: &InstanceMotion, q: Vec3A, n: Vec3A, area: f32) -> (Vec3A, Vec3A, f32) {
    let p: Placement = m.now();
    let (nw, scale) = p.normal_and_area_scale(n);
    (p.world_from_object.transform_point3a(q), nw, area * scale)
}

/// The area `area · J` a moving light's density is over at a hit of world
/// normal `n`, at the path's time.
#[cold]
#[inline(never)]
fn moving_area(m: &InstanceMotion, area: f32, n: Vec3A) -> f32 {
    area * m.now().area_scale(n)
}

impl LightModel for MeshLight {
    /// The triangles' box and their normal cone. A moving light's cone is
    /// the whole sphere, but the motion turns its normals, not the share
    /// of its area a point sees: its weight keeps its rest cone's share
    /// (`tree::projected_share`), or a moving panel would weigh a quarter
    /// of a still one.
    fn bounds(&self, phi: f32) -> Option<LightBounds> {
        let (b, w, cos_theta_o) = self.bounds_and_normal_cone();
        let mut lb = LightBounds::surface(b, w, cos_theta_o, self.two_sided, phi);
        if self.motion.is_some() {
            let sides = if self.two_sided { 0.5 } else { 1.0 };
            lb.phi = phi * sides * super::tree::projected_share(self.rest_normal_cone().1);
        }
        Some(lb)
    }
}
