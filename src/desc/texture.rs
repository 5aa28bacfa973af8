//! Textures: what a colour ([`super::ColorDesc`]) or a number
//! ([`ScalarDesc`]) may be instead of a constant. `docs/textures.md` is the
//! user's page; the forms are:
//!
//! | form | value |
//! |---|---|
//! | `"file.png"` | an image, defaults for everything else |
//! | `Image(file: "…", channel: R, colorspace: Linear, scale: 1, offset: 0, origin: BottomLeft, uv: (…), wrap: Repeat)` | `texel·scale + offset` |
//! | `Checker(a: …, b: …, scale: 4, uv: (…))` | squares of `a` and `b`, `scale` per UV unit |
//! | `Pattern(pattern: Fbm(octaves: 5), a: …, b: …, seed: 0, uv: (…))` | `a + (b − a)·pattern(uv)` |
//! | `VertexColor(factor: …, channel: G)` | the mesh's vertex colours × `factor` |
//!
//! An image with `times_vertex_color: true` is multiplied by the vertex
//! colours (glTF's `COLOR_0` × base colour texture).
//!
//! RON hands a named struct to self-describing deserialisers without its
//! name, so the kind is recognised by its fields: `file` is an image, a
//! `pattern` a procedural pattern, `a` and `b` alone a checker, `factor` the
//! vertex colours.
//!
//! ```
//! #[derive(serde::Deserialize)]
//! struct M { roughness: ronray::desc::ScalarDesc }
//! let m: M = ron::from_str(r#"(roughness: Image(file: "r.png", channel: G))"#).unwrap();
//! assert!(matches!(m.roughness, ronray::desc::ScalarDesc::Texture(_)));
//! ```

use serde::de::{self, DeserializeOwned, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// A texture whose constants (`a`, `b`) are `V`: `[f32; 3]` for colours, `f32`
/// for numbers.
#[derive(Clone, Debug, PartialEq)]
pub enum TexDesc<V> {
    /// An image file, relative to the scene file.
    Image(ImageDesc),
    /// Alternating squares of `a` and `b`, `scale` squares per UV unit; the
    /// square holding uv (0, 0)+ is `a`.
    Checker {
        /// Value of the squares where ⌊u·scale⌋ + ⌊v·scale⌋ is even.
        a: V,
        /// Value of the other squares.
        b: V,
        /// Squares per UV unit, > 0 (default 1).
        scale: f32,
        /// Transform applied to the surface's UVs first.
        uv: UvDesc,
    },
    /// A procedural pattern in [0, 1] mapping `a` (0) to `b` (1).
    Pattern {
        /// Which pattern.
        pattern: PatternDesc,
        /// Value where the pattern is 0.
        a: V,
        /// Value where the pattern is 1.
        b: V,
        /// Varies the noise; the same seed gives the same pattern.
        seed: u32,
        /// Transform applied to the surface's UVs first (a `scale` of 8 gives
        /// 8 noise cells per UV unit).
        uv: UvDesc,
    },
    /// The mesh's vertex colours (OBJ `v x y z r g b`, glTF `COLOR_0`),
    /// linear RGB interpolated over each triangle, times `factor`; white on
    /// shapes and meshes without colours.
    Vertex {
        /// Which channel a number reads (`R`, `G` or `B`; required for a
        /// number, not allowed for a colour).
        channel: Option<ChannelDesc>,
        /// Factor on the colour.
        factor: V,
    },
}

/// An image texture and how its texels become a value.
#[derive(Clone, Debug, PartialEq)]
pub struct ImageDesc {
    /// Image file, relative to the scene file (PNG, JPEG, EXR, HDR, …).
    pub file: String,
    /// Which channel a number reads (`R`, `G`, `B`, `A`); required for a number
    /// read from a colour image. A colour given one channel is that grey.
    pub channel: Option<ChannelDesc>,
    /// How 8-bit texels are decoded (default `Srgb` for colours, `Linear` for
    /// numbers, normal maps and opacity; float images are always linear).
    pub colorspace: Option<ColorspaceDesc>,
    /// Factor on the texel value (default 1).
    pub scale: f32,
    /// Added after `scale` (default 0).
    pub offset: f32,
    /// Where uv (0, 0) is on the image (default `BottomLeft`, the OBJ/OpenGL
    /// convention; Mitsuba's is `TopLeft`).
    pub origin: OriginDesc,
    /// Transform applied to the surface's UVs first.
    pub uv: UvDesc,
    /// What lies past the image's edges (default `Repeat`).
    pub wrap: WrapDesc,
    /// Multiply by the mesh's vertex colours (read through the same
    /// `channel`), as glTF multiplies `COLOR_0` into the base colour
    /// (default false).
    pub times_vertex_color: bool,
}

/// What an image shows past its edges.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum WrapDesc {
    /// The image tiles the plane.
    #[default]
    Repeat,
    /// The edge texels stretch out: a decal or label shows once.
    Clamp,
    /// Tiles, every other one mirrored, so no seam shows.
    Mirror,
}

impl ImageDesc {
    /// An image of `file` with every other field at its default.
    pub fn plain(file: String) -> Self {
        Self {
            file,
            channel: None,
            colorspace: None,
            scale: 1.0,
            offset: 0.0,
            origin: OriginDesc::BottomLeft,
            uv: UvDesc::default(),
            wrap: WrapDesc::Repeat,
            times_vertex_color: false,
        }
    }

    fn is_plain(&self) -> bool {
        *self == Self::plain(self.file.clone())
    }
}

/// One channel of an image.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum ChannelDesc {
    /// Red.
    R,
    /// Green (roughness in glTF's packed metallic–roughness maps).
    G,
    /// Blue (metalness in glTF's packed maps).
    B,
    /// Alpha (1 where the image has none).
    A,
}

/// How an image's 8-bit texels are decoded.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum ColorspaceDesc {
    /// sRGB-encoded: each texel is decoded with the exact sRGB curve before
    /// filtering (colour maps).
    Srgb,
    /// Stored as is: value = byte/255 (roughness, normal, opacity maps).
    Linear,
}

/// Where uv (0, 0) lies on an image.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum OriginDesc {
    /// uv (0, 0) is the bottom-left corner, v grows upward (OBJ, OpenGL, pbrt).
    #[default]
    BottomLeft,
    /// uv (0, 0) is the top-left corner, v grows downward (Mitsuba, DirectX).
    TopLeft,
}

/// A transform of texture coordinates: `uv' = rotate(scale·uv) + offset`.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct UvDesc {
    /// Factor per axis (default (1, 1)): 2 repeats the texture twice.
    #[serde(default = "one2")]
    pub scale: [f32; 2],
    /// Rotation after scaling, counter-clockwise, in degrees (default 0).
    #[serde(default)]
    pub rotation_degrees: f32,
    /// Added last (default (0, 0)).
    #[serde(default)]
    pub offset: [f32; 2],
}

fn one2() -> [f32; 2] {
    [1.0; 2]
}

impl Default for UvDesc {
    fn default() -> Self {
        Self {
            scale: one2(),
            rotation_degrees: 0.0,
            offset: [0.0; 2],
        }
    }
}

impl UvDesc {
    /// Whether the transform leaves UVs unchanged.
    pub fn is_identity(&self) -> bool {
        *self == Self::default()
    }
}

/// A procedural pattern with values in [0, 1], one cell per UV unit before
/// the texture's `uv` transform.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum PatternDesc {
    /// Value noise: random values at integer lattice points, smoothly
    /// interpolated.
    ValueNoise,
    /// Gradient (Perlin) noise, mapped from [−1, 1] to [0, 1].
    GradientNoise,
    /// Fractal sum of gradient noise octaves.
    Fbm {
        /// Number of octaves, 1 to 16 (default 5).
        #[serde(default = "octaves")]
        octaves: u32,
        /// Frequency factor between octaves (default 2).
        #[serde(default = "lacunarity")]
        lacunarity: f32,
        /// Amplitude factor between octaves, in (0, 1) (default 0.5).
        #[serde(default = "gain")]
        gain: f32,
    },
    /// Worley cellular noise: distance to the nearest of one random point per
    /// cell, clamped to [0, 1].
    Cellular,
    /// Stripes across u, one period per UV unit: 1 for the first `duty` of
    /// each period, 0 after.
    Stripes {
        /// Fraction of each period that is 1, in [0, 1] (default 0.5).
        #[serde(default = "duty")]
        duty: f32,
    },
}

fn octaves() -> u32 {
    5
}
fn lacunarity() -> f32 {
    2.0
}
fn gain() -> f32 {
    0.5
}
fn duty() -> f32 {
    0.5
}

impl<V> TexDesc<V> {
    /// The image file, if this is an image (for include path rewriting).
    pub fn file_mut(&mut self) -> Option<&mut String> {
        match self {
            TexDesc::Image(i) => Some(&mut i.file),
            TexDesc::Checker { .. } | TexDesc::Pattern { .. } | TexDesc::Vertex { .. } => None,
        }
    }
}

/// What the texture forms expect, for parse errors.
pub(super) const EXPECTED_TEX: &str = "an image `\"file.png\"`, `Image(file: \"…\")`, `Checker(a: …, b: …, scale: …)`, `Pattern(pattern: Fbm(octaves: 5), a: …, b: …)` or `VertexColor(factor: …)`";

/// Reads the fields of a texture written as a struct (`Image(…)`,
/// `Checker(…)`, `Pattern(…)`), by hand: RON gives no struct name.
pub(super) fn visit_tex_map<'de, V: DeserializeOwned, A: MapAccess<'de>>(
    mut m: A,
) -> Result<TexDesc<V>, A::Error> {
    const FIELDS: &[&str] = &[
        "file",
        "channel",
        "colorspace",
        "scale",
        "offset",
        "origin",
        "uv",
        "wrap",
        "a",
        "b",
        "pattern",
        "seed",
        "factor",
        "times_vertex_color",
    ];
    let mut file = None;
    let mut image = ImageDesc::plain(String::new());
    let (mut a, mut b, mut scale, mut pattern, mut seed) = (None, None, None, None, None);
    let (mut offset, mut uv) = (None, UvDesc::default());
    let mut image_only = Vec::new();
    let mut factor = None;
    while let Some(key) = m.next_key::<String>()? {
        match key.as_str() {
            "file" => file = Some(m.next_value::<String>()?),
            "channel" => {
                image.channel = Some(m.next_value()?);
                image_only.push("channel");
            }
            "colorspace" => {
                image.colorspace = Some(m.next_value()?);
                image_only.push("colorspace");
            }
            "origin" => {
                image.origin = m.next_value()?;
                image_only.push("origin");
            }
            "wrap" => {
                image.wrap = m.next_value()?;
                image_only.push("wrap");
            }
            "scale" => scale = Some(m.next_value::<f32>()?),
            "offset" => offset = Some(m.next_value::<f32>()?),
            "uv" => uv = m.next_value()?,
            "a" => a = Some(m.next_value::<V>()?),
            "b" => b = Some(m.next_value::<V>()?),
            "pattern" => pattern = Some(m.next_value::<PatternDesc>()?),
            "seed" => seed = Some(m.next_value::<u32>()?),
            "factor" => factor = Some(m.next_value::<V>()?),
            "times_vertex_color" => {
                image.times_vertex_color = m.next_value()?;
                image_only.push("times_vertex_color");
            }
            other => return Err(de::Error::unknown_field(other, FIELDS)),
        }
    }
    let misplaced = |what: &str, fields: &[&str]| {
        de::Error::custom(format!(
            "`{}` belongs to an image texture, not {what}",
            fields.join("`, `")
        ))
    };
    if factor.is_some() && (file.is_some() || a.is_some() || b.is_some() || pattern.is_some()) {
        return Err(de::Error::custom(
            "`factor` belongs to `VertexColor(factor: …)`; an image scales with `scale`",
        ));
    }
    if let Some(factor) = factor {
        let channel = image.channel;
        image_only.retain(|f| *f != "channel");
        image_only.extend(offset.map(|_| "offset"));
        image_only.extend(scale.map(|_| "scale"));
        image_only.extend(seed.map(|_| "seed"));
        if !image_only.is_empty() || !uv.is_identity() {
            if !uv.is_identity() {
                image_only.push("uv");
            }
            return Err(de::Error::custom(format!(
                "`VertexColor` takes `factor` and `channel` only, not `{}`",
                image_only.join("`, `")
            )));
        }
        return Ok(TexDesc::Vertex { channel, factor });
    }
    match (file, a, b, pattern) {
        (Some(file), None, None, None) => {
            if seed.is_some() {
                return Err(de::Error::custom("`seed` belongs to a `Pattern`, not an image"));
            }
            image.file = file;
            image.scale = scale.unwrap_or(1.0);
            image.offset = offset.unwrap_or(0.0);
            image.uv = uv;
            Ok(TexDesc::Image(image))
        }
        (None, Some(a), Some(b), None) => {
            if !image_only.is_empty() || offset.is_some() || seed.is_some() {
                image_only.extend(offset.map(|_| "offset"));
                image_only.extend(seed.map(|_| "seed"));
                return Err(misplaced("a `Checker`", &image_only));
            }
            Ok(TexDesc::Checker {
                a,
                b,
                scale: scale.unwrap_or(1.0),
                uv,
            })
        }
        (None, Some(a), Some(b), Some(pattern)) => {
            if !image_only.is_empty() || offset.is_some() || scale.is_some() {
                image_only.extend(offset.map(|_| "offset"));
                image_only.extend(scale.map(|_| "scale"));
                return Err(misplaced(
                    "a `Pattern` (scale it with `uv: (scale: (8, 8))`)",
                    &image_only,
                ));
            }
            Ok(TexDesc::Pattern {
                pattern,
                a,
                b,
                seed: seed.unwrap_or(0),
                uv,
            })
        }
        _ => Err(de::Error::custom(format!("expected {EXPECTED_TEX}"))),
    }
}

impl<V: Serialize + PartialEq> TexDesc<V> {
    /// Writes the struct form, leaving out fields at their defaults; a plain
    /// image is written as its file name.
    pub(super) fn serialize_tex<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        match self {
            TexDesc::Image(i) if i.is_plain() => i.file.serialize(s),
            TexDesc::Image(i) => {
                let mut st = s.serialize_struct("Image", 8)?;
                st.serialize_field("file", &i.file)?;
                if let Some(c) = i.channel {
                    st.serialize_field("channel", &c)?;
                }
                if let Some(c) = i.colorspace {
                    st.serialize_field("colorspace", &c)?;
                }
                if i.scale != 1.0 {
                    st.serialize_field("scale", &i.scale)?;
                }
                if i.offset != 0.0 {
                    st.serialize_field("offset", &i.offset)?;
                }
                if i.origin != OriginDesc::BottomLeft {
                    st.serialize_field("origin", &i.origin)?;
                }
                if i.wrap != WrapDesc::Repeat {
                    st.serialize_field("wrap", &i.wrap)?;
                }
                if !i.uv.is_identity() {
                    st.serialize_field("uv", &i.uv)?;
                }
                if i.times_vertex_color {
                    st.serialize_field("times_vertex_color", &true)?;
                }
                st.end()
            }
            TexDesc::Vertex { channel, factor } => {
                let mut st = s.serialize_struct("VertexColor", 2)?;
                st.serialize_field("factor", factor)?;
                if let Some(c) = channel {
                    st.serialize_field("channel", c)?;
                }
                st.end()
            }
            TexDesc::Checker { a, b, scale, uv } => {
                let mut st = s.serialize_struct("Checker", 4)?;
                st.serialize_field("a", a)?;
                st.serialize_field("b", b)?;
                st.serialize_field("scale", scale)?;
                if !uv.is_identity() {
                    st.serialize_field("uv", uv)?;
                }
                st.end()
            }
            TexDesc::Pattern {
                pattern,
                a,
                b,
                seed,
                uv,
            } => {
                let mut st = s.serialize_struct("Pattern", 5)?;
                st.serialize_field("pattern", pattern)?;
                st.serialize_field("a", a)?;
                st.serialize_field("b", b)?;
                if *seed != 0 {
                    st.serialize_field("seed", seed)?;
                }
                if !uv.is_identity() {
                    st.serialize_field("uv", uv)?;
                }
                st.end()
            }
        }
    }
}

/// A number parameter of a material: a constant or a texture (see the module
/// docs). A texture read by a number gives one channel: a greyscale image, or
/// the `channel` it names.
#[derive(Clone, Debug, PartialEq)]
pub enum ScalarDesc {
    /// The same value everywhere.
    Value(f32),
    /// A texture looked up at the hit's UVs.
    Texture(TexDesc<f32>),
}

impl From<f32> for ScalarDesc {
    fn from(x: f32) -> Self {
        ScalarDesc::Value(x)
    }
}

impl ScalarDesc {
    /// The constant, if this is one.
    pub fn constant(&self) -> Option<f32> {
        match self {
            ScalarDesc::Value(x) => Some(*x),
            ScalarDesc::Texture(_) => None,
        }
    }

    /// The image file, if this is an image texture.
    pub fn file_mut(&mut self) -> Option<&mut String> {
        match self {
            ScalarDesc::Value(_) => None,
            ScalarDesc::Texture(t) => t.file_mut(),
        }
    }
}

impl<'de> Deserialize<'de> for ScalarDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Vis;
        impl<'de> Visitor<'de> for Vis {
            type Value = ScalarDesc;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                write!(f, "a number or {EXPECTED_TEX}")
            }
            fn visit_f64<E: de::Error>(self, x: f64) -> Result<ScalarDesc, E> {
                Ok(ScalarDesc::Value(x as f32))
            }
            fn visit_u64<E: de::Error>(self, x: u64) -> Result<ScalarDesc, E> {
                Ok(ScalarDesc::Value(x as f32))
            }
            fn visit_i64<E: de::Error>(self, x: i64) -> Result<ScalarDesc, E> {
                Ok(ScalarDesc::Value(x as f32))
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<ScalarDesc, E> {
                Ok(ScalarDesc::Texture(TexDesc::Image(ImageDesc::plain(
                    s.to_string(),
                ))))
            }
            fn visit_map<A: MapAccess<'de>>(self, m: A) -> Result<ScalarDesc, A::Error> {
                visit_tex_map(m).map(ScalarDesc::Texture)
            }
        }
        d.deserialize_any(Vis)
    }
}

impl Serialize for ScalarDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            ScalarDesc::Value(x) => x.serialize(s),
            ScalarDesc::Texture(t) => t.serialize_tex(s),
        }
    }
}

/// The JSON Schema of the texture forms whose constants have schema `value`.
pub(super) fn tex_schemas(
    g: &mut schemars::SchemaGenerator,
    value: schemars::Schema,
) -> Vec<schemars::Schema> {
    let uv = g.subschema_for::<UvDesc>();
    let pattern = g.subschema_for::<PatternDesc>();
    let channel = g.subschema_for::<ChannelDesc>();
    let colorspace = g.subschema_for::<ColorspaceDesc>();
    let origin = g.subschema_for::<OriginDesc>();
    let wrap = g.subschema_for::<WrapDesc>();
    vec![
        schemars::json_schema!({ "type": "string", "description": "image file, relative to the scene file" }),
        schemars::json_schema!({
            "title": "Image", "type": "object", "additionalProperties": false, "required": ["file"],
            "description": "Image(file, channel, colorspace, scale, offset, origin, uv, wrap, times_vertex_color)",
            "properties": {
                "file": { "type": "string" }, "channel": channel, "colorspace": colorspace,
                "scale": { "type": "number" }, "offset": { "type": "number" }, "origin": origin, "uv": uv, "wrap": wrap,
                "times_vertex_color": { "type": "boolean" }
            }
        }),
        schemars::json_schema!({
            "title": "Checker", "type": "object", "additionalProperties": false, "required": ["a", "b"],
            "description": "Checker(a, b, scale: squares per UV unit, uv)",
            "properties": { "a": value, "b": value, "scale": { "type": "number", "exclusiveMinimum": 0 }, "uv": uv }
        }),
        schemars::json_schema!({
            "title": "Pattern", "type": "object", "additionalProperties": false, "required": ["pattern", "a", "b"],
            "description": "Pattern(pattern, a, b, seed, uv): a + (b − a)·pattern(uv)",
            "properties": { "pattern": pattern, "a": value, "b": value, "seed": { "type": "integer", "minimum": 0 }, "uv": uv }
        }),
        schemars::json_schema!({
            "title": "VertexColor", "type": "object", "additionalProperties": false, "required": ["factor"],
            "description": "VertexColor(factor, channel): the mesh's vertex colours × factor (white where it has none)",
            "properties": { "factor": value, "channel": channel }
        }),
    ]
}

impl schemars::JsonSchema for ScalarDesc {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Scalar".into()
    }

    fn json_schema(g: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let mut any = vec![schemars::json_schema!({ "type": "number" })];
        any.extend(tex_schemas(g, schemars::json_schema!({ "type": "number" })));
        schemars::json_schema!({
            "description": "A number, or a texture giving one: an image (greyscale, or one `channel`), `Checker(…)` or `Pattern(…)`.",
            "anyOf": any
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Debug)]
    struct M {
        x: ScalarDesc,
    }

    fn parse(s: &str) -> Result<ScalarDesc, ron::error::SpannedError> {
        ron::from_str::<M>(&format!("(x: {s})")).map(|m| m.x)
    }

    #[test]
    fn scalar_desc_accepts_every_form() {
        assert_eq!(parse("0.25").ok(), Some(ScalarDesc::Value(0.25)));
        assert_eq!(parse("1").ok(), Some(ScalarDesc::Value(1.0)));
        let Ok(ScalarDesc::Texture(TexDesc::Image(i))) = parse(
            "Image(file: \"r.png\", channel: G, colorspace: Linear, scale: 2, offset: 0.1, origin: TopLeft)",
        ) else {
            panic!("image form");
        };
        assert_eq!(
            (i.channel, i.colorspace, i.scale, i.offset, i.origin),
            (
                Some(ChannelDesc::G),
                Some(ColorspaceDesc::Linear),
                2.0,
                0.1,
                OriginDesc::TopLeft
            )
        );
        let Ok(ScalarDesc::Texture(TexDesc::Image(i))) =
            parse("Image(file: \"r.png\", channel: R, wrap: Mirror)")
        else {
            panic!("image with a wrap");
        };
        assert_eq!(i.wrap, WrapDesc::Mirror);
        // Written back only when not the default.
        let text = ron::to_string(&ScalarDesc::Texture(TexDesc::Image(i))).expect("writes");
        assert!(text.contains("wrap:Mirror"), "{text}");
        assert!(
            parse("Checker(a: 0.1, b: 0.9, wrap: Clamp)").is_err(),
            "a checker has no edge"
        );
        assert!(matches!(
            parse("Checker(a: 0.1, b: 0.9, scale: 4, uv: (rotation_degrees: 45))"),
            Ok(ScalarDesc::Texture(TexDesc::Checker { .. }))
        ));
        assert!(matches!(
            parse("Pattern(pattern: Fbm(octaves: 3), a: 0.2, b: 0.8, uv: (scale: (8, 8)))"),
            Ok(ScalarDesc::Texture(TexDesc::Pattern {
                pattern: PatternDesc::Fbm { octaves: 3, .. },
                ..
            }))
        ));
        assert!(parse("Pattern(pattern: Cellular, a: 0, b: 1, scale: 2)").is_err());
        assert!(parse("Checker(a: 0, b: 1, channel: R)").is_err());
        assert!(parse("(1, 2, 3)").is_err(), "a colour is not a number");
    }

    #[test]
    fn scalar_desc_round_trips() {
        for s in [
            "0.5",
            "\"r.png\"",
            "Image(file: \"r.png\", channel: A, uv: (scale: (2, 2)))",
            "Checker(a: 0.0, b: 1.0, scale: 3)",
            "Pattern(pattern: Stripes(duty: 0.25), a: 0.0, b: 1.0, seed: 3)",
        ] {
            let x = parse(s).unwrap_or_else(|e| panic!("{s}: {e}"));
            let text = ron::to_string(&x).expect("serialises");
            assert_eq!(parse(&text).ok(), Some(x), "{s} → {text}");
        }
    }
}
