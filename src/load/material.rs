//! Materials: the checks of each `materials` entry and of its colour
//! parameters, and the build step that turns descriptions into runtime
//! [`Material`]s, decoding each image texture once (a file used by several
//! materials is read once). The models themselves live in `materials/`.

use super::validate::Checker;
use crate::desc::{ColorDesc, DielectricFresnelDesc, DistributionDesc, FresnelDesc, MaterialDesc, MetalDesc};
use crate::diagnostic::Problem;
use crate::materials::{ColorTex, DielectricFresnel, Distribution, Fresnel, Material, Metal, Texture};
use crate::materials::{Microfacet, RoughCoat};
use std::collections::{BTreeMap, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

impl Checker {
    /// A colour parameter: constants are range-checked; an image texture
    /// must name an existing file (it is decoded by the build step).
    pub(super) fn color_param(&mut self, path: &str, c: &ColorDesc, upper: Option<f32>) {
        match c {
            ColorDesc::Rgb(c) => self.color(path, c, upper),
            ColorDesc::Image(f) => self.file(path, f, "texture"),
            ColorDesc::Checker { a, b, scale } => {
                self.color(&format!("{path}.a"), a, upper);
                self.color(&format!("{path}.b"), b, upper);
                if !(*scale > 0.0 && scale.is_finite()) {
                    self.push(
                        &format!("{path}.scale"),
                        format!("checker scale {scale} must be > 0"),
                        "it is the number of squares per UV unit",
                    );
                }
            }
        }
    }

    pub(super) fn material(&mut self, path: &str, m: &MaterialDesc) {
        let p = |f: &str| format!("{path}.{f}");
        match m {
            MaterialDesc::Lambert { albedo } => self.color_param(&p("albedo"), albedo, Some(1.0)),
            MaterialDesc::OrenNayar { albedo, sigma } => {
                self.color_param(&p("albedo"), albedo, Some(1.0));
                self.range(
                    &p("sigma"),
                    *sigma,
                    0.0,
                    2.0,
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
            } => self.phong_lobes(path, diffuse, specular, *exponent),
            MaterialDesc::CookTorrance {
                roughness, fresnel, ..
            } => {
                self.range(
                    &p("roughness"),
                    *roughness,
                    0.0,
                    1.0,
                    "roughness",
                    "0 is polished, 1 is very rough (α = roughness²)",
                );
                self.fresnel(&p("fresnel"), fresnel);
            }
            MaterialDesc::MetalPlastic {
                base_color,
                roughness,
                metalness,
            } => {
                self.color_param(&p("base_color"), base_color, Some(1.0));
                self.range(
                    &p("roughness"),
                    *roughness,
                    0.0,
                    1.0,
                    "roughness",
                    "0 is polished, 1 is very rough",
                );
                self.range(
                    &p("metalness"),
                    *metalness,
                    0.0,
                    1.0,
                    "metalness",
                    "0 is plastic, 1 is metal",
                );
            }
            MaterialDesc::Mirror { tint } => self.color_param(&p("tint"), tint, Some(1.0)),
            MaterialDesc::Glass { ior, tint, .. } => {
                self.color_param(&p("tint"), tint, Some(1.0));
                if !(*ior > 0.0 && ior.is_finite() && *ior <= 10.0) {
                    self.push(
                        &p("ior"),
                        format!("index of refraction {ior} is outside (0, 10]"),
                        "glass is about 1.5, water 1.33, diamond 2.42",
                    );
                }
            }
            MaterialDesc::RoughPlastic {
                diffuse,
                specular,
                roughness,
                ior,
                ..
            } => self.rough_plastic(path, diffuse, specular, *roughness, *ior),
            MaterialDesc::RoughGlass {
                ior, tint, roughness, ..
            } => self.rough_glass(path, *ior, tint, *roughness),
        }
    }

    /// `RoughPlastic`: base and coat colours, coat roughness and index.
    fn rough_plastic(
        &mut self,
        path: &str,
        diffuse: &ColorDesc,
        specular: &ColorDesc,
        roughness: f32,
        ior: f32,
    ) {
        self.color_param(&format!("{path}.diffuse"), diffuse, Some(1.0));
        self.color_param(&format!("{path}.specular"), specular, Some(1.0));
        self.microfacet_roughness(&format!("{path}.roughness"), roughness);
        self.coat_ior(
            &format!("{path}.ior"),
            ior,
            "a plastic coat is about 1.5 (polypropylene 1.49)",
        );
    }

    /// `RoughGlass`: tint, roughness, and an index that differs from 1 (a
    /// rough boundary between equal indices would be a delta lobe).
    fn rough_glass(&mut self, path: &str, ior: f32, tint: &ColorDesc, roughness: f32) {
        self.color_param(&format!("{path}.tint"), tint, Some(1.0));
        self.microfacet_roughness(&format!("{path}.roughness"), roughness);
        self.coat_ior(
            &format!("{path}.ior"),
            ior,
            "glass is about 1.5, water 1.33, diamond 2.42",
        );
        if ior == 1.0 {
            self.push(
                &format!("{path}.ior"),
                "a rough boundary with index of refraction 1 does not scatter",
                "light would pass straight through; use an ior other than 1",
            );
        }
    }

    /// Roughness in [0, 1], α = roughness², as for `CookTorrance`.
    fn microfacet_roughness(&mut self, path: &str, roughness: f32) {
        let help = "0 is polished, 1 is very rough (α = roughness²: Mitsuba's alpha a is roughness √a)";
        self.range(path, roughness, 0.0, 1.0, "roughness", help);
    }

    /// A dielectric's relative index of refraction, in (0, 10].
    fn coat_ior(&mut self, path: &str, ior: f32, help: &str) {
        if !(ior > 0.0 && ior.is_finite() && ior <= 10.0) {
            self.push(
                path,
                format!("index of refraction {ior} is outside (0, 10]"),
                help,
            );
        }
    }

    /// The diffuse and specular lobes shared by `Phong` and `BlinnPhong`.
    fn phong_lobes(&mut self, path: &str, diffuse: &ColorDesc, specular: &ColorDesc, exponent: f32) {
        let p = |f: &str| format!("{path}.{f}");
        self.color_param(&p("diffuse"), diffuse, Some(1.0));
        self.color_param(&p("specular"), specular, Some(1.0));
        self.range(
            &p("exponent"),
            exponent,
            0.0,
            100_000.0,
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
    /// Decoded image textures, indexed by [`ColorTex::Image`].
    pub textures: Vec<Texture>,
    /// Index in `materials` of each scene material name.
    pub index: HashMap<String, u32>,
    /// Image files read, for watch mode.
    pub files: Vec<PathBuf>,
}

/// Builds every entry of the scene's `materials`, resolving texture files against
/// `base` (the scene file's folder) and decoding each file once. All texture problems
/// come back together.
pub fn build_materials(
    descs: &BTreeMap<String, MaterialDesc>,
    base: &Path,
) -> Result<Materials, Vec<Problem>> {
    let mut b = Builder {
        base,
        textures: Vec::new(),
        by_path: HashMap::new(),
        problems: Vec::new(),
        coats: Vec::new(),
    };
    let mut materials = Vec::new();
    let mut index = HashMap::new();
    for (name, m) in descs {
        index.insert(name.clone(), materials.len() as u32);
        let mat = build_material(&mut b, name, m);
        materials.push(mat);
    }
    if !b.problems.is_empty() {
        return Err(b.problems);
    }
    let files = b.by_path.keys().cloned().collect();
    Ok(Materials {
        materials,
        textures: b.textures,
        index,
        files,
    })
}

/// The runtime material of entry `name`; its textures are read through `b`.
fn build_material(b: &mut Builder, name: &str, m: &MaterialDesc) -> Material {
    let p = |field: &str| format!("materials.{name}.{field}");
    match m {
        MaterialDesc::Lambert { albedo } => Material::Lambert {
            albedo: b.color(albedo, &p("albedo")),
        },
        MaterialDesc::OrenNayar { albedo, sigma } => Material::OrenNayar {
            albedo: b.color(albedo, &p("albedo")),
            sigma: *sigma,
        },
        MaterialDesc::Phong {
            diffuse,
            specular,
            exponent,
        } => Material::Phong {
            kd: b.color(diffuse, &p("diffuse")),
            ks: b.color(specular, &p("specular")),
            exponent: *exponent,
        },
        MaterialDesc::BlinnPhong {
            diffuse,
            specular,
            exponent,
        } => Material::BlinnPhong {
            kd: b.color(diffuse, &p("diffuse")),
            ks: b.color(specular, &p("specular")),
            exponent: *exponent,
        },
        MaterialDesc::CookTorrance {
            distribution,
            roughness,
            fresnel,
        } => Material::CookTorrance {
            distribution: match distribution {
                DistributionDesc::Ggx => Distribution::Ggx,
                DistributionDesc::Beckmann => Distribution::Beckmann,
            },
            roughness: *roughness,
            fresnel: match fresnel {
                FresnelDesc::Conductor { eta, k } => Fresnel::Conductor {
                    eta: (*eta).into(),
                    k: (*k).into(),
                },
                FresnelDesc::Metal(m) => metal(*m).fresnel(),
                FresnelDesc::Schlick { f0 } => Fresnel::Schlick { f0: (*f0).into() },
            },
        },
        MaterialDesc::MetalPlastic {
            base_color,
            roughness,
            metalness,
        } => Material::MetalPlastic {
            base_color: b.color(base_color, &p("base_color")),
            roughness: *roughness,
            metalness: *metalness,
        },
        MaterialDesc::Mirror { tint } => Material::Mirror {
            tint: b.color(tint, &p("tint")),
        },
        MaterialDesc::Glass { ior, tint, fresnel } => Material::Glass {
            ior: *ior,
            tint: b.color(tint, &p("tint")),
            fresnel: match fresnel {
                DielectricFresnelDesc::Exact => DielectricFresnel::Exact,
                DielectricFresnelDesc::Schlick => DielectricFresnel::Schlick,
            },
        },
        MaterialDesc::RoughPlastic {
            diffuse,
            specular,
            distribution,
            roughness,
            ior,
        } => Material::RoughPlastic {
            diffuse: b.color(diffuse, &p("diffuse")),
            specular: b.color(specular, &p("specular")),
            coat: b.coat(
                Microfacet::from_roughness(distribution_of(*distribution), *roughness),
                *ior,
            ),
        },
        MaterialDesc::RoughGlass {
            ior,
            tint,
            distribution,
            roughness,
        } => Material::RoughGlass {
            distribution: distribution_of(*distribution),
            roughness: *roughness,
            ior: *ior,
            tint: b.color(tint, &p("tint")),
        },
    }
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

struct Builder<'a> {
    base: &'a Path,
    textures: Vec<Texture>,
    by_path: HashMap<PathBuf, u32>,
    problems: Vec<Problem>,
    /// Rough-plastic coats built so far: their tables cost ~0.1 s each, and
    /// materials differing only in colour share one.
    coats: Vec<Arc<RoughCoat>>,
}

impl Builder<'_> {
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

    fn color(&mut self, c: &ColorDesc, path: &str) -> ColorTex {
        match c {
            ColorDesc::Rgb(c) => ColorTex::Const((*c).into()),
            ColorDesc::Checker { a, b, scale } => ColorTex::Checker {
                a: (*a).into(),
                b: (*b).into(),
                scale: *scale,
            },
            ColorDesc::Image(file) => {
                // Keyed by the file itself, not its spelling: `x.png` and
                // `./x.png` are decoded once.
                let full = self.base.join(file);
                let full = std::fs::canonicalize(&full).unwrap_or(full);
                if let Some(&i) = self.by_path.get(&full) {
                    return ColorTex::Image(i);
                }
                match load_texture(&full) {
                    Ok(t) => {
                        let i = self.textures.len() as u32;
                        self.textures.push(t);
                        self.by_path.insert(full, i);
                        ColorTex::Image(i)
                    }
                    Err(msg) => {
                        self.problems.push(Problem::new(path, msg).help(format!(
                            "the path resolves to {} (relative to the scene file's folder)",
                            full.display()
                        )));
                        ColorTex::Const(crate::math::Rgb::ZERO)
                    }
                }
            }
        }
    }
}

/// Decodes an 8-bit image as sRGB-encoded colour.
pub fn load_texture(path: &Path) -> Result<Texture, String> {
    let img = crate::imageio::read::decode_texture(path).map_err(|e| format!("texture: {e}"))?;
    let rgb = img.to_rgb8();
    Texture::try_from_srgb8(rgb.width(), rgb.height(), rgb.as_raw())
        .map_err(|e| format!("texture {}: {e}", path.display()))
}

#[cfg(test)]
#[path = "tests/rough_materials.rs"]
mod rough_tests;
