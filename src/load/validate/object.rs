//! Light and object checks.

use super::Checker;
use crate::desc::{LightDesc, ObjectDesc, TransformDesc, V3};
use crate::diagnostic::{Problem, suggest};
use glam::Vec3;

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
                self.color(&p("intensity"), intensity, None);
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
                self.color(&p("intensity"), intensity, None);
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
            LightDesc::Quad {
                corner,
                edge_u,
                edge_v,
                radiance,
                material,
            } => {
                self.finite(&p("corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
                self.color(&p("radiance"), radiance, None);
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
                self.color(&p("radiance"), radiance, None);
                surface(self, material);
            }
        }
    }

    pub(super) fn parallelogram(&mut self, path: &str, un: &str, u: &V3, vn: &str, v: &V3) {
        if self.finite(&format!("{path}.{un}"), u)
            && self.finite(&format!("{path}.{vn}"), v)
            && Vec3::from(*u).cross(Vec3::from(*v)).length() <= 1e-12
        {
            self.push(
                &format!("{path}.{vn}"),
                format!("zero-area quad: `{un}` {u:?} and `{vn}` {v:?} are parallel or zero"),
                "give the two edges non-zero, non-parallel directions",
            );
        }
    }

    pub(super) fn object(&mut self, path: &str, o: &ObjectDesc) {
        match o {
            ObjectDesc::Sdf {
                shape,
                march,
                transform,
                ..
            } => (self.problems).extend(super::super::validate_sdf::validate_sdf(
                path, shape, march, transform,
            )),
            ObjectDesc::Sphere { center, radius, .. } => {
                self.finite(&format!("{path}.center"), center);
                if !(*radius > 0.0 && radius.is_finite()) {
                    self.push(
                        &format!("{path}.radius"),
                        format!("sphere radius {radius} must be > 0"),
                        "give a positive radius in scene units",
                    );
                }
            }
            ObjectDesc::Plane { point, normal, .. } => {
                self.finite(&format!("{path}.point"), point);
                self.nonzero(&format!("{path}.normal"), normal, "`normal`");
            }
            ObjectDesc::Quad {
                corner,
                edge_u,
                edge_v,
                ..
            } => {
                self.finite(&format!("{path}.corner"), corner);
                self.parallelogram(path, "edge_u", edge_u, "edge_v", edge_v);
            }
            ObjectDesc::Rect {
                center,
                half_u,
                half_v,
                ..
            } => {
                self.finite(&format!("{path}.center"), center);
                self.parallelogram(path, "half_u", half_u, "half_v", half_v);
            }
            ObjectDesc::Mesh { file, .. } => {
                if file.trim().is_empty() {
                    self.push(
                        &format!("{path}.file"),
                        "empty OBJ path",
                        "give the path of a .obj file, relative to the scene file",
                    );
                }
            }
            ObjectDesc::Instance { .. } => {}
        }
        for (k, t) in o.transform().iter().enumerate() {
            let tp = format!("{path}.transform[{k}]");
            match t {
                TransformDesc::Translate(v) => {
                    self.finite(&tp, v);
                }
                TransformDesc::Rotate { axis, degrees } => {
                    self.nonzero(&format!("{tp}.axis"), axis, "the rotation axis");
                    if !degrees.is_finite() {
                        self.push(
                            &format!("{tp}.degrees"),
                            "non-finite angle",
                            "use a finite angle in degrees",
                        );
                    }
                }
                TransformDesc::Scale(s) => {
                    if self.finite(&tp, s) && s.contains(&0.0) {
                        self.push(
                            &tp,
                            format!("scale {s:?} has a zero factor"),
                            "a zero scale flattens the object; use non-zero factors",
                        );
                    }
                }
                TransformDesc::Matrix(m) => {
                    let flat: Vec<f32> = m.iter().flatten().copied().collect();
                    if self.finite(&tp, &flat) && super::super::build::matrix(m).determinant().abs() < 1e-12 {
                        self.push(&tp, "matrix is singular", "a transform matrix must be invertible");
                    }
                }
            }
        }
        if let ObjectDesc::Sphere { transform, .. } = o
            && !transform.is_empty()
            && !super::super::build::is_similarity(&super::super::build::compose(transform))
        {
            self.push(
                &format!("{path}.transform"),
                "a sphere's transform must keep it round",
                "use equal scale factors on all axes (or a Mesh for an ellipsoid)",
            );
        }
    }
}
