//! Fresnel reflectance for unpolarised light: exact dielectric and conductor
//! equations, Schlick's approximation, and named metal presets.
//!
//! `cos_i` is always measured against the normal of the side the light
//! arrives from, except in [`dielectric`] and [`schlick_dielectric`], which
//! accept a negative cosine meaning "arriving from below" and then use
//! `1/eta`, as pbrt-v4 does
//! (<https://pbr-book.org/4ed/Reflection_Models/Specular_Reflection_and_Transmission>).
//!
//! Metal constants: spectral η, k of the elements integrated to linear sRGB,
//! as tabulated in Tungsten's `ComplexIorData.hpp` (B. Bitterli, from the
//! Mitsuba 0.5 spectral data), <https://github.com/tunabrain/tungsten>.

use crate::math::Rgb;
use glam::Vec4;

/// Reflectance model of a [`super::CookTorrance`] surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fresnel {
    /// Exact conductor Fresnel with complex IOR `eta + i·k` per channel,
    /// relative to the outside medium.
    Conductor {
        /// Real part of the index of refraction per channel, > 0.
        eta: Rgb,
        /// Extinction coefficient (imaginary part) per channel, ≥ 0.
        k: Rgb,
    },
    /// Schlick's approximation with reflectance `f0` at normal incidence.
    Schlick {
        /// Reflectance at normal incidence per channel, in [0, 1].
        f0: Rgb,
    },
}

impl Fresnel {
    /// Reflectance per channel for light arriving at angle cosine `cos_i` to the
    /// (micro)surface normal.
    #[inline]
    pub fn eval(&self, cos_i: f32) -> Rgb {
        match self {
            Fresnel::Conductor { eta, k } => conductor(cos_i, *eta, *k),
            Fresnel::Schlick { f0 } => schlick(*f0, cos_i),
        }
    }
}

/// Which formula a smooth dielectric uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DielectricFresnel {
    /// The exact Fresnel equations ([`dielectric`]).
    Exact,
    /// Schlick's approximation ([`schlick_dielectric`]): cheaper, close to exact for
    /// glass-like indices.
    Schlick,
}

impl DielectricFresnel {
    /// Reflectance for light arriving at angle cosine `cos_i` on a boundary of
    /// relative IOR `eta` (η below / η above); `cos_i < 0` arrives from below.
    #[inline]
    pub fn eval(&self, cos_i: f32, eta: f32) -> f32 {
        match self {
            DielectricFresnel::Exact => dielectric(cos_i, eta),
            DielectricFresnel::Schlick => schlick_dielectric(cos_i, eta),
        }
    }
}

/// Named conductors for [`Fresnel::Conductor`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Metal {
    /// Gold (warm yellow).
    Gold,
    /// Silver (nearly white).
    Silver,
    /// Copper (orange-red).
    Copper,
    /// Aluminium (neutral grey-white).
    Aluminium,
}

impl Metal {
    /// `(eta, k)` in linear sRGB (see the module doc for the source).
    pub fn eta_k(self) -> (Rgb, Rgb) {
        let (eta, k) = match self {
            Metal::Gold => (
                [0.143_119, 0.374_957, 1.442_479],
                [3.983_16, 2.385_721, 1.603_215],
            ),
            Metal::Silver => (
                [0.155_265, 0.116_723, 0.138_381],
                [4.828_343, 3.122_246, 2.146_95],
            ),
            Metal::Copper => (
                [0.200_438, 0.924_033, 1.102_212],
                [3.912_949, 2.452_848, 2.142_188],
            ),
            Metal::Aluminium => (
                [1.657_46, 0.880_369, 0.521_229],
                [9.223_869, 6.269_523, 4.837_001],
            ),
        };
        (Rgb::from_array(eta), Rgb::from_array(k))
    }

    /// The preset as an exact conductor Fresnel term.
    pub fn fresnel(self) -> Fresnel {
        let (eta, k) = self.eta_k();
        Fresnel::Conductor { eta, k }
    }
}

/// Exact Fresnel reflectance of a smooth dielectric boundary. `eta` is
/// η(below)/η(above); `cos_i < 0` means the light arrives from below.
/// Returns 1 under total internal reflection.
pub fn dielectric(cos_i: f32, eta: f32) -> f32 {
    let (cos_i, eta) = if cos_i < 0.0 {
        (-cos_i, 1.0 / eta)
    } else {
        (cos_i, eta)
    };
    let cos_i = cos_i.min(1.0);
    // Snell: sin θt = sin θi / η.
    let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin2_t).sqrt();
    // Amplitude coefficients for parallel and perpendicular polarisation.
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    0.5 * (r_parl * r_parl + r_perp * r_perp)
}

/// Schlick, "An Inexpensive BRDF Model for Physically-based Rendering", 1994,
/// <https://doi.org/10.1111/1467-8659.1330233>.
#[inline]
pub fn schlick(f0: Rgb, cos_i: f32) -> Rgb {
    let m = (1.0 - cos_i.clamp(0.0, 1.0)).powi(5);
    f0 + (Rgb::ONE - f0) * m
}

/// Schlick for a dielectric, arguments as in [`dielectric`]. From the dense
/// side the cosine of the *transmitted* angle is used (the law is symmetric
/// in the two angles), and total internal reflection gives 1.
pub fn schlick_dielectric(cos_i: f32, eta: f32) -> f32 {
    let (cos_i, eta) = if cos_i < 0.0 {
        (-cos_i, 1.0 / eta)
    } else {
        (cos_i, eta)
    };
    let f0 = ((eta - 1.0) / (eta + 1.0)).powi(2);
    let cos = if eta >= 1.0 {
        cos_i
    } else {
        let sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        (1.0 - sin2_t).sqrt()
    };
    f0 + (1.0 - f0) * (1.0 - cos.min(1.0)).powi(5)
}

/// Exact conductor reflectance, one complex IOR `eta + i·k` per channel
/// (pbrt-v4's `FrComplex`), the three channels in the lanes of one SIMD
/// computation: channel by channel it was three calls of two complex
/// divisions and a complex square root each (2.3% of `textured_spheres`'
/// time, perf). Each lane does the scalar formula's operations in its
/// order, so the values are its bit for bit (`tests::conductor_lanes_are_the_scalar_formula`).
pub fn conductor(cos_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    let c = Vec4::splat(cos_i.clamp(0.0, 1.0));
    let zero = Vec4::ZERO;
    // The spare lane is a harmless IOR (1 + 0i); its result is dropped.
    let eta = Complex4 {
        re: eta.extend(1.0),
        im: k.extend(0.0),
    };
    let ci = Complex4 { re: c, im: zero };
    // Complex Snell's law for the transmitted cosine.
    let sin2_t = Complex4 {
        re: Vec4::ONE - c * c,
        im: zero,
    }
    .div(eta.mul(eta));
    let cos_t = Complex4 {
        re: Vec4::ONE - sin2_t.re,
        im: -sin2_t.im,
    }
    .sqrt();
    let r_parl = eta.mul(ci).sub(cos_t).div(eta.mul(ci).add(cos_t));
    let r_perp = ci.sub(eta.mul(cos_t)).div(ci.add(eta.mul(cos_t)));
    let r = Vec4::splat(0.5) * (r_parl.norm2() + r_perp.norm2());
    Rgb::new(r.x, r.y, r.z)
}

/// Four complex numbers, lane by lane.
#[derive(Clone, Copy, Debug)]
struct Complex4 {
    re: Vec4,
    im: Vec4,
}

impl Complex4 {
    #[inline]
    fn add(self, o: Self) -> Self {
        Self {
            re: self.re + o.re,
            im: self.im + o.im,
        }
    }
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
    #[inline]
    fn mul(self, o: Self) -> Self {
        Self {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
    #[inline]
    fn div(self, o: Self) -> Self {
        let s = Vec4::ONE / o.norm2();
        Self {
            re: (self.re * o.re + self.im * o.im) * s,
            im: (self.im * o.re - self.re * o.im) * s,
        }
    }
    #[inline]
    fn norm2(self) -> Vec4 {
        self.re * self.re + self.im * self.im
    }
    /// Principal square root (0 where the number is 0).
    #[inline]
    fn sqrt(self) -> Self {
        let n = self.norm2().sqrt();
        let t1 = (Vec4::splat(0.5) * (n + self.re.abs())).sqrt();
        let t2 = Vec4::splat(0.5) * self.im / t1;
        let upper = self.re.cmpge(Vec4::ZERO);
        let re = Vec4::select(upper, t1, t2.abs());
        let im = Vec4::select(upper, t2, t1.copysign(self.im));
        let none = n.cmpeq(Vec4::ZERO);
        Self {
            re: Vec4::select(none, Vec4::ZERO, re),
            im: Vec4::select(none, Vec4::ZERO, im),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scalar formula (pbrt-v4's `FrComplex`, one channel), which
    /// [`conductor`]'s lanes must reproduce bit for bit.
    fn conductor1(cos_i: f32, eta: Complex) -> f32 {
        let ci = Complex::new(cos_i, 0.0);
        let sin2_t = Complex::new(1.0 - cos_i * cos_i, 0.0).div(eta.mul(eta));
        let cos_t = Complex::new(1.0 - sin2_t.re, -sin2_t.im).sqrt();
        let r_parl = eta.mul(ci).sub(cos_t).div(eta.mul(ci).add(cos_t));
        let r_perp = ci.sub(eta.mul(cos_t)).div(ci.add(eta.mul(cos_t)));
        0.5 * (r_parl.norm2() + r_perp.norm2())
    }

    #[derive(Clone, Copy, Debug)]
    struct Complex {
        re: f32,
        im: f32,
    }

    impl Complex {
        fn new(re: f32, im: f32) -> Self {
            Self { re, im }
        }
        fn add(self, o: Self) -> Self {
            Self::new(self.re + o.re, self.im + o.im)
        }
        fn sub(self, o: Self) -> Self {
            Self::new(self.re - o.re, self.im - o.im)
        }
        fn mul(self, o: Self) -> Self {
            Self::new(self.re * o.re - self.im * o.im, self.re * o.im + self.im * o.re)
        }
        fn div(self, o: Self) -> Self {
            let s = 1.0 / o.norm2();
            Self::new(
                (self.re * o.re + self.im * o.im) * s,
                (self.im * o.re - self.re * o.im) * s,
            )
        }
        fn norm2(self) -> f32 {
            self.re * self.re + self.im * self.im
        }
        fn sqrt(self) -> Self {
            let n = self.norm2().sqrt();
            if n == 0.0 {
                return Self::new(0.0, 0.0);
            }
            let t1 = (0.5 * (n + self.re.abs())).sqrt();
            let t2 = 0.5 * self.im / t1;
            if self.re >= 0.0 {
                Self::new(t1, t2)
            } else {
                Self::new(t2.abs(), t1.copysign(self.im))
            }
        }
    }

    #[test]
    fn conductor_lanes_are_the_scalar_formula() {
        let mut rng = crate::math::Pcg32::new(4, 11);
        let mut cases: Vec<(f32, Rgb, Rgb)> = vec![
            (1.0, Metal::Gold.eta_k().0, Metal::Gold.eta_k().1),
            (0.0, Rgb::new(0.2, 1.0, 3.0), Rgb::new(3.9, 0.0, 1e-6)),
            (1e-7, Rgb::splat(1.0), Rgb::ZERO),
            (0.5, Rgb::new(0.05, 0.5, 1.5), Rgb::new(0.0, 2.0, 7.0)),
        ];
        for _ in 0..100_000 {
            let eta = Rgb::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 4.0 + Rgb::splat(0.01);
            let k = Rgb::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 8.0;
            cases.push((rng.next_f32(), eta, k));
        }
        for (c, eta, k) in cases {
            let lanes = conductor(c, eta, k);
            let cc = c.clamp(0.0, 1.0);
            for ch in 0..3 {
                let one = conductor1(cc, Complex::new(eta[ch], k[ch]));
                assert_eq!(
                    lanes[ch].to_bits(),
                    one.to_bits(),
                    "cos {c}, eta {eta}, k {k}, channel {ch}"
                );
            }
        }
    }

    const DEG: f32 = std::f32::consts::PI / 180.0;

    #[test]
    fn fresnel_dielectric_normal_incidence_and_grazing() {
        for n in [1.33f32, 1.5, 2.4] {
            let want = ((n - 1.0) / (n + 1.0)).powi(2);
            let got = dielectric(1.0, n);
            assert!((got - want).abs() < 1e-6, "n={n}: F(0°) = {got}, want {want}");
            let inside = dielectric(-1.0, n);
            assert!(
                (inside - want).abs() < 1e-6,
                "from inside at 0°: {inside}, want {want}"
            );
            assert!(dielectric(1e-4, n) > 0.99, "n={n}: F must → 1 at grazing");
            assert_eq!(dielectric(0.0, n), 1.0);
        }
    }

    #[test]
    fn fresnel_dielectric_total_internal_reflection() {
        let n = 1.5f32;
        let critical = (1.0 / n).asin();
        let beyond = (critical + 0.5 * DEG).cos();
        let before = (critical - 0.5 * DEG).cos();
        assert_eq!(dielectric(-beyond, n), 1.0, "TIR beyond {:.2}°", critical / DEG);
        assert_eq!(schlick_dielectric(-beyond, n), 1.0);
        assert!(dielectric(-before, n) < 1.0, "no TIR before the critical angle");
        // Same physics written with eta < 1 and a positive cosine.
        assert_eq!(dielectric(beyond, 1.0 / n), 1.0);
    }

    #[test]
    fn fresnel_schlick_matches_exact_at_ends_and_errs_as_known() {
        let n = 1.5f32;
        assert!((schlick_dielectric(1.0, n) - dielectric(1.0, n)).abs() < 1e-6);
        assert_eq!(schlick_dielectric(0.0, n), 1.0);
        assert_eq!(dielectric(0.0, n), 1.0);
        // Schlick underestimates around 60° (exact 0.089, Schlick 0.070) and
        // overestimates near grazing (85°: exact 0.613, Schlick 0.649).
        let d60 = dielectric((60.0 * DEG).cos(), n) - schlick_dielectric((60.0 * DEG).cos(), n);
        assert!((0.015..0.025).contains(&d60), "exact − Schlick at 60° = {d60}");
        let d85 = schlick_dielectric((85.0 * DEG).cos(), n) - dielectric((85.0 * DEG).cos(), n);
        assert!((0.025..0.05).contains(&d85), "Schlick − exact at 85° = {d85}");
        // The error stays small below 30°.
        let d30 = (dielectric((30.0 * DEG).cos(), n) - schlick_dielectric((30.0 * DEG).cos(), n)).abs();
        assert!(d30 < 0.002, "|exact − Schlick| at 30° = {d30}");
    }

    #[test]
    fn fresnel_conductor_presets_are_sane() {
        for m in [Metal::Gold, Metal::Silver, Metal::Copper, Metal::Aluminium] {
            let (eta, k) = m.eta_k();
            let f = conductor(1.0, eta, k);
            // Closed form at normal incidence: ((n−1)² + k²) / ((n+1)² + k²).
            let want = ((eta - Rgb::ONE).powf(2.0) + k * k) / ((eta + Rgb::ONE).powf(2.0) + k * k);
            assert!(
                (f - want).abs().max_element() < 1e-4,
                "{m:?}: F(0°) = {f}, want {want}"
            );
            assert!(
                f.min_element() > 0.3 && f.max_element() <= 1.0,
                "{m:?}: F(0°) = {f}"
            );
            assert!(
                conductor(1e-4, eta, k).min_element() > 0.99,
                "{m:?} → 1 at grazing"
            );
        }
        let gold = conductor(1.0, Metal::Gold.eta_k().0, Metal::Gold.eta_k().1);
        assert!(gold.x > gold.z + 0.4, "gold is yellow: {gold}");
        let copper = conductor(1.0, Metal::Copper.eta_k().0, Metal::Copper.eta_k().1);
        assert!(
            copper.x > copper.y && copper.y > copper.z * 0.9,
            "copper is red: {copper}"
        );
        let silver = conductor(1.0, Metal::Silver.eta_k().0, Metal::Silver.eta_k().1);
        assert!(silver.min_element() > 0.9, "silver is bright: {silver}");
        // With k = 0 the conductor formula is the dielectric one.
        let c = (50.0 * DEG).cos();
        let as_dielectric = conductor(c, Rgb::splat(1.5), Rgb::ZERO).x;
        assert!((as_dielectric - dielectric(c, 1.5)).abs() < 1e-5);
    }
}
