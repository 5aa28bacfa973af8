//! Lights: the checks of each `lights` entry and the build step that turns
//! them into runtime [`Light`]s. An area light is also a shape in the
//! scene's BVH (camera rays see it), so it adds its quad to the shapes. An
//! environment reads its map here (`.exr` or `.hdr` through the `image`
//! crate) and builds its sampling tables.

use super::build_context::BuildContext;
use super::validate::{Checker, MAX_RADIANCE, RADIANCE_HELP};
use crate::desc::LightDesc;
use crate::diagnostic::{Problem, suggest};
use crate::geometry::{Quad, Shape};
use crate::imageio::read::MAX_IMAGE_SIDE;
use crate::lights::{DirectionalLight, EnvMap, EnvironmentLight, Light, PointLight, QuadLight, SpotLight};
use crate::math::Rgb;
use glam::Vec3A;
use std::path::Path;

/// File extensions an environment map may have: linear formats only.
const MAP_EXTENSIONS: [&str; 2] = ["exr", "hdr"];

impl Checker {
    pub(super) fn light(&mut self, path: &str, l: &LightDesc, materials: &[&str]) {
        let p = |f: &str| format!("{path}.{f}");
        let surface = |v: &mut Self, m: &Option<String>| {
            if let Some(name) = m.as_deref().filter(|n| !materials.contains(n)) {
                let mut pr = Problem::new(p("material"), format!("unknown material `{name}`"));
                if let Some(s) = suggest(name, materials.iter().copied()) {
                    pr = pr.help(format!("did you mean `{s}`?"));
                }
                v.problems.push(pr);
            }
        };
        match l {
            LightDesc::Point { position, intensity } => {
                self.finite(&p("position"), position);
                self.emitted(&p("intensity"), intensity, "intensity");
            }
            LightDesc::Spot {
                position,
                direction,
                intensity,
                cone_degrees,
                falloff_degrees,
            } => {
                self.finite(&p("position"), position);
                self.nonzero(&p("direction"), direction, "`direction`");
                self.emitted(&p("intensity"), intensity, "intensity");
                if !(*cone_degrees > 0.0 && *cone_degrees < 180.0) {
                    self.push(
                        &p("cone_degrees"),
                        format!("cone angle {cone_degrees} is outside (0, 180)"),
                        "the full opening angle of the cone, in degrees",
                    );
                }
                if !(*falloff_degrees >= 0.0 && *falloff_degrees <= *cone_degrees) {
                    self.push(
                        &p("falloff_degrees"),
                        format!("falloff {falloff_degrees} is outside [0, cone_degrees = {cone_degrees}]"),
                        "the falloff band is the outer part of the cone",
                    );
                }
            }
            LightDesc::Directional {
                direction,
                irradiance,
                angle_degrees,
            } => {
                self.nonzero(&p("direction"), direction, "`direction`");
                self.emitted(&p("irradiance"), irradiance, "irradiance");
                self.range(
                    &p("angle_degrees"),
                    *angle_degrees,
                    0.0,
                    180.0,
                    "angular diameter",
                    "the sun's disk in degrees: 0 is a hard sun, the real sun is about 0.53",
                );
            }
            LightDesc::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
                material,
            } => {
                self.finite(&p("corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
                self.emitted_param(&p("radiance"), radiance);
                surface(self, material);
            }
            LightDesc::Rect {
                center,
                half_u,
                half_v,
                radiance,
                material,
            } => {
                self.finite(&p("center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
                self.emitted_param(&p("radiance"), radiance);
                surface(self, material);
            }
            LightDesc::Environment {
                radiance,
                map,
                strength,
                rotation_degrees,
                visible,
                background,
            } => {
                self.environment(path, radiance.as_ref(), map.as_deref(), *strength);
                if !rotation_degrees.is_finite() {
                    self.push(
                        &p("rotation_degrees"),
                        "non-finite angle",
                        "use a finite angle in degrees",
                    );
                }
                if let Some(b) = background {
                    self.color(&p("background"), b, None);
                    if *visible {
                        self.push(
                            &p("background"),
                            "`background` is only seen when `visible` is false",
                            "add `visible: false` to hide the environment behind the scene, or remove `background`",
                        );
                    }
                }
            }
        }
    }

    /// An environment's source (exactly one of `radiance` and `map`) and strength.
    fn environment(&mut self, path: &str, radiance: Option<&[f32; 3]>, map: Option<&str>, strength: f32) {
        let p = |f: &str| format!("{path}.{f}");
        match (radiance, map) {
            (None, None) => self.push(
                path,
                "an environment needs `radiance` or `map`",
                "give a constant `radiance: (0.8, 0.9, 1.0)` or an equirectangular `map: \"sky.exr\"`",
            ),
            (Some(_), Some(_)) => self.push(
                &p("radiance"),
                "an environment takes `radiance` or `map`, not both",
                "remove one; `strength` scales a map",
            ),
            _ => {}
        }
        if let Some(c) = radiance {
            self.emitted(&p("radiance"), c, "radiance");
        }
        if let Some(f) = map {
            let ext = Path::new(f)
                .extension()
                .and_then(|e| e.to_str())
                .unwrap_or("")
                .to_ascii_lowercase();
            if MAP_EXTENSIONS.contains(&ext.as_str()) {
                self.file(&p("map"), f, "environment map");
            } else {
                self.push(
                    &p("map"),
                    format!("environment map `{f}` is not a linear HDR image"),
                    "use an OpenEXR (`.exr`) or Radiance (`.hdr`) file: 8-bit images clip the sun and sky",
                );
            }
        }
        if !(strength >= 0.0 && strength.is_finite()) {
            self.push(
                &p("strength"),
                format!("strength {strength} must be ≥ 0 and finite"),
                "it multiplies the radiance or map; 1 keeps it as given",
            );
        } else {
            // The radiance the sky has: each channel times `strength` (a map's
            // texels are bounded once read, in the build step).
            let brightest = radiance.map_or(1.0, |c| c.iter().fold(0.0f32, |m, &x| m.max(x)));
            if brightest <= MAX_RADIANCE && strength * brightest > MAX_RADIANCE {
                self.push(
                    &p("strength"),
                    format!(
                        "strength {strength:e} makes the sky's radiance {:e}, above the limit of {MAX_RADIANCE:e}",
                        strength * brightest
                    ),
                    RADIANCE_HELP,
                );
            }
        }
    }

    /// At most one environment among all lights (includes counted): the second
    /// and later ones are errors.
    pub(super) fn one_environment(&mut self, lights: &[LightDesc]) {
        let mut envs = lights
            .iter()
            .enumerate()
            .filter(|(_, l)| matches!(l, LightDesc::Environment { .. }))
            .map(|(i, _)| i);
        let Some(first) = envs.next() else {
            return;
        };
        for i in envs {
            self.push(
                &format!("lights[{i}]"),
                format!("a scene has one environment, and lights[{first}] is already one"),
                "merge them into one `Environment`",
            );
        }
    }
}

/// Adds the runtime light of `l`, entry `i` of the scene's lights (and the quad
/// of an area light), to `ctx`.
pub(super) fn build_light(ctx: &mut BuildContext, i: usize, l: &LightDesc) {
    // An area light's surface is black unless the scene gives it a material.
    let surface = |ctx: &BuildContext, m: &Option<String>| {
        m.as_ref()
            .and_then(|n| ctx.material_index.get(n).copied())
            .unwrap_or(ctx.emitter)
    };
    match l {
        LightDesc::Point { position, intensity } => ctx.lights.push(Light::Point(PointLight {
            position: (*position).into(),
            intensity: (*intensity).into(),
        })),
        LightDesc::Spot {
            position,
            direction,
            intensity,
            cone_degrees,
            falloff_degrees,
        } => ctx.lights.push(Light::Spot(SpotLight::new(
            (*position).into(),
            (*direction).into(),
            (*intensity).into(),
            *cone_degrees,
            *falloff_degrees,
        ))),
        LightDesc::Directional {
            direction,
            irradiance,
            angle_degrees,
        } => ctx.lights.push(Light::Directional(
            DirectionalLight::new((*direction).into(), (*irradiance).into()).with_angle(*angle_degrees),
        )),
        LightDesc::Quad {
            corner,
            edge_u,
            edge_v,
            radiance,
            material,
        } => {
            let e = ctx.emission(&format!("lights[{i}].radiance"), radiance);
            let q = QuadLight::new((*corner).into(), (*edge_u).into(), (*edge_v).into(), e.radiance)
                .with_emission(e);
            let m = surface(ctx, material);
            push_quad_light(ctx, m, q);
        }
        LightDesc::Rect {
            center,
            half_u,
            half_v,
            radiance,
            material,
        } => {
            let (c, u, v) = (Vec3A::from(*center), Vec3A::from(*half_u), Vec3A::from(*half_v));
            let e = ctx.emission(&format!("lights[{i}].radiance"), radiance);
            let q = QuadLight::new(c - u - v, 2.0 * u, 2.0 * v, e.radiance).with_emission(e);
            let m = surface(ctx, material);
            push_quad_light(ctx, m, q);
        }
        LightDesc::Environment {
            radiance,
            map,
            strength,
            rotation_degrees,
            visible,
            background,
        } => {
            let t0 = std::time::Instant::now();
            if let Some(file) = map {
                ctx.light_files.push(ctx.base.join(file));
            }
            let env = match (radiance, map) {
                (_, Some(file)) => match read_map(&ctx.base.join(file)) {
                    Ok(mut m) => {
                        if let Some(what) = super::texels::repair_values(m.values_mut()) {
                            ctx.notes.push(format!(
                                "lights[{i}].map: {file} has {what}, read as 0 (one NaN texel \
                                 darkened a whole image by 11%); fix the map to silence this"
                            ));
                        }
                        let brightest =
                            m.texels.as_flattened().iter().fold(0.0f32, |b, &x| b.max(x)) * *strength;
                        if brightest.is_nan() || brightest > MAX_RADIANCE {
                            ctx.problems.push(
                                Problem::new(
                                    format!("lights[{i}].map"),
                                    format!(
                                        "{file}'s brightest texel times `strength` is {brightest:e} W/(m²·sr), \
                                         above the limit of {MAX_RADIANCE:e}"
                                    ),
                                )
                                .help(RADIANCE_HELP),
                            );
                            return;
                        }
                        let t1 = std::time::Instant::now();
                        let env = EnvironmentLight::from_map(m, *strength, *rotation_degrees);
                        ctx.env_times = (t1 - t0, t1.elapsed());
                        env
                    }
                    Err(e) => {
                        let at = format!("lights[{i}].map");
                        ctx.problems.push(Problem::new(at, e).help(
                            "the file must be an equirectangular image in linear OpenEXR or Radiance HDR",
                        ));
                        return;
                    }
                },
                (c, None) => EnvironmentLight::constant(Rgb::from(c.unwrap_or_default()) * *strength),
            };
            let mut env = Box::new(env);
            env.visible = *visible;
            env.background = background.map_or(Rgb::ZERO, Rgb::from);
            ctx.environment = Some(ctx.lights.len() as u32);
            ctx.lights.push(Light::Environment(env));
        }
    }
}

/// What the `envmap` fuzz target runs: the sky map at `path` read as the
/// build step reads it (limits, repair of texels that are not radiance)
/// and its sampling tables built; whether it was accepted.
pub fn fuzz_sky_map(path: &Path) -> bool {
    let Ok(mut m) = read_map(path) else {
        return false;
    };
    let _ = super::texels::repair_values(m.values_mut());
    let env = EnvironmentLight::from_map(m, 1.0, 0.0);
    std::hint::black_box(&env);
    true
}

/// Reads an environment map into linear RGB floats: `.exr` through the `exr`
/// crate (blocks decompressed on all cores, pixels written straight into the
/// map), `.hdr` through `image`.
pub fn read_map(path: &Path) -> Result<EnvMap, String> {
    let is_exr = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let map = if is_exr { read_exr(path) } else { read_hdr(path) }
        .map_err(|e| format!("cannot read environment map {}: {e}", path.display()))?;
    if map.width == 0 || map.height == 0 {
        return Err(format!("environment map {} is empty", path.display()));
    }
    Ok(map)
}

/// What a sky map's header may claim: each side at most
/// [`MAX_IMAGE_SIDE`], its pixels as the map holds them within the memory
/// available, and as f32 RGB no more than [`MAX_EXR_RATIO`] times the file's own size.
/// Checked before anything is allocated: the decoder sizes its buffers
/// from the header, and a few hundred bytes claiming 100,000² pixels
/// aborted the process.
fn check_exr_header(path: &Path) -> Result<(), String> {
    let file_len = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    for h in meta.headers.iter() {
        let (w, ht) = (h.layer_size.width(), h.layer_size.height());
        if w.max(ht) > MAX_IMAGE_SIDE as usize {
            return Err(format!(
                "its header claims {w}×{ht} pixels, above the limit of {MAX_IMAGE_SIDE} a side"
            ));
        }
        let bytes = 12 * w as u64 * ht as u64;
        // As the map holds them, 16 bytes a pixel (`EnvMap::texels`), and
        // its sampling tables, about 13 a cell (`EnvTable`).
        let held = 29 * w as u64 * ht as u64;
        if let Some(free) = crate::memory::available()
            && held > free
        {
            return Err(format!(
                "its {w}×{ht} pixels need {} MB, more than the {} MB of memory available",
                held >> 20,
                free >> 20
            ));
        }
        if bytes > MAX_EXR_RATIO * file_len.max(1) {
            return Err(format!(
                "its header claims {w}×{ht} pixels ({} MB as floats) but the file holds {file_len} bytes: \
                 truncated or corrupt",
                bytes >> 20
            ));
        }
    }
    Ok(())
}

/// How many times its file size a sky map's pixels may take as f32 RGB
/// (see [`check_exr_header`]): ZIP and PIZ compress a real sky 2–5×;
/// deflate cannot pass ~1,032× (a flat half-float map as ZIP: ~2,000× as
/// f32 RGB), so only a corrupt header or a flat lossy map reaches this.
const MAX_EXR_RATIO: u64 = 16_384;

fn read_exr(path: &Path) -> Result<EnvMap, String> {
    use exr::prelude::{ReadChannels, ReadLayers};
    check_exr_header(path)?;
    let image = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |size, _| EnvMap {
                width: size.width() as u32,
                height: size.height() as u32,
                texels: vec![[0.0; 4]; size.area()],
            },
            |m: &mut EnvMap, pos, (r, g, b, _): (f32, f32, f32, f32)| {
                m.texels[pos.y() * m.width as usize + pos.x()] = [r, g, b, 0.0];
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| e.to_string())?;
    Ok(image.layer_data.channel_data.pixels)
}

/// Radiance RGBE. Files that begin `#?RGBE` (Mitsuba, some HDR tools) are read
/// as `#?RADIANCE`, the only signature `image` accepts; the format is the same.
fn read_hdr(path: &Path) -> Result<EnvMap, String> {
    let mut bytes = std::fs::read(path).map_err(|e| e.to_string())?;
    if bytes.starts_with(b"#?") && !bytes.starts_with(b"#?RADIANCE") {
        let end = bytes.iter().position(|&b| b == b'\n').unwrap_or(0);
        bytes.splice(..end, b"#?RADIANCE".iter().copied());
    }
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Hdr)
        .map_err(|e| e.to_string())?
        .into_rgb32f();
    drop(bytes);
    let (width, height) = img.dimensions();
    Ok(EnvMap {
        width,
        height,
        texels: rgb_to_texels(img.into_raw()),
    })
}

/// `3·N` floats of RGB as `N` 16-byte pixels (weight 0), in the same
/// allocation where the allocator allows: grown once to exactly `4·N`
/// floats (glibc grows a large block with `mremap`, without copying it),
/// each pixel moved up from the last (pixel k from float 3k to 4k ≥ 3k), and
/// the buffer reinterpreted. So a decoded map peaks at 16 bytes a pixel, not
/// 12 + 16 for a copy (940 MB for an 8192 × 4096 map).
fn rgb_to_texels(mut v: Vec<f32>) -> Vec<[f32; 4]> {
    let n = v.len() / 3;
    v.truncate(3 * n);
    v.reserve_exact(n);
    v.resize(4 * n, 0.0);
    for k in (0..n).rev() {
        v.copy_within(3 * k..3 * k + 3, 4 * k);
        v[4 * k + 3] = 0.0;
    }
    v.shrink_to_fit();
    // A capacity that is not a whole number of pixels cannot be
    // reinterpreted: copy instead (same values).
    bytemuck::allocation::try_cast_vec(v)
        .unwrap_or_else(|(_, v)| v.chunks_exact(4).map(|p| [p[0], p[1], p[2], p[3]]).collect())
}

fn push_quad_light(ctx: &mut BuildContext, material: u32, q: QuadLight) {
    let id = ctx.lights.len() as u32;
    ctx.shapes
        .push(Shape::Quad(Quad::new(q.corner, q.u, q.v, material, id)));
    ctx.lights.push(Light::Quad(q));
}

#[cfg(test)]
mod tests {
    /// RGB spread to 16-byte pixels in place gives what copying gives.
    #[test]
    fn rgb_spreads_to_texels_as_a_copy_would() {
        for n in [0usize, 1, 2, 7, 1000] {
            let rgb: Vec<f32> = (0..3 * n).map(|k| k as f32 * 0.5 - 3.0).collect();
            let want: Vec<[f32; 4]> = rgb.chunks_exact(3).map(|p| [p[0], p[1], p[2], 0.0]).collect();
            assert_eq!(super::rgb_to_texels(rgb), want, "{n} pixels");
        }
    }
}
