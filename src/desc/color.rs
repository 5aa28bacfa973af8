//! Colour parameters: a constant or a texture.
//!
//! Written as `(r, g, b)`, a single number for grey, `"file.png"` for an
//! image texture (sRGB-decoded, repeated, bilinear), `Image(file: "…")`, or
//! `Checker(a: (r, g, b), b: (r, g, b), scale: s)`, or a `Pattern(…)`; every
//! texture form is in [`super::texture`].
//!
//! RON hands a named struct to self-describing deserialisers without its name,
//! so the texture kind is recognised by its fields, not by `Image`/`Checker`.

use super::texture::{ImageDesc, TexDesc, tex_schemas, visit_tex_map};
use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// A colour parameter of a material: a constant or a texture looked up at the
/// hit's UV coordinates. Written in any of the forms in the module docs; its
/// JSON Schema is hand-written (its `JsonSchema` impl), since the forms are
/// told apart by shape rather than by a tag.
#[derive(Clone, Debug, PartialEq)]
pub enum ColorDesc {
    /// A constant linear RGB colour; a bare number `g` is read as `(g, g, g)`.
    Rgb([f32; 3]),
    /// A texture: an image, a checker or a procedural pattern
    /// (see [`super::texture`]).
    Texture(TexDesc<[f32; 3]>),
}

impl From<[f32; 3]> for ColorDesc {
    fn from(c: [f32; 3]) -> Self {
        ColorDesc::Rgb(c)
    }
}

impl ColorDesc {
    /// A plain image texture of `file` (every other field at its default).
    pub fn image(file: &str) -> Self {
        ColorDesc::Texture(TexDesc::Image(ImageDesc::plain(file.to_string())))
    }

    /// The image file, if this is an image texture.
    pub fn file_mut(&mut self) -> Option<&mut String> {
        match self {
            ColorDesc::Rgb(_) => None,
            ColorDesc::Texture(t) => t.file_mut(),
        }
    }
}

const EXPECTED: &str = "a colour `(r, g, b)`, a grey level, an image `\"file.png\"`, `Image(file: \"…\")`, `Checker(a: (…), b: (…), scale: …)` or `Pattern(pattern: …, a: (…), b: (…))`";

impl<'de> Deserialize<'de> for ColorDesc {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = ColorDesc;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> Result<ColorDesc, A::Error> {
                let mut v = [0.0f32; 3];
                for (i, c) in v.iter_mut().enumerate() {
                    *c = s
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &"3 channels (r, g, b)"))?;
                }
                if s.next_element::<f32>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &"3 channels (r, g, b)"));
                }
                Ok(ColorDesc::Rgb(v))
            }
            fn visit_f64<E: de::Error>(self, x: f64) -> Result<ColorDesc, E> {
                Ok(ColorDesc::Rgb([x as f32; 3]))
            }
            fn visit_u64<E: de::Error>(self, x: u64) -> Result<ColorDesc, E> {
                Ok(ColorDesc::Rgb([x as f32; 3]))
            }
            fn visit_i64<E: de::Error>(self, x: i64) -> Result<ColorDesc, E> {
                Ok(ColorDesc::Rgb([x as f32; 3]))
            }
            fn visit_str<E: de::Error>(self, s: &str) -> Result<ColorDesc, E> {
                Ok(ColorDesc::image(s))
            }
            fn visit_map<A: MapAccess<'de>>(self, m: A) -> Result<ColorDesc, A::Error> {
                visit_tex_map(m).map(ColorDesc::Texture)
            }
        }
        d.deserialize_any(V)
    }
}

impl Serialize for ColorDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            ColorDesc::Rgb(c) => c.serialize(s),
            ColorDesc::Texture(t) => t.serialize_tex(s),
        }
    }
}

impl schemars::JsonSchema for ColorDesc {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Color".into()
    }

    fn json_schema(g: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let rgb = schemars::json_schema!({
            "type": "array", "items": { "type": "number", "minimum": 0 }, "minItems": 3, "maxItems": 3
        });
        let mut any = vec![
            rgb.clone(),
            schemars::json_schema!({ "type": "number", "minimum": 0 }),
        ];
        any.extend(tex_schemas(g, rgb));
        schemars::json_schema!({
            "description": "A linear RGB colour `(r, g, b)`, a grey level, an image file (sRGB unless `colorspace: Linear`, relative to the scene file), `Image(file: ...)`, `Checker(a: (r, g, b), b: (r, g, b), scale: squares per UV unit)` or `Pattern(pattern: ..., a: (r, g, b), b: (r, g, b))`; docs/textures.md.",
            "anyOf": any
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Debug)]
    struct M {
        c: ColorDesc,
    }

    fn parse(s: &str) -> Result<ColorDesc, ron::error::SpannedError> {
        ron::from_str::<M>(&format!("(c: {s})")).map(|m| m.c)
    }

    #[test]
    fn color_desc_accepts_every_form() {
        assert_eq!(parse("(0.5, 1, 0)").ok(), Some(ColorDesc::Rgb([0.5, 1.0, 0.0])));
        assert_eq!(parse("0.25").ok(), Some(ColorDesc::Rgb([0.25; 3])));
        assert_eq!(parse("\"wood.png\"").ok(), Some(ColorDesc::image("wood.png")));
        assert_eq!(
            parse("Image(file: \"wood.png\")").ok(),
            Some(ColorDesc::image("wood.png"))
        );
        assert_eq!(
            parse("Checker(a: (1, 1, 1), b: (0, 0, 0), scale: 4)").ok(),
            Some(ColorDesc::Texture(super::super::texture::TexDesc::Checker {
                a: [1.0; 3],
                b: [0.0; 3],
                scale: 4.0,
                uv: Default::default(),
            }))
        );
        assert!(parse("(1, 2)").is_err() && parse("(1, 2, 3, 4)").is_err());
        assert!(
            parse("Checker(a: (1, 1, 1), c: (0, 0, 0))").is_err(),
            "unknown field"
        );
    }
}
