//! MTL materials → ronray materials, for OBJ groups the scene does not
//! override. The MTL model (Kd, Ks, Ns, Ni, d/Tr, illum) is mapped onto the
//! closest runtime model:
//!
//! | MTL | ronray |
//! |---|---|
//! | `illum` 4, 6, 7, or `d` < 1 / `Tr` > 0 | `Glass(ior: Ni or 1.5)`, tinted by `Tf` if given |
//! | `illum` 3 (ray-traced reflection) | `Mirror(tint: Ks)` |
//! | `Ks` non-zero | `Phong(diffuse: Kd, specular: Ks, exponent: Ns)` |
//! | otherwise | `Lambert(albedo: Kd)` (`map_Kd` → sRGB image texture) |
//!
//! Maps: `map_Kd` (sRGB) → the diffuse colour, `map_Ks` (sRGB) → a Phong
//! specular colour, `map_Ns` (linear, times `Ns`) → the Phong exponent;
//! `Pr`/`map_Pr` and `Pm`/`map_Pm` (the PBR extension, linear) make the
//! material `MetalPlastic(base_color: Kd, roughness, metalness)`; `map_d`
//! (linear; the alpha channel when the image has one) makes it a stochastic
//! `Cutout`. `norm` is a tangent-space normal map (MikkTSpace tangents, as
//! glTF's); `map_Bump`/`bump` too when its image looks like one (Blender
//! writes normal maps there), else a height map (`Bump`, [`BUMP_SCALE`]
//! scene units per unit at `-bm 1`, with a note).
//!
//! Colours are clamped to [0, 1]. `Ke` (emitted radiance, W/(m²·sr), at
//! most [`MAX_RADIANCE`], the scene's own limit; NaN, infinite and negative channels of any
//! colour read as 0, each repair with a note) makes the groups that use the material emit from the
//! counter-clockwise front of their triangles (see `mesh.rs`); `map_Ke` (sRGB)
//! is an emission texture, times `Ke` when both are given, alone when `Ke` is
//! not. The material itself is mapped as above, so the surface also reflects
//! its `Kd`.

use super::validate::MAX_RADIANCE;
use crate::lights::Emission;
use crate::materials::{
    Channel, ColorTex, Cutout, DielectricFresnel, GlassMaterial, ImageLookup, LambertMaterial, Material,
    MetalPlasticMaterial, MirrorMaterial, Perturb, PhongMaterial, Roughness, ScalarTex, Surface, Tex,
    Texture, UvTransform,
};
use crate::math::Rgb;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Materials and textures created for MTL files, appended after the
/// scene's own (`first` is the index of the first).
pub struct MtlMaterials {
    first: u32,
    /// Index the first MTL texture will have in the scene's texture list.
    first_texture: u32,
    pub materials: Vec<Material>,
    names: Vec<Option<String>>,
    /// `Ke` (times `map_Ke`) of each material, when positive.
    emission: Vec<Option<Emission>>,
    /// What each material does to the surface (`map_d` cut-outs), in the
    /// order of `materials`.
    pub surfaces: Vec<Surface>,
    pub textures: Vec<Texture>,
    textures_by_path: HashMap<PathBuf, Option<u32>>,
    /// Linear decodes (scalar maps), with the file's channel count.
    linear_by_path: HashMap<PathBuf, Option<(u32, u8)>>,
    /// `--root`: textures outside it are not read.
    root: Option<PathBuf>,
    /// Textures refused by `--root` since the last look, one sentence each:
    /// the mesh build turns them into located problems.
    pub refused: Vec<String>,
}

fn rgb(c: Option<[f32; 3]>, default: f32) -> Rgb {
    Rgb::from(c.unwrap_or([default; 3])).clamp(Rgb::ZERO, Rgb::ONE)
}

/// An MTL colour statement (`key`, of material `name`) with the channels
/// that are no colour repaired, and a note saying which: NaN, infinite and
/// negative read as 0, above `max` as `max`. Before, they were dropped or
/// clamped without a word (a NaN `Ke` turned the light off, a `Ke` of
/// 1e38 whitened the image).
fn repaired(name: &str, key: &str, c: [f32; 3], max: f32, notes: &mut Vec<String>) -> [f32; 3] {
    let mut found: Vec<&str> = Vec::new();
    let out = c.map(|x| {
        let (v, what) = if x.is_nan() {
            (0.0, "NaN")
        } else if x.is_infinite() {
            (0.0, "infinite")
        } else if x < 0.0 {
            (0.0, "negative")
        } else if x > max {
            (max, "above the largest value read")
        } else {
            return x;
        };
        if !found.contains(&what) {
            found.push(what);
        }
        v
    });
    if !found.is_empty() {
        notes.push(format!(
            "MTL material `{name}`: `{key} {} {} {}` has a channel that is {}; read as `{key} {} {} {}` \
             (NaN, infinite and negative as 0, at most {max:e}); fix the MTL file to silence this",
            c[0],
            c[1],
            c[2],
            found.join(", "),
            out[0],
            out[1],
            out[2]
        ));
    }
    out
}

/// Scene units per unit of an MTL height map (`map_Bump` of a grey image)
/// at `-bm 1`. MTL gives bump maps no unit: on a mesh whose UVs span a
/// metre, heights up to 2 mm, the relief of a brick wall or a plaster.
pub const BUMP_SCALE: f32 = 0.002;

/// The number after option `name` in an MTL map statement (`-bm 1.5
/// bump.png`), if any.
fn option_value(spec: &str, name: &str) -> Option<f32> {
    let mut words = spec.split_whitespace();
    words.by_ref().find(|w| *w == name)?;
    words.next()?.parse().ok()
}

/// Whether linear texels look like a tangent-space normal map: colour (not
/// grey), and their mean, read as 2c − 1, within 45° of +z.
fn looks_like_normal_map(t: &Texture) -> bool {
    let n = t.texels.len().max(1) as f32;
    let mean = t.texels.iter().fold(Rgb::ZERO, |a, &c| a + c) / n;
    let grey = t
        .texels
        .iter()
        .all(|c| (c.x - c.y).abs() < 1e-3 && (c.y - c.z).abs() < 1e-3);
    let v = 2.0 * mean - Rgb::ONE;
    let len = (v.x * v.x + v.y * v.y + v.z * v.z).sqrt();
    !grey && len > 0.0 && v.z / len > std::f32::consts::FRAC_1_SQRT_2
}

/// Whether MTL material `m` names a normal or bump map (its mesh then
/// needs tangents).
pub fn wants_tangents(m: &tobj::Material) -> bool {
    m.normal_texture.is_some() || m.unknown_param.contains_key("norm")
}

impl MtlMaterials {
    pub fn new(first: u32, first_texture: u32, root: Option<&Path>) -> Self {
        Self {
            root: root.map(Path::to_path_buf),
            refused: Vec::new(),
            first,
            first_texture,
            materials: Vec::new(),
            names: Vec::new(),
            emission: Vec::new(),
            surfaces: Vec::new(),
            textures: Vec::new(),
            textures_by_path: HashMap::new(),
            linear_by_path: HashMap::new(),
        }
    }

    /// Adds a material that has no MTL name; returns its scene index.
    pub fn push(&mut self, m: Material) -> u32 {
        self.materials.push(m);
        self.surfaces.push(Surface::default());
        self.names.push(None);
        self.emission.push(None);
        self.first + self.materials.len() as u32 - 1
    }

    /// `--root`, when the scene is untrusted.
    pub fn root(&self) -> Option<&Path> {
        self.root.as_deref()
    }

    /// Adds a material with its surface effects (normal map, cut-out);
    /// returns its scene index.
    pub fn push_with_surface(&mut self, m: Material, surface: Surface) -> u32 {
        let i = self.push(m);
        if let Some(s) = self.surfaces.last_mut() {
            *s = surface;
        }
        i
    }

    /// Adds a decoded texture (a glTF image); returns its scene index.
    pub fn push_texture(&mut self, t: Texture) -> u32 {
        self.textures.push(t);
        self.first_texture + self.textures.len() as u32 - 1
    }

    /// A copy of texture `i` (one of these) with every texel times `f`, or
    /// `None` if `i` is not one of these.
    pub fn push_scaled_texture(&mut self, i: u32, f: Rgb) -> Option<u32> {
        let t = self.textures.get(i.checked_sub(self.first_texture)? as usize)?;
        let mut copy = t.clone();
        for texel in &mut copy.texels {
            *texel *= f;
        }
        Some(self.push_texture(copy))
    }

    /// The `Ke` of scene material `i`, if it came from an MTL file that gives a
    /// positive one.
    pub fn emission(&self, i: u32) -> Option<&Emission> {
        self.emission.get(i.checked_sub(self.first)? as usize)?.as_ref()
    }

    /// The MTL name of scene material `i`, if it came from an MTL file.
    pub fn name(&self, i: u32) -> Option<String> {
        self.names.get(i.checked_sub(self.first)? as usize)?.clone()
    }

    /// Maps one MTL material (textures relative to `dir`).
    /// Multiplies material `i`'s base colour (`base_color`, `albedo`,
    /// `kd`, a glass's `tint`; both materials of a blend) by the hit's
    /// vertex colour: glTF's rule for a primitive with `COLOR_0`. A
    /// material already painted is left as it is.
    pub fn paint(&mut self, i: u32) {
        self.paint_at(i, 0);
    }

    fn paint_at(&mut self, i: u32, depth: u32) {
        let Some(k) = (i as usize).checked_sub(self.first as usize) else {
            return;
        };
        if let Some(b) = self.surfaces.get(k).and_then(|s| s.blend.clone()) {
            if depth < 8 {
                self.paint_at(b.a, depth + 1);
                self.paint_at(b.b, depth + 1);
            }
            return;
        }
        let Some(m) = self.materials.get_mut(k) else {
            return;
        };
        let color = match m {
            Material::MetalPlastic(x) => &mut x.base_color,
            Material::Lambert(x) => &mut x.albedo,
            Material::Glass(x) => &mut x.tint,
            Material::RoughGlass(x) => &mut x.tint,
            Material::Phong(x) => &mut x.kd,
            Material::BlinnPhong(x) => &mut x.kd,
            Material::OrenNayar(x) => &mut x.albedo,
            Material::RoughPlastic(x) => &mut x.diffuse,
            Material::Mirror(x) => &mut x.tint,
            Material::CookTorrance(_) | Material::Emitter(_) => return,
        };
        *color = match std::mem::replace(color, Tex::Const(Rgb::ONE)) {
            Tex::Const(c) => Tex::Vertex {
                channel: Channel::All,
                factor: c,
            },
            Tex::Image(look) => Tex::Image(ImageLookup {
                times_vertex: true,
                ..look
            }),
            other => other,
        };
    }

    /// The scene material of MTL material `m`; on an OBJ with vertex
    /// colours (`painted`) its diffuse colour (`Kd`, `map_Kd`) is multiplied
    /// by them, as MeshLab and Blender show such a file.
    pub fn add(&mut self, m: &tobj::Material, dir: &Path, painted: bool, notes: &mut Vec<String>) -> u32 {
        let colour = |key: &str, c: Option<[f32; 3]>, notes: &mut Vec<String>| {
            c.map(|c| repaired(&m.name, key, c, 1.0, notes))
        };
        let kd = rgb(colour("Kd", m.diffuse, notes), 0.8);
        let ks = rgb(colour("Ks", m.specular, notes), 0.0);
        let illum = m.illumination_model.unwrap_or(2);
        let tr = m
            .unknown_param
            .get("Tr")
            .and_then(|t| t.trim().parse::<f32>().ok());
        let transparent = m.dissolve.is_some_and(|d| d < 1.0) || tr.is_some_and(|t| t > 0.0);
        let ke_map = m
            .unknown_param
            .get("map_Ke")
            .and_then(|f| crate::geometry::obj::texture_file(f))
            .and_then(|f| self.texture(&dir.join(f), notes));
        // `map_Ke` alone glows at the map's value; with `Ke` it is scaled by it.
        let ke = m
            .emissive
            .map(|e| Rgb::from(repaired(&m.name, "Ke", e, MAX_RADIANCE, notes)))
            .or(ke_map.map(|_| Rgb::ONE))
            .filter(|e| e.is_finite() && e.max_element() > 0.0)
            .map(|ke| match ke_map {
                Some(t) => self.emission_map(t, ke),
                None => Emission::constant(ke),
            });
        let albedo = match m
            .diffuse_texture
            .as_deref()
            .and_then(crate::geometry::obj::texture_file)
        {
            Some(file) => match self.texture(&dir.join(file), notes) {
                Some(t) => ColorTex::image(t),
                None => ColorTex::Const(kd),
            },
            None => ColorTex::Const(kd),
        };
        let albedo = match albedo {
            Tex::Const(kd) if painted => Tex::Vertex {
                channel: Channel::All,
                factor: kd,
            },
            Tex::Image(look) if painted => Tex::Image(ImageLookup {
                times_vertex: true,
                ..look
            }),
            other => other,
        };
        // The scalar maps: a linear image, times the statement's number.
        let mut scalar =
            |this: &mut Self, file: Option<&str>, times: f32, alpha: bool| -> Option<ScalarTex> {
                let file = crate::geometry::obj::texture_file(file?)?;
                let (index, channels) = this.linear_texture(&dir.join(file), notes)?;
                Some(Tex::Image(ImageLookup {
                    index,
                    channel: if alpha && channels % 2 == 0 {
                        Channel::A
                    } else {
                        Channel::R
                    },
                    scale: times,
                    offset: 0.0,
                    rows_down: false,
                    uv: UvTransform::default(),
                    wrap: [crate::materials::Wrap::Repeat; 2],
                    times_vertex: false,
                }))
            };
        let param = |k: &str| {
            m.unknown_param
                .get(k)
                .and_then(|v| v.trim().parse::<f32>().ok())
                .filter(|x| x.is_finite())
        };
        let (pr, pm) = (param("Pr"), param("Pm"));
        let pr_map = scalar(
            self,
            m.unknown_param.get("map_Pr").map(String::as_str),
            1.0,
            false,
        );
        let pm_map = scalar(
            self,
            m.unknown_param.get("map_Pm").map(String::as_str),
            1.0,
            false,
        );
        let ns = m.shininess.filter(|n| n.is_finite() && *n > 0.0);
        let ns_map = scalar(self, m.shininess_texture.as_deref(), ns.unwrap_or(1.0), false);
        let opacity = scalar(self, m.dissolve_texture.as_deref(), 1.0, true);
        let ks_map = m
            .specular_texture
            .as_deref()
            .and_then(crate::geometry::obj::texture_file)
            .and_then(|f| self.texture(&dir.join(f), notes))
            .map(ColorTex::image);
        let normal = self.normal_or_bump(m, dir, notes);
        let material = if matches!(illum, 4 | 6 | 7) || transparent {
            let tint = m
                .unknown_param
                .get("Tf")
                .and_then(|t| {
                    let v: Vec<f32> = t.split_whitespace().filter_map(|x| x.parse().ok()).collect();
                    (v.len() == 3).then(|| [v[0], v[1], v[2]])
                })
                .map_or(Rgb::ONE, |c| rgb(Some(c), 1.0));
            Material::Glass(GlassMaterial {
                ior: Tex::Const(
                    m.optical_density
                        .filter(|n| n.is_finite() && *n >= 1.0)
                        .unwrap_or(1.5),
                ),
                tint: ColorTex::Const(tint),
                fresnel: DielectricFresnel::Exact,
                thin: false,
                absorption: Rgb::ZERO,
            })
        } else if illum == 3 {
            let tint = if ks.max_element() > 0.0 {
                ks
            } else {
                Rgb::splat(0.9)
            };
            Material::Mirror(MirrorMaterial {
                tint: ColorTex::Const(tint),
            })
        } else if pr.is_some() || pm.is_some() || pr_map.is_some() || pm_map.is_some() {
            Material::MetalPlastic(MetalPlasticMaterial {
                base_color: albedo,
                roughness: Roughness {
                    tex: pr_map.unwrap_or(Tex::Const(pr.unwrap_or(0.5).clamp(0.0, 1.0))),
                    is_alpha: false,
                },
                metalness: pm_map.unwrap_or(Tex::Const(pm.unwrap_or(0.0).clamp(0.0, 1.0))),
            })
        } else if ks.max_element() > 0.0 || ks_map.is_some() {
            Material::Phong(PhongMaterial {
                kd: albedo,
                ks: ks_map.unwrap_or(ColorTex::Const(ks)),
                exponent: ns_map.unwrap_or(Tex::Const(ns.unwrap_or(10.0))),
            })
        } else {
            Material::Lambert(LambertMaterial { albedo })
        };
        let i = self.push_with_surface(
            material,
            Surface {
                normal,
                cutout: opacity.map(|opacity| Cutout {
                    opacity,
                    threshold: None,
                }),
                blend: None,
                vertex_color: false,
            },
        );
        *self.names.last_mut().expect("just pushed") = Some(m.name.clone());
        *self.emission.last_mut().expect("just pushed") = ke;
        i
    }

    /// The shading normal of MTL material `m`: `norm` is a tangent-space
    /// normal map; `map_Bump` (or `bump`) is one too when its image looks
    /// like one (colour texels averaging a normal tilted less than 45° from
    /// +z: Blender's exporter writes its normal maps there), and otherwise
    /// a height map (its red or grey channel). `-bm s` is a normal map's
    /// strength, or scales a height map's [`BUMP_SCALE`].
    fn normal_or_bump(&mut self, m: &tobj::Material, dir: &Path, notes: &mut Vec<String>) -> Option<Perturb> {
        let bump = m.normal_texture.as_deref().map(|v| ("map_Bump", v));
        let (key, spec) = m
            .unknown_param
            .get("norm")
            .map(|v| ("norm", v.as_str()))
            .or(bump)?;
        let file = crate::geometry::obj::texture_file(spec)?;
        let (index, channels) = self.linear_texture(&dir.join(file), notes)?;
        let bm = option_value(spec, "-bm").filter(|b| b.is_finite() && (0.0..=100.0).contains(b));
        let texture = index
            .checked_sub(self.first_texture)
            .and_then(|k| self.textures.get(k as usize));
        let normal_map = key == "norm" || (channels >= 3 && texture.is_some_and(looks_like_normal_map));
        let look = |channel| ImageLookup {
            channel,
            ..ImageLookup::plain(index)
        };
        if normal_map {
            return Some(Perturb::NormalMap {
                map: Tex::Image(look(Channel::All)),
                strength: bm.unwrap_or(1.0),
                flip_green: false,
                frame: crate::geometry::TangentFrame::Vertex,
            });
        }
        let scale = bm.unwrap_or(1.0) * BUMP_SCALE;
        notes.push(format!(
            "MTL material `{name}`: `{key} {spec}` read as a height map, {scale} scene units per unit of height \
             (`-bm` scales it; `materials: {{\"material:{name}\": …}}` on the mesh replaces it)",
            name = m.name
        ));
        Some(Perturb::Bump {
            height: Tex::Image(look(Channel::R)),
            scale,
        })
    }

    /// The emission of image `t` (a scene texture index) times `ke`.
    fn emission_map(&self, t: u32, ke: Rgb) -> Emission {
        self.emission_lookup(crate::materials::ImageLookup::plain(t), ke)
    }

    /// The emission `look` reads (its `index` a scene texture index, one
    /// of these files' textures) times `ke`; constant `ke` when it names
    /// none of them.
    pub(crate) fn emission_lookup(&self, look: crate::materials::ImageLookup, ke: Rgb) -> Emission {
        match look.index.checked_sub(self.first_texture) {
            Some(local) if (local as usize) < self.textures.len() => {
                let local = ColorTex::Image(crate::materials::ImageLookup { index: local, ..look });
                Emission::new(&local, &self.textures).scaled(ke)
            }
            _ => Emission::constant(ke),
        }
    }

    /// Decodes a scalar map (linear) once per path: its index and channel
    /// count, `None` (with a note) if unreadable.
    fn linear_texture(&mut self, path: &Path, notes: &mut Vec<String>) -> Option<(u32, u8)> {
        if let Some(t) = self.linear_by_path.get(path) {
            return *t;
        }
        if let Some(why) = self
            .root
            .as_deref()
            .and_then(|r| crate::files::outside_root(r, path))
        {
            self.refused.push(format!("MTL texture {why}"));
            return None;
        }
        let t = match super::material::load_texture_as(path, false) {
            Ok(super::material::DecodedTexture {
                texture,
                channels,
                repaired,
            }) => {
                if let Some(what) = repaired {
                    notes.push(format!(
                        "texture {} has {what}, read as 0 (NaN, infinite and negative texels are no value); \
                         fix the image to silence this",
                        path.display()
                    ));
                }
                self.textures.push(texture);
                Some((self.first_texture + self.textures.len() as u32 - 1, channels))
            }
            Err(e) => {
                notes.push(format!("texture {} not used: {e}", path.display()));
                None
            }
        };
        self.linear_by_path.insert(path.to_path_buf(), t);
        t
    }

    /// The texture files MTL materials named, read or not (watch mode
    /// re-renders when one changes or appears).
    pub fn files(&self) -> impl Iterator<Item = &PathBuf> {
        self.textures_by_path.keys().chain(self.linear_by_path.keys())
    }

    /// Decodes an image once per path; `None` (with a note) if unreadable.
    fn texture(&mut self, path: &Path, notes: &mut Vec<String>) -> Option<u32> {
        if let Some(t) = self.textures_by_path.get(path) {
            return *t;
        }
        if let Some(why) = self
            .root
            .as_deref()
            .and_then(|r| crate::files::outside_root(r, path))
        {
            self.refused.push(format!("MTL texture {why}"));
            return None;
        }
        let t = match crate::imageio::read::decode_texture(path) {
            Ok(mut img) => {
                if let Some(what) = super::texels::repair_image(&mut img) {
                    notes.push(format!(
                        "texture {} has {what}, read as 0 (NaN, infinite and negative texels are no value); \
                         fix the image to silence this",
                        path.display()
                    ));
                }
                let rgb = img.to_rgb8();
                match Texture::try_from_srgb8(rgb.width(), rgb.height(), rgb.as_raw()) {
                    Ok(t) => {
                        self.textures.push(t);
                        Some(self.first_texture + self.textures.len() as u32 - 1)
                    }
                    Err(e) => {
                        notes.push(format!("texture {} not used: {e}", path.display()));
                        None
                    }
                }
            }
            Err(e) => {
                notes.push(format!("texture {} not used: {e}", path.display()));
                None
            }
        };
        self.textures_by_path.insert(path.to_path_buf(), t);
        t
    }
}
