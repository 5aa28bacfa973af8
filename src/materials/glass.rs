//! Smooth dielectric boundary (glass, water): Fresnel-weighted choice between
//! the mirror direction and the refracted one (pbrt-v4 `DielectricBxDF`,
//! <https://pbr-book.org/4ed/Reflection_Models/Dielectric_BSDF>).
//!
//! * **Sides.** The normal points outside: `wo.z > 0` arrives from outside,
//!   `wo.z < 0` from inside the object. `ior` is η(inside)/η(outside).
//! * **Sampling.** Reflect with probability F, refract with 1 − F (Snell's
//!   law); under total internal reflection F = 1. Both lobes are deltas:
//!   `pdf` is the lobe probability and `eval`/`pdf` of a direction are 0.
//! * **Radiance scaling.** Radiance is not invariant across a refraction:
//!   L/η² is. The weight of a refracted *camera* path therefore carries
//!   `(η_from/η_to)²`, i.e. `1/η²` entering a denser medium, where "from" is
//!   `wo`'s side (Mitsuba 3 `dielectric`, radiance mode; Veach's thesis
//!   §5.2). [`BsdfSample::eta`] is `η_to/η_from`, so `weight·eta²` is the
//!   flux-conserving part. The scaling is undone on the way out, so an
//!   object seen through does not change brightness.
//! * **Tint** colours transmitted light only, once per refraction (a cheap
//!   stand-in for absorption inside); reflection off glass stays white.
//! * **Thin** glass is a sheet, not a solid's boundary (Mitsuba 3's
//!   `thindielectric`): light passes straight through (`wi = −wo`, no
//!   bending and no radiance scaling), tinted once, and the light both
//!   faces reflect, bouncing between them, adds up: with F the Fresnel
//!   reflectance at the angle of incidence, R = F + (1 − F)² F / (1 − F²)
//!   = 2F / (1 + F), T = 1 − R. The same from either side.

use super::{Bsdf, BsdfSample, Bxdf, ColorTex, DielectricFresnel, MaterialModel, ScalarTex, Texture};
use super::{TexPoint, TexProbe};
use crate::math::Rgb;
use glam::{Vec2, Vec3A};

/// Smooth-dielectric BSDF at one hit (both lobes are deltas; see the module docs for
/// sides and radiance scaling).
#[derive(Clone, Copy, Debug)]
pub struct Glass {
    /// Index of refraction η(inside)/η(outside), > 0; inside is where the normal does
    /// not point.
    pub ior: f32,
    /// Colour of transmitted light per refraction; reflection stays white.
    pub tint: Rgb,
    /// Which Fresnel formula picks between reflection and refraction.
    pub fresnel: DielectricFresnel,
    /// A thin sheet: straight through, both faces' reflections (module docs).
    pub thin: bool,
}

impl Glass {
    /// The thin sheet's sample (module docs): reflect with probability
    /// R = 2F/(1 + F), else pass straight through, tinted.
    fn sample_thin(&self, wo: Vec3A, u_lobe: f32) -> Option<BsdfSample> {
        let f = self.fresnel.eval(wo.z.abs(), self.ior);
        let r = if f < 1.0 { 2.0 * f / (1.0 + f) } else { 1.0 };
        if u_lobe < r {
            return Some(BsdfSample::delta(
                Vec3A::new(-wo.x, -wo.y, wo.z),
                Rgb::ONE,
                r,
                1.0,
            ));
        }
        Some(BsdfSample::delta(-wo, self.tint, 1.0 - r, 1.0))
    }
}

impl Bxdf for Glass {
    fn eval(&self, _wo: Vec3A, _wi: Vec3A) -> Rgb {
        Rgb::ZERO
    }

    fn pdf(&self, _wo: Vec3A, _wi: Vec3A) -> f32 {
        0.0
    }

    fn sample(&self, wo: Vec3A, u_lobe: f32, _u: Vec2) -> Option<BsdfSample> {
        let cos_o = wo.z;
        if cos_o == 0.0 {
            return None;
        }
        if self.thin {
            return self.sample_thin(wo, u_lobe);
        }
        let f = self.fresnel.eval(cos_o, self.ior);
        // Reflection has throughput F; chosen with probability `prob` (F, or 1
        // under total internal reflection) its weight is 1 either way.
        let mirrored = Vec3A::new(-wo.x, -wo.y, wo.z);
        let reflection = |prob| Some(BsdfSample::delta(mirrored, Rgb::ONE, prob, 1.0));
        if u_lobe < f {
            return reflection(f);
        }
        // Relative IOR η_to/η_from and the normal on wo's side.
        let (eta, n) = if cos_o > 0.0 {
            (self.ior, Vec3A::Z)
        } else {
            (1.0 / self.ior, -Vec3A::Z)
        };
        let cos_o = cos_o.abs();
        // Snell: sin²θt = sin²θo / η².
        let sin2_t = (1.0 - cos_o * cos_o) / (eta * eta);
        if sin2_t >= 1.0 {
            // Total internal reflection (F is already 1 here; guard rounding).
            return reflection(1.0);
        }
        let cos_t = (1.0 - sin2_t).sqrt();
        let wi = (-wo / eta + (cos_o / eta - cos_t) * n).normalize();
        Some(BsdfSample::delta(wi, self.tint / (eta * eta), 1.0 - f, eta))
    }

    fn is_delta(&self) -> bool {
        true
    }

    fn transmits(&self) -> bool {
        true
    }
}

/// A smooth dielectric boundary (glass, water) as the scene gives it: what
/// [`super::Material::Glass`] holds.
#[derive(Clone, Debug)]
pub struct GlassMaterial {
    /// Index of refraction η(inside)/η(outside), > 0.
    pub ior: ScalarTex,
    /// Colour of transmitted light, applied once per refraction.
    pub tint: ColorTex,
    /// Which Fresnel formula chooses between reflection and refraction.
    pub fresnel: DielectricFresnel,
    /// A thin sheet rather than a solid's boundary.
    pub thin: bool,
    /// Absorption coefficient inside the solid, per channel, in 1/scene
    /// units (zero: clear glass); see [`super::Material::interior`].
    pub absorption: Rgb,
}

impl MaterialModel for GlassMaterial {
    #[inline]
    fn bsdf(&self, at: &TexPoint, textures: &[Texture]) -> Bsdf<'_> {
        Bsdf::Glass(Glass {
            ior: self.ior.eval(at, textures),
            tint: self.tint.eval(at, textures),
            fresnel: self.fresnel,
            thin: self.thin,
        })
    }
    /// 1 times the absorption tint, as OIDN asks of dielectrics.
    fn albedo(&self, at: &TexPoint, textures: &[Texture]) -> Rgb {
        self.tint.eval(at, textures)
    }
    fn any_tex(&self, f: &dyn Fn(&dyn TexProbe) -> bool) -> bool {
        f(&self.tint) || f(&self.ior)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::materials::fresnel;
    use crate::math::{Pcg32, sampling};

    fn glass(fresnel: DielectricFresnel) -> Glass {
        Glass {
            ior: 1.5,
            tint: Rgb::ONE,
            fresnel,
            thin: false,
        }
    }

    #[test]
    fn glass_obeys_reflection_and_snell() {
        let g = glass(DielectricFresnel::Exact);
        let mut rng = Pcg32::new(8, 1);
        for _ in 0..2000 {
            let wo = sampling::uniform_sphere(rng.next_vec2());
            let s = g
                .sample(wo, rng.next_f32(), rng.next_vec2())
                .expect("glass always scatters");
            assert!(s.delta && g.is_delta() && (s.wi.length() - 1.0).abs() < 1e-5);
            if s.wi.z * wo.z > 0.0 {
                assert_eq!(
                    (s.wi.x, s.wi.y, s.wi.z),
                    (-wo.x, -wo.y, wo.z),
                    "law of reflection"
                );
                continue;
            }
            // η sin θ is conserved; the tangent part flips, staying in the plane of incidence.
            let (eta_o, eta_i) = if wo.z > 0.0 { (1.0, 1.5) } else { (1.5, 1.0) };
            let sin_o = (1.0 - wo.z * wo.z).sqrt();
            let sin_i = (1.0 - s.wi.z * s.wi.z).sqrt();
            assert!(
                (eta_o * sin_o - eta_i * sin_i).abs() < 1e-4,
                "Snell: {eta_o}·{sin_o} vs {eta_i}·{sin_i}"
            );
            assert!(
                (wo.x * s.wi.y - wo.y * s.wi.x).abs() < 1e-5,
                "wi leaves the plane of incidence"
            );
            assert!(wo.x * s.wi.x + wo.y * s.wi.y <= 1e-6, "tangent part must flip");
            assert!((s.eta - eta_i / eta_o).abs() < 1e-6);
            let want = 1.0 / (s.eta * s.eta);
            assert!(
                (s.weight.x - want).abs() < 1e-6,
                "radiance scaling: {} vs {want}",
                s.weight.x
            );
        }
    }

    #[test]
    fn glass_reflects_with_probability_fresnel() {
        for fr in [DielectricFresnel::Exact, DielectricFresnel::Schlick] {
            let g = glass(fr);
            for (i, cos_o) in [0.95f32, 0.5, 0.1, -0.95, -0.8, -0.5].into_iter().enumerate() {
                let wo = Vec3A::new((1.0 - cos_o * cos_o).sqrt(), 0.0, cos_o);
                let f = fr.eval(cos_o, 1.5);
                let mut rng = Pcg32::new(9, i as u64);
                let n = 200_000;
                let (mut reflected, mut energy) = (0u32, 0.0f64);
                for _ in 0..n {
                    let s = g.sample(wo, rng.next_f32(), rng.next_vec2()).unwrap();
                    reflected += (s.wi.z * wo.z > 0.0) as u32;
                    energy += (s.weight.x * s.eta * s.eta) as f64;
                }
                let p = reflected as f32 / n as f32;
                let sigma = (f * (1.0 - f) / n as f32).sqrt();
                assert!(
                    (p - f).abs() <= 5.0 * sigma + 1e-6,
                    "{fr:?} cos {cos_o}: P(reflect) {p}, F {f}"
                );
                let e = energy / n as f64;
                assert!((0.99..=1.01).contains(&e), "{fr:?} cos {cos_o}: R + T = {e}");
            }
        }
        // Beyond the critical angle (41.8°) from inside, always reflect.
        assert_eq!(fresnel::dielectric(-0.5, 1.5), 1.0);
    }

    /// A thin sheet passes light straight through or mirrors it, from
    /// either side alike, with Mitsuba's `thindielectric` probabilities
    /// (R = 2F/(1 + F): 0.0769 at normal incidence for η 1.5), tints only
    /// what passes, and neither bends nor rescales radiance.
    #[test]
    fn thin_glass_passes_straight_through_with_both_faces_reflecting() {
        let tint = Rgb::new(0.9, 0.5, 0.2);
        let g = Glass {
            thin: true,
            tint,
            ..glass(DielectricFresnel::Exact)
        };
        for (i, cos_o) in [1.0f32, 0.7, 0.2, -0.7, -1.0].into_iter().enumerate() {
            let wo = Vec3A::new((1.0 - cos_o * cos_o).max(0.0).sqrt(), 0.0, cos_o);
            let f = fresnel::dielectric(cos_o.abs(), 1.5);
            let want = 2.0 * f / (1.0 + f);
            let mut rng = Pcg32::new(11, i as u64);
            let n = 200_000;
            let mut reflected = 0u32;
            for _ in 0..n {
                let s = g.sample(wo, rng.next_f32(), rng.next_vec2()).expect("scatters");
                assert!(s.delta && s.eta == 1.0);
                if s.wi.z * wo.z > 0.0 {
                    reflected += 1;
                    assert_eq!((s.wi.x, s.wi.y, s.wi.z), (-wo.x, -wo.y, wo.z));
                    assert_eq!(s.weight, Rgb::ONE);
                } else {
                    assert_eq!(s.wi, -wo, "straight through");
                    assert_eq!(s.weight, tint);
                }
            }
            let p = reflected as f32 / n as f32;
            let sigma = (want * (1.0 - want) / n as f32).sqrt();
            assert!(
                (p - want).abs() <= 5.0 * sigma + 1e-6,
                "cos {cos_o}: {p} vs {want}"
            );
        }
        let f0 = fresnel::dielectric(1.0, 1.5);
        assert!((2.0 * f0 / (1.0 + f0) - 0.076_923).abs() < 1e-4);
    }
}
