//! What a partial read of a file produces: the kinds of file ([`Document`]:
//! a scene, an included file), the sections each may hold, the stand-ins for
//! broken ones, and the [`Gaps`] that map problems in the partial document
//! back to the paths the user wrote.

use crate::desc::{
    CameraDesc, ColorDesc, FilmDesc, IncludeDesc, IntegratorDesc, LightDesc, MaterialDesc, MediumDesc,
    MeshDesc, ObjectDesc, SceneDesc, TestDesc,
};
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;

/// What a partial read left out, so that problems found in the rest keep the
/// paths the user wrote.
#[derive(Clone, Debug, Default)]
pub struct Gaps {
    /// For `objects` and `lights`: the written index of each element kept.
    kept: Vec<(&'static str, Vec<usize>)>,
    /// Sections replaced by a stand-in (`camera`, `materials.glass`).
    stand_ins: Vec<String>,
    /// Fields of entries read with them repaired (also stand-ins).
    repaired: Vec<String>,
}

impl Gaps {
    /// `list` (`objects`, `lights`) kept only the elements written at
    /// indices `kept`.
    pub(super) fn keep(&mut self, list: &'static str, kept: Vec<usize>) {
        self.kept.push((list, kept));
    }

    /// `path` (`camera`, `materials.glass`) holds a stand-in.
    pub(super) fn stand_in(&mut self, path: String) {
        self.stand_ins.push(path);
    }

    /// `path` is a field of an entry that was read with it repaired
    /// (`objects[3].center`): the entry itself is whole.
    pub(super) fn repaired(&mut self, path: String) {
        self.repaired.push(path.clone());
        self.stand_ins.push(path);
    }

    /// Whether `path` (as written) is in a repaired field.
    pub fn is_repaired(&self, path: &str) -> bool {
        self.repaired.iter().any(|s| {
            path.strip_prefix(s.as_str())
                .is_some_and(|r| r.is_empty() || r.starts_with(['.', '[']))
        })
    }

    /// The path the user wrote for `path` of the partial document, or `None`
    /// for a path inside a stand-in (nothing is reported there: its own
    /// parse error already was).
    pub fn original(&self, path: &str) -> Option<String> {
        let written = self.written(path);
        // Stand-ins are named as written (`materials.glass`, and for the
        // repaired fields of a list element, `objects[3].center`).
        let under = |p: &str| {
            written
                .strip_prefix(p)
                .is_some_and(|r| r.is_empty() || r.starts_with(['.', '[']))
        };
        if self.stand_ins.iter().any(|s| under(s)) {
            return None;
        }
        Some(written)
    }

    /// `path` of the partial document with list indices as written.
    fn written(&self, path: &str) -> String {
        for (list, kept) in &self.kept {
            let Some(rest) = path.strip_prefix(list).and_then(|r| r.strip_prefix('[')) else {
                continue;
            };
            let Some((index, tail)) = rest.split_once(']') else {
                continue;
            };
            if let Some(written) = index.parse::<usize>().ok().and_then(|i| kept.get(i)) {
                return format!("{list}[{written}]{tail}");
            }
        }
        path.to_string()
    }
}

/// Every top-level section a scene or included file may hold, each read on
/// its own; `None` when absent or broken.
#[derive(Default)]
pub struct Sections {
    /// `version: N`.
    pub version: Option<u32>,
    /// `include: [...]`.
    pub include: Option<Vec<String>>,
    /// `camera: (...)`.
    pub camera: Option<CameraDesc>,
    /// `film: (...)`.
    pub film: Option<FilmDesc>,
    /// `integrator: ...`.
    pub integrator: Option<IntegratorDesc>,
    /// `test: (...)`.
    pub test: Option<TestDesc>,
    /// `animation: (...)`.
    pub animation: Option<crate::desc::AnimationDesc>,
    /// The `materials` entries that read; broken ones are stand-ins.
    pub materials: BTreeMap<String, MaterialDesc>,
    /// The `meshes` entries that read; broken ones are stand-ins.
    pub meshes: BTreeMap<String, MeshDesc>,
    /// The `media` entries that read; broken ones are stand-ins.
    pub media: BTreeMap<String, MediumDesc>,
    /// `medium: "name"`.
    pub medium: Option<String>,
    /// The `lights` elements that read (broken ones are left out).
    pub lights: Vec<LightDesc>,
    /// The `objects` elements that read (broken ones are left out).
    pub objects: Vec<ObjectDesc>,
}

/// A kind of file: a scene or an included file.
pub trait Document: DeserializeOwned {
    /// Its top-level fields, as serde names them.
    const FIELDS: &'static [&'static str];
    /// Required fields (stand-ins are used when they are missing or broken).
    const REQUIRED: &'static [&'static str];
    /// The document made of the sections that were read.
    fn assemble(s: Sections) -> Self;
}

impl Document for SceneDesc {
    const FIELDS: &'static [&'static str] = &[
        "version",
        "include",
        "camera",
        "film",
        "integrator",
        "materials",
        "lights",
        "objects",
        "media",
        "medium",
        "meshes",
        "test",
        "animation",
    ];
    const REQUIRED: &'static [&'static str] = &["camera"];
    fn assemble(s: Sections) -> Self {
        SceneDesc {
            version: s.version,
            include: s.include.unwrap_or_default(),
            camera: s.camera.unwrap_or_else(stand_in_camera),
            film: s.film.unwrap_or_default(),
            integrator: s.integrator.unwrap_or_default(),
            materials: s.materials,
            lights: s.lights,
            objects: s.objects,
            meshes: s.meshes,
            media: s.media,
            medium: s.medium,
            test: s.test,
            animation: s.animation,
        }
    }
}

impl Document for IncludeDesc {
    const FIELDS: &'static [&'static str] = &["include", "materials", "lights", "objects"];
    const REQUIRED: &'static [&'static str] = &[];
    fn assemble(s: Sections) -> Self {
        IncludeDesc {
            include: s.include.unwrap_or_default(),
            materials: s.materials,
            lights: s.lights,
            objects: s.objects,
        }
    }
}

fn stand_in_camera() -> CameraDesc {
    CameraDesc {
        eye: Some([0.0, 0.0, 1.0]),
        target: Some([0.0; 3]),
        gltf: None,
        up: [0.0, 1.0, 0.0],
        fov_y_degrees: Some(40.0),
        projection: crate::desc::ProjectionDesc::Perspective,
        aperture_radius: 0.0,
        focus_distance: None,
        shutter: None,
        keys: Vec::new(),
        interpolation: Default::default(),
    }
}

/// What a broken `media` entry reads as: clear air, so names referring to
/// it are not reported as unknown.
pub(super) fn stand_in_medium() -> MediumDesc {
    MediumDesc::Homogeneous {
        sigma_t: Some([0.0; 3]),
        albedo: None,
        sigma_a: None,
        sigma_s: None,
        scale: 1.0,
        g: 0.0,
    }
}

pub(super) fn stand_in_material() -> MaterialDesc {
    MaterialDesc::Lambert {
        albedo: ColorDesc::Rgb([0.5; 3]),
    }
}

pub(super) fn stand_in_mesh() -> MeshDesc {
    MeshDesc {
        file: String::new(),
        smooth: false,
    }
}

/// The fields serde's derive lists for `T`, read from its unknown-field error.
#[cfg(test)]
fn fields_of<T: DeserializeOwned>() -> Vec<&'static str> {
    match ron::from_str::<T>("(not_a_field: 0)") {
        Err(e) => match e.code {
            ron::Error::NoSuchStructField { expected, .. } => expected.to_vec(),
            _ => Vec::new(),
        },
        Ok(_) => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnostic::suggest;

    /// `FIELDS` must list what serde accepts, or a new field would be
    /// reported as unknown whenever another part of the file is broken.
    #[test]
    fn sections_know_every_field_serde_knows() {
        assert_eq!(fields_of::<SceneDesc>(), SceneDesc::FIELDS);
        assert_eq!(fields_of::<IncludeDesc>(), IncludeDesc::FIELDS);
        assert!(suggest("objcts", SceneDesc::FIELDS.iter().copied()) == Some("objects"));
    }

    #[test]
    fn gaps_keep_written_indices_and_hide_stand_ins() {
        let g = Gaps {
            kept: vec![("objects", vec![0, 2, 3])],
            stand_ins: vec!["materials.glass".into()],
            repaired: Vec::new(),
        };
        assert_eq!(
            g.original("objects[1].radius").as_deref(),
            Some("objects[2].radius")
        );
        assert_eq!(g.original("objects[2]").as_deref(), Some("objects[3]"));
        assert_eq!(g.original("materials.glass.ior"), None);
        assert_eq!(
            g.original("materials.glassy").as_deref(),
            Some("materials.glassy")
        );
        assert_eq!(g.original("film.spp").as_deref(), Some("film.spp"));
    }
}
