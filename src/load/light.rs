//! Lights: the checks of each `lights` entry and the build step that turns
//! them into runtime [`Light`]s. An area light is also a shape in the
//! scene's BVH (camera rays see it), so it adds its quad to the shapes.

use super::build::BuildContext;
use super::validate::Checker;
use crate::desc::LightDesc;
use crate::diagnostic::{Problem, suggest};
use crate::geometry::{Quad, Shape};
use crate::lights::{Light, PointLight, QuadLight, SpotLight};
use glam::Vec3A;

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
}

/// Adds the runtime light of `l` (and the quad of an area light) to `ctx`.
pub(super) fn build_light(ctx: &mut BuildContext, l: &LightDesc) {
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
        LightDesc::Quad {
            corner,
            edge_u,
            edge_v,
            radiance,
            material,
        } => {
            let q = QuadLight::new(
                (*corner).into(),
                (*edge_u).into(),
                (*edge_v).into(),
                (*radiance).into(),
            );
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
            let q = QuadLight::new(c - u - v, 2.0 * u, 2.0 * v, (*radiance).into());
            let m = surface(ctx, material);
            push_quad_light(ctx, m, q);
        }
    }
}

fn push_quad_light(ctx: &mut BuildContext, material: u32, q: QuadLight) {
    let id = ctx.lights.len() as u32;
    ctx.shapes
        .push(Shape::Quad(Quad::new(q.corner, q.u, q.v, material, id)));
    ctx.lights.push(Light::Quad(q));
}
