//! The scene format's JSON Schema (generated from `desc/`, whose doc
//! comments are the field docs) walked along a [`Context`]'s brackets: what
//! a key means, which keys and variants a bracket takes.

use crate::syntax::cursor::{Context, Step};
use serde_json::Value;

/// The scene schema, parsed once when the server starts.
pub struct Schema {
    root: Value,
}

/// A schema node reached from the root, and whether it is the payload of a
/// newtype variant (`Translate((1, 0, 0))`: the tuple inside is the value).
#[derive(Clone, Copy)]
pub struct Node<'a> {
    /// The schema node.
    pub value: &'a Value,
    newtype: bool,
}

impl Schema {
    /// Parses the schema generated from `desc/` ([`crate::schema::schema_json`]).
    pub fn new() -> Self {
        let root = serde_json::from_str(&crate::schema::schema_json()).unwrap_or(Value::Null);
        Self { root }
    }

    /// Follows `$ref`, and an optional value to its non-null alternative.
    pub fn resolve<'a>(&'a self, mut v: &'a Value) -> &'a Value {
        for _ in 0..8 {
            if let Some(r) = v.get("$ref").and_then(Value::as_str) {
                let name = r.rsplit('/').next().unwrap_or("");
                match self.root.get("$defs").and_then(|d| d.get(name)) {
                    Some(d) => v = d,
                    None => return v,
                }
                continue;
            }
            let alts = alternatives(v);
            let non_null: Vec<&Value> = alts
                .iter()
                .copied()
                .filter(|a| a.get("type").and_then(Value::as_str) != Some("null"))
                .collect();
            if alts.len() == 2 && non_null.len() == 1 {
                v = non_null[0];
                continue;
            }
            return v;
        }
        v
    }

    /// The payload schema of variant `name` of an enum node, or `None`.
    pub fn variant<'a>(&'a self, v: &'a Value, name: &str) -> Option<&'a Value> {
        let v = self.resolve(v);
        for alt in alternatives(v) {
            let alt = self.resolve(alt);
            if let Some(p) = alt.get("properties").and_then(|p| p.get(name))
                && alt
                    .get("required")
                    .and_then(Value::as_array)
                    .is_some_and(|r| r.len() == 1)
            {
                return Some(p);
            }
            if alt.get("const").and_then(Value::as_str) == Some(name)
                || enum_names(alt).iter().any(|n| n == name)
                || struct_title(alt) == Some(name)
            {
                return Some(alt);
            }
        }
        None
    }

    /// Every variant of an enum node: (name, description).
    pub fn variants<'a>(&'a self, v: &'a Value) -> Vec<(String, Option<&'a str>)> {
        let v = self.resolve(v);
        let mut out: Vec<(String, Option<&str>)> = enum_names(v).into_iter().map(|n| (n, None)).collect();
        for alt in alternatives(v) {
            let alt = self.resolve(alt);
            let doc = alt.get("description").and_then(Value::as_str);
            if let Some(c) = alt.get("const").and_then(Value::as_str) {
                out.push((c.to_string(), doc));
            }
            out.extend(enum_names(alt).into_iter().map(|n| (n, doc)));
            out.extend(struct_title(alt).map(|t| (t.to_string(), doc)));
            if alt
                .get("required")
                .and_then(Value::as_array)
                .is_some_and(|r| r.len() == 1)
                && let Some(props) = alt.get("properties").and_then(Value::as_object)
                && props.len() == 1
            {
                out.extend(props.keys().map(|k| (k.clone(), doc)));
            }
        }
        out
    }

    fn step<'a>(&'a self, n: Node<'a>, step: &Step) -> Option<Node<'a>> {
        if n.newtype && *step == Step::Index(0) {
            return Some(Node {
                value: n.value,
                newtype: false,
            });
        }
        let v = self.resolve(n.value);
        let value = match step {
            Step::Named(k) => match v.get("properties").and_then(|p| p.get(k)) {
                Some(p) => p,
                None => match self.variant(v, k) {
                    Some(p) => p,
                    None => v.get("additionalProperties").filter(|a| a.is_object())?,
                },
            },
            Step::Index(i) => match v.get("prefixItems").and_then(Value::as_array) {
                Some(items) => items.get(*i)?,
                None => match v.get("items")? {
                    Value::Array(items) => items.get(*i)?,
                    items => items,
                },
            },
        };
        Some(Node {
            value,
            newtype: false,
        })
    }

    /// Enters a bracket written after `variant` (`Sphere(`): the variant's
    /// payload; a struct name (`Scene(`) or `Some(` leaves the node as is.
    fn enter<'a>(&'a self, n: Node<'a>, variant: Option<&str>, open: char) -> Node<'a> {
        let Some(name) = variant else {
            return n;
        };
        match self.variant(n.value, name) {
            Some(p) => {
                let payload = self.resolve(p);
                let is_struct = payload.get("properties").is_some();
                Node {
                    value: p,
                    newtype: open == '(' && !is_struct,
                }
            }
            None => n,
        }
    }

    /// The schema of the innermost bracket of `cx`.
    pub fn frame<'a>(&'a self, cx: &Context) -> Option<Node<'a>> {
        let mut n = Node {
            value: &self.root,
            newtype: false,
        };
        for f in &cx.frames {
            if let Some(s) = &f.step {
                n = self.step(n, s)?;
            }
            n = self.enter(n, f.variant.as_deref(), f.open);
        }
        Some(n)
    }

    /// The schema of the value being written at `cx` (after `key:`, or the
    /// current element).
    pub fn value<'a>(&'a self, cx: &Context) -> Option<&'a Value> {
        let n = self.frame(cx)?;
        self.step(n, &cx.value_step()?).map(|n| n.value)
    }

    /// The struct fields a bracket takes: (name, schema), in schema order.
    pub fn fields<'a>(&'a self, frame: Node<'a>) -> Vec<(&'a str, &'a Value)> {
        let v = self.resolve(frame.value);
        v.get("properties")
            .and_then(Value::as_object)
            .map(|p| p.iter().map(|(k, v)| (k.as_str(), v)).collect())
            .unwrap_or_default()
    }

    /// Whether `key` is required in the struct `frame`.
    pub fn required(&self, frame: Node<'_>, key: &str) -> bool {
        self.resolve(frame.value)
            .get("required")
            .and_then(Value::as_array)
            .is_some_and(|r| r.iter().any(|k| k == key))
    }

    /// Markdown for a field: its documentation, type, default and range.
    pub fn describe(&self, name: &str, field: &Value, required: bool) -> String {
        let v = self.resolve(field);
        let doc = field
            .get("description")
            .or_else(|| v.get("description"))
            .and_then(Value::as_str)
            .unwrap_or("");
        let mut s = format!("**`{name}`**: {}", self.type_name(field));
        s += if required { " (required)" } else { "" };
        if let Some(d) = field.get("default").or_else(|| v.get("default")) {
            s += &format!("\n\ndefault: `{}`", ron_like(d));
        }
        if let Some(r) = range(v) {
            s += &format!("\n\nrange: {r}");
        }
        if !doc.is_empty() {
            s += &format!("\n\n{doc}");
        }
        s
    }

    /// A short type: `number`, `vector (x, y, z)`, `Camera`, `one of A | B`.
    pub fn type_name(&self, field: &Value) -> String {
        if let Some(r) = field.get("$ref").and_then(Value::as_str) {
            let name = r.rsplit('/').next().unwrap_or("");
            return name.trim_end_matches("Desc").to_string();
        }
        let v = self.resolve(field);
        let variants = self.variants(v);
        if !variants.is_empty() {
            let names: Vec<&str> = variants.iter().map(|(n, _)| n.as_str()).collect();
            return format!("one of {}", names.join(" | "));
        }
        let ty = match v.get("type") {
            Some(Value::Array(a)) => a
                .iter()
                .filter_map(Value::as_str)
                .find(|t| *t != "null")
                .unwrap_or("value"),
            Some(Value::String(t)) => t.as_str(),
            _ => "value",
        };
        match ty {
            "array"
                if v.get("minItems") == Some(&Value::from(3))
                    && v.get("maxItems") == Some(&Value::from(3)) =>
            {
                "vector (x, y, z)".into()
            }
            "array" => format!(
                "list of {}",
                v.get("items").map_or("values".into(), |i| self.type_name(i))
            ),
            "object" if v.get("additionalProperties").is_some_and(Value::is_object) => {
                "map name → value".into()
            }
            t => t.into(),
        }
    }
}

impl Default for Schema {
    fn default() -> Self {
        Self::new()
    }
}

fn alternatives(v: &Value) -> Vec<&Value> {
    ["oneOf", "anyOf"]
        .iter()
        .filter_map(|k| v.get(*k).and_then(Value::as_array))
        .flatten()
        .collect()
}

/// The name of a struct told apart by its fields rather than a tag (a
/// texture: `Image(file: …)`, `Checker(a: …, b: …)`), which its schema
/// carries as `title`.
fn struct_title(v: &Value) -> Option<&str> {
    v.get("properties")?;
    v.get("title").and_then(Value::as_str)
}

fn enum_names(v: &Value) -> Vec<String> {
    v.get("enum")
        .and_then(Value::as_array)
        .map(|a| a.iter().filter_map(Value::as_str).map(String::from).collect())
        .unwrap_or_default()
}

fn range(v: &Value) -> Option<String> {
    let num = |k: &str| v.get(k).and_then(Value::as_f64);
    let lo = num("exclusiveMinimum")
        .map(|x| format!("> {x}"))
        .or(num("minimum").map(|x| format!("≥ {x}")));
    let hi = num("exclusiveMaximum")
        .map(|x| format!("< {x}"))
        .or(num("maximum").map(|x| format!("≤ {x}")));
    match (lo, hi) {
        (None, None) => None,
        (a, b) => Some([a, b].into_iter().flatten().collect::<Vec<_>>().join(", ")),
    }
}

/// A JSON default written as RON: arrays as tuples, objects as structs.
fn ron_like(v: &Value) -> String {
    match v {
        Value::Array(a) => format!("({})", a.iter().map(ron_like).collect::<Vec<_>>().join(", ")),
        Value::Object(o) if o.len() == 1 => {
            let (k, v) = o.iter().next().map(|(k, v)| (k.clone(), v)).unwrap_or_default();
            match v {
                Value::Object(_) => format!("{k}{}", ron_like(v)),
                _ => format!("{k}({})", ron_like(v)),
            }
        }
        Value::Object(o) if o.is_empty() => "{}".into(),
        Value::Object(o) => format!(
            "({})",
            o.iter()
                .map(|(k, v)| format!("{k}: {}", ron_like(v)))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        Value::String(s) => s.clone(),
        v => v.to_string(),
    }
}
