//! `--set path=value`: typed overrides applied to the parsed scene, not to
//! its text. The scene is serialised to a JSON tree, the value (written in
//! RON) replaces the node at `path`, and the tree is deserialised again, so
//! every override is type-checked by the same serde types as the file.
//!
//! Paths use the diagnostic syntax: `film.spp`, `camera.fov_y_degrees`,
//! `materials.floor.albedo`, `objects[2].radius`. Enum variant names are
//! skipped, as in diagnostics (`materials.floor.albedo`, not
//! `materials.floor.Lambert.albedo`).

use crate::desc::SceneDesc;
use crate::diagnostic::{Problem, suggest};
use serde_json::Value;

/// A problem with one `--set` argument, kept with the argument as written so
/// the diagnostic can point at it.
#[derive(Clone, Debug, PartialEq)]
pub struct SetProblem {
    /// The `--set` argument as the user wrote it.
    pub arg: String,
    /// What is wrong with it.
    pub problem: Problem,
}

/// Applies every `path=value` in order; all problems are reported together.
/// Each override is type-checked as it is applied, so a value that does not
/// fit is blamed on its own argument. The overrides that fit are applied even
/// when others do not, so the scene is still checked as the user meant it.
pub fn apply_sets(desc: &mut SceneDesc, sets: &[String]) -> Result<(), Vec<SetProblem>> {
    if sets.is_empty() {
        return Ok(());
    }
    let blame = |arg: &str, problem: Problem| SetProblem {
        arg: arg.to_string(),
        problem,
    };
    let mut tree =
        serde_json::to_value(&*desc).map_err(|e| vec![blame("", Problem::new("", e.to_string()))])?;
    let mut problems = Vec::new();
    for s in sets {
        match apply_one(&tree, s) {
            Ok(next) => tree = next,
            Err(p) => problems.push(blame(s, p)),
        }
    }
    // Every override kept has type-checked the whole tree.
    if let Ok(d) = serde_json::from_value::<SceneDesc>(tree) {
        *desc = d;
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems)
    }
}

/// `tree` with the override `s` applied, if it names a field and its value
/// fits there.
fn apply_one(tree: &Value, s: &str) -> Result<Value, Problem> {
    let Some((path, text)) = s.split_once('=') else {
        return Err(Problem::new(s, format!("`--set {s}` has no `=`"))
            .help("write `--set path=value`, e.g. `--set film.spp=256`"));
    };
    let (path, text) = (path.trim(), text.trim());
    let value = parse_value(text).map_err(|e| {
        Problem::new(path, format!("cannot parse `{text}`: {e}"))
            .help("values are written in RON: `256`, `30.5`, `(0.2, 0.2, 0.2)`, `\"file.obj\"`")
    })?;
    let mut next = tree.clone();
    *node_mut(&mut next, path)? = value;
    match serde_json::from_value::<SceneDesc>(next.clone()) {
        Ok(_) => Ok(next),
        Err(e) => {
            // The serde help (a close variant name) when there is one.
            let (why, help) = super::words::serde_message(&e.to_string());
            Err(
                Problem::new(path, format!("`{text}` does not fit here: {why}")).help(help.unwrap_or_else(
                    || "check the value's type: numbers, `(r, g, b)` colours, `\"strings\"`".into(),
                )),
            )
        }
    }
}

/// RON text to the JSON shape serde gives the scene types. `ron::Value`
/// drops enum variant names (`Sobol` parses as a unit, `Path(max_depth: 8)`
/// as a bare map), so a leading identifier is kept as the externally tagged
/// variant it names: `Sobol` → `"Sobol"`, `Path(max_depth: 8)` →
/// `{"Path": {"max_depth": 8}}`; `Some(x)` is `x` and `None` is null.
fn parse_value(text: &str) -> Result<Value, String> {
    let plain = |t: &str| {
        ron::from_str::<ron::Value>(t)
            .map_err(|e| {
                let at = crate::diagnostic::offset_of(t, e.span.start.line, e.span.start.col);
                super::words::ron_error(&e.code, &t[at..]).0
            })
            .and_then(|v| serde_json::to_value(v).map_err(|e| e.to_string()))
    };
    let end = text
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(text.len());
    let (ident, rest) = text.split_at(end);
    if !ident.starts_with(|c: char| c.is_ascii_alphabetic()) || matches!(ident, "true" | "false") {
        return plain(text);
    }
    let rest = rest.trim();
    let body = || match plain(rest)? {
        // `(x)`: a newtype variant's one value.
        Value::Array(mut a) if a.len() == 1 => Ok(a.remove(0)),
        // `()`: a struct variant with every field at its default, as a
        // file writes `Path()` or `Gaussian()`.
        Value::Null => Ok(Value::Object(Default::default())),
        v => Ok(v),
    };
    match (ident, rest) {
        ("None", "") => Ok(Value::Null),
        (_, "") => Ok(Value::String(ident.to_string())),
        (_, r) if r.starts_with('(') && r.ends_with(')') => match ident {
            "Some" => body(),
            _ => Ok(Value::Object(
                [(ident.to_string(), body()?)].into_iter().collect(),
            )),
        },
        _ => plain(text),
    }
}

enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

fn segments(path: &str) -> Result<Vec<Seg<'_>>, String> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, mut rest) = match part.find('[') {
            Some(i) => (&part[..i], &part[i..]),
            None => (part, ""),
        };
        if !key.is_empty() {
            out.push(Seg::Key(key));
        }
        while let Some(r) = rest.strip_prefix('[') {
            let end = r.find(']').ok_or_else(|| format!("unclosed `[` in `{path}`"))?;
            let i = r[..end]
                .parse()
                .map_err(|_| format!("`{}` is not an index in `{path}`", &r[..end]))?;
            out.push(Seg::Index(i));
            rest = &r[end + 1..];
        }
    }
    Ok(out)
}

/// Is `v` an externally tagged enum value (`{"Variant": {...}}`)?
fn variant_body(v: &Value) -> Option<&str> {
    let o = v.as_object()?;
    let (k, _) = o.iter().next()?;
    (o.len() == 1 && k.starts_with(|c: char| c.is_ascii_uppercase())).then_some(k.as_str())
}

fn node_mut<'v>(root: &'v mut Value, path: &str) -> Result<&'v mut Value, Problem> {
    let segs = segments(path).map_err(|m| Problem::new(path, m))?;
    if segs.is_empty() {
        return Err(Problem::new(path, "empty path").help("name a field, e.g. `film.spp`"));
    }
    let mut node = root;
    let mut done = String::new();
    for seg in segs {
        // Step through an enum variant layer transparently.
        if let (Seg::Key(k), Some(variant)) = (&seg, variant_body(node))
            && *k != variant
        {
            let variant = variant.to_string();
            node = node
                .get_mut(&variant)
                .ok_or_else(|| Problem::new(path, "internal: variant vanished"))?;
        }
        match seg {
            Seg::Key(k) => {
                let keys: Vec<String> = node
                    .as_object()
                    .map(|o| o.keys().cloned().collect())
                    .unwrap_or_default();
                let here = if done.is_empty() {
                    "the scene".to_string()
                } else {
                    format!("`{done}`")
                };
                if !keys.iter().any(|x| x == k) {
                    let mut p = Problem::new(path, format!("{here} has no field `{k}`"));
                    p = match suggest(k, keys.iter().map(String::as_str)) {
                        Some(s) => p.help(format!("did you mean `{s}`?")),
                        None if keys.is_empty() => p.help(format!("{here} is not a struct or map")),
                        None => p.help(format!("its fields are: {}", keys.join(", "))),
                    };
                    return Err(p);
                }
                node = node
                    .get_mut(k)
                    .ok_or_else(|| Problem::new(path, "internal: key vanished"))?;
                done = if done.is_empty() {
                    k.to_string()
                } else {
                    format!("{done}.{k}")
                };
            }
            Seg::Index(i) => {
                let len = node.as_array().map(Vec::len);
                match len {
                    Some(n) if i < n => node = &mut node[i],
                    Some(n) => {
                        return Err(Problem::new(
                            path,
                            format!("`{done}` has {n} elements; index {i} is out of range"),
                        ));
                    }
                    None => return Err(Problem::new(path, format!("`{done}` is not a list"))),
                }
                done = format!("{done}[{i}]");
            }
        }
    }
    Ok(node)
}

#[cfg(test)]
mod tests {
    use super::parse_value;
    use serde_json::json;

    #[test]
    fn enum_variants_keep_their_names() {
        let v = |t: &str| parse_value(t).unwrap_or_else(|e| panic!("{t}: {e}"));
        assert_eq!(v("Sobol"), json!("Sobol"));
        assert_eq!(
            v("Path(max_depth: 8, rr_depth: 5)"),
            json!({"Path": {"max_depth": 8, "rr_depth": 5}})
        );
        assert_eq!(v("Path()"), json!({"Path": {}}), "as a file writes it");
        assert_eq!(v("Some(3.5)"), json!(3.5));
        assert_eq!(v("None"), json!(null));
        assert_eq!(v("true"), json!(true));
        assert_eq!(v("256"), json!(256));
        assert_eq!(v("(0.2, 0.2, 0.2)"), json!([0.2, 0.2, 0.2]));
        assert_eq!(v("\"box.obj\""), json!("box.obj"));
    }
}
