//! The environment: radiance arriving from infinitely far away, a constant
//! colour or an equirectangular (latitude–longitude) image, at most one per
//! scene. Camera rays that miss everything see it.
//!
//! # Mapping
//! The radiance arriving from unit direction `d` (pointing from the scene
//! toward the sky), in the environment's own frame, is the image at
//! `u = atan2(d.x, −d.z) / 2π` (wrapped to [0, 1)) and `v = acos(d.y) / π`
//! (computed as `atan2(sin θ, d.y)`), bilinearly interpolated between pixels
//! at `u = (i + ½)/W` and `v = j/(H − 1)`: u = ½ looks along +z, ¼ along +x,
//! the seam is at −z; columns wrap across the seam, row 0 is exactly the
//! zenith and row H − 1 the nadir. This is what Mitsuba 3.9.1's `envmap`
//! evaluates (probed through its Python API: a map whose row j holds j
//! returns `v·(H − 1)`); the Mitsuba reference set's notes give row centres at
//! `(j + ½)/H`, which stretches the sky's rows by H/(H − 1) less and left
//! the floor of `env_spheres` 0.35% darker than Mitsuba's. The environment's
//! frame is the world's turned by `rotation` about +y (right-handed).
//!
//! # Sampling
//! An image is importance sampled in proportion to its bilinearly
//! interpolated `luminance × sin θ` ([`EnvTable`], as Mitsuba 3 does): a
//! cell between four pixel centres by its mean, then a point in it from
//! the bilinear patch, so a sample's weight `L / pdf` hardly varies even
//! across a sun a few pixels wide. A point `(u, v)` of density `p(u, v)` is
//! the direction of density `p(u, v) / (2π² sin θ)`. The image takes 16
//! bytes per pixel (f32 RGB and the corner weight, `env_map.rs`), the
//! cells' CDFs and alias tables about 13 (`env_table.rs`).
//! A constant environment is sampled by the cosine about the shading
//! normal when the integrator gives one (the hemisphere a reflecting
//! surface sees: for an unoccluded Lambert surface every sample then
//! carries the same weight), uniformly over the sphere otherwise
//! (transmitting surfaces, media). Mitsuba 3's `constant` samples the
//! sphere uniformly: half its shadow rays from a floor go into the floor.

use super::env_map::EnvMap;
use super::env_table::EnvTable;
use super::irradiance::{ShSum, SkyWeight};
use super::tree::LightBounds;
use super::{LightModel, LightSample};
use crate::math::Frame;
use crate::math::sampling::{UNIFORM_SPHERE_PDF, cosine_hemisphere, uniform_sphere};
use crate::math::trig::{sin_cos_turns, turns_lanes};
use crate::math::{Rgb, luminance};
use crate::sampler::Draw;
use glam::{Vec2, Vec3A, Vec4};
use rayon::prelude::*;
use std::f32::consts::PI;

/// How next-event estimation picks directions toward the environment.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum EnvSampling {
    /// By the image's bilinear luminance × sin θ; a constant environment by
    /// the cosine about the shading normal (over the sphere without one).
    #[default]
    Importance,
    /// Uniformly over the sphere: only for comparisons (`tests/reference.rs`
    /// measures what importance sampling gains).
    Uniform,
}

/// Radiance from infinitely far away in every direction; see the module docs.
#[derive(Clone, Debug)]
pub struct EnvironmentLight {
    /// Multiplies the image (or is the constant radiance), W/(m²·sr).
    scale: Rgb,
    map: Option<EnvMap>,
    distribution: Option<EnvTable>,
    /// cos and sin of the rotation about +y (world from environment).
    cos_sin: (f32, f32),
    /// Which directions next-event estimation draws.
    pub sampling: EnvSampling,
    /// Whether camera rays that miss see the environment (else `background`).
    pub visible: bool,
    /// What camera rays that miss see when not `visible`, W/(m²·sr).
    pub background: Rgb,
    /// Radius of the scene's bounding sphere, for [`Self::power`].
    pub scene_radius: f32,
    /// Power, ∫ L dω over the sphere, W/(m²) per channel (cached).
    radiant_exitance: Rgb,
    /// Irradiance and its second moment by surface normal, world frame
    /// (light selection's weight for the sky).
    weight: SkyWeight,
}

impl EnvironmentLight {
    /// A constant environment of radiance `radiance` (W/(m²·sr)) from every
    /// direction.
    pub fn constant(radiance: Rgb) -> Self {
        Self {
            scale: radiance,
            map: None,
            distribution: None,
            cos_sin: (1.0, 0.0),
            sampling: EnvSampling::Importance,
            visible: true,
            background: Rgb::ZERO,
            scene_radius: 1.0,
            radiant_exitance: 4.0 * PI * radiance,
            weight: SkyWeight::constant(radiance),
        }
    }

    /// The image `map` times `strength`, turned by `rotation_degrees` about +y;
    /// builds the sampling tables on all cores.
    pub fn from_map(map: EnvMap, strength: f32, rotation_degrees: f32) -> Self {
        let (w, h) = (map.width as usize, map.height as usize);
        let mut map = map;
        let distribution = EnvTable::new(&mut map);
        // ∫ L dω of the bilinear image, exactly: (2π/W) Σ_j ω_j Σ_i L(i, j),
        // with ω_j = ∫ sin θ of row j's hat function in θ (θj = πj/(H − 1)).
        let sum: [f64; 3] = map
            .texels
            .par_chunks(w)
            .enumerate()
            .map(|(j, row)| {
                let s = row_weight(j, h);
                let mut acc = [0.0f64; 3];
                for px in row {
                    for c in 0..3 {
                        acc[c] += px[c].max(0.0) as f64 * s;
                    }
                }
                acc
            })
            .reduce(|| [0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        let cell = 2.0 * std::f64::consts::PI / w as f64;
        let integral = Rgb::new(sum[0] as f32, sum[1] as f32, sum[2] as f32) * (cell as f32);
        let (s, c) = rotation_degrees.to_radians().sin_cos();
        let weight = map_weight(&map, strength, (c, s));
        Self {
            scale: Rgb::splat(strength),
            map: Some(map),
            distribution: Some(distribution),
            cos_sin: (c, s),
            sampling: EnvSampling::Importance,
            visible: true,
            background: Rgb::ZERO,
            scene_radius: 1.0,
            radiant_exitance: strength * integral,
            weight,
        }
    }

    /// World direction `d` in the environment's frame (turned back by the rotation).
    #[inline]
    fn to_env(&self, d: Vec3A) -> Vec3A {
        let (c, s) = self.cos_sin;
        Vec3A::new(c * d.x - s * d.z, d.y, s * d.x + c * d.z)
    }

    /// Environment direction `d` in the world (turned by the rotation).
    #[inline]
    fn to_world(&self, d: Vec3A) -> Vec3A {
        turn(self.cos_sin, d)
    }

    /// Image coordinates of environment-frame direction `d` (unit); the
    /// spherical camera (`camera/spherical.rs`) inverts it.
    #[inline]
    pub fn uv(d: Vec3A) -> Vec2 {
        // θ = atan2(sin θ, cos θ): acos(d.y) loses precision near the poles.
        // Both angles in lanes of one computation ([`turns_lanes`]).
        let sin_t = (d.x * d.x + d.z * d.z).sqrt();
        let turns = turns_lanes(Vec4::new(d.x, sin_t, 0.0, 0.0), Vec4::new(-d.z, d.y, 1.0, 1.0));
        let mut u = turns.x;
        if u < 0.0 {
            u += 1.0;
        }
        Vec2::new(u.min(1.0 - f32::EPSILON), turns.y)
    }

    /// Radiance arriving from world direction `d` (unit, pointing away from the
    /// scene), W/(m²·sr).
    #[inline]
    pub fn le(&self, d: Vec3A) -> Rgb {
        match &self.map {
            Some(m) => self.scale * m.lookup(Self::uv(self.to_env(d))),
            None => self.scale,
        }
    }

    /// What a camera ray that misses everything sees along `d`: the
    /// environment, or the background when the environment is not `visible`.
    #[inline]
    pub fn seen_by_camera(&self, d: Vec3A) -> Rgb {
        if self.visible { self.le(d) } else { self.background }
    }

    /// A direction toward the environment for `u` ∈ [0, 1)², seen from a
    /// surface of unit normal `n` on the side light is wanted from (zero:
    /// every direction, for transmitting surfaces); the sample's distance is
    /// infinite (shadow rays are unbounded). `draw`: whether `u` is
    /// stratified across the pixel's samples (`env_table.rs`).
    pub fn sample(&self, p: Vec3A, n: Vec3A, u: Vec2, draw: Draw) -> Option<LightSample> {
        let (wi, pdf, li) = match (&self.distribution, &self.map, self.sampling) {
            (Some(dist), Some(m), EnvSampling::Importance) => {
                let (uv, uv_pdf, at) = dist.sample(m, u, draw);
                // θ = π v is half a turn of v, φ = 2π u a turn of u.
                let (sin_t, cos_t) = sin_cos_turns(0.5 * uv.y);
                if sin_t <= 0.0 || uv_pdf <= 0.0 {
                    return None;
                }
                let (sin_p, cos_p) = sin_cos_turns(uv.x);
                let d = Vec3A::new(sin_t * sin_p, cos_t, -sin_t * cos_p);
                // The image at the sampled point: no atan2/acos round trip,
                // and the pixels the sample was drawn between.
                let li = self.scale * m.bilerp(&at);
                (self.to_world(d), uv_pdf / (2.0 * PI * PI * sin_t), li)
            }
            (None, _, EnvSampling::Importance) if n != Vec3A::ZERO => {
                let local = cosine_hemisphere(u);
                if local.z <= 0.0 {
                    return None;
                }
                let d = Frame::from_normal(n).to_world(local);
                (d, local.z * std::f32::consts::FRAC_1_PI, self.scale)
            }
            _ => {
                let d = uniform_sphere(u);
                (d, UNIFORM_SPHERE_PDF, self.le(d))
            }
        };
        Some(LightSample {
            wi,
            dist: f32::INFINITY,
            p,
            n: Vec3A::ZERO,
            li,
            pdf,
            delta: false,
        })
    }

    /// Asks for the memory [`Self::sample`] will read for the numbers `u`
    /// ([`EnvTable::prefetch`]): only independent draws of a sky map
    /// sampled by importance read a table entry chosen by a number.
    #[inline]
    pub fn prefetch(&self, u: Vec2, draw: Draw) {
        if let (Some(dist), Some(m), EnvSampling::Importance, Draw::Independent) =
            (&self.distribution, &self.map, self.sampling, draw)
        {
            dist.prefetch(m, u);
        }
    }

    /// Solid-angle density with which [`Self::sample`] from a surface of
    /// normal `n` draws world direction `d`.
    #[inline]
    pub fn pdf(&self, d: Vec3A, n: Vec3A) -> f32 {
        match (&self.distribution, &self.map, self.sampling) {
            (Some(dist), Some(m), EnvSampling::Importance) => {
                let e = self.to_env(d);
                let sin_t = (e.x * e.x + e.z * e.z).sqrt();
                if sin_t <= 0.0 {
                    return 0.0;
                }
                // Through the lookup's footprint, as `le_and_pdf` (bit for bit).
                dist.pdf_at(m, &m.footprint(Self::uv(e))) / (2.0 * PI * PI * sin_t)
            }
            (None, _, EnvSampling::Importance) if n != Vec3A::ZERO => {
                n.dot(d).max(0.0) * std::f32::consts::FRAC_1_PI
            }
            _ => UNIFORM_SPHERE_PDF,
        }
    }

    /// [`Self::le`] and [`Self::pdf`] of world direction `d` at once, for a
    /// BSDF sample that escaped: the direction is mapped to the image once
    /// (two `atan2`, ~95 instructions), not twice. Same values, bit for bit.
    /// Not inlined: inside `Path::li` it changed the loop's code enough to
    /// cost scenes without an environment 0.2% (callgrind, `cornell`).
    #[inline(never)]
    pub fn le_and_pdf(&self, d: Vec3A, n: Vec3A) -> (Rgb, f32) {
        let Some(m) = &self.map else {
            return (self.scale, self.pdf(d, n));
        };
        let e = self.to_env(d);
        let at = m.footprint(Self::uv(e));
        let le = self.scale * m.bilerp(&at);
        let pdf = match (&self.distribution, self.sampling) {
            (Some(dist), EnvSampling::Importance) => {
                let sin_t = (e.x * e.x + e.z * e.z).sqrt();
                if sin_t <= 0.0 {
                    return (le, 0.0);
                }
                // The lookup's footprint is the table's cell.
                dist.pdf_at(m, &at) / (2.0 * PI * PI * sin_t)
            }
            _ => UNIFORM_SPHERE_PDF,
        };
        (le, pdf)
    }

    /// `∫ L dω` over the sphere, W/m² per channel: what the sky sends
    /// through a unit area facing it, summed over every way it faces.
    pub fn radiance_integral(&self) -> Rgb {
        self.radiant_exitance
    }

    /// Power for light selection: the flux through the scene's bounding disk,
    /// π·R²·∫L dω (pbrt-v4's `ImageInfiniteLight::Phi`), W per channel.
    pub fn power(&self) -> Rgb {
        PI * self.scene_radius * self.scene_radius * self.radiant_exitance
    }

    /// Its weight in light selection by surface normal, in the world
    /// (from its irradiance and that of its square).
    pub fn weight(&self) -> &SkyWeight {
        &self.weight
    }

    /// The image, if the environment has one (not a constant).
    pub fn map(&self) -> Option<&EnvMap> {
        self.map.as_ref()
    }

    /// Heap bytes of the sampling tables (the image itself not included).
    pub fn table_bytes(&self) -> usize {
        self.distribution.as_ref().map_or(0, EnvTable::bytes)
    }
}

/// Direction `d` turned about +y by the angle of cosine and sine `cos_sin`
/// (world from environment).
#[inline]
fn turn((c, s): (f32, f32), d: Vec3A) -> Vec3A {
    Vec3A::new(c * d.x + s * d.z, d.y, -s * d.x + c * d.z)
}

/// Solid angle per unit of `φ` (2π in all) of row `j` of `h`: the integral
/// of `sin θ` under the row's hat function in θ (rows at θj = πj/(h − 1)),
/// exactly, so the rows' weights sum to 2 as `∫ sin θ dθ` does.
fn row_weight(j: usize, h: usize) -> f64 {
    if h == 1 {
        return 2.0;
    }
    let step = std::f64::consts::PI / (h - 1) as f64;
    // Over [a, a + step], ∫ t sin θ dθ with t rising 0 → 1, and the rest.
    let rising = |a: f64| {
        let b = a + step;
        (b.sin() - a.sin()) / step - b.cos()
    };
    let falling = |a: f64| (a.cos() - (a + step).cos()) - rising(a);
    let theta = j as f64 * step;
    let below = if j + 1 < h { falling(theta) } else { 0.0 };
    let above = if j > 0 { rising(theta - step) } else { 0.0 };
    below + above
}

/// The irradiance by world normal of `map` × `strength` turned by
/// `cos_sin` about +y, and that of its square: every texel's luminance (and
/// its square) × solid angle projected on the first nine spherical
/// harmonics, rows in parallel.
fn map_weight(map: &EnvMap, strength: f32, cos_sin: (f32, f32)) -> SkyWeight {
    let (w, h) = (map.width as usize, map.height as usize);
    let dphi = 2.0 * PI / w as f32;
    // Columns are summed in blocks of `bw` (at most 1,024 blocks a row) and
    // each block projected once from its centre: the irradiance is smooth,
    // a block is at most ~0.35° wide on the widest maps, and the SH terms
    // per texel were most of the load time of an 8192 × 4096 map.
    let bw = w.div_ceil(1024).max(1);
    let blocks: Vec<(f32, f32)> = (0..w.div_ceil(bw))
        .map(|k| {
            let (first, last) = (k * bw, ((k + 1) * bw).min(w));
            let centre = 0.5 * (first + last) as f32;
            (2.0 * PI * centre / w as f32).sin_cos()
        })
        .collect();
    let sum = map
        .texels
        .par_chunks(w)
        .enumerate()
        .map(|(j, row)| {
            let d_omega = row_weight(j, h) as f32 * dphi;
            let theta = if h > 1 {
                PI * j as f32 / (h - 1) as f32
            } else {
                0.5 * PI
            };
            let (sin_t, cos_t) = theta.sin_cos();
            let (mut acc, mut acc2) = (ShSum::default(), ShSum::default());
            for (block, &(sin_p, cos_p)) in row.chunks(bw).zip(&blocks) {
                let (mut l, mut l2) = (0.0f32, 0.0f32);
                for px in block {
                    let v = strength * luminance(Rgb::new(px[0], px[1], px[2])).max(0.0);
                    l += v;
                    l2 += v * v;
                }
                // The image's direction (as `sample` maps it), turned into the world.
                let d = turn(cos_sin, Vec3A::new(sin_t * sin_p, cos_t, -sin_t * cos_p));
                acc.add(d, l * d_omega);
                acc2.add(d, l2 * d_omega);
            }
            (acc, acc2)
        })
        .reduce(
            || (ShSum::default(), ShSum::default()),
            |a, b| (a.0.merge(b.0), a.1.merge(b.1)),
        );
    SkyWeight::new(sum.0.irradiance(), sum.1.irradiance())
}

impl LightModel for EnvironmentLight {
    /// None: the sky is infinitely far; the tree weighs it beside its root
    /// by its irradiance instead.
    fn bounds(&self, _phi: f32) -> Option<LightBounds> {
        None
    }
    fn as_environment(&self) -> Option<&EnvironmentLight> {
        Some(self)
    }
}
