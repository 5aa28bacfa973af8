//! Emissive triangles: the emitting part of a placed mesh (one material slot
//! of one `Mesh` or `Instance` object), sampled uniformly by area — a
//! triangle by an alias table over the areas, then a uniform point on it.

use super::LightSample;
use super::QuadLight;
use super::alias::AliasTable;
use super::emission::{Emission, EmissionTexture};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};
use std::f32::consts::PI;
use std::sync::Arc;

/// Triangles emitting uniform radiance from their front (the side their
/// counter-clockwise winding faces), or both sides when `two_sided`; in world
/// space, copied from the placed mesh (48 bytes per triangle for its corners,
/// 16 for its normal and 12 for the alias table).
#[derive(Clone, Debug)]
pub struct MeshLight {
    /// World-space corners, wound so that `(b − a) × (c − a)` is the emitting side.
    tris: Vec<[Vec3A; 3]>,
    /// Unit normal of each triangle's emitting side (zero when degenerate),
    /// kept rather than made from the corners at every sample.
    normals: Vec<Vec3A>,
    /// Picks a triangle in proportion to its area.
    alias: AliasTable,
    /// Total area in m².
    area: f32,
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

    /// The same light as one parallelogram, when it is one: two untextured
    /// triangles sharing an edge, coplanar, wound alike, whose unshared
    /// corners sum to the shared ones (the rectangle an OBJ file writes for
    /// an area lamp). A [`QuadLight`] samples the same uniform-by-area
    /// density without the alias table and the triangle's square root, and
    /// a rectangle near a shading point by solid angle instead; the OBJ
    /// Cornell box spent 10% of its time in [`MeshLight::sample`] against
    /// 2.4% for the analytic box's quad light.
    pub fn as_parallelogram(&self) -> Option<QuadLight> {
        let ([t0, t1], [n0, n1]) = (self.tris.as_slice(), self.normals.as_slice()) else {
            return None;
        };
        if self.texture.is_some() || n0.dot(*n1) < 1.0 - 1e-6 {
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
        if !(gap <= 1e-5 * (u.length() + v.length())) {
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
    /// pdf = d² / (|cos θl| · A).
    pub fn sample(&self, p: Vec3A, u: Vec2) -> Option<LightSample> {
        let (k, _, ux) = self.alias.sample(u.x);
        let [a, b, c] = self.tris[k];
        // Uniform on the triangle (square-root parametrisation).
        let su = ux.sqrt();
        let (b1, b2) = (1.0 - su, u.y * su);
        let q = a * b1 + b * b2 + c * (1.0 - b1 - b2);
        let n = self.normals[k];
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
            pdf: dist2 / (cos_l * self.area),
            delta: false,
        })
    }

    /// Solid-angle density of [`Self::sample`] for a ray that reached the mesh
    /// along unit `wi` at distance `dist`, where its geometric normal is `n`.
    #[inline]
    pub fn pdf(&self, wi: Vec3A, dist: f32, n: Vec3A) -> f32 {
        let cos_l = wi.dot(n).abs();
        if cos_l > 0.0 {
            dist * dist / (cos_l * self.area)
        } else {
            0.0
        }
    }

    /// Total area in m².
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
    pub fn bounds_and_normal_cone(&self) -> (crate::accel::Aabb, Vec3A, f32) {
        let bounds = self.tris.iter().fold(crate::accel::Aabb::EMPTY, |acc, t| {
            acc.union(crate::accel::Aabb::from_points(t))
        });
        let normals = || self.tris.iter().map(|[a, b, c]| (*b - *a).cross(*c - *a));
        let w = normals().sum::<Vec3A>().normalize_or_zero();
        if w == Vec3A::ZERO {
            return (bounds, Vec3A::Z, -1.0);
        }
        let cos_o = normals()
            .filter_map(|n| n.try_normalize())
            .map(|n| n.dot(w))
            .fold(1.0f32, f32::min);
        // A little wider than the tightest: rounding must not leave a
        // normal outside (a wider cone is still a bound).
        (bounds, w, (cos_o - 1e-4).max(-1.0))
    }

    /// Φ = π·A·L, twice that when two-sided.
    pub fn power(&self) -> Rgb {
        let sides = if self.two_sided { 2.0 } else { 1.0 };
        sides * PI * self.area * self.radiance
    }
}
