//! A homogeneous medium: the same coefficients everywhere, so free-flight
//! distances are sampled and transmittance is evaluated in closed form.
//!
//! Coefficients are per scene unit (1/length): σ_a absorbs, σ_s scatters,
//! σ_t = σ_a + σ_s attenuates; the transmittance over a distance d is
//! T(d) = exp(−σ_t d) per channel.

use super::{Collision, HenyeyGreenstein};
use glam::{Vec2, Vec3A};

/// Constant σ_t and σ_s per RGB channel, and a phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Homogeneous {
    /// Extinction σ_t per channel, ≥ 0.
    pub sigma_t: Vec3A,
    /// Scattering σ_s per channel, 0 ≤ σ_s ≤ σ_t.
    pub sigma_s: Vec3A,
    /// How scattered light leaves.
    pub phase: HenyeyGreenstein,
}

impl Homogeneous {
    /// Transmittance exp(−σ_t·d) over distance `d` (infinite allowed: a
    /// channel without extinction keeps all its light).
    #[inline]
    pub fn transmittance(&self, d: f32) -> Vec3A {
        transmittance(self.sigma_t, d)
    }

    /// The next collision along a ray within `t_max` (the surface ahead,
    /// or infinity), for `u` ∈ [0, 1)².
    ///
    /// A channel c is picked uniformly by `u.x` and the distance drawn from
    /// its density σ_t,c exp(−σ_t,c t) by `u.y`; the density charged is the
    /// mean over the three channels (one-sample MIS across channels, as
    /// pbrt-v4's spectral path tracer), which stays finite where one
    /// channel's would not. A scattering event weighs T(t)·σ_s / p(t); going
    /// through to `t_max` weighs T(t_max) / P(t ≥ t_max).
    ///
    /// A purely absorbing medium (σ_s = 0) never scatters: the collision
    /// would weigh 0, so the ray goes through with weight T(t_max), exact
    /// rather than a 0-or-1 estimate of it.
    #[inline]
    pub fn sample(&self, t_max: f32, u: Vec2) -> Collision {
        self.collision(self.free_flight(u), t_max)
    }

    /// What [`Self::sample`] returns for `u` when `t` is
    /// [`Self::free_flight`]`(u)`: for a caller that drew the distance
    /// first (the path tracer, which looks for the surface only up to it).
    #[inline]
    pub fn collision(&self, t: f32, t_max: f32) -> Collision {
        if self.sigma_s == Vec3A::ZERO {
            return Collision {
                t: None,
                weight: self.transmittance(t_max),
            };
        }
        if self.sigma_t.x == self.sigma_t.y && self.sigma_t.y == self.sigma_t.z {
            // Grey extinction: the density charged is σ_t·T(t) (or T(t_max) to
            // pass), so the weights are σ_s/σ_t and 1 whatever the distance,
            // without the `expf` that cancels out.
            return if t < t_max {
                Collision {
                    t: Some(t),
                    weight: self.sigma_s / self.sigma_t,
                }
            } else {
                Collision {
                    t: None,
                    weight: Vec3A::ONE,
                }
            };
        }
        if t < t_max {
            let tr = self.transmittance(t);
            let pdf = (self.sigma_t * tr).element_sum() / 3.0;
            let weight = if pdf > 0.0 {
                tr * self.sigma_s / pdf
            } else {
                Vec3A::ZERO
            };
            Collision { t: Some(t), weight }
        } else {
            let tr = self.transmittance(t_max);
            let pdf = tr.element_sum() / 3.0;
            let weight = if pdf > 0.0 { tr / pdf } else { Vec3A::ZERO };
            Collision { t: None, weight }
        }
    }

    /// The distance [`Self::sample`] collides at for `u` whatever `t_max`
    /// is (it collides iff this is below `t_max`): infinite where the
    /// medium never collides (no scattering, or a channel without
    /// extinction picked). Known before the surface ahead is, so the path
    /// tracer can look for that surface only up to here (Mitsuba 3's
    /// `volpath` shortens its ray the same way): a collision then needs no
    /// surface record at all.
    #[inline]
    pub fn free_flight(&self, u: Vec2) -> f32 {
        if self.sigma_s == Vec3A::ZERO {
            return f32::INFINITY;
        }
        self.distance(u)
    }

    /// The free-flight distance in channel `u.x` picks, drawn by `u.y`.
    #[inline]
    fn distance(&self, u: Vec2) -> f32 {
        let c = ((u.x * 3.0) as usize).min(2);
        let sigma = self.sigma_t[c];
        // −ln(1 − u) / σ: u < 1, so the logarithm is finite.
        if sigma > 0.0 {
            -(1.0 - u.y).ln() / sigma
        } else {
            f32::INFINITY
        }
    }
}

/// exp(−σ·d) per channel, 1 where σ = 0 (also for d = ∞). A grey medium
/// (the same σ in every channel, the usual fog or smoke) takes one `expf`
/// for all three: the same value bit for bit, and `expf` was 9% of
/// `fog_box`'s time with three (perf).
#[inline]
pub fn transmittance(sigma_t: Vec3A, d: f32) -> Vec3A {
    let e = |s: f32| if s > 0.0 { (-s * d).exp() } else { 1.0 };
    if sigma_t.x == sigma_t.y && sigma_t.y == sigma_t.z {
        return Vec3A::splat(e(sigma_t.x));
    }
    Vec3A::new(e(sigma_t.x), e(sigma_t.y), e(sigma_t.z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rng::Pcg32;

    /// What lets the path tracer look for the surface only up to
    /// `free_flight(u)`: `sample(t_max, u)` collides exactly when that
    /// distance is below `t_max`, at it, and otherwise passes with a
    /// weight that depends on `t_max` alone — for grey, coloured (one
    /// channel without extinction) and purely absorbing media.
    #[test]
    fn free_flight_is_where_sample_collides() {
        let mut rng = Pcg32::new(7, 2);
        for m in [
            medium(Vec3A::splat(0.5), Vec3A::splat(0.8)),
            medium(Vec3A::new(0.5, 2.0, 0.0), Vec3A::new(0.9, 0.5, 0.0)),
            medium(Vec3A::splat(1.5), Vec3A::ZERO),
        ] {
            for _ in 0..20_000 {
                let u = rng.next_vec2();
                let t_max = 4.0 * rng.next_f32();
                let reach = m.free_flight(u);
                let c = m.sample(t_max, u);
                if reach < t_max {
                    assert_eq!(c.t, Some(reach), "{m:?} u {u}");
                    // Unbounded, the same collision and weight.
                    let far = m.sample(f32::INFINITY, u);
                    assert_eq!((far.t, far.weight), (c.t, c.weight));
                } else {
                    assert_eq!(c.t, None, "{m:?} u {u} t_max {t_max}");
                    let other = m.sample(t_max, rng.next_vec2());
                    if other.t.is_none() {
                        assert_eq!(other.weight, c.weight);
                    }
                }
            }
        }
    }

    /// The grey shortcut is the per-channel value bit for bit.
    #[test]
    fn grey_transmittance_is_each_channels_exactly() {
        for (s, d) in [
            (0.5f32, 0.3f32),
            (1e-3, 7.0),
            (3.0, 1e-4),
            (0.0, 2.0),
            (2.0, f32::INFINITY),
        ] {
            let grey = transmittance(Vec3A::splat(s), d);
            let each = if s > 0.0 { (-s * d).exp() } else { 1.0 };
            assert_eq!(
                grey.to_array().map(f32::to_bits),
                [each.to_bits(); 3],
                "σ {s}, d {d}"
            );
        }
        let coloured = transmittance(Vec3A::new(0.5, 1.0, 0.0), 2.0);
        assert_eq!(coloured, Vec3A::new((-1.0f32).exp(), (-2.0f32).exp(), 1.0));
    }

    fn medium(sigma_t: Vec3A, albedo: Vec3A) -> Homogeneous {
        Homogeneous {
            sigma_t,
            sigma_s: sigma_t * albedo,
            phase: HenyeyGreenstein { g: 0.0 },
        }
    }

    /// The expected weight of going through equals the transmittance's
    /// share: E[weight · 1(no collision)] = T(t_max) per channel, and the
    /// expected scattering weight equals ∫ T(t) σ_s dt = σ_s/σ_t (1 − T),
    /// with channels of different σ_t.
    #[test]
    fn homogeneous_sampling_is_unbiased_per_channel() {
        // Coloured extinction, and grey extinction under a coloured albedo
        // (the shortcut without `expf`).
        for m in [
            medium(Vec3A::new(0.5, 1.5, 3.0), Vec3A::new(0.9, 0.5, 0.2)),
            medium(Vec3A::splat(1.5), Vec3A::new(0.9, 0.5, 0.2)),
        ] {
            let t_max = 0.8;
            let mut rng = Pcg32::new(3, 9);
            let n = 400_000;
            let (mut through, mut scattered) = (Vec3A::ZERO, Vec3A::ZERO);
            for _ in 0..n {
                let c = m.sample(t_max, rng.next_vec2());
                match c.t {
                    Some(t) => {
                        assert!(t < t_max);
                        scattered += c.weight;
                    }
                    None => through += c.weight,
                }
            }
            let (through, scattered) = (through / n as f32, scattered / n as f32);
            let tr = m.transmittance(t_max);
            let expect_s = m.sigma_s / m.sigma_t * (Vec3A::ONE - tr);
            for ch in 0..3 {
                assert!(
                    (through[ch] - tr[ch]).abs() < 0.01 * tr[ch],
                    "{m:?}: through {through} vs {tr}"
                );
                assert!(
                    (scattered[ch] - expect_s[ch]).abs() < 0.01 * expect_s[ch],
                    "{m:?}: scattered {scattered} vs {expect_s}"
                );
            }
        }
    }

    /// A channel without extinction lets everything through, even to
    /// infinity, and an infinite distance with extinction lets nothing.
    #[test]
    fn homogeneous_transmittance_handles_zero_and_infinity() {
        let tr = transmittance(Vec3A::new(0.0, 1.0, 2.0), f32::INFINITY);
        assert_eq!(tr, Vec3A::new(1.0, 0.0, 0.0));
        assert!((transmittance(Vec3A::splat(0.5), 2.0).x - (-1.0f32).exp()).abs() < 1e-6);
    }
}
