//! Parameters that vary over a surface: colours ([`ColorTex`]) and numbers
//! ([`ScalarTex`]), both a [`Tex`] — a constant, an image, a checker or a
//! procedural [`Pattern`] — with an optional [`UvTransform`].
//!
//! Images are stored decoded, in **linear** RGB (plus alpha when the file
//! has one): the scene loader reads the file and decodes each texel once
//! (sRGB or linear, as the scene says), so this module does no file IO and
//! the render path never converts colour spaces; bilinear filtering then
//! interpolates decoded values (as Mitsuba does).
//!
//! Texture coordinates: with the default origin `uv = (0, 0)` is the
//! **bottom-left** corner of the image and `(1, 1)` the top-right
//! (OpenGL/OBJ convention); `rows_down` images put `(0, 0)` at the top-left
//! (Mitsuba). Texels are stored in file order, top row first. Lookups wrap
//! (repeat) in both axes.

use super::pattern::Pattern;
use crate::math::Rgb;
use glam::{Affine2, Vec2};

/// What a texture yields: [`Rgb`] for colours, `f32` for numbers.
pub trait TexValue: Copy + std::fmt::Debug {
    /// The value of a decoded texel (linear RGB and alpha) read through `channel`.
    fn from_texel(rgb: Rgb, alpha: f32, channel: Channel) -> Self;
    /// `a + (b − a)·t`.
    fn mix(a: Self, b: Self, t: f32) -> Self;
    /// `self·scale + offset`.
    fn scale_offset(self, scale: f32, offset: f32) -> Self;
    /// The product, channel by channel.
    fn times(self, other: Self) -> Self;
}

impl TexValue for Rgb {
    #[inline]
    fn from_texel(rgb: Rgb, alpha: f32, channel: Channel) -> Self {
        match channel {
            Channel::All => rgb,
            Channel::R => Rgb::splat(rgb.x),
            Channel::G => Rgb::splat(rgb.y),
            Channel::B => Rgb::splat(rgb.z),
            Channel::A => Rgb::splat(alpha),
        }
    }
    #[inline]
    fn mix(a: Self, b: Self, t: f32) -> Self {
        a + (b - a) * t
    }
    #[inline]
    fn scale_offset(self, scale: f32, offset: f32) -> Self {
        self * scale + Rgb::splat(offset)
    }
    #[inline]
    fn times(self, other: Self) -> Self {
        self * other
    }
}

impl TexValue for f32 {
    #[inline]
    fn from_texel(rgb: Rgb, alpha: f32, channel: Channel) -> Self {
        match channel {
            // A greyscale image (the loader refuses a colour one without a channel).
            Channel::All | Channel::R => rgb.x,
            Channel::G => rgb.y,
            Channel::B => rgb.z,
            Channel::A => alpha,
        }
    }
    #[inline]
    fn mix(a: Self, b: Self, t: f32) -> Self {
        a + (b - a) * t
    }
    #[inline]
    fn scale_offset(self, scale: f32, offset: f32) -> Self {
        self * scale + offset
    }
    #[inline]
    fn times(self, other: Self) -> Self {
        self * other
    }
}

/// Where a texture is looked up: the surface's texture coordinates and its
/// vertex colour (linear RGB interpolated over a mesh's triangle; white off
/// meshes, on meshes without colours, and wherever the scene did not ask
/// for it: `Scene::intersect` fills it only for materials that read it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TexPoint {
    /// Texture coordinates.
    pub uv: Vec2,
    /// Vertex colour, linear RGB.
    pub color: Rgb,
}

impl TexPoint {
    /// Where `hit`'s material looks its textures up.
    #[inline(always)]
    pub fn at(hit: &crate::geometry::Hit) -> Self {
        TexPoint {
            uv: hit.uv,
            color: hit.color,
        }
    }

    /// Coordinates `uv` with a white vertex colour.
    #[inline]
    pub fn uv(uv: Vec2) -> Self {
        TexPoint { uv, color: Rgb::ONE }
    }
}

/// Which channel of an image a texture reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Channel {
    /// RGB for a colour; the (grey) value for a number.
    All,
    /// Red.
    R,
    /// Green.
    G,
    /// Blue.
    B,
    /// Alpha (1 where the image has none).
    A,
}

/// `uv' = rotate(scale·uv) + offset`, or nothing: an identity transform is
/// stored as `None` so untransformed lookups do exactly what they did before
/// transforms existed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UvTransform(pub Option<Affine2>);

impl UvTransform {
    /// The transform scaling by `scale`, rotating by `rotation_degrees`
    /// counter-clockwise and then adding `offset`.
    pub fn new(scale: Vec2, rotation_degrees: f32, offset: Vec2) -> Self {
        if scale == Vec2::ONE && rotation_degrees == 0.0 && offset == Vec2::ZERO {
            return Self(None);
        }
        Self(Some(Affine2::from_scale_angle_translation(
            scale,
            rotation_degrees.to_radians(),
            offset,
        )))
    }

    #[inline]
    fn apply(&self, uv: Vec2) -> Vec2 {
        match &self.0 {
            Some(a) => a.transform_point2(uv),
            None => uv,
        }
    }
}

/// How an image is looked up and its texels turned into a value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ImageLookup {
    /// Index into the scene's texture list (checked by the loader).
    pub index: u32,
    /// The channel read.
    pub channel: Channel,
    /// Factor on the texel value.
    pub scale: f32,
    /// Added after `scale`.
    pub offset: f32,
    /// Whether uv (0, 0) is the top-left corner (Mitsuba) rather than the
    /// bottom-left.
    pub rows_down: bool,
    /// Applied to the surface's UVs first.
    pub uv: UvTransform,
    /// What lies past the image's edge, along u and along v.
    pub wrap: [Wrap; 2],
    /// Whether the value is multiplied by the vertex colour read through
    /// the same `channel` (glTF's `COLOR_0` × base colour texture).
    pub times_vertex: bool,
}

/// What an image shows past its edges (Mitsuba's `wrap_mode`, glTF's
/// sampler `wrapS`/`wrapT`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Wrap {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The edge texels stretch out: a decal or label shows once.
    Clamp,
    /// Tiles, every other one mirrored, so no seam shows.
    Mirror,
}

impl Wrap {
    /// Coordinate `u` over an image `n` texels wide, brought to where the
    /// repeating lookup reads what this mode shows: for clamp and mirror,
    /// within the outer texels' centres, so the 2 × 2 block of a bilinear
    /// lookup never reaches across the edge to the other side.
    #[inline]
    fn apply(self, u: f32, n: u32) -> f32 {
        let half = 0.5 / n.max(1) as f32;
        match self {
            Wrap::Repeat => u,
            Wrap::Clamp => u.clamp(half, 1.0 - half),
            Wrap::Mirror => {
                let m = u.rem_euclid(2.0);
                (if m > 1.0 { 2.0 - m } else { m }).clamp(half, 1.0 - half)
            }
        }
    }
}

impl ImageLookup {
    /// Image `index` as it is: every channel, unscaled, no UV transform.
    pub fn plain(index: u32) -> Self {
        ImageLookup {
            index,
            channel: Channel::All,
            scale: 1.0,
            offset: 0.0,
            rows_down: false,
            uv: UvTransform::default(),
            wrap: [Wrap::Repeat; 2],
            times_vertex: false,
        }
    }
}

/// A parameter that may vary over the surface: a closed set of kinds, all
/// `Copy`-free plain data evaluated without allocation.
#[derive(Clone, Debug, PartialEq)]
pub enum Tex<T> {
    /// The same value everywhere.
    Const(T),
    /// A bilinear, repeating image lookup.
    Image(ImageLookup),
    /// Squares of side `1/scale` in uv space alternating `a` and `b`; the
    /// square containing uv (0, 0)+ is `a`.
    Checker {
        /// Value of the square at uv (0, 0) and every other square.
        a: T,
        /// Value of the remaining squares.
        b: T,
        /// Squares per uv unit, > 0.
        scale: f32,
        /// Applied to the surface's UVs first.
        uv: UvTransform,
    },
    /// `a + (b − a)·pattern(uv)`.
    Pattern {
        /// The procedural pattern, values in [0, 1].
        pattern: Pattern,
        /// Value where the pattern is 0.
        a: T,
        /// Value where the pattern is 1.
        b: T,
        /// Applied to the surface's UVs first.
        uv: UvTransform,
    },
    /// The mesh's vertex colour read through `channel` (all three for a
    /// colour; for a number, `R`, `G` or `B`, or the red of a grey), times
    /// `factor`. White off meshes and on meshes without colours.
    Vertex {
        /// The channel read (`A` reads 1: colours are stored without alpha).
        channel: Channel,
        /// Factor on the colour.
        factor: T,
    },
}

/// A colour parameter.
pub type ColorTex = Tex<Rgb>;
/// A number parameter.
pub type ScalarTex = Tex<f32>;

impl<T: TexValue> Tex<T> {
    /// The value at texture coordinates `uv`. A constant (most inputs of
    /// most scenes) inline; the rest out of line: inlined whole, every
    /// material's BSDF construction paid for the image and pattern code
    /// (4% of the Cornell box's instructions, callgrind).
    #[inline(always)]
    pub fn eval(&self, at: &TexPoint, textures: &[Texture]) -> T {
        match self {
            Tex::Const(c) => *c,
            _ => self.eval_varying(at, textures),
        }
    }

    /// [`Tex::eval`] of everything but a constant.
    #[inline(never)]
    fn eval_varying(&self, at: &TexPoint, textures: &[Texture]) -> T {
        let uv = at.uv;
        match self {
            Tex::Const(c) => *c,
            Tex::Image(l) => match textures.get(l.index as usize) {
                Some(t) => {
                    let mut uv = l.uv.apply(uv);
                    if l.wrap != [Wrap::Repeat; 2] {
                        uv = Vec2::new(l.wrap[0].apply(uv.x, t.width), l.wrap[1].apply(uv.y, t.height));
                    }
                    let v = if l.channel == Channel::All {
                        T::from_texel(t.bilinear_rows(uv, l.rows_down), 1.0, Channel::All)
                    } else {
                        let (rgb, alpha) = t.bilinear_rgba(uv, l.rows_down);
                        T::from_texel(rgb, alpha, l.channel)
                    };
                    let v = if l.scale == 1.0 && l.offset == 0.0 {
                        v
                    } else {
                        v.scale_offset(l.scale, l.offset)
                    };
                    if l.times_vertex {
                        v.times(T::from_texel(at.color, 1.0, l.channel))
                    } else {
                        v
                    }
                }
                None => {
                    debug_assert!(false, "texture index {} out of range", l.index);
                    T::from_texel(Rgb::ZERO, 0.0, Channel::All)
                }
            },
            Tex::Checker { a, b, scale, uv: tr } => {
                let p = (tr.apply(uv) * *scale).floor();
                if (p.x + p.y).rem_euclid(2.0) < 0.5 { *a } else { *b }
            }
            Tex::Pattern {
                pattern,
                a,
                b,
                uv: tr,
            } => T::mix(*a, *b, pattern.eval(tr.apply(uv))),
            Tex::Vertex { channel, factor } => T::from_texel(at.color, 1.0, *channel).times(*factor),
        }
    }

    /// Whether the value varies over the surface (so shading needs `uv`).
    pub fn is_textured(&self) -> bool {
        !matches!(self, Tex::Const(_))
    }

    /// Whether the value needs the hit's vertex colour.
    pub fn reads_vertex_color(&self) -> bool {
        match self {
            Tex::Vertex { .. } => true,
            Tex::Image(l) => l.times_vertex,
            Tex::Const(_) | Tex::Checker { .. } | Tex::Pattern { .. } => false,
        }
    }
}

/// What a material asks of each of its parameters, whatever their value
/// type ([`MaterialModel::any_tex`](super::MaterialModel::any_tex)).
pub trait TexProbe {
    /// [`Tex::is_textured`].
    fn is_textured(&self) -> bool;
    /// [`Tex::reads_vertex_color`].
    fn reads_vertex_color(&self) -> bool;
}

impl<T: TexValue> TexProbe for Tex<T> {
    fn is_textured(&self) -> bool {
        Tex::is_textured(self)
    }
    fn reads_vertex_color(&self) -> bool {
        Tex::reads_vertex_color(self)
    }
}

impl ColorTex {
    /// A colour image read whole, with no transform: what a plain file name
    /// in a scene gives.
    pub fn image(index: u32) -> Self {
        Tex::Image(ImageLookup::plain(index))
    }
}

/// A decoded image texture (linear RGB texels, row-major, top row first).
#[derive(Clone, Debug)]
pub struct Texture {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Linear RGB texels, row-major, top row first: texel `(x, y)` is
    /// `texels[y·width + x]`.
    pub texels: Vec<Rgb>,
    /// Alpha per texel in the same order, or empty when the image has none
    /// (alpha 1).
    pub alpha: Vec<f32>,
}

/// The sRGB transfer function lives with the other image conversions.
pub use crate::imageio::srgb_decode as srgb_to_linear;

impl Texture {
    /// As [`Texture::from_srgb8`], but running out of memory for the texels
    /// (a 8192² texture is 1 GiB of them) is an error, not an abort.
    pub fn try_from_srgb8(width: u32, height: u32, rgb: &[u8]) -> Result<Self, String> {
        let mut texels = Vec::new();
        let n = rgb.len() / 3;
        texels.try_reserve_exact(n).map_err(|_| {
            format!(
                "not enough memory for a {width}×{height} texture ({} MiB)",
                (n * std::mem::size_of::<Rgb>()) >> 20
            )
        })?;
        let lut: Vec<f32> = (0..=255u8).map(|b| srgb_to_linear(b as f32 / 255.0)).collect();
        texels.extend(
            rgb.chunks_exact(3)
                .map(|p| Rgb::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize])),
        );
        Ok(Self {
            width,
            height,
            texels,
            alpha: Vec::new(),
        })
    }

    /// Decodes 8-bit sRGB texels (`rgb.len() == 3·width·height`, file order)
    /// to linear RGB.
    pub fn from_srgb8(width: u32, height: u32, rgb: &[u8]) -> Self {
        debug_assert_eq!(rgb.len(), 3 * width as usize * height as usize);
        // 256 entries: decoding stays exact and costs one lookup per byte.
        let lut: Vec<f32> = (0..=255u8).map(|b| srgb_to_linear(b as f32 / 255.0)).collect();
        let texels = rgb
            .chunks_exact(3)
            .map(|p| Rgb::new(lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]))
            .collect();
        Self {
            width,
            height,
            texels,
            alpha: Vec::new(),
        }
    }

    /// Bilinear lookup with repeat wrapping, v = 0 at the bottom row; texel
    /// centres sit at half-integer positions, so a 1×1 image is constant.
    pub fn bilinear(&self, uv: Vec2) -> Rgb {
        self.bilinear_rows(uv, false)
    }

    /// [`Texture::bilinear`] with v = 0 at the top row when `rows_down`
    /// (Mitsuba's convention: no flip).
    #[inline]
    pub fn bilinear_rows(&self, uv: Vec2, rows_down: bool) -> Rgb {
        if self.texels.is_empty() {
            return Rgb::ZERO;
        }
        let (x0, y0, fx, fy) = self.footprint(uv, rows_down);
        let ([xa, xb], [ya, yb]) = self.wrap_block(x0, y0);
        let w = self.width as usize;
        let t = |x: usize, y: usize| self.texels[y * w + x];
        let top = t(xa, ya).lerp(t(xb, ya), fx);
        let bottom = t(xa, yb).lerp(t(xb, yb), fx);
        top.lerp(bottom, fy)
    }

    /// The columns and rows of the 2×2 block whose top-left texel is
    /// `(x0, y0)`, wrapped into the image (repeat). Two wraps, not one per
    /// texel and axis: each `rem_euclid` was a 64-bit division, eight per
    /// lookup, the largest cost of a texture lookup (perf); and none when
    /// the block's corner is inside the image already. The same indices as
    /// wrapping each texel on its own.
    #[inline]
    fn wrap_block(&self, x0: i64, y0: i64) -> ([usize; 2], [usize; 2]) {
        // A power-of-two side (most textures) wraps by a mask, the same
        // index as `rem_euclid` in two's complement, without its division:
        // a floor whose UVs are scaled past 1 wraps every other lookup.
        let wrap = |v: i64, n: u32| {
            let n = i64::from(n);
            (if (0..n).contains(&v) {
                v
            } else if n & (n - 1) == 0 {
                v & (n - 1)
            } else {
                v.rem_euclid(n)
            }) as usize
        };
        let (x, y) = (wrap(x0, self.width), wrap(y0, self.height));
        let x1 = if x + 1 == self.width as usize { 0 } else { x + 1 };
        let y1 = if y + 1 == self.height as usize { 0 } else { y + 1 };
        ([x, x1], [y, y1])
    }

    /// Bilinear RGB and alpha (1 where the image has none).
    pub fn bilinear_rgba(&self, uv: Vec2, rows_down: bool) -> (Rgb, f32) {
        let rgb = self.bilinear_rows(uv, rows_down);
        if self.alpha.is_empty() {
            return (rgb, 1.0);
        }
        let (x0, y0, fx, fy) = self.footprint(uv, rows_down);
        let ([xa, xb], [ya, yb]) = self.wrap_block(x0, y0);
        let w = self.width as usize;
        let a = |x: usize, y: usize| self.alpha[y * w + x];
        let top = a(xa, ya) + (a(xb, ya) - a(xa, ya)) * fx;
        let bottom = a(xa, yb) + (a(xb, yb) - a(xa, yb)) * fx;
        (rgb, top + (bottom - top) * fy)
    }

    /// The top-left texel of the 2×2 block around `uv` and the weights.
    #[inline]
    fn footprint(&self, uv: Vec2, rows_down: bool) -> (i64, i64, f32, f32) {
        // Continuous texel coordinates, v flipped unless rows run down.
        let x = uv.x * self.width as f32 - 0.5;
        let v = if rows_down { uv.y } else { 1.0 - uv.y };
        let y = v * self.height as f32 - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        (x0 as i64, y0 as i64, fx, fy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Past the edge, clamp repeats the edge texel, mirror reads the image
    /// backwards, repeat tiles; inside it the three agree. A 4 × 1 image
    /// of values 1, 2, 3, 4 (texel centres at u = ⅛, ⅜, ⅝, ⅞).
    #[test]
    fn wrap_modes_read_past_the_edge_as_named() {
        let t = Texture {
            width: 4,
            height: 1,
            texels: (1..=4).map(|k| Rgb::splat(k as f32)).collect(),
            alpha: Vec::new(),
        };
        let at = |wrap: Wrap, u: f32| -> f32 {
            let tex: ColorTex = Tex::Image(ImageLookup {
                wrap: [wrap, Wrap::Repeat],
                ..ImageLookup::plain(0)
            });
            tex.eval(&TexPoint::uv(Vec2::new(u, 0.5)), std::slice::from_ref(&t))
                .x
        };
        for u in [0.2f32, 0.5, 0.8] {
            assert_eq!(at(Wrap::Clamp, u), at(Wrap::Repeat, u));
            assert_eq!(at(Wrap::Mirror, u), at(Wrap::Repeat, u));
        }
        // Clamp: the edge texels, however far out.
        assert_eq!(at(Wrap::Clamp, 1.3), 4.0);
        assert_eq!(at(Wrap::Clamp, 0.95), 4.0);
        assert_eq!(at(Wrap::Clamp, -7.0), 1.0);
        // Mirror: 1.3 reads 0.7, −0.2 reads 0.2, 2.3 reads 0.3 again.
        let near = |a: f32, b: f32| assert!((a - b).abs() < 1e-5, "{a} against {b}");
        near(at(Wrap::Mirror, 1.3), at(Wrap::Repeat, 0.7));
        near(at(Wrap::Mirror, -0.2), at(Wrap::Repeat, 0.2));
        near(at(Wrap::Mirror, 2.3), at(Wrap::Repeat, 0.3));
        // Across the seam, mirror holds the edge texel where repeat blends
        // the last texel with the first.
        assert_eq!(at(Wrap::Mirror, 1.0), 4.0);
        assert!(at(Wrap::Repeat, 1.0) < 3.0);
    }

    /// The block wrapped once gives, bit for bit, what wrapping each of the
    /// four texels on its own gives, inside the image, across its edges and
    /// far outside it (tiled, negative), for images of odd sizes and of
    /// powers of two (wrapped by a mask).
    #[test]
    fn wrapped_block_matches_texel_by_texel_wrapping() {
        for (w, h) in [(5u32, 3u32), (8, 4), (1, 2), (16, 5)] {
            block_wraps_as_texels(w, h);
        }
    }

    fn block_wraps_as_texels(w: u32, h: u32) {
        let srgb: Vec<u8> = (0..w * h * 3).map(|k| (k * 37 % 251) as u8).collect();
        let t = Texture::from_srgb8(w, h, &srgb);
        let texel = |x: i64, y: i64| {
            let x = x.rem_euclid(i64::from(w)) as usize;
            let y = y.rem_euclid(i64::from(h)) as usize;
            t.texels[y * w as usize + x]
        };
        let mut rng = crate::math::rng::Pcg32::new(3, 1);
        for k in 0..4000 {
            let uv = Vec2::new(rng.next_f32(), rng.next_f32()) * 14.0 - Vec2::splat(7.0);
            let rows_down = k % 2 == 0;
            let (x0, y0, fx, fy) = t.footprint(uv, rows_down);
            let top = texel(x0, y0).lerp(texel(x0 + 1, y0), fx);
            let bottom = texel(x0, y0 + 1).lerp(texel(x0 + 1, y0 + 1), fx);
            let want = top.lerp(bottom, fy);
            let got = t.bilinear_rows(uv, rows_down);
            assert_eq!(
                got.to_array().map(f32::to_bits),
                want.to_array().map(f32::to_bits),
                "uv {uv}"
            );
        }
    }

    #[test]
    fn texture_srgb_decode_endpoints_and_mid_grey() {
        let t = Texture::from_srgb8(3, 1, &[255, 255, 255, 0, 0, 0, 128, 128, 128]);
        assert_eq!(t.texels[0], Rgb::ONE, "sRGB 255 must decode to 1");
        assert_eq!(t.texels[1], Rgb::ZERO, "sRGB 0 must decode to 0");
        let mid = srgb_to_linear(0.5);
        assert!((mid - 0.214).abs() < 1e-3, "sRGB 0.5 → {mid}, expected ≈ 0.214");
        assert!(
            (t.texels[2].x - 0.2158).abs() < 1e-3,
            "sRGB 128 → {}",
            t.texels[2].x
        );
    }

    #[test]
    fn texture_checker_alternates() {
        let c = ColorTex::Checker {
            a: Rgb::ONE,
            b: Rgb::ZERO,
            scale: 4.0,
            uv: UvTransform::default(),
        };
        let at = |u: f32, v: f32| c.eval(&TexPoint::uv(Vec2::new(u, v)), &[]).x;
        assert_eq!(at(0.1, 0.1), 1.0);
        assert_eq!(at(0.3, 0.1), 0.0);
        assert_eq!(at(0.1, 0.3), 0.0);
        assert_eq!(at(0.3, 0.3), 1.0);
        assert_eq!(at(-0.1, 0.1), 0.0, "negative uv continues the pattern");
    }

    #[test]
    fn texture_bilinear_interpolates_and_wraps() {
        // 2×1 image: black on the left, white on the right.
        let t = Texture {
            width: 2,
            height: 1,
            texels: vec![Rgb::ZERO, Rgb::ONE],
            alpha: Vec::new(),
        };
        let at = |u: f32| t.bilinear(Vec2::new(u, 0.5)).x;
        assert!((at(0.25) - 0.0).abs() < 1e-6, "left texel centre: {}", at(0.25));
        assert!((at(0.75) - 1.0).abs() < 1e-6, "right texel centre: {}", at(0.75));
        assert!((at(0.5) - 0.5).abs() < 1e-6, "halfway: {}", at(0.5));
        assert!((at(0.375) - 0.25).abs() < 1e-6, "quarter: {}", at(0.375));
        // u = 0 lies halfway between the right texel (wrapped) and the left one.
        assert!((at(0.0) - 0.5).abs() < 1e-6, "wrap: {}", at(0.0));
        assert!((at(1.25) - at(0.25)).abs() < 1e-6, "repeat");
        // uv (0,0) is the bottom-left: a 1×2 image with white on the top row.
        let t = Texture {
            width: 1,
            height: 2,
            texels: vec![Rgb::ONE, Rgb::ZERO],
            alpha: Vec::new(),
        };
        assert!(
            t.bilinear(Vec2::new(0.5, 0.75)).x > 0.99,
            "v = 0.75 is the top row"
        );
        assert!(
            t.bilinear(Vec2::new(0.5, 0.25)).x < 0.01,
            "v = 0.25 is the bottom row"
        );
    }
}
