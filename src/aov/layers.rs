//! The AOV layers of one frame, per pixel, before they are written.

use super::AovSet;
use crate::math::Rgb;
use glam::Vec3A;

/// Every first-hit layer of a frame (all are computed: the pass is one
/// intersection per sample), and which of them the film asked to write.
#[derive(Clone, Debug, PartialEq)]
pub struct AovLayers {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The layers `film.aovs` asks to write (the denoiser reads albedo and
    /// normal whatever this says).
    pub written: AovSet,
    /// Mean albedo over the pixel's samples, a miss counting as 0; row-major.
    pub albedo: Vec<Rgb>,
    /// Mean unit shading normal facing the camera, a miss counting as 0 (Open
    /// Image Denoise's "no surface"), so shorter than 1 on silhouettes.
    pub normal: Vec<Vec3A>,
    /// Mean distance along the camera ray over the samples that hit
    /// something; +∞ where none does.
    pub depth: Vec<f32>,
    /// Mean world-space hit point over the samples that hit something; 0
    /// where none does (tell those pixels by their infinite depth).
    pub position: Vec<Vec3A>,
    /// 1 + the material index most of the pixel's samples hit (ties go to
    /// the smaller id), 0 when most samples hit nothing: averaging ids would
    /// make ids that exist nowhere.
    pub material_id: Vec<u32>,
    /// 1 + the index in `objects` of the object most of the pixel's samples
    /// hit (area lights after the objects, see [`crate::scene::Scene::objects`]),
    /// 0 when most samples hit nothing; ties as for `material_id`.
    pub object_id: Vec<u32>,
    /// Mean first-hit emission, filter weight included, over all the pixel's
    /// samples: exactly what the beauty pass adds for the emitters and sky
    /// its camera rays see (every integrator counts those fully). Never
    /// written; the denoiser leaves it out and adds it back, since it holds no
    /// Monte Carlo noise and OIDN shifts a bright light's colour by ~1%.
    pub emission: Vec<Rgb>,
    /// Whether albedo and normal vary within a pixel only with where its
    /// samples land (a pinhole camera: no lens sample moves the first hit),
    /// so they hold no noise, only anti-aliasing: Open Image Denoise's
    /// `cleanAux`, which keeps edges sharper.
    pub aux_noise_free: bool,
}
