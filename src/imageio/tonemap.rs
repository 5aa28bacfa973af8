//! From scene-linear radiance to display values: exposure, then a tone map,
//! then (in the encoder) the sRGB transfer function. Applied to PNG outputs
//! and the watch page only: EXR, PFM and HDR files keep the radiance as
//! rendered, so they can be compared with references and re-exposed later.

use crate::math::Rgb;

/// The tone maps; each takes linear values ≥ 0 to display-linear [0, 1] and
/// maps 0 to 0.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tonemap {
    /// Cut to [0, 1]: what ronray's PNGs always were.
    #[default]
    Clamp,
    /// Reinhard et al. 2002, "Photographic tone reproduction", eq. 3:
    /// `x / (1 + x)` per channel.
    Reinhard,
    /// Krzysztof Narkowicz's fit of the ACES RRT + ODT filmic curve,
    /// <https://knarkowicz.wordpress.com/2016/01/06/aces-filmic-tone-mapping-curve/>:
    /// `x(2.51x + 0.03) / (x(2.43x + 0.59) + 0.14)` per channel, as
    /// published (without the 0.6 pre-scale some ports add: use exposure).
    Aces,
    /// Troy Sobotka's AgX, as in Blender 4 (<https://github.com/sobotka/AgX>),
    /// in Benjamin Wrensch's minimal form
    /// (<https://iolite-engine.com/blog_posts/minimal_agx_implementation>):
    /// the inset matrix, log2 between −12.47 and +4.03 EV around 0.18, the
    /// 6th-order fit of the default contrast sigmoid, the outset (inverse)
    /// matrix; its result is display-encoded, so it is decoded back to
    /// linear here for the encoder to encode again.
    AgX,
}

/// What turns a linear image into display values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Display {
    /// Exposure in stops: linear values are multiplied by 2^exposure.
    pub exposure: f32,
    /// The tone map applied after exposure.
    pub tonemap: Tonemap,
    /// Bits per channel of PNG outputs: 8 or 16.
    pub png_bits: u8,
}

impl Default for Display {
    fn default() -> Self {
        Self {
            exposure: 0.0,
            tonemap: Tonemap::Clamp,
            png_bits: 8,
        }
    }
}

impl Display {
    /// Display-linear value in [0, 1] of linear radiance `c`.
    #[inline]
    pub fn map(&self, c: Rgb) -> Rgb {
        // Skipped at 0 stops so default outputs are bit-identical to before.
        let c = if self.exposure == 0.0 {
            c
        } else {
            c * self.exposure.exp2()
        };
        self.tonemap.apply(c)
    }
}

impl Tonemap {
    /// The curve applied to `c` (negative channels count as 0).
    #[inline]
    pub fn apply(self, c: Rgb) -> Rgb {
        match self {
            Tonemap::Clamp => c.clamp(Rgb::ZERO, Rgb::ONE),
            Tonemap::Reinhard => {
                let c = c.max(Rgb::ZERO);
                c / (Rgb::ONE + c)
            }
            Tonemap::Aces => {
                let x = c.max(Rgb::ZERO);
                let y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
                y.clamp(Rgb::ZERO, Rgb::ONE)
            }
            Tonemap::AgX => agx(c),
        }
    }
}

/// AgX's inset matrix (rows; Wrensch's column-major GLSL transposed).
const AGX_INSET: [[f32; 3]; 3] = [
    [0.842_479_06, 0.078_433_6, 0.079_223_745],
    [0.042_328_242, 0.878_468_6, 0.079_166_13],
    [0.042_375_655, 0.078_433_6, 0.879_143],
];
/// Its inverse, the outset matrix.
const AGX_OUTSET: [[f32; 3]; 3] = [
    [1.196_879, -0.098_020_88, -0.099_029_74],
    [-0.052_896_85, 1.151_903_1, -0.098_961_18],
    [-0.052_971_635, -0.098_043_45, 1.151_073_7],
];
const AGX_MIN_EV: f32 = -12.473_931;
const AGX_MAX_EV: f32 = 4.026_069;

fn mul(m: &[[f32; 3]; 3], c: Rgb) -> Rgb {
    Rgb::new(
        m[0][0] * c.x + m[0][1] * c.y + m[0][2] * c.z,
        m[1][0] * c.x + m[1][1] * c.y + m[1][2] * c.z,
        m[2][0] * c.x + m[2][1] * c.y + m[2][2] * c.z,
    )
}

/// AgX's default-contrast sigmoid, a 6th-order polynomial on [0, 1].
fn agx_contrast(x: f32) -> f32 {
    let x2 = x * x;
    let x4 = x2 * x2;
    15.5 * x4 * x2 - 40.14 * x4 * x + 31.96 * x4 - 6.868 * x2 * x + 0.4298 * x2 + 0.1191 * x - 0.002_32
}

fn agx(c: Rgb) -> Rgb {
    // Black stays black (log2 of 0 would sit at the curve's −0.002 floor).
    let c = c.max(Rgb::ZERO);
    if c == Rgb::ZERO {
        return Rgb::ZERO;
    }
    let inset = mul(&AGX_INSET, c);
    // Log encoding: EV range mapped to [0, 1].
    let log = |x: f32| {
        let ev = x.max(1e-10).log2().clamp(AGX_MIN_EV, AGX_MAX_EV);
        agx_contrast((ev - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV))
    };
    let encoded = mul(&AGX_OUTSET, Rgb::new(log(inset.x), log(inset.y), log(inset.z)));
    // The sigmoid's output is display-encoded (sRGB-like): back to linear.
    let decode = |x: f32| super::srgb_decode(x.clamp(0.0, 1.0));
    Rgb::new(decode(encoded.x), decode(encoded.y), decode(encoded.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Tonemap; 4] = [Tonemap::Clamp, Tonemap::Reinhard, Tonemap::Aces, Tonemap::AgX];

    #[test]
    fn tonemaps_map_black_to_black() {
        for t in ALL {
            assert_eq!(t.apply(Rgb::ZERO), Rgb::ZERO, "{t:?}");
        }
    }

    /// Along grey ramps from 0 to 64 every curve is non-decreasing, stays in
    /// [0, 1], and is increasing somewhere.
    #[test]
    fn tonemaps_are_monotone_on_grey_ramps() {
        for t in ALL {
            let mut prev = -1.0f32;
            let mut rose = false;
            for i in 0..=4096 {
                let x = 64.0 * (i as f32 / 4096.0).powi(3);
                let y = t.apply(Rgb::splat(x));
                assert!(
                    y.min_element() >= 0.0 && y.max_element() <= 1.0,
                    "{t:?}({x}) = {y:?}"
                );
                assert!(y.x >= prev, "{t:?} decreases at {x}: {} after {prev}", y.x);
                rose |= y.x > prev && prev >= 0.0;
                prev = y.x;
            }
            assert!(rose, "{t:?} is flat");
        }
    }

    /// Per-channel curves are monotone in each channel; AgX, which mixes
    /// channels, keeps the luminance monotone (to 1e-4) along exposure ramps
    /// of colours.
    #[test]
    fn tonemaps_are_monotone_along_coloured_exposure_ramps() {
        let colours = [
            Rgb::new(1.0, 0.2, 0.05),
            Rgb::new(0.1, 0.5, 1.0),
            Rgb::new(0.9, 0.9, 0.2),
        ];
        for t in ALL {
            for c in colours {
                let mut prev = Rgb::splat(-1.0);
                for i in 0..=2000 {
                    let k = (i as f32 / 2000.0 * 16.0 - 10.0).exp2();
                    let y = t.apply(c * k);
                    if t == Tonemap::AgX {
                        let (l, lp) = (crate::math::luminance(y), crate::math::luminance(prev));
                        // Within 1e-4: the fitted sigmoid wobbles by ~5e-6 where
                        // a channel reaches white.
                        assert!(l >= lp - 1e-4, "{t:?} luminance falls at {k}·{c:?}: {l} < {lp}");
                    } else {
                        assert!(
                            y.cmpge(prev).all(),
                            "{t:?} decreases at {k}·{c:?}: {y:?} after {prev:?}"
                        );
                    }
                    prev = y;
                }
            }
        }
    }

    #[test]
    fn one_stop_doubles_linear_values() {
        let d = Display {
            exposure: 1.0,
            ..Display::default()
        };
        for x in [0.0, 0.01, 0.125, 0.3, 0.49] {
            assert_eq!(d.map(Rgb::splat(x)), Rgb::splat(2.0 * x), "+1 stop of {x}");
        }
        let down = Display {
            exposure: -1.0,
            ..Display::default()
        };
        assert_eq!(down.map(Rgb::splat(0.8)), Rgb::splat(0.4));
    }

    #[test]
    fn clamp_at_zero_stops_is_the_old_clamp() {
        let d = Display::default();
        for x in [-1.0, 0.0, 0.5, 1.0, 7.0] {
            assert_eq!(d.map(Rgb::splat(x)), Rgb::splat(x.clamp(0.0, 1.0)));
        }
    }

    #[test]
    fn filmic_curves_keep_highlights_below_white_and_mid_grey_visible() {
        for t in [Tonemap::Reinhard, Tonemap::Aces, Tonemap::AgX] {
            let mid = t.apply(Rgb::splat(0.18)).x;
            let bright = t.apply(Rgb::splat(4.0)).x;
            assert!(mid > 0.02 && mid < 0.5, "{t:?}: 0.18 → {mid}");
            assert!(bright > mid && bright <= 1.0, "{t:?}: 4 → {bright}");
        }
    }
}
