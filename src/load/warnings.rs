//! Warnings: scenes that load but will surprise (issue 12).
//!
//! Validation rejects what cannot be rendered; this pass looks at a scene that
//! passed it and names what will render, but almost certainly not as meant.
//! Each rule errs on the side of silence: a warning that fires on a scene
//! that was fine teaches people to ignore warnings. The rules:
//!
//! - **No light.** Nothing emits (no `lights`, no emissive object, or all of
//!   zero power): the image is black. [`emits`] is the one place that knows
//!   what emits; a mesh that keeps its MTL materials counts as emitting
//!   (its `Ke` is not known without reading the files).
//! - **Specular under `Direct`.** An object, mesh override or area light
//!   surface uses a material that is perfectly specular ([`specular_kind`]),
//!   and the integrator is `Direct` (the default), which never follows a
//!   specular bounce: those surfaces come out black.
//! - **Area light facing away.** A `Quad`/`Rect` light emits only on the side
//!   its normal (`edge_u × edge_v`, `half_u × half_v`) points to; it warns
//!   when every receiver lies behind or in that plane (`facing`).
//!   Meshes, instances and SDFs are judged by their bounds once built
//!   ([`warnings_built`]); where those are not known they count as lit.
//! - **Sun from below.** A `Directional` light whose `direction` (the way
//!   the light travels) points more than 5° up the camera's `up`: the
//!   light comes from under the horizon, which is what writing the
//!   direction *toward* the sun gives (pbrt's `from`/`to`, Blender's
//!   gizmo); the ground is then lit from beneath.
//! - **Field of view under 5°.** `fov_y_degrees` written in radians by habit
//!   (`0.7`) still validates and zooms in about 57 times.
//! - **Coloured glass too dark to see through.** An object of coloured glass
//!   (`attenuation`) so thick for its `distance` that light crossing its
//!   thinnest side keeps under 1/1000 of every channel: it renders black
//!   (a `distance` written in centimetres in a scene of metres). Judged by
//!   the object's bounds once built ([`warnings_built`]).
//!
//! Reflectances written on a 0–255 scale are not here: any reflectance
//! channel above 1 is already an error (`validate::Checker::color`), whose
//! help says "divide by 255" when the colour looks like bytes.
//!
//! The functions are pure on the checked description; the loader locates
//! their problems like errors ([`located`]) and marks them warnings.

mod facing;

use super::include::Composition;
use crate::desc::{CameraDesc, ColorDesc, IntegratorDesc, LightDesc, MaterialDesc, ObjectDesc, SceneDesc};
use crate::diagnostic::{Diagnostic, Problem, Report, Severity};
use crate::syntax::spans::Spans;
use std::collections::BTreeSet;

/// Narrowest field of view that is not suspicious, in degrees. Real long
/// lenses go below it (a 600 mm lens on full frame is about 2.3°), but a
/// scene file with such a camera is far rarer than `fov_y_degrees: 0.7`.
pub const MIN_FOV_DEGREES: f32 = 5.0;

pub use facing::object_extents;

/// Every warning for a scene that passed validation, in a stable order:
/// lights, materials, area lights in file order, camera. Meshes, instances
/// and SDFs count as lit by every area light (see [`warnings_built`]).
pub fn warnings(desc: &SceneDesc) -> Vec<Problem> {
    warnings_built(desc, &[], None)
}

/// As [`warnings`], with the world bounds of each object as built
/// ([`object_extents`]), so that meshes, instances and SDFs are judged too,
/// and `lit`: whether the built scene has a light of positive power (what
/// its files hold is then known: an MTL's `Ke`, a glTF's emission or
/// punctual lights).
pub fn warnings_built(
    desc: &SceneDesc,
    built: &[Option<crate::accel::Aabb>],
    lit: Option<bool>,
) -> Vec<Problem> {
    let mut out = Vec::new();
    out.extend(no_light(desc, lit));
    out.extend(specular_under_direct(desc));
    out.extend(facing::lights_facing_away(desc, built));
    out.extend(suns_from_below(desc));
    out.extend(narrow_fov(&desc.camera));
    out.extend(dark_coloured_glass(desc, built));
    out
}

/// The warnings a scene with mistakes can still trust, shown with its
/// errors: a rule speaks only when none of the sections it reads has one
/// (`broken(section)`: `lights`, `objects`, …), since a broken entry left
/// out of a partial description could make it speak falsely (a lamp that
/// did not parse is not "no light").
pub fn warnings_beside(desc: &SceneDesc, broken: &dyn Fn(&str) -> bool) -> Vec<Problem> {
    let clean = |sections: &[&str]| !sections.iter().any(|s| broken(s));
    let lit = clean(&["include", "lights", "objects", "meshes"]);
    let mut out = Vec::new();
    if lit {
        out.extend(no_light(desc, None));
    }
    if clean(&["include", "materials", "integrator", "objects", "lights"]) {
        out.extend(specular_under_direct(desc));
    }
    if lit {
        out.extend(facing::lights_facing_away(desc, &[]));
    }
    if clean(&["include", "lights", "camera"]) {
        out.extend(suns_from_below(desc));
    }
    if clean(&["include", "camera"]) {
        out.extend(narrow_fov(&desc.camera));
    }
    out
}

/// Locates warnings as [`Composition::locate`] locates errors (through
/// includes), marked [`Severity::Warning`]. A warning about something the
/// top file does not write at all (no `lights:`) points at the start of the
/// scene rather than at no line.
pub fn located(composition: &Composition, problems: &[Problem]) -> Report {
    let mut report = composition.locate(problems).with_severity(Severity::Warning);
    let Some((top, text)) = composition.sources.first() else {
        return report;
    };
    let Some(root) = Spans::scan(text).get("") else {
        return report;
    };
    // The scene's first line (`Scene(` or `{`), not the whole file.
    let line_end = text[root.start..].find('\n').map_or(root.end, |n| root.start + n);
    let start = root.start..line_end.min(root.end).max(root.start + 1);
    for d in report.diagnostics.iter_mut() {
        if d.span.is_none() && d.file == *top {
            let mut at = Diagnostic::new(top, text, Some(start.clone()), d.message.clone());
            at.severity = d.severity;
            at.path = d.path.take();
            at.help = d.help.take();
            *d = at;
        }
    }
    report
}

/// Whether anything in the scene emits light: a light of positive power, an
/// object with positive `emission`, a mesh that keeps some of its MTL
/// materials (an MTL `Ke` emits, and reading the files to find out is the
/// build's work: such a mesh errs on the side of silence), or any glTF
/// asset (emissive materials or `KHR_lights_punctual` lights).
pub fn emits(desc: &SceneDesc) -> bool {
    let positive = |c: &[f32; 3]| c.iter().any(|&x| x > 0.0);
    // A texture is taken to glow somewhere: its checks report a black one.
    let glows = |c: &ColorDesc| match c {
        ColorDesc::Rgb(c) => positive(c),
        ColorDesc::Texture(_) => true,
    };
    let light = desc.lights.iter().any(|l| match l {
        LightDesc::Point { intensity, .. } | LightDesc::Spot { intensity, .. } => positive(intensity),
        LightDesc::Directional { irradiance, .. } => positive(irradiance),
        LightDesc::Quad { radiance, .. } | LightDesc::Rect { radiance, .. } => glows(radiance),
        LightDesc::Environment {
            radiance, strength, ..
        } => *strength > 0.0 && radiance.as_ref().is_none_or(positive),
    });
    let object = desc.objects.iter().any(|o| {
        // An OBJ's MTL or a glTF's own materials may emit (`Ke`,
        // `emissiveFactor`) unless the scene replaces them all.
        let mtl =
            matches!(o, ObjectDesc::Mesh { .. } | ObjectDesc::Instance { .. }) && o.material().is_none();
        // A glTF may also carry `KHR_lights_punctual` lights, whatever
        // replaces its materials.
        let gltf = matches!(o, ObjectDesc::Gltf { .. });
        mtl || gltf || o.emission().is_some_and(|e| glows(&e.radiance))
    });
    light || object
}

/// The black-image warning: from the built scene's lights when known
/// (`lit`), else from the description ([`emits`]).
fn no_light(desc: &SceneDesc, lit: Option<bool>) -> Option<Problem> {
    if lit.unwrap_or_else(|| emits(desc)) {
        return None;
    }
    let message = if desc.lights.is_empty() {
        "the scene has no lights and no emissive objects: it will render black"
    } else {
        "every light has zero intensity or radiance: the scene will render black"
    };
    Some(Problem::new("lights", message).help(
        "add a light with a positive intensity or radiance, e.g. \
         `lights: [Rect(center: (0, 3, 0), half_u: (1, 0, 0), half_v: (0, 0, 1), radiance: (5, 5, 5))]`, \
         a sky (`lights: [Environment(radiance: (0.8, 0.9, 1))]`), or an object's `emission`",
    ))
}

/// Why `m` is perfectly specular, or `None` if it has a lobe that direct
/// lighting can see. Mirror and Glass are delta distributions; a microfacet
/// model at roughness 0 is clamped to α = 10⁻³ (`microfacet::MIN_ALPHA`),
/// a mirror in effect, and MetalPlastic only if also fully metallic (else its
/// diffuse base is lit).
pub fn specular_kind(m: &MaterialDesc) -> Option<&'static str> {
    match m {
        MaterialDesc::Mirror { .. } => Some("a perfect mirror"),
        MaterialDesc::Glass { .. } => Some("smooth glass"),
        MaterialDesc::CookTorrance { roughness, .. } if roughness.constant().is_some_and(|r| r <= 0.0) => {
            Some("a microfacet reflector at roughness 0 (a mirror in effect)")
        }
        MaterialDesc::MetalPlastic {
            roughness, metalness, ..
        } if roughness.constant().is_some_and(|r| r <= 0.0)
            && metalness.constant().is_some_and(|m| m >= 1.0) =>
        {
            Some("a polished metal (roughness 0, metalness 1: a mirror in effect)")
        }
        MaterialDesc::NormalMap { material, .. }
        | MaterialDesc::Bump { material, .. }
        | MaterialDesc::Cutout { material, .. } => specular_kind(material),
        // Specular only if both are: either's smooth lobe is lit.
        MaterialDesc::Blend { a, b, .. } => specular_kind(a).and(specular_kind(b)),
        // Listed, not `_`: a new material must say whether it is specular.
        MaterialDesc::CookTorrance { .. }
        | MaterialDesc::MetalPlastic { .. }
        | MaterialDesc::Lambert { .. }
        | MaterialDesc::OrenNayar { .. }
        | MaterialDesc::Phong { .. }
        | MaterialDesc::BlinnPhong { .. }
        | MaterialDesc::RoughPlastic { .. }
        | MaterialDesc::RoughGlass { .. } => None,
    }
}

/// One warning per specular material that something uses, located at the
/// material (the integrator is often not written: `Direct` is the default).
/// Mirrors and glass that meshes take from their MTL files are not seen.
fn specular_under_direct(desc: &SceneDesc) -> Vec<Problem> {
    if !matches!(desc.integrator, IntegratorDesc::Direct { .. }) {
        return Vec::new();
    }
    let lights = desc.lights.iter().filter_map(|l| match l {
        LightDesc::Quad { material, .. } | LightDesc::Rect { material, .. } => material.as_deref(),
        LightDesc::Point { .. }
        | LightDesc::Spot { .. }
        | LightDesc::Directional { .. }
        | LightDesc::Environment { .. } => None,
    });
    let overrides = desc.objects.iter().flat_map(|o| {
        o.material_overrides()
            .into_iter()
            .flatten()
            .map(|(_, m)| m.as_str())
    });
    let used: BTreeSet<&str> = desc
        .objects
        .iter()
        .filter_map(ObjectDesc::material)
        .chain(overrides)
        .chain(lights)
        .collect();
    desc.materials
        .iter()
        .filter(|(name, _)| used.contains(name.as_str()))
        .filter_map(|(name, m)| {
            let kind = specular_kind(m)?;
            Some(
                Problem::new(
                    format!("materials.{name}"),
                    format!(
                        "material `{name}` is {kind}, but the `Direct` integrator (the default) \
                         does not follow specular bounces: it will look black"
                    ),
                )
                .help("use `integrator: Path(max_depth: 8)` or `integrator: Whitted(max_depth: 5)`"),
            )
        })
        .collect()
}

/// Least share of a channel that light crossing a coloured glass object's
/// thinnest side may keep, in every channel, before the object is
/// reported as rendering black.
pub const DARK_GLASS_KEEPS: f32 = 1e-3;

/// The `attenuation` of `m` or of any material inside it (through
/// wrappers and both sides of blends): colour and distance.
fn attenuation_in(m: &MaterialDesc) -> Option<crate::desc::AttenuationDesc> {
    match m.inner() {
        crate::desc::MaterialInner::Wrapped(inner) => attenuation_in(inner),
        crate::desc::MaterialInner::Blend(a, b) => attenuation_in(a).or_else(|| attenuation_in(b)),
        crate::desc::MaterialInner::Model => {
            if let MaterialDesc::Glass { attenuation, .. } | MaterialDesc::RoughGlass { attenuation, .. } = m
            {
                *attenuation
            } else {
                None
            }
        }
    }
}

/// One warning per object of coloured glass that keeps under
/// [`DARK_GLASS_KEEPS`] of every channel across its thinnest side (its
/// bounds as built; objects whose bounds are not known are not judged).
fn dark_coloured_glass(desc: &SceneDesc, built: &[Option<crate::accel::Aabb>]) -> Vec<Problem> {
    let mut out = Vec::new();
    for (i, o) in desc.objects.iter().enumerate() {
        let Some(name) = o.material() else { continue };
        let Some(a) = desc.materials.get(name).and_then(attenuation_in) else {
            continue;
        };
        let Some(Some(b)) = built.get(i) else { continue };
        let size = b.max - b.min;
        let thinnest = size.min_element();
        if !(thinnest > 0.0 && thinnest.is_finite() && a.distance > 0.0) {
            continue;
        }
        // log₁₀ of the most any channel keeps (in logs: the share itself
        // leaves f32 for thick objects).
        let keeps = a
            .color
            .iter()
            .map(|c| c.log10() * thinnest / a.distance)
            .fold(f32::NEG_INFINITY, f32::max);
        if keeps < DARK_GLASS_KEEPS.log10() {
            out.push(
                Problem::new(
                    format!("materials.{name}.attenuation.distance"),
                    format!(
                        "object `objects[{i}]` is {thinnest:.3} scene units across its thinnest side, and its \
                         coloured glass keeps `color` every {} units: light crossing it keeps at most 1e{keeps:.0} \
                         of any channel, so it will look black",
                        a.distance
                    ),
                )
                .help(format!(
                    "`distance` is in scene units: about the object's thickness ({thinnest:.3}) gives it `color` \
                     across"
                )),
            );
        }
    }
    out
}

/// One warning per directional light of positive irradiance that travels
/// upward, more than 5° above the camera's horizon (module docs).
fn suns_from_below(desc: &SceneDesc) -> Vec<Problem> {
    let up = glam::Vec3::from(desc.camera.up).normalize_or_zero();
    desc.lights
        .iter()
        .enumerate()
        .filter_map(|(i, l)| match l {
            LightDesc::Directional {
                direction, irradiance, ..
            } if irradiance.iter().any(|&e| e > 0.0) => {
                let d = glam::Vec3::from(*direction).normalize_or_zero();
                let sin_elevation = d.dot(up);
                (sin_elevation > 5f32.to_radians().sin()).then(|| {
                    let [x, y, z] = (-d).to_array();
                    Problem::new(
                        format!("lights[{i}].direction"),
                        format!(
                            "this light travels upward ({:.0}° above the horizon): it shines from below the scene",
                            sin_elevation.clamp(-1.0, 1.0).asin().to_degrees()
                        ),
                    )
                    .help(format!(
                        "`direction` is the way the light travels, from the sky toward the scene (a sun overhead is \
                         `(0, -1, 0)`); if the sun was meant to be where this points, write `direction: ({x:.3}, {y:.3}, {z:.3})`"
                    ))
                })
            }
            LightDesc::Directional { .. }
            | LightDesc::Point { .. }
            | LightDesc::Spot { .. }
            | LightDesc::Quad { .. }
            | LightDesc::Rect { .. }
            | LightDesc::Environment { .. } => None,
        })
        .collect()
}

/// A field of view under [`MIN_FOV_DEGREES`]; the help offers the radian
/// reading when it would be a valid angle.
fn narrow_fov(camera: &CameraDesc) -> Option<Problem> {
    let f = camera.fov_y_degrees?;
    if f >= MIN_FOV_DEGREES {
        return None;
    }
    let help = if f < std::f32::consts::PI {
        format!(
            "`fov_y_degrees` is in degrees; if {f} was meant in radians, write {:.1}",
            f.to_degrees()
        )
    } else {
        "`fov_y_degrees` is the full vertical angle in degrees; typical values are 30–90".to_string()
    };
    Some(
        Problem::new(
            "camera.fov_y_degrees",
            format!(
                "a field of view of {f}° is very narrow (under {MIN_FOV_DEGREES}°): \
                 the image will show a tiny, magnified part of the scene"
            ),
        )
        .help(help),
    )
}

#[cfg(test)]
mod tests;
