//! Procedural patterns: textures that need no file, with values in [0, 1].
//!
//! Every pattern is a pure function of `uv` and a seed — integer hashing
//! of lattice cells, no tables, no state — so a pattern is identical on any
//! thread count and in any order of evaluation. One lattice cell per UV unit;
//! a texture's `uv` transform scales it.
//!
//! - value noise: a hashed value per lattice point, quintic interpolation;
//! - gradient noise: Perlin's improved noise in 2D (Perlin 2002,
//!   <https://doi.org/10.1145/566654.566636>), a hashed unit gradient per
//!   lattice point, quintic fade, mapped from about [−0.7, 0.7] to [0, 1];
//! - fBm: Σ gainᵏ·gradient(lacunarityᵏ·uv), normalised by Σ gainᵏ;
//! - cellular: Worley's F1 (Worley 1996, <https://doi.org/10.1145/237170.237267>),
//!   the distance to the nearest of one hashed point per cell, clamped to 1;
//! - stripes: 1 on the first `duty` of each unit of u, else 0.

use glam::Vec2;

/// A procedural pattern (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Pattern {
    /// Value noise.
    Value {
        /// Varies the lattice values.
        seed: u32,
    },
    /// Gradient (Perlin) noise.
    Gradient {
        /// Varies the lattice gradients.
        seed: u32,
    },
    /// Fractal Brownian motion over gradient noise.
    Fbm {
        /// Varies the lattice gradients.
        seed: u32,
        /// Number of octaves, ≥ 1.
        octaves: u32,
        /// Frequency factor between octaves.
        lacunarity: f32,
        /// Amplitude factor between octaves.
        gain: f32,
    },
    /// Worley F1 cellular noise.
    Cellular {
        /// Varies the feature points.
        seed: u32,
    },
    /// Stripes across u.
    Stripes {
        /// Fraction of each period that is 1.
        duty: f32,
    },
}

impl Pattern {
    /// The pattern's value at `uv`, in [0, 1].
    #[inline]
    pub fn eval(&self, uv: Vec2) -> f32 {
        match *self {
            Pattern::Value { seed } => value_noise(uv, seed),
            Pattern::Gradient { seed } => (0.5 + gradient_noise(uv, seed) * (0.5 / 0.7)).clamp(0.0, 1.0),
            Pattern::Fbm {
                seed,
                octaves,
                lacunarity,
                gain,
            } => {
                let (mut sum, mut norm, mut amp, mut p) = (0.0, 0.0, 1.0, uv);
                for k in 0..octaves {
                    sum += amp * gradient_noise(p, seed.wrapping_add(k));
                    norm += amp;
                    amp *= gain;
                    p *= lacunarity;
                }
                (0.5 + sum / norm * (0.5 / 0.7)).clamp(0.0, 1.0)
            }
            Pattern::Cellular { seed } => cellular(uv, seed),
            Pattern::Stripes { duty } => {
                if uv.x - uv.x.floor() < duty {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

/// A well-mixed 32-bit hash of a lattice point and a seed (the finaliser of
/// MurmurHash3 over a combination of the three).
#[inline]
fn hash(x: i32, y: i32, seed: u32) -> u32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 16;
    h = h.wrapping_mul(0x85eb_ca6b);
    h ^= h >> 13;
    h = h.wrapping_mul(0xc2b2_ae35);
    h ^ (h >> 16)
}

/// The hash as a number in [0, 1).
#[inline]
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// Perlin's quintic fade 6t⁵ − 15t⁴ + 10t³.
#[inline]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn value_noise(uv: Vec2, seed: u32) -> f32 {
    let (c, f) = (uv.floor(), uv - uv.floor());
    let (x, y) = (c.x as i32, c.y as i32);
    let v = |dx: i32, dy: i32| unit(hash(x + dx, y + dy, seed));
    let (sx, sy) = (fade(f.x), fade(f.y));
    let bottom = v(0, 0) + (v(1, 0) - v(0, 0)) * sx;
    let top = v(0, 1) + (v(1, 1) - v(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

/// 2D gradient noise in about [−0.7, 0.7], 0 at every lattice point.
fn gradient_noise(uv: Vec2, seed: u32) -> f32 {
    let (c, f) = (uv.floor(), uv - uv.floor());
    let (x, y) = (c.x as i32, c.y as i32);
    let g = |dx: i32, dy: i32| {
        // A unit gradient at one of 256 angles.
        let a = unit(hash(x + dx, y + dy, seed)) * std::f32::consts::TAU;
        Vec2::new(a.cos(), a.sin()).dot(f - Vec2::new(dx as f32, dy as f32))
    };
    let (sx, sy) = (fade(f.x), fade(f.y));
    let bottom = g(0, 0) + (g(1, 0) - g(0, 0)) * sx;
    let top = g(0, 1) + (g(1, 1) - g(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

fn cellular(uv: Vec2, seed: u32) -> f32 {
    let c = uv.floor();
    let (x, y) = (c.x as i32, c.y as i32);
    let mut best = f32::INFINITY;
    // The nearest feature point lies in the 3×3 block of cells around uv.
    for dy in -1..=1 {
        for dx in -1..=1 {
            let h = hash(x + dx, y + dy, seed);
            let p = Vec2::new(
                (x + dx) as f32 + unit(h),
                (y + dy) as f32 + unit(hash(h as i32, 0x5bd1_e995u32 as i32, seed)),
            );
            best = best.min(p.distance_squared(uv));
        }
    }
    best.sqrt().min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all() -> [Pattern; 5] {
        [
            Pattern::Value { seed: 1 },
            Pattern::Gradient { seed: 2 },
            Pattern::Fbm {
                seed: 3,
                octaves: 5,
                lacunarity: 2.0,
                gain: 0.5,
            },
            Pattern::Cellular { seed: 4 },
            Pattern::Stripes { duty: 0.3 },
        ]
    }

    #[test]
    fn pattern_values_lie_in_unit_interval_and_vary() {
        for p in all() {
            let (mut lo, mut hi) = (f32::INFINITY, f32::NEG_INFINITY);
            for i in 0..4096 {
                let uv = Vec2::new((i % 64) as f32 * 0.173 - 5.0, (i / 64) as f32 * 0.119 - 3.0);
                let v = p.eval(uv);
                assert!((0.0..=1.0).contains(&v), "{p:?} at {uv}: {v}");
                lo = lo.min(v);
                hi = hi.max(v);
            }
            assert!(hi - lo > 0.5, "{p:?} spans only [{lo}, {hi}]");
        }
    }

    #[test]
    fn pattern_is_the_same_on_every_thread() {
        let grid = |p: Pattern| -> Vec<u32> {
            (0..1024)
                .map(|i| p.eval(Vec2::new(i as f32 * 0.37, i as f32 * 0.11)).to_bits())
                .collect()
        };
        for p in all() {
            let here = grid(p);
            let there = std::thread::spawn(move || grid(p)).join().expect("thread");
            assert_eq!(here, there, "{p:?} differs between threads");
        }
    }

    #[test]
    fn noise_is_continuous_across_cells() {
        for p in &all()[..4] {
            for i in 0..200 {
                let uv = Vec2::new(i as f32 * 0.5 + 1.0, 0.3 * i as f32);
                let d = (p.eval(uv - Vec2::splat(1e-4)) - p.eval(uv + Vec2::splat(1e-4))).abs();
                assert!(d < 0.01, "{p:?} jumps by {d} at {uv}");
            }
        }
    }
}
