//! What a material does to the surface itself rather than to light: a
//! shading normal from a normal or bump map, alpha cut-outs, and which of a
//! blend's two materials a hit is shaded with. The scene
//! applies these at intersection time (`Scene::intersect`), so every
//! integrator, shadow ray and AOV sees the same surface; the BSDFs never
//! know.
//!
//! # Normal maps (Mitsuba's `normalmap`, pbrt-v4's `NormalMap`)
//! The texel c (linear) gives `n_t = normalize(2c − 1)` in the tangent frame
//! `(s, t, n)`: `s` is ∂p/∂u made perpendicular to `n`, `t = n × s` (so
//! green runs along +v), `n` the unperturbed normal. `strength` k scales the
//! tilt: `(k·x, k·y, z)`. A map whose tilt is exactly 0 (the flat colour
//! (0.5, 0.5, 1)) returns `n` bit for bit.
//!
//! # Bump maps (pbrt-v4 `BumpMap`, without the ∂n/∂u term)
//! The surface is displaced by `h(u, v)·scale` along `n`:
//! `∂p'/∂u ≈ ∂p/∂u + (∂h/∂u)·n`, likewise for v, and
//! `n' = normalize(∂p'/∂u × ∂p'/∂v)` on `n`'s side. Derivatives are central
//! differences over 1/1024 of a UV unit.
//!
//! # Blends (pbrt-v4's `MixMaterial`)
//! A blend of `a` and `b` with weight w reflects (1 − w)·f_a + w·f_b. As
//! pbrt-v4 does, each hit picks one of the two, `b` with probability w, by
//! a hash of the ray and the hit (the same whatever the thread or tiling),
//! and everything after — light sampling, the BSDF's sample and its MIS
//! weights — is that material's: the estimate's expectation over the pick
//! is the mix, without a BSDF that knows of two lobes' pdfs (a blend of
//! glass and plaster would need a delta and a smooth pdf in one sum). Each
//! component is a material of its own in the scene's table, with its own
//! surface effects; the choice is made before them.
//!
//! # Light leaks
//! A perturbed normal can face away from a viewer who sees the front of the
//! geometric surface. As Mitsuba (with `flip_invalid_normals = false`), the
//! surface is then black for that ray: the scene swaps in a black material
//! ([`Surface::valid_for`]); no flipping, no shadowing term. Light arriving
//! from below the geometric surface but above the perturbed one is
//! reflected, as in Mitsuba; transmission through opaque models cannot
//! happen because their BSDFs are zero across the perturbed surface.

use super::TexPoint;
use super::{ColorTex, ScalarTex, Texture};
use crate::geometry::TangentFrame;
use glam::{Vec2, Vec3A};

/// A material's effect on the surface (none for most).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Surface {
    /// Replaces the shading normal.
    pub normal: Option<Perturb>,
    /// Removes the surface where it is transparent.
    pub cutout: Option<Cutout>,
    /// Hands the hit to one of two materials.
    pub blend: Option<Blend>,
    /// The material, its surface or a blend's pick reads the vertex colour:
    /// the scene interpolates it at the hit.
    pub vertex_color: bool,
}

/// A blend: the hit is shaded by material `b` with probability `weight`,
/// by `a` otherwise (indices in the scene's material table).
#[derive(Clone, Debug, PartialEq)]
pub struct Blend {
    /// The share of `b`, clamped to [0, 1].
    pub weight: ScalarTex,
    /// The material where the weight is 0.
    pub a: u32,
    /// The material where the weight is 1.
    pub b: u32,
}

impl Blend {
    /// The material a hit at `uv` is shaded with, for its uniform number
    /// `u` ∈ [0, 1), and `u` stretched back over [0, 1) for the choice the
    /// chosen material may make in turn (a blend inside a blend).
    #[inline]
    pub fn pick(&self, at: &TexPoint, textures: &[Texture], u: f32) -> (u32, f32) {
        let w = self.weight.eval(at, textures);
        let w = if w.is_nan() { 0.0 } else { w.clamp(0.0, 1.0) };
        if u < w {
            (self.b, (u / w).min(ONE_MINUS_EPSILON))
        } else {
            (self.a, ((u - w) / (1.0 - w)).clamp(0.0, ONE_MINUS_EPSILON))
        }
    }
}

/// The largest `f32` below 1.
const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// How a shading normal is perturbed.
#[derive(Clone, Debug, PartialEq)]
pub enum Perturb {
    /// Tangent-space normal map.
    NormalMap {
        /// Linear texels, `normalize(2c − 1)` in (s, t, n).
        map: ColorTex,
        /// Factor on the tilt.
        strength: f32,
        /// Negate green (DirectX-style maps).
        flip_green: bool,
        /// Where the tangent frame comes from on meshes.
        frame: TangentFrame,
    },
    /// Bump (height) map.
    Bump {
        /// Height, in units of `scale`.
        height: ScalarTex,
        /// Scene units per unit of height.
        scale: f32,
    },
}

/// An alpha cut-out.
#[derive(Clone, Debug, PartialEq)]
pub struct Cutout {
    /// Opacity in [0, 1].
    pub opacity: ScalarTex,
    /// `None`: stochastic (present with probability = opacity); `Some(c)`:
    /// present where opacity ≥ c.
    pub threshold: Option<f32>,
}

impl Surface {
    /// True when the material leaves the surface as it is.
    pub fn is_plain(&self) -> bool {
        self.normal.is_none() && self.cutout.is_none() && self.blend.is_none() && !self.vertex_color
    }

    /// Whether a map, cut-out or blend weight of this surface reads the
    /// vertex colour.
    pub fn reads_vertex_color(&self) -> bool {
        let normal = match &self.normal {
            Some(Perturb::NormalMap { map, .. }) => map.reads_vertex_color(),
            Some(Perturb::Bump { height, .. }) => height.reads_vertex_color(),
            None => false,
        };
        normal
            || self
                .cutout
                .as_ref()
                .is_some_and(|c| c.opacity.reads_vertex_color())
            || self.blend.as_ref().is_some_and(|b| b.weight.reads_vertex_color())
    }
}

impl Cutout {
    /// Whether the surface is there at `uv` for a ray whose own uniform
    /// number is `u` ∈ [0, 1).
    #[inline]
    pub fn present(&self, at: &TexPoint, textures: &[Texture], u: f32) -> bool {
        let a = self.opacity.eval(at, textures);
        match self.threshold {
            Some(c) => a >= c,
            None => u < a,
        }
    }
}

impl Perturb {
    /// The perturbed unit normal at `uv`, on `n`'s side for bump maps; `dpdu`,
    /// `dpdv` are the surface's derivatives (only their directions matter to
    /// normal maps) and `sign` the handedness of a mesh's tangent (the
    /// bitangent is `sign·(n × s)`; 1 on every other shape, whose frames
    /// follow Mitsuba's `n × s` whatever the UVs' orientation).
    #[inline]
    pub fn normal(
        &self,
        n: Vec3A,
        dpdu: Vec3A,
        dpdv: Vec3A,
        sign: f32,
        at: &TexPoint,
        textures: &[Texture],
    ) -> Vec3A {
        match self {
            Perturb::NormalMap {
                map,
                strength,
                flip_green,
                ..
            } => {
                let c = map.eval(at, textures);
                let mut t = 2.0 * c - crate::math::Rgb::ONE;
                if *flip_green {
                    t.y = -t.y;
                }
                t.x *= strength;
                t.y *= strength;
                if t.x == 0.0 && t.y == 0.0 {
                    return n;
                }
                // normalize(normalize(t) in the frame) is normalize(t in the
                // frame): (s, ±n × s, n) is orthonormal, so the texel's own
                // normalisation (a square root and a division on the
                // shading chain) changes nothing but the rounding.
                let (s, bt) = tangent_frame(n, dpdu);
                (t.x * s + t.y * sign * bt + t.z * n).try_normalize().unwrap_or(n)
            }
            Perturb::Bump { height, scale } => {
                const DU: f32 = 1.0 / 1024.0;
                let h = |d: Vec2| {
                    let shifted = TexPoint { uv: at.uv + d, ..*at };
                    height.eval(&shifted, textures) * scale
                };
                let dhdu = (h(Vec2::new(DU, 0.0)) - h(Vec2::new(-DU, 0.0))) / (2.0 * DU);
                let dhdv = (h(Vec2::new(0.0, DU)) - h(Vec2::new(0.0, -DU))) / (2.0 * DU);
                if dhdu == 0.0 && dhdv == 0.0 {
                    return n;
                }
                let (s, t) = tangent_frame(n, dpdu);
                // Keep the parametrisation's lengths: a bump of given height
                // tilts less on a larger surface.
                let (lu, lv) = (dpdu.length().max(1e-12), dpdv.length().max(1e-12));
                let pu = s * lu + dhdu * n;
                let pv = t * lv + dhdv * n;
                let np = pu.cross(pv).try_normalize().unwrap_or(n);
                if np.dot(n) < 0.0 { -np } else { np }
            }
        }
    }
}

/// The unit tangent `s` (∂p/∂u made perpendicular to `n`) and `t = n × s`;
/// any perpendicular pair where ∂p/∂u is parallel to `n` or zero (a pole).
#[inline]
pub fn tangent_frame(n: Vec3A, dpdu: Vec3A) -> (Vec3A, Vec3A) {
    let s = match (dpdu - n * n.dot(dpdu)).try_normalize() {
        Some(s) => s,
        None => crate::math::Frame::from_normal(n).s,
    };
    (s, n.cross(s))
}

/// Whether a ray arriving along `d` may shade with normal `ns` on a surface of
/// geometric normal `ng`: `-d` must lie on the same side of both (see the
/// module docs on light leaks).
#[inline]
pub fn valid_for(d: Vec3A, ng: Vec3A, ns: Vec3A) -> bool {
    d.dot(ng) * d.dot(ns) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::Tex;
    use crate::math::Rgb;

    /// `b` with probability w, and the number handed on is uniform again
    /// on either side (a nested blend's pick is independent of this one).
    #[test]
    fn blend_picks_b_with_probability_weight_and_hands_on_a_uniform_number() {
        for w in [0.0, 0.3, 1.0, 1.7, f32::NAN] {
            let blend = Blend {
                weight: Tex::Const(w),
                a: 4,
                b: 9,
            };
            let n = 10_000;
            let (mut picked_b, mut below_half) = ([0u32; 2], [0u32; 2]);
            for k in 0..n {
                let u = (k as f32 + 0.5) / n as f32;
                let (m, rest) = blend.pick(&TexPoint::uv(Vec2::ZERO), &[], u);
                assert!((0.0..1.0).contains(&rest), "w {w}, u {u}: handed on {rest}");
                let side = usize::from(m == 9);
                assert!(m == 4 || m == 9);
                picked_b[side] += 1;
                below_half[side] += u32::from(rest < 0.5);
            }
            let share = picked_b[1] as f32 / n as f32;
            let want = if w.is_nan() { 0.0 } else { w.clamp(0.0, 1.0) };
            assert!((share - want).abs() < 1e-3, "w {w}: b picked {share}");
            for side in 0..2 {
                if picked_b[side] > 0 {
                    let half = below_half[side] as f32 / picked_b[side] as f32;
                    assert!((half - 0.5).abs() < 2e-3, "w {w}, side {side}: {half} below ½");
                }
            }
        }
    }

    #[test]
    fn flat_normal_map_keeps_the_normal_bit_for_bit() {
        let flat = Perturb::NormalMap {
            map: Tex::Const(Rgb::new(0.5, 0.5, 1.0)),
            strength: 1.0,
            flip_green: false,
            frame: TangentFrame::Vertex,
        };
        let n = Vec3A::new(0.3, 0.4, 0.5).normalize();
        let got = flat.normal(n, Vec3A::X, Vec3A::Y, -1.0, &TexPoint::uv(Vec2::ZERO), &[]);
        assert_eq!(got.to_array().map(f32::to_bits), n.to_array().map(f32::to_bits));
    }

    #[test]
    fn normal_map_tilts_toward_the_tangents() {
        // Red > 0.5 tilts toward +u (s), green > 0.5 toward +v (t = n × s).
        let n = Vec3A::Y;
        let (dpdu, dpdv) = (Vec3A::X, Vec3A::NEG_Z);
        let map = |c: Rgb, flip_green| Perturb::NormalMap {
            map: Tex::Const(c),
            strength: 1.0,
            flip_green,
            frame: TangentFrame::Vertex,
        };
        let r =
            map(Rgb::new(1.0, 0.5, 1.0), false).normal(n, dpdu, dpdv, 1.0, &TexPoint::uv(Vec2::ZERO), &[]);
        assert!(r.x > 0.6 && r.y > 0.6, "red tilts to +x: {r}");
        let g =
            map(Rgb::new(0.5, 1.0, 1.0), false).normal(n, dpdu, dpdv, 1.0, &TexPoint::uv(Vec2::ZERO), &[]);
        assert!(g.z < -0.6, "green tilts to +v = −z: {g}");
        let g = map(Rgb::new(0.5, 1.0, 1.0), true).normal(n, dpdu, dpdv, 1.0, &TexPoint::uv(Vec2::ZERO), &[]);
        assert!(g.z > 0.6, "flipped green tilts to +z: {g}");
        // A left-handed mesh tangent (mirrored UVs) turns the bitangent.
        let g =
            map(Rgb::new(0.5, 1.0, 1.0), false).normal(n, dpdu, dpdv, -1.0, &TexPoint::uv(Vec2::ZERO), &[]);
        assert!(g.z > 0.6, "green with handedness −1 tilts to +z: {g}");
    }

    #[test]
    fn bump_of_a_constant_height_keeps_the_normal() {
        let bump = Perturb::Bump {
            height: Tex::Pattern {
                pattern: crate::materials::Pattern::Stripes { duty: 2.0 },
                a: 0.0,
                b: 0.0,
                uv: Default::default(),
            },
            scale: 1.0,
        };
        let n = Vec3A::Y;
        assert_eq!(
            bump.normal(
                n,
                Vec3A::X,
                Vec3A::NEG_Z,
                1.0,
                &TexPoint::uv(Vec2::splat(0.5)),
                &[]
            ),
            n
        );
    }

    #[test]
    fn cutout_threshold_and_stochastic() {
        let c = Cutout {
            opacity: Tex::Const(0.3),
            threshold: Some(0.5),
        };
        assert!(!c.present(&TexPoint::uv(Vec2::ZERO), &[], 0.0));
        let c = Cutout {
            opacity: Tex::Const(0.3),
            threshold: None,
        };
        assert!(
            c.present(&TexPoint::uv(Vec2::ZERO), &[], 0.29)
                && !c.present(&TexPoint::uv(Vec2::ZERO), &[], 0.31)
        );
    }
}
