//! `KHR_lights_punctual`: an asset's point, spot and directional lights,
//! placed by their nodes (glTF 2.0 extension,
//! <https://github.com/KhronosGroup/glTF/tree/main/extensions/2.0/Khronos/KHR_lights_punctual>).
//!
//! Units: glTF gives point and spot lights in candela (lm/sr) and
//! directional lights in lux (lm/m²); ronray's lights are radiometric (W/sr,
//! W/m² per linear-RGB channel). They are divided by 683 lm/W, the
//! luminous efficacy of 555 nm light, as Blender's glTF importer does in its
//! default ("standard") lighting mode, so an asset exported from Blender
//! comes back at the watts it was lit with. `color` multiplies each channel
//! (the extension's rule: the intensity is that of white light).
//!
//! Placement: a light sits at its node's origin and shines along its
//! node's −z, the node's world transform (posed at the frame drawn) times
//! the object's `transform`; scale changes neither intensity nor cone. A
//! spot's `innerConeAngle` and `outerConeAngle` (half-angles, radians)
//! become `Spot`'s full `cone_degrees` (twice the outer) and its
//! `falloff_degrees` (twice their difference), faded by ronray's smoothstep
//! rather than the extension's suggested ramp in cos θ. `range` (a hint
//! where the light may be cut off) is not applied: light falls off with
//! the inverse square, as the extension asks when it is absent.

use super::super::validate::MAX_RADIANCE;
use glam::{Mat4, Vec3, Vec3A};
use gltf::khr_lights_punctual::Kind;

/// Lumens per watt of 555 nm light: photometric glTF intensities over
/// this are radiometric.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// What kind of light, with its cone for a spot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PunctualKind {
    /// A point light: `emitted` is its intensity, W/sr.
    Point,
    /// A spot light: `emitted` is its intensity on the axis, W/sr; the
    /// cone as `Spot` takes it (full angle, falloff band), in degrees.
    Spot {
        /// Full opening angle, twice `outerConeAngle`.
        cone_degrees: f32,
        /// The outer band that fades, twice `outer − inner`.
        falloff_degrees: f32,
    },
    /// A directional light: `emitted` is its irradiance, W/m².
    Directional,
}

/// One of the asset's lights as placed by a node, in the asset's space.
#[derive(Clone, Copy, Debug)]
pub struct ImportedLight {
    /// The node that places it (for messages).
    pub node: usize,
    /// The node's world transform (posed), before the object's `transform`.
    pub world: Mat4,
    /// Its kind.
    pub kind: PunctualKind,
    /// Intensity (W/sr) or irradiance (W/m²) per channel.
    pub emitted: Vec3,
}

impl ImportedLight {
    /// Where it is and the way it shines (unit), in a space `to` maps the
    /// asset's into; `None` for the direction when the transform leaves
    /// none (a node scaled to nothing).
    pub fn placed(&self, to: Mat4) -> (Vec3A, Option<Vec3A>) {
        let m = to * self.world;
        let p = m.transform_point3(Vec3::ZERO);
        let d = m.transform_vector3(Vec3::NEG_Z);
        let largest = d.abs().max_element();
        let d = (largest > 0.0 && largest.is_finite())
            .then(|| (d / largest).normalize())
            .filter(|d| d.is_finite());
        (p.into(), d.map(Vec3A::from))
    }
}

/// The light `light` of the asset placed by node `node` at `world`, its
/// photometric values converted; an error naming the light when a value is
/// outside the extension's ranges or past ronray's limit.
pub fn import(
    light: &gltf::khr_lights_punctual::Light,
    node: usize,
    world: Mat4,
) -> Result<ImportedLight, String> {
    let at = format!("KHR_lights_punctual light {} (nodes[{node}])", light.index());
    let color = Vec3::from(light.color());
    let intensity = light.intensity();
    if !(color.is_finite() && color.min_element() >= 0.0) {
        return Err(format!("{at}: color {color} is not three finite numbers ≥ 0"));
    }
    if !(intensity.is_finite() && intensity >= 0.0) {
        return Err(format!("{at}: intensity {intensity} is not a finite number ≥ 0"));
    }
    let emitted = color * (intensity / LUMENS_PER_WATT);
    if !emitted.is_finite() || emitted.max_element() > MAX_RADIANCE {
        return Err(format!(
            "{at}: intensity × color is {:e} W a channel (over 683 lm/W), past the limit of {MAX_RADIANCE:e}",
            emitted.max_element()
        ));
    }
    let kind = match light.kind() {
        Kind::Point => PunctualKind::Point,
        Kind::Directional => PunctualKind::Directional,
        Kind::Spot {
            inner_cone_angle,
            outer_cone_angle,
        } => {
            // The extension: 0 ≤ inner < outer ≤ π/2. `Spot` takes full
            // angles under 180°, so a hemisphere is a hair narrower.
            if !(inner_cone_angle >= 0.0
                && inner_cone_angle < outer_cone_angle
                && outer_cone_angle <= std::f32::consts::FRAC_PI_2)
            {
                return Err(format!(
                    "{at}: spot cone angles inner {inner_cone_angle}, outer {outer_cone_angle} are not \
                     0 ≤ inner < outer ≤ π/2"
                ));
            }
            let cone_degrees = (2.0 * outer_cone_angle.to_degrees()).min(179.99);
            let inner = (2.0 * inner_cone_angle.to_degrees()).min(cone_degrees);
            PunctualKind::Spot {
                cone_degrees,
                falloff_degrees: cone_degrees - inner,
            }
        }
    };
    Ok(ImportedLight {
        node,
        world,
        kind,
        emitted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn light(world: Mat4) -> ImportedLight {
        ImportedLight {
            node: 0,
            world,
            kind: PunctualKind::Directional,
            emitted: Vec3::ONE,
        }
    }

    #[test]
    fn a_light_sits_at_its_node_and_shines_along_its_minus_z() {
        let world = Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
            * Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2);
        let (p, d) = light(world).placed(Mat4::from_scale(Vec3::splat(2.0)));
        assert!((p - Vec3A::new(2.0, 4.0, 6.0)).length() < 1e-5, "{p}");
        // −z turned a quarter turn about x points down.
        assert!((d.expect("a direction") - Vec3A::NEG_Y).length() < 1e-5);
        // Scaled to nothing: no direction.
        assert!(
            light(Mat4::from_scale(Vec3::ZERO))
                .placed(Mat4::IDENTITY)
                .1
                .is_none()
        );
        // Scaled hugely (its squared length past f32): still a unit direction.
        let (_, d) = light(Mat4::from_scale(Vec3::splat(1e18))).placed(Mat4::from_scale(Vec3::splat(1e18)));
        assert!((d.expect("a direction") - Vec3A::NEG_Z).length() < 1e-6);
    }
}
