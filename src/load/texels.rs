//! Image values that are no value — NaN, infinite or negative — in any image
//! the build reads: sky maps, and every texture decoded for a parameter
//! (a colour, a roughness, an emission; scene, MTL and glTF textures alike).
//! One rule, written once: each such channel value is read as 0, and the
//! build step turns what was found into a note that names the file and the
//! scene path (or MTL material, or glTF image) that read it.
//!
//! Only float images (OpenEXR, Radiance HDR, PFM) can hold them; 8- and
//! 16-bit files decode to [0, 1]. One NaN texel is enough to do harm: a
//! bilinear lookup spreads it to every sample that touches its four
//! neighbours, a NaN roughness or albedo turns a path's throughput NaN,
//! and in a sky map it reached the importance tables and darkened a whole
//! image by 11%.
//!
//! **Repair, not refusal.** pbrt-v4 refuses an image with NaN or infinite
//! pixels where it is a light (`ErrorExit(loc, "... not suitable as a
//! light")`) and checks nothing in image textures; Mitsuba 3 warns when a
//! bitmap texture holds values outside [0, 1] and renders them as they are.
//! ronray repairs them, as it already did for MTL colours and sky maps:
//! the image is a file the scene names but does not hold (often from an
//! asset library), a few broken texels should not stop a render or a farm
//! job, and the note says exactly which texels were changed, to what, and
//! where the file was read, so nothing is silent.

use crate::materials::Texture;

/// Counts of the channel values repaired, by kind.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Repairs {
    /// NaN values.
    pub nan: usize,
    /// Infinite values (either sign).
    pub infinite: usize,
    /// Finite values below zero.
    pub negative: usize,
}

impl Repairs {
    /// `x` if it is a value (finite, ≥ 0), else 0, counted by kind.
    #[inline]
    pub fn value(&mut self, x: f32) -> f32 {
        if x >= 0.0 && x.is_finite() {
            return x;
        }
        if x.is_nan() {
            self.nan += 1;
        } else if x.is_infinite() {
            self.infinite += 1;
        } else {
            self.negative += 1;
        }
        0.0
    }

    /// What was repaired (`2 NaN channel values, 1 negative channel
    /// value`), `None` when nothing was.
    pub fn summary(&self) -> Option<String> {
        let parts: Vec<String> = [
            (self.nan, "NaN"),
            (self.infinite, "infinite"),
            (self.negative, "negative"),
        ]
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, what)| format!("{n} {what} channel value{}", if *n == 1 { "" } else { "s" }))
        .collect();
        (!parts.is_empty()).then(|| parts.join(", "))
    }
}

/// Repairs `values` in place (see the module docs); what was repaired.
pub fn repair_values(values: &mut [f32]) -> Option<String> {
    let mut r = Repairs::default();
    for x in values.iter_mut() {
        *x = r.value(*x);
    }
    r.summary()
}

/// Repairs a decoded texture's colour and alpha in place (see the module
/// docs); what was repaired, counting alpha values with the colours.
pub fn repair_texture(t: &mut Texture) -> Option<String> {
    let mut r = Repairs::default();
    for c in t.texels.iter_mut() {
        let fixed = crate::math::Rgb::new(r.value(c.x), r.value(c.y), r.value(c.z));
        *c = fixed;
    }
    for a in t.alpha.iter_mut() {
        *a = r.value(*a);
    }
    r.summary()
}

/// Repairs a decoded float image in place before it is converted to 8
/// bits (where NaN would become 0 but +∞ white, without a word); 8- and
/// 16-bit images hold only values. What was repaired.
pub fn repair_image(img: &mut image::DynamicImage) -> Option<String> {
    match img {
        image::DynamicImage::ImageRgb32F(b) => repair_values(b),
        image::DynamicImage::ImageRgba32F(b) => repair_values(b),
        // Integer samples: every one is a value.
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repair_reads_every_kind_of_non_value_as_zero_and_counts_it() {
        let mut v = [
            1.0,
            f32::NAN,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            -2.0,
            3e38,
            f32::NAN,
        ];
        let said = repair_values(&mut v).expect("repaired");
        assert_eq!(v, [1.0, 0.0, -0.0, 0.0, 0.0, 0.0, 3e38, 0.0]);
        assert_eq!(
            said,
            "2 NaN channel values, 2 infinite channel values, 1 negative channel value"
        );
        assert_eq!(repair_values(&mut [0.0, 0.5, 1e30]), None);
    }
}
