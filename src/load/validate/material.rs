//! Material and colour-parameter checks.

use super::Checker;
use crate::desc::{ColorDesc, FresnelDesc, MaterialDesc};

impl Checker {
    /// A colour parameter: constants are range-checked; textures are
    /// checked when they are loaded (build).
    pub(super) fn color_param(&mut self, path: &str, c: &ColorDesc, upper: Option<f32>) {
        match c {
            ColorDesc::Rgb(c) => self.color(path, c, upper),
            ColorDesc::Image(f) if f.trim().is_empty() => self.push(
                path,
                "empty texture path",
                "give an image file (PNG, JPEG) relative to the scene file",
            ),
            ColorDesc::Image(_) => {}
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

    pub(super) fn range(&mut self, path: &str, x: f32, lo: f32, hi: f32, what: &str, help: &str) {
        if !(x >= lo && x <= hi) {
            self.push(path, format!("{what} {x} is outside [{lo}, {hi}]"), help);
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
            } => {
                self.color_param(&p("diffuse"), diffuse, Some(1.0));
                self.color_param(&p("specular"), specular, Some(1.0));
                self.range(
                    &p("exponent"),
                    *exponent,
                    0.0,
                    100_000.0,
                    "exponent",
                    "the lobe sharpness: 1 is broad, 1000 is nearly a mirror",
                );
                if let (ColorDesc::Rgb(d), ColorDesc::Rgb(s)) = (diffuse, specular)
                    && d.iter().zip(s).any(|(a, b)| a + b > 1.0 + 1e-6)
                {
                    self.push(&p("specular"), format!("diffuse {d:?} + specular {s:?} exceeds 1 in a channel"), "keep diffuse + specular ≤ 1 per channel so the surface reflects no more light than it receives");
                }
            }
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
                match fresnel {
                    FresnelDesc::Conductor { eta, k } => {
                        self.color(&p("fresnel.eta"), eta, None);
                        self.color(&p("fresnel.k"), k, None);
                        if eta.contains(&0.0) {
                            self.push(
                                &p("fresnel.eta"),
                                "a conductor's η must be > 0",
                                "use a preset such as `Metal(Gold)`",
                            );
                        }
                    }
                    FresnelDesc::Schlick { f0 } => self.color(&p("fresnel.f0"), f0, Some(1.0)),
                    FresnelDesc::Metal(_) => {}
                }
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
        }
    }
}
