//! Media: the checks of each `media` entry, of the global `medium` and of
//! the `interior`/`exterior` names objects give, and the build step that
//! makes the runtime [`Media`] table (only when something uses a medium,
//! so scenes without media carry none and render as before).

use super::validate::Checker;
use crate::desc::{Color, IntegratorDesc, MediumDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::Problem;
use crate::media::vol::{MAX_VOXELS, parse_vol};
use crate::media::{Boundary, Grid, HenyeyGreenstein, Homogeneous, Media, Medium, NO_MEDIUM};
use glam::Vec3A;
use std::collections::HashMap;
use std::path::Path;

/// Largest optical depth (σ_t × length) across a grid's box: delta and ratio
/// tracking take about that many steps per ray segment through it, so the
/// bound keeps a render's cost per ray finite (and far below
/// `media::grid::MAX_STEPS`).
pub const MAX_GRID_OPTICAL_DEPTH: f32 = 10_000.0;

impl Checker {
    /// The scene's `media`, its global `medium`, and whether the integrator
    /// renders them.
    pub(super) fn media(&mut self, scene: &SceneDesc) {
        for (name, m) in &scene.media {
            self.medium(&format!("media.{name}"), m);
        }
        if let Some(name) = &scene.medium {
            self.name_ref("medium", "medium", name, scene.media.keys(), "media");
        }
        let used = scene.medium.is_some()
            || scene.objects.iter().any(|o| {
                let (i, e) = o.media();
                i.is_some() || e.is_some()
            });
        if used && !matches!(scene.integrator, IntegratorDesc::Path { .. }) {
            self.push(
                "integrator",
                "this integrator ignores participating media",
                "media are rendered by `Path(...)` (Mitsuba's volpath conventions)",
            );
        }
    }

    fn medium(&mut self, path: &str, m: &MediumDesc) {
        match m {
            MediumDesc::Homogeneous {
                sigma_t,
                albedo,
                sigma_a,
                sigma_s,
                scale,
                g,
            } => {
                match (sigma_t, sigma_a, sigma_s) {
                    (Some(t), None, None) => self.coefficient(&format!("{path}.sigma_t"), t),
                    (None, Some(a), Some(s)) => {
                        self.coefficient(&format!("{path}.sigma_a"), a);
                        self.coefficient(&format!("{path}.sigma_s"), s);
                    }
                    _ => self.push(
                        path,
                        "give either `sigma_t` (with an optional `albedo`) or both `sigma_a` and `sigma_s`",
                        "e.g. `Homogeneous(sigma_t: (0.5, 0.5, 0.5), albedo: (0.8, 0.8, 0.8))`",
                    ),
                }
                if let Some(a) = albedo {
                    if sigma_t.is_none() {
                        self.push(
                            &format!("{path}.albedo"),
                            "`albedo` goes with `sigma_t`",
                            "with `sigma_a` and `sigma_s` the albedo is σ_s/(σ_a + σ_s)",
                        );
                    }
                    self.color(&format!("{path}.albedo"), a, Some(1.0));
                }
                self.scale(&format!("{path}.scale"), *scale);
                self.phase_g(&format!("{path}.g"), *g);
            }
            MediumDesc::Grid {
                file,
                min,
                max,
                scale,
                albedo,
                g,
            } => {
                self.file(&format!("{path}.file"), file, "density grid");
                if self.finite(&format!("{path}.min"), min)
                    && self.finite(&format!("{path}.max"), max)
                    && (0..3).any(|k| min[k] >= max[k])
                {
                    self.push(
                        &format!("{path}.max"),
                        format!("the box {min:?}–{max:?} is empty"),
                        "`max` must exceed `min` on every axis",
                    );
                }
                self.scale(&format!("{path}.scale"), *scale);
                self.color(&format!("{path}.albedo"), albedo, Some(1.0));
                self.phase_g(&format!("{path}.g"), *g);
            }
        }
    }

    /// Coefficients per channel: finite and ≥ 0.
    fn coefficient(&mut self, path: &str, c: &Color) {
        if self.finite(path, c) && c.iter().any(|&x| x < 0.0) {
            self.push(
                path,
                format!("negative coefficient {c:?}"),
                "absorption, scattering and extinction are ≥ 0 per scene unit",
            );
        }
    }

    fn scale(&mut self, path: &str, s: f32) {
        if !(s.is_finite() && s >= 0.0) {
            self.push(
                path,
                format!("scale {s} must be finite and ≥ 0"),
                "it multiplies the coefficients",
            );
        }
    }

    fn phase_g(&mut self, path: &str, g: f32) {
        if !(g > -1.0 && g < 1.0) {
            self.push(
                path,
                format!("g {g} is outside (−1, 1)"),
                "the Henyey–Greenstein mean cosine: 0 is isotropic, 0.3–0.9 forward scattering",
            );
        }
    }

    /// Object `path`'s `interior`/`exterior` names, and a sphere's missing
    /// material (only a medium shape may leave it out).
    pub(super) fn object_media(&mut self, path: &str, o: &ObjectDesc, scene: &SceneDesc) {
        let (interior, exterior) = o.media();
        for (key, name) in [("interior", interior), ("exterior", exterior)] {
            if let Some(name) = name {
                self.name_ref(
                    &format!("{path}.{key}"),
                    "medium",
                    name,
                    scene.media.keys(),
                    "media",
                );
            }
        }
        if let ObjectDesc::Sphere { material, .. } = o
            && material.is_empty()
            && interior.is_none()
        {
            self.push(
                &format!("{path}.material"),
                "a sphere needs a material",
                "name one from `materials` (only a sphere with an `interior` medium may leave it out)",
            );
        }
    }
}

/// The built media in name order, and each one's index by name.
pub(super) type BuiltMedia = (Vec<Medium>, HashMap<String, u32>);

/// The scene's media by name, built (grid files read), in name order.
pub(super) fn build_media(desc: &SceneDesc, base: &Path) -> Result<BuiltMedia, Vec<Problem>> {
    let mut media = Vec::new();
    let mut index = HashMap::new();
    let mut problems = Vec::new();
    for (name, m) in &desc.media {
        let at = format!("media.{name}");
        match build_medium(m, base) {
            Ok(medium) => {
                index.insert(name.clone(), media.len() as u32);
                media.push(medium);
            }
            Err(p) => problems.push(Problem::new(at, p.0).help(p.1)),
        }
    }
    if problems.is_empty() {
        Ok((media, index))
    } else {
        Err(problems)
    }
}

/// One medium; on failure, the message and its help.
fn build_medium(m: &MediumDesc, base: &Path) -> Result<Medium, (String, String)> {
    Ok(match m {
        MediumDesc::Homogeneous {
            sigma_t,
            albedo,
            sigma_a,
            sigma_s,
            scale,
            g,
        } => {
            let v = |c: &Color| Vec3A::from(*c) * *scale;
            let (t, s) = match (sigma_t, sigma_a, sigma_s) {
                (Some(t), _, _) => (v(t), v(t) * Vec3A::from(albedo.unwrap_or([1.0; 3]))),
                (None, Some(a), Some(s)) => (v(a) + v(s), v(s)),
                _ => (Vec3A::ZERO, Vec3A::ZERO),
            };
            Medium::Homogeneous(Homogeneous {
                sigma_t: t,
                sigma_s: s,
                phase: HenyeyGreenstein { g: *g },
            })
        }
        MediumDesc::Grid {
            file,
            min,
            max,
            scale,
            albedo,
            g,
        } => {
            let full = base.join(file);
            let len = std::fs::metadata(&full).map(|m| m.len()).unwrap_or(0);
            if len > 48 + 4 * MAX_VOXELS {
                return Err((
                    format!("`{file}` is {len} bytes, more than a grid of {MAX_VOXELS} values"),
                    "resample the grid (256³ at most)".into(),
                ));
            }
            let bytes =
                std::fs::read(&full).map_err(|e| (format!("cannot read `{file}`: {e}"), String::new()))?;
            let vol = parse_vol(&bytes).map_err(|e| {
                (
                    format!("`{file}`: {e}"),
                    "write Mitsuba's .vol version 3, float32, one channel".into(),
                )
            })?;
            let (lo, hi) = (Vec3A::from(*min), Vec3A::from(*max));
            let grid = Grid::new(
                vol.res,
                vol.values,
                (lo, hi),
                *scale,
                Vec3A::from(*albedo),
                HenyeyGreenstein { g: *g },
            );
            let depth = grid.majorant * (hi - lo).length();
            if depth.is_nan() || depth > MAX_GRID_OPTICAL_DEPTH {
                return Err((
                    format!("optical depth {depth:e} across the grid's box is above {MAX_GRID_OPTICAL_DEPTH}"),
                    "lower `scale`: such a dense grid is opaque, and tracking through it would take that many steps per ray".into(),
                ));
            }
            Medium::Grid(Box::new(grid))
        }
    })
}

/// The runtime media table: boundaries by object id (`objects[i]` is
/// `1 + i`; ids up to `ids` exist), or `None` when neither the camera nor
/// any object is in a medium.
pub(super) fn scene_media(
    desc: &SceneDesc,
    media: Vec<Medium>,
    index: &HashMap<String, u32>,
    ids: usize,
) -> Option<Box<Media>> {
    let find = |n: Option<&str>| n.and_then(|n| index.get(n)).copied();
    let camera = find(desc.medium.as_deref()).unwrap_or(NO_MEDIUM);
    let mut boundaries = vec![None; ids];
    for (i, o) in desc.objects.iter().enumerate() {
        let (interior, exterior) = o.media();
        if interior.is_none() && exterior.is_none() {
            continue;
        }
        let null = match o {
            ObjectDesc::Sphere { material, .. } => material.is_empty(),
            ObjectDesc::Mesh {
                material, materials, ..
            } => material.is_none() && materials.is_empty(),
            ObjectDesc::Sdf { .. }
            | ObjectDesc::Plane { .. }
            | ObjectDesc::Quad { .. }
            | ObjectDesc::Rect { .. }
            | ObjectDesc::Instance { .. }
            | ObjectDesc::Gltf { .. } => false,
        };
        if let Some(b) = boundaries.get_mut(i + 1) {
            *b = Some(Boundary {
                inside: find(interior).unwrap_or(NO_MEDIUM),
                outside: find(exterior).unwrap_or(camera),
                null,
            });
        }
    }
    if camera == NO_MEDIUM && boundaries.iter().all(Option::is_none) {
        return None;
    }
    let any_null = boundaries.iter().flatten().any(|b| b.null);
    Some(Box::new(Media {
        media,
        camera,
        boundaries,
        any_null,
    }))
}
