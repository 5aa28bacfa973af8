//! Reading a file that does not parse as a whole, one section at a time, so
//! that every mistake in it is reported in one run.
//!
//! Each top-level field, each element of `objects` and `lights` and each
//! entry of `materials` and `meshes` is deserialised on its own. What parses
//! is assembled into a partial document that semantic checks still run on:
//! a failed element is left out (its neighbours keep their indices through
//! [`Gaps`]), a failed map entry or required field is replaced by a stand-in
//! so that names referring to it are not reported as unknown. A partial
//! document is never built: the file's own errors fail the load.

use super::document::{Document, Gaps, Sections, stand_in_material, stand_in_medium, stand_in_mesh};
use super::format::Format;
use super::slip::Slip;
use crate::desc::{AnimationDesc, TestDesc};
use crate::syntax::outline::{Entry, Outline};
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;
use std::ops::Range;

/// Reads `text` section by section; `whole` is the error the whole file
/// gave, reported if no section shows a mistake of its own.
pub(super) fn read<T: Document>(
    format: &Format,
    text: &str,
    outline: &Outline,
    whole: Slip,
) -> (T, Gaps, Vec<Slip>) {
    let mut r = Reader {
        format,
        text,
        gaps: Gaps::default(),
        slips: Vec::new(),
        seen: Vec::new(),
    };
    for at in &outline.missing_commas {
        let help = "separate fields, elements and entries with commas";
        r.push(Slip::new(at.clone(), "expected `,`".into(), Some(help.into())));
    }
    let mut s = Sections::default();
    for field in &outline.fields {
        r.field::<T>(&mut s, field);
    }
    for name in T::REQUIRED {
        if !r.seen.contains(name) {
            let help = format!("add `{name}: ...`");
            r.push(Slip::new(
                outline.open.clone(),
                format!("missing field `{name}`"),
                Some(help),
            ));
            r.gaps.stand_in(name.to_string());
        }
    }
    // The whole file's first error is kept when no section explains it: it
    // is then about the file's own frame (`Scen(`, text after the end).
    let in_a_section = outline.fields.iter().any(|f| {
        f.value.contains(&whole.span.start) || f.key.as_ref().is_some_and(|k| k.1.contains(&whole.span.start))
    });
    let told = r.slips.iter().any(|s| s.message == whole.message);
    if r.slips.is_empty() || !(in_a_section || told) {
        r.push(whole);
    }
    (T::assemble(s), r.gaps, r.slips)
}

struct Reader<'a> {
    format: &'a Format,
    text: &'a str,
    gaps: Gaps,
    slips: Vec<Slip>,
    /// Top-level fields met so far.
    seen: Vec<&'static str>,
}

impl Reader<'_> {
    /// Records `slip` unless a mistake at the same place already is.
    fn push(&mut self, slip: Slip) {
        if !self
            .slips
            .iter()
            .any(|s| s.span.contains(&slip.span.start) || s.span.start == slip.span.start)
        {
            self.slips.push(slip);
        }
    }

    fn field<T: Document>(&mut self, s: &mut Sections, field: &Entry) {
        let Some((name, key)) = &field.key else {
            return;
        };
        let Some(&known) = T::FIELDS.iter().find(|f| *f == name) else {
            let (message, help) = super::words::unknown("field", name, T::FIELDS, "");
            return self.push(Slip::new(key.clone(), message, help));
        };
        if self.seen.contains(&known) {
            let help = Some("keep one of them".to_string());
            return self.push(Slip::new(
                key.clone(),
                format!("field `{name}` is given twice"),
                help,
            ));
        }
        self.seen.push(known);
        match known {
            "version" => s.version = self.section(known, &field.value),
            "include" => s.include = self.section(known, &field.value),
            "camera" => s.camera = self.section(known, &field.value),
            "film" => s.film = self.section(known, &field.value),
            "integrator" => s.integrator = self.section(known, &field.value),
            "test" => s.test = self.section::<Option<TestDesc>>(known, &field.value).flatten(),
            "animation" => {
                s.animation = self
                    .section::<Option<AnimationDesc>>(known, &field.value)
                    .flatten()
            }
            "materials" => s.materials = self.map(field, "materials", stand_in_material),
            "meshes" => s.meshes = self.map(field, "meshes", stand_in_mesh),
            "media" => s.media = self.map(field, "media", stand_in_medium),
            "medium" => s.medium = self.section::<Option<String>>(known, &field.value).flatten(),
            "lights" => s.lights = self.list(field, "lights"),
            "objects" => s.objects = self.list(field, "objects"),
            _ => {}
        }
    }

    /// A top-level field read as one value; when broken, the document gets
    /// a stand-in (or the default) that nothing is reported on.
    fn section<V: DeserializeOwned>(&mut self, name: &'static str, value: &Range<usize>) -> Option<V> {
        let v = self.one(value);
        if v.is_none() {
            self.gaps.stand_in(name.to_string());
        }
        v
    }

    fn one<V: DeserializeOwned>(&mut self, value: &Range<usize>) -> Option<V> {
        match self.format.read(self.text, value.clone()) {
            Ok(v) => Some(v),
            Err(slip) => {
                self.push(slip);
                None
            }
        }
    }

    /// Reports `whole` (the list's or map's own error) when none of its
    /// items showed a mistake: the mistake is between them.
    /// As [`Self::one`], or the entry with its broken fields repaired
    /// (`repair.rs`); those fields (under `path`) hold stand-ins.
    fn one_or_repaired<V: DeserializeOwned>(&mut self, value: &Range<usize>, path: &str) -> Option<V> {
        if let Some(v) = self.one(value) {
            return Some(v);
        }
        let r = super::repair::repaired(self.format, self.text, value)?;
        for f in r.fields {
            self.gaps.repaired(format!("{path}.{f}"));
        }
        for slip in r.slips {
            self.push(slip);
        }
        Some(r.value)
    }

    fn fallback(&mut self, field: &Entry, whole: Slip) {
        if !self.slips.iter().any(|s| field.value.contains(&s.span.start)) {
            self.push(whole);
        }
    }

    fn list<V: DeserializeOwned>(&mut self, field: &Entry, name: &'static str) -> Vec<V> {
        let whole = match self.format.read::<Vec<V>>(self.text, field.value.clone()) {
            Ok(all) => return all,
            Err(slip) => slip,
        };
        let (mut out, mut kept) = (Vec::new(), Vec::new());
        for (i, item) in field.items.iter().enumerate() {
            if let Some(v) = self.one_or_repaired(&item.value, &format!("{name}[{i}]")) {
                out.push(v);
                kept.push(i);
            }
        }
        self.fallback(field, whole);
        self.gaps.keep(name, kept);
        out
    }

    fn map<V: DeserializeOwned>(
        &mut self,
        field: &Entry,
        name: &str,
        stand_in: fn() -> V,
    ) -> BTreeMap<String, V> {
        let whole = match self
            .format
            .read::<BTreeMap<String, V>>(self.text, field.value.clone())
        {
            Ok(all) => return all,
            Err(slip) => slip,
        };
        let mut out = BTreeMap::new();
        for item in &field.items {
            let Some((written, key)) = &item.key else { continue };
            // A key that does not parse (`“white”`) still names its entry.
            let key_name = self.one::<String>(key).unwrap_or_else(|| {
                let quotes: &[char] = &[
                    '"', '\u{201c}', '\u{201d}', '\u{2018}', '\u{2019}', '\'', '\u{ab}', '\u{bb}',
                ];
                written.trim_matches(quotes).to_string()
            });
            let at = format!("{name}.{key_name}");
            let value = self.one_or_repaired(&item.value, &at).unwrap_or_else(|| {
                self.gaps.stand_in(format!("{name}.{key_name}"));
                stand_in()
            });
            out.insert(key_name, value);
        }
        self.fallback(field, whole);
        out
    }
}
