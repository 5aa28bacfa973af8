//! glTF materials → ronray materials. `pbrMetallicRoughness` maps onto
//! [`Material::MetalPlastic`], whose model is the specification's appendix
//! B (its one departure, the diffuse coupling, is in
//! `materials/metal_plastic.rs`):
//!
//! | glTF | ronray |
//! |---|---|
//! | `baseColorTexture` × `baseColorFactor` | `base_color`, sRGB image (a non-grey factor is multiplied into a copy of the texels) |
//! | `metallicRoughnessTexture` G × `roughnessFactor`, B × `metallicFactor` | `roughness` (perceptual) and `metalness`, linear |
//! | `normalTexture` with `scale` | `NormalMap(strength: scale)` over the material, MikkTSpace tangents when the mesh has none |
//! | `alphaMode: MASK` with `alphaCutoff` | `Cutout(mode: Threshold(cutoff))` on base-colour alpha |
//! | `alphaMode: BLEND` | stochastic `Cutout` on alpha (a warning: blending is approximated by coverage) |
//! | `emissiveFactor` × `KHR_materials_emissive_strength` × `emissiveTexture` (sRGB) | the primitive's light, as an emissive mesh group, the texture sampled as an MTL's `map_Ke` |
//! | `KHR_texture_transform` | the lookup's UV transform (its `texCoord` override included) |
//! | `KHR_materials_ior` | a note when ≠ 1.5: `MetalPlastic`'s F0 is 0.04; the glass's ior |
//! | `KHR_materials_transmission` (× `transmissionTexture`) × (1 − metallic) | a `Blend` of the metallic–roughness model and glass by that weight (glass alone at 1): `Glass(thin: true)` tinted by the base colour; with `KHR_materials_volume` (`thicknessFactor` > 0) a solid: `Glass`, or `RoughGlass` (GGX) above roughness 0.05 |
//! | `KHR_materials_volume` `attenuationColor` / `attenuationDistance` | the solid glass's `attenuation` (absorption −ln(colour)/distance inside) |
//! | `occlusionTexture` | ignored with a note: a path tracer computes occlusion |
//! | `doubleSided: false` | a note: ronray materials shade both sides |
//!
//! UVs: glTF puts `(0, 0)` at an image's top-left; the importer stores
//! `v' = 1 − v` so every mesh in ronray has v up (OBJ's convention, which
//! MikkTSpace and the normal-map frame assume), and images are read with
//! the default bottom-left origin: the same texel either way.

use super::super::validate::MAX_RADIANCE;
use super::document::{Files, view_bytes};
use crate::materials::{
    Channel, Cutout, ImageLookup, Material, MetalPlasticMaterial, Perturb, Roughness, Surface, Tex,
    UvTransform,
};
use crate::math::Rgb;
use glam::{Affine2, Mat2, Vec2};
use std::collections::HashMap;

/// What the mesh step needs of a mapped material.
#[derive(Clone, Copy, Debug)]
pub struct Mapped {
    /// Scene material index.
    pub index: u32,
    /// Which UV set (`TEXCOORD_n`) the material's textures read.
    pub uv_set: u32,
    /// Whether it has a normal map (the mesh then needs tangents).
    pub normal_mapped: bool,
    /// Emitted radiance, if any (`emissiveFactor` × strength).
    pub emission: Option<Rgb>,
    /// The `emissiveTexture` the radiance is multiplied by, if any.
    pub emission_map: Option<ImageLookup>,
    /// glTF's `doubleSided` (an emissive primitive then emits both ways).
    pub double_sided: bool,
}

/// Decoded images by (image index, sRGB?): texture index and alpha presence.
#[derive(Default)]
pub struct Images {
    cache: HashMap<(usize, bool), Option<(u32, bool)>>,
}

/// Where images come from: the asset's buffers (GLB, embedded views) and
/// the files it names.
pub struct Source<'a> {
    /// The buffers' bytes.
    pub buffers: &'a [Vec<u8>],
    /// Reads image files.
    pub files: &'a mut Files,
}

/// Pushes textures and materials into the scene's MTL-style list.
pub(crate) struct Sink<'a> {
    /// Where materials and textures go.
    pub mtl: &'a mut super::super::mtl::MtlMaterials,
    /// What was approximated or dropped.
    pub notes: &'a mut Vec<String>,
    /// Names the asset in notes.
    pub label: &'a str,
}

/// Maps material `m` (or glTF's default material for `None`).
pub(crate) fn map(
    asset: &mut Source,
    images: &mut Images,
    sink: &mut Sink,
    m: Option<gltf::Material>,
) -> Mapped {
    let Some(m) = m else {
        let index = sink.mtl.push(Material::MetalPlastic(MetalPlasticMaterial {
            base_color: Tex::Const(Rgb::ONE),
            roughness: Roughness::perceptual(1.0),
            metalness: Tex::Const(1.0),
        }));
        return Mapped {
            index,
            uv_set: 0,
            normal_mapped: false,
            emission: None,
            emission_map: None,
            double_sided: false,
        };
    };
    let name = m.name().map_or_else(
        || format!("materials[{}]", m.index().unwrap_or(0)),
        |n| format!("material `{n}`"),
    );
    let label = sink.label.to_string();
    let mut note = |s: String| sink.notes.push(format!("{label}: {name}: {s}"));
    let pbr = m.pbr_metallic_roughness();
    let factor = pbr.base_color_factor();
    let mut uv_sets = Vec::new();
    let base = pbr.base_color_texture();
    let (base_color, alpha) = match &base {
        Some(info) => {
            uv_sets.push(set_of(info));
            let f = Rgb::new(factor[0], factor[1], factor[2]);
            match texture(asset, images, sink.mtl, &info.texture(), true, Some(f), &mut note) {
                Some((index, has_alpha)) => {
                    let look = lookup(index, Channel::All, 1.0, info);
                    let alpha = has_alpha.then(|| lookup(index, Channel::A, factor[3], info));
                    (Tex::Image(look), alpha.map(Tex::Image))
                }
                None => (Tex::Const(f), None),
            }
        }
        None => (Tex::Const(Rgb::new(factor[0], factor[1], factor[2])), None),
    };
    let alpha: crate::materials::ScalarTex = alpha.unwrap_or(Tex::Const(factor[3]));
    let (rough_f, metal_f) = (pbr.roughness_factor(), pbr.metallic_factor());
    let (roughness, metalness) = match pbr.metallic_roughness_texture() {
        Some(info) => {
            uv_sets.push(set_of(&info));
            match texture(asset, images, sink.mtl, &info.texture(), false, None, &mut note) {
                Some((index, _)) => (
                    Tex::Image(lookup(index, Channel::G, rough_f, &info)),
                    Tex::Image(lookup(index, Channel::B, metal_f, &info)),
                ),
                None => (Tex::Const(rough_f), Tex::Const(metal_f)),
            }
        }
        None => (Tex::Const(rough_f), Tex::Const(metal_f)),
    };
    let mut surface = Surface::default();
    let mut normal_mapped = false;
    if let Some(n) = m.normal_texture() {
        let (uv, set) = normal_transform(&n);
        uv_sets.push(set);
        if let Some((index, _)) = texture(asset, images, sink.mtl, &n.texture(), false, None, &mut note) {
            normal_mapped = true;
            surface.normal = Some(Perturb::NormalMap {
                map: Tex::Image(ImageLookup {
                    wrap: wrap_of(&n.texture()),
                    uv,
                    ..ImageLookup::plain(index)
                }),
                strength: n.scale(),
                flip_green: false,
                frame: crate::geometry::TangentFrame::Vertex,
            });
        }
    }
    match m.alpha_mode() {
        gltf::material::AlphaMode::Opaque => {}
        gltf::material::AlphaMode::Mask => {
            surface.cutout = Some(Cutout {
                opacity: alpha,
                threshold: Some(m.alpha_cutoff().unwrap_or(0.5)),
            });
        }
        gltf::material::AlphaMode::Blend => {
            note("alphaMode BLEND approximated by a stochastic cut-out (coverage, not blending)".into());
            surface.cutout = Some(Cutout {
                opacity: alpha,
                threshold: None,
            });
        }
    }
    if m.occlusion_texture().is_some() {
        note("occlusionTexture ignored (the path tracer computes occlusion)".into());
    }
    if !m.double_sided() {
        note("doubleSided is false, but ronray materials shade both sides".into());
    }
    let e = m.emissive_factor();
    let strength = m.emissive_strength().unwrap_or(1.0);
    // As MTL `Ke`: channels that are no radiance read as 0, and at most
    // MAX_RADIANCE (a strength of 1e38 made the light's power infinite).
    let asked = Rgb::new(e[0], e[1], e[2]) * strength;
    let mut repairs = super::super::texels::Repairs::default();
    let fixed = |x: f32, r: &mut super::super::texels::Repairs| r.value(x).min(MAX_RADIANCE);
    let emission = Rgb::new(
        fixed(asked.x, &mut repairs),
        fixed(asked.y, &mut repairs),
        fixed(asked.z, &mut repairs),
    );
    if repairs.summary().is_some() || asked.max_element() > MAX_RADIANCE {
        note(format!(
            "emissiveFactor {e:?} × emissive strength {strength} is {asked}, no radiance (NaN, infinite \
             and negative channels read as 0, at most {MAX_RADIANCE:e}); read as {emission}"
        ));
    }
    // The emission varies over the surface as the texture does: the mesh
    // light samples it (`lights::Emission`), as an MTL's `map_Ke`.
    let mut emission_map = None;
    if let Some(info) = m.emissive_texture()
        && emission.max_element() > 0.0
    {
        uv_sets.push(set_of(&info));
        emission_map = texture(asset, images, sink.mtl, &info.texture(), true, None, &mut note)
            .map(|(i, _)| lookup(i, Channel::All, 1.0, &info));
    }
    if let Some(info) = m.transmission().and_then(|t| t.transmission_texture()) {
        uv_sets.push(set_of(&info));
    }
    uv_sets.dedup();
    if uv_sets.len() > 1 {
        note(format!(
            "textures read UV sets {uv_sets:?}; ronray meshes carry one, so all read TEXCOORD_{}",
            uv_sets[0]
        ));
    }
    let see_through = Transmissive {
        tint: base_color.clone(),
        roughness: rough_f,
        metalness: metal_f,
    };
    let opaque = Material::MetalPlastic(MetalPlasticMaterial {
        base_color,
        roughness: Roughness {
            tex: roughness,
            is_alpha: false,
        },
        metalness,
    });
    let index = match transmissive(asset, images, sink.mtl, &m, see_through, &mut note) {
        Some((glass, Tex::Const(w))) if w >= 1.0 => sink.mtl.push_with_surface(glass, surface),
        Some((glass, weight)) => {
            // Partly transmissive (the specification's mix of the
            // dielectric BRDF and the BTDF, and of both with the metal):
            // each hit is the opaque model or the glass, as a scene's
            // `Blend`, both with the surface's normal map and alpha.
            let a = sink.mtl.push_with_surface(opaque, surface.clone());
            let b = sink.mtl.push_with_surface(glass, surface);
            let blend = crate::materials::Blend { weight, a, b };
            sink.mtl.push_with_surface(
                Material::Emitter(crate::materials::Emitter),
                Surface {
                    blend: Some(blend),
                    ..Surface::default()
                },
            )
        }
        None => {
            if let Some(ior) = m.ior().filter(|&i| (i - 1.5).abs() > 1e-3) {
                note(format!(
                    "KHR_materials_ior {ior} not used: MetalPlastic's dielectric F0 is 0.04 (ior 1.5)"
                ));
            }
            sink.mtl.push_with_surface(opaque, surface)
        }
    };
    Mapped {
        index,
        uv_set: uv_sets.first().copied().unwrap_or(0),
        normal_mapped,
        emission: (emission.is_finite() && emission.max_element() > 0.0).then_some(emission),
        emission_map,
        double_sided: m.double_sided(),
    }
}

/// What a transmissive material keeps of the metallic–roughness one.
struct Transmissive {
    /// The base colour (texture × factor): the tint of what passes.
    tint: crate::materials::ColorTex,
    /// `roughnessFactor` (perceptual).
    roughness: f32,
    /// `metallicFactor`: transmission is the dielectric part's only.
    metalness: f32,
}

/// `KHR_materials_transmission` (with `KHR_materials_volume`, `KHR_materials_ior`)
/// as ronray glass and its share of the surface, transmission (× the red
/// channel of `transmissionTexture`) × (1 − metallic); `None` where nothing
/// transmits. Without a volume (`thicknessFactor` 0, the extension's default) the
/// surface is thin-walled, as the extension defines it — a thin `Glass`
/// sheet; with one, the boundary of a solid — `Glass`, or `RoughGlass`
/// (GGX) when `roughnessFactor` > 0.05. The base colour tints each
/// crossing; `attenuationColor` after `attenuationDistance` is the solid's
/// absorption (the glass's `attenuation`).
fn transmissive(
    asset: &mut Source,
    images: &mut Images,
    mtl: &mut super::super::mtl::MtlMaterials,
    m: &gltf::Material,
    t: Transmissive,
    note: &mut dyn FnMut(String),
) -> Option<(Material, crate::materials::ScalarTex)> {
    use crate::materials::{DielectricFresnel, Distribution, GlassMaterial, RoughGlassMaterial};
    let ext = m.transmission()?;
    let share = ext.transmission_factor();
    let share = if share.is_finite() {
        share.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let metal = if t.metalness.is_finite() {
        t.metalness.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let glass = share * (1.0 - metal);
    if glass <= 0.0 {
        return None;
    }
    let weight = match ext.transmission_texture() {
        Some(info) => match texture(asset, images, mtl, &info.texture(), false, None, note) {
            Some((i, _)) => Tex::Image(lookup(i, Channel::R, glass, &info)),
            None => Tex::Const(glass),
        },
        None => Tex::Const(glass),
    };
    let ior = match m.ior() {
        None => 1.5,
        Some(i) if (1.0..=10.0).contains(&i) => i,
        Some(i) => {
            note(format!(
                "KHR_materials_ior {i} is outside [1, 10]: glass of ior 1.5"
            ));
            1.5
        }
    };
    let volume = m.volume().filter(|v| v.thickness_factor() > 0.0);
    // Beer–Lambert absorption inside the solid: `attenuationColor` left
    // after `attenuationDistance` (infinite, the default: clear).
    let absorption = match &volume {
        Some(v) => {
            let (c, d) = (v.attenuation_color(), v.attenuation_distance());
            let usable = c.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x));
            if d.is_finite() && d > 0.0 && usable {
                // A channel of 0 absorbs everything: read as 10⁻⁶, and the
                // coefficient kept finite (a tiny distance overflows it).
                let sigma = c.map(|x| (-x.max(1e-6).ln() / d).min(f32::MAX));
                Rgb::new(sigma[0], sigma[1], sigma[2])
            } else {
                if !(d.is_infinite() && d > 0.0 && usable) {
                    note(format!(
                        "KHR_materials_volume attenuationColor {c:?} over attenuationDistance {d} is no \
                         absorption (colour channels in [0, 1], a distance > 0): clear glass"
                    ));
                }
                Rgb::ZERO
            }
        }
        None => Rgb::ZERO,
    };
    let rough = if t.roughness.is_finite() {
        t.roughness.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let material = match volume {
        // Rough glass refracts through microfacets, which needs η ≠ 1.
        Some(_) if rough > 0.05 && (ior - 1.0).abs() > 1e-3 => Material::RoughGlass(RoughGlassMaterial {
            distribution: Distribution::Ggx,
            roughness: Roughness::perceptual(rough),
            ior: crate::materials::Tex::Const(ior),
            tint: t.tint,
            absorption,
        }),
        solid => {
            if solid.is_none() && rough > 0.05 {
                note(format!(
                    "roughness {rough} of a thin-walled transmissive surface not applied: a smooth thin sheet"
                ));
            }
            Material::Glass(GlassMaterial {
                ior: crate::materials::Tex::Const(ior),
                tint: t.tint,
                fresnel: DielectricFresnel::Exact,
                thin: solid.is_none(),
                absorption,
            })
        }
    };
    Some((material, weight))
}

/// A normal texture's `KHR_texture_transform` and UV set: the `gltf` crate
/// reads the extension on every texture reference but the normal map's,
/// whose JSON it hands over as is (a tiled floor's normal map tiled as its
/// colour is). A field that is not what the extension says is its default.
fn normal_transform(n: &gltf::material::NormalTexture) -> (UvTransform, u32) {
    let Some(t) = n.extension_value("KHR_texture_transform") else {
        return (UvTransform::default(), n.tex_coord());
    };
    let pair = |key: &str, default: [f32; 2]| -> [f32; 2] {
        match t.get(key).and_then(|v| v.as_array()).map(|a| a.as_slice()) {
            Some([x, y]) => match (x.as_f64(), y.as_f64()) {
                (Some(x), Some(y)) if x.is_finite() && y.is_finite() => [x as f32, y as f32],
                _ => default,
            },
            _ => default,
        }
    };
    let rotation = t
        .get("rotation")
        .and_then(|v| v.as_f64())
        .filter(|r| r.is_finite())
        .unwrap_or(0.0) as f32;
    let set = t
        .get("texCoord")
        .and_then(|v| v.as_u64())
        .and_then(|s| u32::try_from(s).ok())
        .unwrap_or_else(|| n.tex_coord());
    (
        uv_transform(pair("offset", [0.0, 0.0]), rotation, pair("scale", [1.0, 1.0])),
        set,
    )
}

/// The UV set a texture reads (`KHR_texture_transform` may override it).
fn set_of(info: &gltf::texture::Info) -> u32 {
    info.texture_transform()
        .and_then(|t| t.tex_coord())
        .unwrap_or_else(|| info.tex_coord())
}

/// An image lookup of `index` through `info`'s `KHR_texture_transform`.
fn lookup(index: u32, channel: Channel, scale: f32, info: &gltf::texture::Info) -> ImageLookup {
    ImageLookup {
        index,
        channel,
        scale,
        offset: 0.0,
        rows_down: false,
        uv: info.texture_transform().map_or(UvTransform::default(), |t| {
            uv_transform(t.offset(), t.rotation(), t.scale())
        }),
        wrap: wrap_of(&info.texture()),
        times_vertex: false,
    }
}

/// The texture's sampler's `wrapS` and `wrapT` (u, then v: the importer's
/// flip of v leaves a mode as it is).
fn wrap_of(t: &gltf::Texture) -> [crate::materials::Wrap; 2] {
    use crate::materials::Wrap;
    use gltf::texture::WrappingMode;
    let one = |m: WrappingMode| match m {
        WrappingMode::Repeat => Wrap::Repeat,
        WrappingMode::ClampToEdge => Wrap::Clamp,
        WrappingMode::MirroredRepeat => Wrap::Mirror,
    };
    let s = t.sampler();
    [one(s.wrap_s()), one(s.wrap_t())]
}

/// `KHR_texture_transform` in ronray's v-up UVs. In glTF's own UVs it is
/// `uv' = offset + R·(scale ⊙ uv)` with `R = [[cos r, sin r], [−sin r,
/// cos r]]` (the extension's example: offset (0, 1), rotation π/2, scale
/// ½ reads the lower-left quadrant turned by 90°); conjugated by the flip
/// `F(u, v) = (u, 1 − v)` the importer applies to every UV.
pub fn uv_transform(offset: [f32; 2], rotation: f32, scale: [f32; 2]) -> UvTransform {
    if offset == [0.0, 0.0] && rotation == 0.0 && scale == [1.0, 1.0] {
        return UvTransform::default();
    }
    let (s, c) = rotation.sin_cos();
    let gltf = Affine2::from_mat2_translation(
        Mat2::from_cols(Vec2::new(c, -s), Vec2::new(s, c)) * Mat2::from_diagonal(Vec2::from(scale)),
        Vec2::from(offset),
    );
    let flip = Affine2::from_mat2_translation(Mat2::from_diagonal(Vec2::new(1.0, -1.0)), Vec2::new(0.0, 1.0));
    UvTransform(Some(flip * gltf * flip))
}

/// Decodes texture `t`'s image once per colour space (`srgb` for colours);
/// `factor` (base colour) is multiplied into a copy of the texels when it
/// is not white. Returns the texture index and whether it has alpha; a
/// failure is a note and `None`.
fn texture(
    asset: &mut Source,
    images: &mut Images,
    mtl: &mut super::super::mtl::MtlMaterials,
    t: &gltf::Texture,
    srgb: bool,
    factor: Option<Rgb>,
    note: &mut dyn FnMut(String),
) -> Option<(u32, bool)> {
    let image = t.source();
    let key = (image.index(), srgb);
    let cached = match images.cache.get(&key) {
        Some(c) => *c,
        None => {
            let decoded = decode(asset, &image, srgb);
            let r = match decoded {
                Ok(super::super::material::DecodedTexture {
                    texture: tex,
                    repaired,
                    ..
                }) => {
                    if let Some(what) = repaired {
                        note(format!(
                            "images[{}] has {what}, read as 0 (NaN, infinite and negative texels are no value)",
                            image.index()
                        ));
                    }
                    let alpha = !tex.alpha.is_empty();
                    Some((mtl.push_texture(tex), alpha))
                }
                Err(e) => {
                    note(format!("images[{}] not used: {e}", image.index()));
                    None
                }
            };
            images.cache.insert(key, r);
            r
        }
    };
    let (index, alpha) = cached?;
    match factor {
        Some(f) if f != Rgb::ONE => mtl.push_scaled_texture(index, f).map(|i| (i, alpha)),
        _ => Some((index, alpha)),
    }
}

/// The image's bytes (a buffer view or a URI) decoded.
fn decode(
    asset: &mut Source,
    image: &gltf::Image,
    srgb: bool,
) -> Result<super::super::material::DecodedTexture, String> {
    let bytes = match image.source() {
        gltf::image::Source::View { view, .. } => view_bytes(asset.buffers, &view)?.to_vec(),
        gltf::image::Source::Uri { uri, .. } => asset.files.uri_bytes(uri)?,
    };
    let img = crate::imageio::read::decode_texture_bytes(&bytes)?;
    super::super::material::texture_from_image(&img, srgb)
}
