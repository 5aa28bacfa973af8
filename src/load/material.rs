//! Materials: the checks of each `materials` entry and of its colour
//! parameters, and the build step that turns descriptions into runtime
//! [`Material`]s, decoding each image texture once (a file used by several
//! materials is read once). The models themselves live in `materials/`.

use super::validate::{Checker, MAX_RADIANCE, RADIANCE_HELP};
use crate::desc::{
    ChannelDesc, ColorDesc, ColorspaceDesc, CutoutModeDesc, DielectricFresnelDesc, DistributionDesc,
    FresnelDesc, ImageDesc, MaterialDesc, MaterialInner, MetalDesc, OriginDesc, PatternDesc,
    RoughnessUnitDesc, ScalarDesc, TexDesc, WrapDesc,
};
use crate::diagnostic::Problem;
use crate::materials::{
    Blend, Channel, ColorTex, Cutout, DielectricFresnel, Distribution, Fresnel, ImageLookup, Material, Metal,
    Pattern, Perturb, Roughness, ScalarTex, Surface, Tex, Texture, UvTransform, Wrap,
};
use crate::materials::{
    BlinnPhongMaterial, CookTorranceMaterial, GlassMaterial, LambertMaterial, MetalPlasticMaterial,
    Microfacet, MirrorMaterial, OrenNayarMaterial, PhongMaterial, RoughCoat, RoughGlassMaterial,
    RoughPlasticMaterial,
};
use crate::math::Rgb;
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl Checker {
    /// A colour parameter: constants are range-checked; a texture's
    /// constants, transform and file too (its channels are checked when the
    /// build step decodes it).
    pub(super) fn color_param(&mut self, path: &str, c: &ColorDesc, upper: Option<f32>) {
        match c {
            ColorDesc::Rgb(c) => self.color(path, c, upper),
            ColorDesc::Texture(t) => self.texture(path, t, &mut |ck, p, v: &[f32; 3]| ck.color(p, v, upper)),
        }
    }

    /// An emitted radiance: constants through [`Checker::emitted`], and an
    /// image's `scale` and `offset` at most [`MAX_RADIANCE`] too (a scale of
    /// 1e38 passed as finite and made the light's power infinite); the
    /// texels themselves are bounded when the build decodes them.
    pub(super) fn emitted_param(&mut self, path: &str, c: &ColorDesc) {
        match c {
            ColorDesc::Rgb(c) => self.emitted(path, c, "radiance"),
            ColorDesc::Texture(t) => {
                let vertex = match t {
                    TexDesc::Vertex { .. } => true,
                    TexDesc::Image(i) => i.times_vertex_color,
                    TexDesc::Checker { .. } | TexDesc::Pattern { .. } => false,
                };
                if vertex {
                    self.push(
                        path,
                        "emission does not read vertex colours",
                        "give the radiance as a colour or an image; vertex colours tint materials (`albedo`, `base_color`, …)",
                    );
                }
                if let TexDesc::Image(i) = t {
                    for (field, v) in [("scale", i.scale), ("offset", i.offset)] {
                        if v.is_finite() && v.abs() > MAX_RADIANCE {
                            self.push(
                                &format!("{path}.{field}"),
                                format!("an emission texture's {field} of {v:e} is above the limit of {MAX_RADIANCE:e}"),
                                RADIANCE_HELP,
                            );
                        }
                    }
                }
                self.texture(path, t, &mut |ck, p, v: &[f32; 3]| ck.emitted(p, v, "radiance"))
            }
        }
    }

    /// A number parameter in [lo, hi] (`what` names it in messages, `help`
    /// says what the values mean).
    pub(super) fn scalar_param(
        &mut self,
        path: &str,
        x: &ScalarDesc,
        (lo, hi): (f32, f32),
        what: &str,
        help: &str,
    ) {
        match x {
            ScalarDesc::Value(x) => self.range(path, *x, lo, hi, what, help),
            ScalarDesc::Texture(t) => {
                self.texture(path, t, &mut |ck, p, v: &f32| ck.range(p, *v, lo, hi, what, help))
            }
        }
    }

    /// The parts of a texture every kind shares: constants through `value`,
    /// the image file and scale, the pattern's numbers, the UV transform.
    fn texture<V>(&mut self, path: &str, t: &TexDesc<V>, value: &mut dyn FnMut(&mut Self, &str, &V)) {
        let uv = match t {
            TexDesc::Image(i) => {
                self.file(&format!("{path}.file"), &i.file, "texture");
                if !(i.scale.is_finite() && i.offset.is_finite()) {
                    self.push(path, "non-finite texture scale or offset", "use finite numbers");
                }
                &i.uv
            }
            TexDesc::Checker { a, b, scale, uv } => {
                value(self, &format!("{path}.a"), a);
                value(self, &format!("{path}.b"), b);
                if !(*scale > 0.0 && scale.is_finite()) {
                    self.push(
                        &format!("{path}.scale"),
                        format!("checker scale {scale} must be > 0"),
                        "it is the number of squares per UV unit",
                    );
                }
                uv
            }
            TexDesc::Pattern {
                pattern, a, b, uv, ..
            } => {
                value(self, &format!("{path}.a"), a);
                value(self, &format!("{path}.b"), b);
                self.pattern(&format!("{path}.pattern"), pattern);
                uv
            }
            TexDesc::Vertex { factor, .. } => {
                value(self, &format!("{path}.factor"), factor);
                return;
            }
        };
        if !(uv.scale.iter().chain(&uv.offset).all(|x| x.is_finite()) && uv.rotation_degrees.is_finite()) {
            self.push(
                &format!("{path}.uv"),
                "non-finite UV transform",
                "use finite numbers",
            );
        } else if uv.scale.contains(&0.0) {
            self.push(
                &format!("{path}.uv.scale"),
                "a UV scale of 0 collapses the texture to one texel",
                "use a non-zero scale: 2 repeats the texture twice, -1 mirrors it",
            );
        }
    }

    fn pattern(&mut self, path: &str, p: &PatternDesc) {
        match *p {
            PatternDesc::Fbm {
                octaves,
                lacunarity,
                gain,
            } => {
                if !(1..=16).contains(&octaves) {
                    self.push(
                        &format!("{path}.octaves"),
                        format!("{octaves} octaves is outside [1, 16]"),
                        "5 is a usual choice; each octave adds finer detail",
                    );
                }
                self.range(
                    &format!("{path}.lacunarity"),
                    lacunarity,
                    1.0,
                    16.0,
                    "lacunarity",
                    "the frequency factor between octaves, usually 2",
                );
                self.range(
                    &format!("{path}.gain"),
                    gain,
                    0.0,
                    1.0,
                    "gain",
                    "the amplitude factor between octaves, usually 0.5",
                );
            }
            PatternDesc::Stripes { duty } => self.range(
                &format!("{path}.duty"),
                duty,
                0.0,
                1.0,
                "duty",
                "the fraction of each stripe period that is `b`",
            ),
            PatternDesc::ValueNoise | PatternDesc::GradientNoise | PatternDesc::Cellular => {}
        }
    }

    pub(super) fn material(&mut self, path: &str, m: &MaterialDesc) {
        let p = |f: &str| format!("{path}.{f}");
        match m {
            MaterialDesc::Lambert { albedo } => self.color_param(&p("albedo"), albedo, Some(1.0)),
            MaterialDesc::OrenNayar { albedo, sigma } => {
                self.color_param(&p("albedo"), albedo, Some(1.0));
                self.scalar_param(
                    &p("sigma"),
                    sigma,
                    (0.0, 2.0),
                    "sigma",
                    "sigma is a unitless roughness: 0 is Lambert, 1 is very rough",
                );
            }
            MaterialDesc::Phong {
                diffuse,
                specular,
                exponent,
            }
            | MaterialDesc::BlinnPhong {
                diffuse,
                specular,
                exponent,
            } => self.phong_lobes(path, diffuse, specular, exponent),
            MaterialDesc::CookTorrance {
                roughness,
                roughness_unit,
                fresnel,
                ..
            } => {
                self.microfacet_roughness(&p("roughness"), roughness, *roughness_unit);
                self.fresnel(&p("fresnel"), fresnel);
            }
            MaterialDesc::MetalPlastic {
                base_color,
                roughness,
                roughness_unit,
                metalness,
            } => {
                self.color_param(&p("base_color"), base_color, Some(1.0));
                self.microfacet_roughness(&p("roughness"), roughness, *roughness_unit);
                self.scalar_param(
                    &p("metalness"),
                    metalness,
                    (0.0, 1.0),
                    "metalness",
                    "0 is plastic, 1 is metal",
                );
            }
            MaterialDesc::Mirror { tint } => self.color_param(&p("tint"), tint, Some(1.0)),
            MaterialDesc::Glass {
                ior,
                tint,
                thin,
                attenuation,
                ..
            } => {
                self.color_param(&p("tint"), tint, Some(1.0));
                self.coat_ior(&p("ior"), ior, "glass is about 1.5, water 1.33, diamond 2.42");
                if let Some(a) = attenuation {
                    self.attenuation(&p("attenuation"), a);
                    if *thin {
                        self.push(
                            &p("attenuation"),
                            "a thin sheet has no inside to absorb in",
                            "drop `thin: true` for a solid of coloured glass, or `attenuation` and colour the sheet with `tint`",
                        );
                    }
                }
            }
            MaterialDesc::RoughPlastic {
                diffuse,
                specular,
                roughness,
                roughness_unit,
                ior,
                ..
            } => self.rough_plastic(path, diffuse, specular, (roughness, *roughness_unit), ior),
            MaterialDesc::RoughGlass {
                ior,
                tint,
                roughness,
                roughness_unit,
                attenuation,
                ..
            } => {
                self.rough_glass(path, ior, tint, (roughness, *roughness_unit));
                if let Some(a) = attenuation {
                    self.attenuation(&p("attenuation"), a);
                }
            }
            MaterialDesc::NormalMap {
                map,
                strength,
                material,
                ..
            } => {
                self.color_param(&p("map"), map, Some(1.0));
                if let ColorDesc::Texture(TexDesc::Image(ImageDesc {
                    colorspace: Some(ColorspaceDesc::Srgb),
                    ..
                })) = map
                {
                    self.push(
                        &p("map.colorspace"),
                        "a normal map read as sRGB bends every normal",
                        "normal maps store directions, not colours: remove `colorspace: Srgb` (they are read as Linear)",
                    );
                }
                self.range(
                    &p("strength"),
                    *strength,
                    0.0,
                    100.0,
                    "strength",
                    "1 is the map as authored, 0 the unmapped surface",
                );
                self.material(&p("material"), material);
            }
            MaterialDesc::Bump {
                height,
                scale,
                material,
            } => {
                self.scalar_param(
                    &p("height"),
                    height,
                    (f32::MIN, f32::MAX),
                    "height",
                    "heights are any finite numbers, times `scale`",
                );
                if !scale.is_finite() {
                    self.push(
                        &p("scale"),
                        "non-finite bump scale",
                        "scene units per unit of height, e.g. 0.01",
                    );
                }
                self.material(&p("material"), material);
            }
            MaterialDesc::Cutout {
                opacity,
                mode,
                material,
            } => {
                self.scalar_param(
                    &p("opacity"),
                    opacity,
                    (0.0, 1.0),
                    "opacity",
                    "0 is a hole, 1 is solid",
                );
                if let CutoutModeDesc::Threshold(c) = mode
                    && !(*c > 0.0 && *c <= 1.0)
                {
                    self.push(
                        &p("mode"),
                        format!("cut-off {c} is outside (0, 1]"),
                        "the surface is kept where opacity ≥ the cut-off: 0.5 is usual",
                    );
                }
                if has_cutout(material, 0) {
                    self.push(
                        &p("material"),
                        "a cut-out inside a cut-out",
                        "combine the two opacities into one texture",
                    );
                }
                self.material(&p("material"), material);
            }
            MaterialDesc::Blend { weight, a, b } => {
                self.scalar_param(
                    &p("weight"),
                    weight,
                    (0.0, 1.0),
                    "weight",
                    "0 is all `a`, 1 is all `b`",
                );
                if blend_depth(m, 0) > MAX_BLEND_DEPTH {
                    self.push(
                        path,
                        format!("blends nested more than {MAX_BLEND_DEPTH} deep"),
                        "a blend of blends this deep is a texture's job: mix the colours in one image \
                         (MAX_BLEND_DEPTH in src/load/material.rs is the limit)",
                    );
                } else {
                    self.material(&p("a"), a);
                    self.material(&p("b"), b);
                }
            }
        }
    }

    /// `RoughPlastic`: base and coat colours, coat roughness and index.
    fn rough_plastic(
        &mut self,
        path: &str,
        diffuse: &ColorDesc,
        specular: &ColorDesc,
        (roughness, unit): (&ScalarDesc, RoughnessUnitDesc),
        ior: &ScalarDesc,
    ) {
        self.color_param(&format!("{path}.diffuse"), diffuse, Some(1.0));
        self.color_param(&format!("{path}.specular"), specular, Some(1.0));
        self.microfacet_roughness(&format!("{path}.roughness"), roughness, unit);
        for (field, x) in [("roughness", roughness), ("ior", ior)] {
            if x.constant().is_none() {
                self.push(
                    &format!("{path}.{field}"),
                    format!("a RoughPlastic's {field} must be a number"),
                    "its coat's tables are integrated once per roughness and index at load; use CookTorrance or MetalPlastic for a textured roughness",
                );
            }
        }
        self.coat_ior(
            &format!("{path}.ior"),
            ior,
            "a plastic coat is about 1.5 (polypropylene 1.49)",
        );
    }

    /// `RoughGlass`: tint, roughness, and an index that differs from 1 (a
    /// rough boundary between equal indices would be a delta lobe).
    fn rough_glass(
        &mut self,
        path: &str,
        ior: &ScalarDesc,
        tint: &ColorDesc,
        (roughness, unit): (&ScalarDesc, RoughnessUnitDesc),
    ) {
        self.color_param(&format!("{path}.tint"), tint, Some(1.0));
        self.microfacet_roughness(&format!("{path}.roughness"), roughness, unit);
        self.coat_ior(
            &format!("{path}.ior"),
            ior,
            "glass is about 1.5, water 1.33, diamond 2.42",
        );
        if ior.constant() == Some(1.0) {
            self.push(
                &format!("{path}.ior"),
                "a rough boundary with index of refraction 1 does not scatter",
                "light would pass straight through; use an ior other than 1",
            );
        }
    }

    /// Roughness in [0, 1] (α = roughness²), or α in [0, 4] with
    /// `roughness_unit: Alpha`.
    fn microfacet_roughness(&mut self, path: &str, roughness: &ScalarDesc, unit: RoughnessUnitDesc) {
        match unit {
            RoughnessUnitDesc::Perceptual => {
                let help = "0 is polished, 1 is very rough (α = roughness²: Mitsuba's alpha a is roughness √a, or say `roughness_unit: Alpha`)";
                self.scalar_param(path, roughness, (0.0, 1.0), "roughness", help);
            }
            RoughnessUnitDesc::Alpha => {
                let help = "with `roughness_unit: Alpha` the value is the distribution's α: 0.01 is polished, 1 very rough";
                self.scalar_param(path, roughness, (0.0, 4.0), "α", help);
            }
        }
    }

    /// A dielectric's relative index of refraction, in (0, 10].
    fn coat_ior(&mut self, path: &str, ior: &ScalarDesc, help: &str) {
        match ior {
            ScalarDesc::Value(ior) => {
                if !(*ior > 0.0 && ior.is_finite() && *ior <= 10.0) {
                    self.push(
                        path,
                        format!("index of refraction {ior} is outside (0, 10]"),
                        help,
                    );
                }
            }
            ScalarDesc::Texture(_) => {
                self.scalar_param(path, ior, (f32::MIN_POSITIVE, 10.0), "index of refraction", help)
            }
        }
    }

    /// A glass's `attenuation`: colour channels in (0, 1] (0 would absorb
    /// everything in no distance), a distance > 0.
    fn attenuation(&mut self, path: &str, a: &crate::desc::AttenuationDesc) {
        if !a.color.iter().all(|c| *c > 0.0 && *c <= 1.0) {
            self.push(
                &format!("{path}.color"),
                format!("attenuation colour {:?} has a channel outside (0, 1]", a.color),
                "the fraction of each channel left after `distance` inside: (0.9, 0.6, 0.3) is amber, 1 leaves a channel unabsorbed",
            );
        }
        if !(a.distance > 0.0 && a.distance.is_finite()) {
            self.push(
                &format!("{path}.distance"),
                format!("attenuation distance {} is not a length > 0", a.distance),
                "scene units inside the glass after which `color` is left: about the object's thickness for a visible tint",
            );
        }
    }

    /// The diffuse and specular lobes shared by `Phong` and `BlinnPhong`.
    fn phong_lobes(&mut self, path: &str, diffuse: &ColorDesc, specular: &ColorDesc, exponent: &ScalarDesc) {
        let p = |f: &str| format!("{path}.{f}");
        self.color_param(&p("diffuse"), diffuse, Some(1.0));
        self.color_param(&p("specular"), specular, Some(1.0));
        self.scalar_param(
            &p("exponent"),
            exponent,
            (0.0, 100_000.0),
            "exponent",
            "the lobe sharpness: 1 is broad, 1000 is nearly a mirror",
        );
        if let (ColorDesc::Rgb(d), ColorDesc::Rgb(s)) = (diffuse, specular)
            && d.iter().zip(s).any(|(a, b)| a + b > 1.0 + 1e-6)
        {
            self.push(
                &p("specular"),
                format!("diffuse {d:?} + specular {s:?} exceeds 1 in a channel"),
                "keep diffuse + specular ≤ 1 per channel so the surface reflects no more light than it receives",
            );
        }
    }

    /// A conductor's Fresnel term (`CookTorrance`'s `fresnel`).
    fn fresnel(&mut self, path: &str, fresnel: &FresnelDesc) {
        match fresnel {
            FresnelDesc::Conductor { eta, k } => {
                self.color(&format!("{path}.eta"), eta, None);
                self.color(&format!("{path}.k"), k, None);
                if eta.contains(&0.0) {
                    self.push(
                        &format!("{path}.eta"),
                        "a conductor's η must be > 0",
                        "use a preset such as `Metal(Gold)`",
                    );
                }
            }
            FresnelDesc::Schlick { f0 } => self.color(&format!("{path}.f0"), f0, Some(1.0)),
            FresnelDesc::Metal(_) => {}
        }
    }
}

/// The runtime materials (in name order), the textures they use, and the
/// index of each name.
pub struct Materials {
    /// The runtime materials, in the name order of the scene's `materials`.
    pub materials: Vec<Material>,
    /// What each material does to the surface (normal maps, cut-outs), in
    /// the same order.
    pub surfaces: Vec<Surface>,
    /// Decoded image textures, indexed by [`ImageLookup::index`].
    pub textures: Vec<Texture>,
    /// Index in `materials` of each scene material name.
    pub index: HashMap<String, u32>,
    /// Image files read, for watch mode.
    pub files: Vec<PathBuf>,
    /// The emission textures, by the scene path of their `radiance`.
    pub emissions: HashMap<String, ColorTex>,
    /// Notes at the scene paths whose image had texels repaired.
    pub notes: Vec<Problem>,
}

/// Builds every entry of the scene's `materials`, resolving texture files against
/// `base` (the scene file's folder) and decoding each file once per colour
/// space. All texture problems come back together.
///
/// `emissions` are the textured radiances of lights and emitting objects, by
/// scene path: their images are read here too, so a file an emitter and a
/// material share is decoded once.
pub fn build_materials(
    descs: &BTreeMap<String, MaterialDesc>,
    emissions: &[(String, &ColorDesc)],
    base: &Path,
) -> Result<Materials, Vec<Problem>> {
    let mut b = Builder {
        base,
        textures: Vec::new(),
        by_path: HashMap::new(),
        problems: Vec::new(),
        notes: Vec::new(),
        coats: Vec::new(),
        first_component: descs.len() as u32,
        components: Vec::new(),
    };
    let mut materials = Vec::new();
    let mut surfaces = Vec::new();
    let mut index = HashMap::new();
    for (name, m) in descs {
        index.insert(name.clone(), materials.len() as u32);
        let mut surface = Surface::default();
        let mat = build_material(&mut b, &format!("materials.{name}"), m, &mut surface);
        materials.push(mat);
        surfaces.push(surface);
    }
    for (m, s) in std::mem::take(&mut b.components) {
        materials.push(m);
        surfaces.push(s);
    }
    let emissions = emissions
        .iter()
        .map(|(path, c)| (path.clone(), b.color(c, path, true)))
        .collect();
    if !b.problems.is_empty() {
        return Err(b.problems);
    }
    let mut files: Vec<PathBuf> = b.by_path.keys().map(|(p, _)| p.clone()).collect();
    files.sort();
    files.dedup();
    Ok(Materials {
        materials,
        surfaces,
        textures: b.textures,
        index,
        files,
        emissions,
        notes: b.notes,
    })
}

/// How deep blends may nest (`Blend(a: Blend(a: …))`): each level is one
/// more step of the scene's per-hit surface loop, which gives up after 64.
pub const MAX_BLEND_DEPTH: u32 = 16;

/// Blends on the deepest path through `m`'s wrappers and blends, from
/// `depth` (stops counting past the limit, so a hostile file's depth costs
/// no more than the limit's).
fn blend_depth(m: &MaterialDesc, depth: u32) -> u32 {
    if depth > MAX_BLEND_DEPTH {
        return depth;
    }
    match m.inner() {
        MaterialInner::Model => depth,
        MaterialInner::Wrapped(inner) => blend_depth(inner, depth),
        MaterialInner::Blend(a, b) => blend_depth(a, depth + 1).max(blend_depth(b, depth + 1)),
    }
}

/// Whether `m` has a cut-out anywhere inside (through wrappers and blends).
fn has_cutout(m: &MaterialDesc, depth: u32) -> bool {
    matches!(m, MaterialDesc::Cutout { .. })
        || match m.inner() {
            MaterialInner::Model => false,
            MaterialInner::Wrapped(inner) => has_cutout(inner, depth),
            MaterialInner::Blend(a, b) => {
                depth <= MAX_BLEND_DEPTH && (has_cutout(a, depth + 1) || has_cutout(b, depth + 1))
            }
        }
}

/// The runtime material at scene path `path`; its textures are read through
/// `b`, and wrappers (`NormalMap`, `Bump`, `Cutout`) fill `surface`. A
/// `Blend`'s two materials go to the end of the table (`b.components`),
/// each with the surface effects of the wrappers around the blend; the
/// blend's own entry only picks between them and is never shaded.
fn build_material(b: &mut Builder, path: &str, m: &MaterialDesc, surface: &mut Surface) -> Material {
    let p = |field: &str| format!("{path}.{field}");
    match m {
        MaterialDesc::Lambert { albedo } => Material::Lambert(LambertMaterial {
            albedo: b.color(albedo, &p("albedo"), true),
        }),
        MaterialDesc::OrenNayar { albedo, sigma } => Material::OrenNayar(OrenNayarMaterial {
            albedo: b.color(albedo, &p("albedo"), true),
            sigma: b.scalar(sigma, &p("sigma")),
        }),
        MaterialDesc::Phong {
            diffuse,
            specular,
            exponent,
        } => Material::Phong(PhongMaterial {
            kd: b.color(diffuse, &p("diffuse"), true),
            ks: b.color(specular, &p("specular"), true),
            exponent: b.scalar(exponent, &p("exponent")),
        }),
        MaterialDesc::BlinnPhong {
            diffuse,
            specular,
            exponent,
        } => Material::BlinnPhong(BlinnPhongMaterial {
            kd: b.color(diffuse, &p("diffuse"), true),
            ks: b.color(specular, &p("specular"), true),
            exponent: b.scalar(exponent, &p("exponent")),
        }),
        MaterialDesc::CookTorrance {
            distribution,
            roughness,
            roughness_unit,
            fresnel,
        } => Material::CookTorrance(CookTorranceMaterial {
            distribution: distribution_of(*distribution),
            roughness: b.roughness(roughness, *roughness_unit, &p("roughness")),
            fresnel: match fresnel {
                FresnelDesc::Conductor { eta, k } => Fresnel::Conductor {
                    eta: (*eta).into(),
                    k: (*k).into(),
                },
                FresnelDesc::Metal(m) => metal(*m).fresnel(),
                FresnelDesc::Schlick { f0 } => Fresnel::Schlick { f0: (*f0).into() },
            },
        }),
        MaterialDesc::MetalPlastic {
            base_color,
            roughness,
            roughness_unit,
            metalness,
        } => Material::MetalPlastic(MetalPlasticMaterial {
            base_color: b.color(base_color, &p("base_color"), true),
            roughness: b.roughness(roughness, *roughness_unit, &p("roughness")),
            metalness: b.scalar(metalness, &p("metalness")),
        }),
        MaterialDesc::Mirror { tint } => Material::Mirror(MirrorMaterial {
            tint: b.color(tint, &p("tint"), true),
        }),
        MaterialDesc::Glass {
            ior,
            tint,
            fresnel,
            thin,
            attenuation,
        } => Material::Glass(GlassMaterial {
            ior: b.scalar(ior, &p("ior")),
            tint: b.color(tint, &p("tint"), true),
            fresnel: match fresnel {
                DielectricFresnelDesc::Exact => DielectricFresnel::Exact,
                DielectricFresnelDesc::Schlick => DielectricFresnel::Schlick,
            },
            thin: *thin,
            absorption: absorption_of(attenuation.as_ref()),
        }),
        MaterialDesc::RoughPlastic {
            diffuse,
            specular,
            distribution,
            roughness,
            roughness_unit,
            ior,
        } => {
            // Constants: the checks refuse textures here.
            let r = roughness.constant().unwrap_or(0.0);
            let microfacet = match roughness_unit {
                RoughnessUnitDesc::Perceptual => {
                    Microfacet::from_roughness(distribution_of(*distribution), r)
                }
                RoughnessUnitDesc::Alpha => Microfacet::from_alpha(distribution_of(*distribution), r),
            };
            Material::RoughPlastic(RoughPlasticMaterial {
                diffuse: b.color(diffuse, &p("diffuse"), true),
                specular: b.color(specular, &p("specular"), true),
                coat: b.coat(microfacet, ior.constant().unwrap_or(1.5)),
            })
        }
        MaterialDesc::RoughGlass {
            ior,
            tint,
            distribution,
            roughness,
            roughness_unit,
            attenuation,
        } => Material::RoughGlass(RoughGlassMaterial {
            distribution: distribution_of(*distribution),
            roughness: b.roughness(roughness, *roughness_unit, &p("roughness")),
            ior: b.scalar(ior, &p("ior")),
            tint: b.color(tint, &p("tint"), true),
            absorption: absorption_of(attenuation.as_ref()),
        }),
        MaterialDesc::NormalMap {
            map,
            strength,
            flip_green,
            tangents,
            material,
        } => {
            surface.normal = Some(Perturb::NormalMap {
                map: b.color(map, &p("map"), false),
                strength: *strength,
                flip_green: *flip_green,
                frame: match tangents {
                    crate::desc::TangentFrameDesc::Vertex => crate::geometry::TangentFrame::Vertex,
                    crate::desc::TangentFrameDesc::Triangle => crate::geometry::TangentFrame::Triangle,
                },
            });
            build_material(b, &p("material"), material, surface)
        }
        MaterialDesc::Bump {
            height,
            scale,
            material,
        } => {
            surface.normal = Some(Perturb::Bump {
                height: b.scalar(height, &p("height")),
                scale: *scale,
            });
            build_material(b, &p("material"), material, surface)
        }
        MaterialDesc::Cutout {
            opacity,
            mode,
            material,
        } => {
            surface.cutout = Some(Cutout {
                opacity: b.scalar(opacity, &p("opacity")),
                threshold: match mode {
                    CutoutModeDesc::Stochastic => None,
                    CutoutModeDesc::Threshold(c) => Some(*c),
                },
            });
            build_material(b, &p("material"), material, surface)
        }
        MaterialDesc::Blend { weight, a, b: second } => {
            let outer = std::mem::take(surface);
            let a = b.component(&p("a"), a, &outer);
            let second = b.component(&p("b"), second, &outer);
            surface.blend = Some(Blend {
                weight: b.scalar(weight, &p("weight")),
                a,
                b: second,
            });
            // Never shaded: the scene hands every hit on to `a` or `b`.
            Material::Emitter(crate::materials::Emitter)
        }
    }
}

/// The absorption coefficient of a glass's `attenuation` (zero: clear).
fn absorption_of(a: Option<&crate::desc::AttenuationDesc>) -> Rgb {
    a.map_or(Rgb::ZERO, |a| Rgb::from_array(a.sigma()))
}

fn distribution_of(d: DistributionDesc) -> Distribution {
    match d {
        DistributionDesc::Ggx => Distribution::Ggx,
        DistributionDesc::Beckmann => Distribution::Beckmann,
    }
}

/// The runtime conductor preset of a scene's `Metal(...)` name.
pub fn metal(m: MetalDesc) -> Metal {
    match m {
        MetalDesc::Gold => Metal::Gold,
        MetalDesc::Silver => Metal::Silver,
        MetalDesc::Copper => Metal::Copper,
        MetalDesc::Aluminium => Metal::Aluminium,
    }
}

/// A decoded image and what the checks need to know of its file.
struct Decoded {
    index: u32,
    /// Channels in the file (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA).
    channels: u8,
}

struct Builder<'a> {
    base: &'a Path,
    textures: Vec<Texture>,
    /// Each file once per colour space (true = sRGB-decoded).
    by_path: HashMap<(PathBuf, bool), Decoded>,
    problems: Vec<Problem>,
    /// Images whose texels were repaired (`src/load/texels.rs`), as notes at
    /// the scene path that first read them.
    notes: Vec<Problem>,
    /// Rough-plastic coats built so far: their tables cost ~0.1 s each, and
    /// materials differing only in colour share one.
    coats: Vec<Arc<RoughCoat>>,
    /// Where blends' components start in the material table (after the
    /// named materials).
    first_component: u32,
    /// Blends' components, in table order from `first_component`.
    components: Vec<(Material, Surface)>,
}

impl Builder<'_> {
    /// A blend's component: built with a copy of the surface effects of
    /// the wrappers around the blend (its own wrappers replace them) and
    /// added to the table; its index.
    fn component(&mut self, path: &str, m: &MaterialDesc, outer: &Surface) -> u32 {
        let mut surface = outer.clone();
        let material = build_material(self, path, m, &mut surface);
        self.components.push((material, surface));
        self.first_component
            .saturating_add(self.components.len() as u32 - 1)
    }

    /// The coat of `microfacet` and `eta`, integrated once per load.
    fn coat(&mut self, microfacet: Microfacet, eta: f32) -> Arc<RoughCoat> {
        let same = |c: &&Arc<RoughCoat>| {
            c.microfacet.distribution == microfacet.distribution
                && c.microfacet.alpha == microfacet.alpha
                && c.eta == eta
        };
        if let Some(c) = self.coats.iter().find(same) {
            return c.clone();
        }
        let c = Arc::new(RoughCoat::new(microfacet, eta));
        self.coats.push(c.clone());
        c
    }

    /// A colour parameter; an image is sRGB-decoded unless `srgb` is false
    /// (normal maps) or the scene says otherwise.
    fn color(&mut self, c: &ColorDesc, path: &str, srgb: bool) -> ColorTex {
        match c {
            ColorDesc::Rgb(c) => Tex::Const((*c).into()),
            ColorDesc::Texture(t) => self.tex(t, path, srgb, false, |v| Rgb::from(*v)),
        }
    }

    /// A number parameter; images are linear unless the scene says otherwise.
    fn scalar(&mut self, x: &ScalarDesc, path: &str) -> ScalarTex {
        match x {
            ScalarDesc::Value(x) => Tex::Const(*x),
            ScalarDesc::Texture(t) => self.tex(t, path, false, true, |v| *v),
        }
    }

    fn roughness(&mut self, x: &ScalarDesc, unit: RoughnessUnitDesc, path: &str) -> Roughness {
        Roughness {
            tex: self.scalar(x, path),
            is_alpha: unit == RoughnessUnitDesc::Alpha,
        }
    }

    /// The runtime texture of `t`; `scalar` parameters need one channel.
    fn tex<V, T>(
        &mut self,
        t: &TexDesc<V>,
        path: &str,
        srgb: bool,
        scalar: bool,
        value: impl Fn(&V) -> T,
    ) -> Tex<T> {
        let uv =
            |u: &crate::desc::UvDesc| UvTransform::new(u.scale.into(), u.rotation_degrees, u.offset.into());
        match t {
            TexDesc::Checker { a, b, scale, uv: u } => Tex::Checker {
                a: value(a),
                b: value(b),
                scale: *scale,
                uv: uv(u),
            },
            TexDesc::Pattern {
                pattern,
                a,
                b,
                seed,
                uv: u,
            } => Tex::Pattern {
                pattern: match *pattern {
                    PatternDesc::ValueNoise => Pattern::Value { seed: *seed },
                    PatternDesc::GradientNoise => Pattern::Gradient { seed: *seed },
                    PatternDesc::Fbm {
                        octaves,
                        lacunarity,
                        gain,
                    } => Pattern::Fbm {
                        seed: *seed,
                        octaves,
                        lacunarity,
                        gain,
                    },
                    PatternDesc::Cellular => Pattern::Cellular { seed: *seed },
                    PatternDesc::Stripes { duty } => Pattern::Stripes { duty },
                },
                a: value(a),
                b: value(b),
                uv: uv(u),
            },
            TexDesc::Vertex { channel, factor } => {
                if scalar && channel.is_none() {
                    self.problems.push(
                        Problem::new(path, "a number reads one channel of the vertex colours")
                            .help("say which, e.g. `VertexColor(factor: 1, channel: G)`"),
                    );
                }
                if *channel == Some(ChannelDesc::A) {
                    self.problems.push(
                        Problem::new(format!("{path}.channel"), "vertex colours have no alpha channel")
                            .help("read `R`, `G` or `B` (the alpha of glTF's COLOR_0 is not kept)"),
                    );
                }
                Tex::Vertex {
                    channel: match channel {
                        None => Channel::All,
                        Some(ChannelDesc::R) => Channel::R,
                        Some(ChannelDesc::G) => Channel::G,
                        Some(ChannelDesc::B) => Channel::B,
                        Some(ChannelDesc::A) => Channel::A,
                    },
                    factor: value(factor),
                }
            }
            TexDesc::Image(i) => {
                let srgb = match i.colorspace {
                    Some(ColorspaceDesc::Srgb) => true,
                    Some(ColorspaceDesc::Linear) => false,
                    None => srgb,
                };
                let Some((index, channels)) = self.image(&i.file, srgb, path) else {
                    return Tex::Image(ImageLookup {
                        index: 0,
                        channel: Channel::All,
                        scale: 0.0,
                        offset: 0.0,
                        rows_down: false,
                        uv: UvTransform::default(),
                        wrap: [Wrap::Repeat; 2],
                        times_vertex: false,
                    });
                };
                let channel = match i.channel {
                    None => Channel::All,
                    Some(ChannelDesc::R) => Channel::R,
                    Some(ChannelDesc::G) => Channel::G,
                    Some(ChannelDesc::B) => Channel::B,
                    Some(ChannelDesc::A) => Channel::A,
                };
                let grey = channels <= 2;
                if scalar && channel == Channel::All && !grey {
                    self.problems.push(
                        Problem::new(path, format!("{} is a colour image but this parameter is a number", i.file))
                            .help("say which channel to read, e.g. `Image(file: \"…\", channel: G)` (glTF packs roughness in G, metalness in B)"),
                    );
                }
                if grey && matches!(channel, Channel::G | Channel::B) {
                    self.problems.push(
                        Problem::new(
                            format!("{path}.channel"),
                            format!("{} is a greyscale image: it has no {:?} channel", i.file, channel),
                        )
                        .help("read it without `channel` (or `channel: R`)"),
                    );
                }
                if channel == Channel::A && channels % 2 == 1 {
                    self.problems.push(
                        Problem::new(
                            format!("{path}.channel"),
                            format!("{} has no alpha channel", i.file),
                        )
                        .help("export the image with alpha, or read a colour channel"),
                    );
                }
                Tex::Image(ImageLookup {
                    index,
                    channel,
                    scale: i.scale,
                    offset: i.offset,
                    rows_down: i.origin == OriginDesc::TopLeft,
                    uv: uv(&i.uv),
                    wrap: [match i.wrap {
                        WrapDesc::Repeat => Wrap::Repeat,
                        WrapDesc::Clamp => Wrap::Clamp,
                        WrapDesc::Mirror => Wrap::Mirror,
                    }; 2],
                    times_vertex: i.times_vertex_color,
                })
            }
        }
    }

    /// The index and channel count of image `file`, decoded once per colour
    /// space; `None` after reporting a problem at `path`.
    fn image(&mut self, file: &str, srgb: bool, path: &str) -> Option<(u32, u8)> {
        // Keyed by the file itself, not its spelling: `x.png` and `./x.png`
        // are decoded once.
        let full = self.base.join(file);
        let full = std::fs::canonicalize(&full).unwrap_or(full);
        if let Some(d) = self.by_path.get(&(full.clone(), srgb)) {
            return Some((d.index, d.channels));
        }
        match load_texture_as(&full, srgb) {
            Ok(DecodedTexture {
                texture,
                channels,
                repaired,
            }) => {
                if let Some(what) = repaired {
                    self.notes.push(Problem::new(
                        format!("{path}.file"),
                        format!("{file} has {what}, read as 0 (NaN, infinite and negative texels are no value); fix the image to silence this"),
                    ));
                }
                let index = self.textures.len() as u32;
                self.textures.push(texture);
                self.by_path.insert((full, srgb), Decoded { index, channels });
                Some((index, channels))
            }
            Err(msg) => {
                self.problems
                    .push(Problem::new(format!("{path}.file"), msg).help(format!(
                        "the path resolves to {} (relative to the scene file's folder)",
                        full.display()
                    )));
                None
            }
        }
    }
}

/// Decodes an 8-bit image as sRGB-encoded colour.
pub fn load_texture(path: &Path) -> Result<Texture, String> {
    load_texture_as(path, true).map(|d| d.texture)
}

/// A texture as decoded from its file.
#[derive(Clone, Debug)]
pub struct DecodedTexture {
    /// The texels, linear, repaired.
    pub texture: Texture,
    /// Channels in the file (1 grey, 2 grey + alpha, 3 RGB, 4 RGBA).
    pub channels: u8,
    /// What was repaired in a float image's texels (NaN, infinite or
    /// negative values read as 0, see `src/load/texels.rs`), for the caller
    /// to report where the file was read; `None` when nothing was.
    pub repaired: Option<String>,
}

/// Decodes an image, 8- and 16-bit texels through the sRGB curve when
/// `srgb` (float images are linear), with its alpha when it has one.
pub fn load_texture_as(path: &Path, srgb: bool) -> Result<DecodedTexture, String> {
    let img = crate::imageio::read::decode_texture(path).map_err(|e| format!("texture: {e}"))?;
    texture_from_image(&img, srgb).map_err(|e| format!("texture {}: {e}", path.display()))
}

/// A decoded image as a texture (see [`load_texture_as`]), its texels
/// repaired: every texture decoded for a parameter goes through here, so
/// none reaches the render with a NaN, infinite or negative texel.
pub fn texture_from_image(img: &image::DynamicImage, srgb: bool) -> Result<DecodedTexture, String> {
    let color = img.color();
    let channels = color.channel_count();
    let float = matches!(color, image::ColorType::Rgb32F | image::ColorType::Rgba32F);
    let fail = |e: String| e;
    let mut t = if srgb && !float {
        let rgb = img.to_rgb8();
        Texture::try_from_srgb8(rgb.width(), rgb.height(), rgb.as_raw()).map_err(fail)?
    } else {
        let rgb = img.to_rgb32f();
        let mut texels = Vec::new();
        texels
            .try_reserve_exact(rgb.len() / 3)
            .map_err(|_| fail("not enough memory for its texels".into()))?;
        texels.extend(rgb.as_raw().chunks_exact(3).map(|p| Rgb::new(p[0], p[1], p[2])));
        Texture {
            width: rgb.width(),
            height: rgb.height(),
            texels,
            alpha: Vec::new(),
        }
    };
    if color.has_alpha() {
        t.alpha = img.to_rgba32f().as_raw().chunks_exact(4).map(|p| p[3]).collect();
    }
    let repaired = super::texels::repair_texture(&mut t);
    Ok(DecodedTexture {
        texture: t,
        channels,
        repaired,
    })
}

#[cfg(test)]
#[path = "tests/rough_materials.rs"]
mod rough_tests;
