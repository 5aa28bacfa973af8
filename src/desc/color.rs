//! Colour parameters: a constant or a texture.
//!
//! Written as `(r, g, b)`, a single number for grey, `"file.png"` for an
//! image texture (sRGB-decoded, repeated, bilinear), `Image(file: "…")`, or
//! `Checker(a: (r, g, b), b: (r, g, b), scale: s)`.
//!
//! RON hands a named struct to self-describing deserialisers without its name,
//! so the texture kind is recognised by its fields, not by `Image`/`Checker`.

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
    /// Image file, relative to the scene file.
    Image(String),
    /// Alternating squares of `a` and `b`, `scale` squares per UV unit.
    Checker {
        /// Colour of the squares where ⌊u·scale⌋ + ⌊v·scale⌋ is even, linear RGB.
        a: [f32; 3],
        /// Colour of the other squares, linear RGB.
        b: [f32; 3],
        /// Squares per UV unit (default 1), > 0.
        scale: f32,
    },
}

impl From<[f32; 3]> for ColorDesc {
    fn from(c: [f32; 3]) -> Self {
        ColorDesc::Rgb(c)
    }
}

const EXPECTED: &str = "a colour `(r, g, b)`, a grey level, an image `\"file.png\"`, `Image(file: \"…\")` or `Checker(a: (…), b: (…), scale: …)`";

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
                Ok(ColorDesc::Image(s.to_string()))
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<ColorDesc, A::Error> {
                // Read the fields by hand: `Option` fields would need `Some(…)`.
                const FIELDS: &[&str] = &["file", "a", "b", "scale"];
                let (mut file, mut a, mut b, mut scale) = (None, None, None, None);
                while let Some(key) = m.next_key::<String>()? {
                    match key.as_str() {
                        "file" => file = Some(m.next_value::<String>()?),
                        "a" => a = Some(m.next_value::<[f32; 3]>()?),
                        "b" => b = Some(m.next_value::<[f32; 3]>()?),
                        "scale" => scale = Some(m.next_value::<f32>()?),
                        other => return Err(de::Error::unknown_field(other, FIELDS)),
                    }
                }
                match (file, a, b, scale) {
                    (Some(file), None, None, None) => Ok(ColorDesc::Image(file)),
                    (None, Some(a), Some(b), scale) => Ok(ColorDesc::Checker {
                        a,
                        b,
                        scale: scale.unwrap_or(1.0),
                    }),
                    _ => Err(de::Error::custom(format!("expected {EXPECTED}"))),
                }
            }
        }
        d.deserialize_any(V)
    }
}

impl Serialize for ColorDesc {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        match self {
            ColorDesc::Rgb(c) => c.serialize(s),
            ColorDesc::Image(f) => f.serialize(s),
            ColorDesc::Checker { a, b, scale } => {
                let mut st = s.serialize_struct("Checker", 3)?;
                st.serialize_field("a", a)?;
                st.serialize_field("b", b)?;
                st.serialize_field("scale", scale)?;
                st.end()
            }
        }
    }
}

impl schemars::JsonSchema for ColorDesc {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Color".into()
    }

    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let rgb = schemars::json_schema!({
            "type": "array", "items": { "type": "number", "minimum": 0 }, "minItems": 3, "maxItems": 3
        });
        schemars::json_schema!({
            "description": "A linear RGB colour `(r, g, b)`, a grey level, an image file (sRGB, relative to the scene file), `Image(file: ...)` or `Checker(a: (r, g, b), b: (r, g, b), scale: squares per UV unit)`.",
            "anyOf": [
                rgb,
                { "type": "number", "minimum": 0 },
                { "type": "string", "description": "image file" },
                {
                    "type": "object", "additionalProperties": false, "required": ["file"],
                    "properties": { "file": { "type": "string" } }
                },
                {
                    "type": "object", "additionalProperties": false, "required": ["a", "b"],
                    "properties": { "a": rgb, "b": rgb, "scale": { "type": "number", "exclusiveMinimum": 0 } }
                }
            ]
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
        assert_eq!(
            parse("\"wood.png\"").ok(),
            Some(ColorDesc::Image("wood.png".into()))
        );
        assert_eq!(
            parse("Image(file: \"wood.png\")").ok(),
            Some(ColorDesc::Image("wood.png".into()))
        );
        assert_eq!(
            parse("Checker(a: (1, 1, 1), b: (0, 0, 0), scale: 4)").ok(),
            Some(ColorDesc::Checker {
                a: [1.0; 3],
                b: [0.0; 3],
                scale: 4.0
            })
        );
        assert!(parse("(1, 2)").is_err() && parse("(1, 2, 3, 4)").is_err());
        assert!(
            parse("Checker(a: (1, 1, 1), c: (0, 0, 0))").is_err(),
            "unknown field"
        );
    }
}
