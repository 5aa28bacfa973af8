//! What [`crate::frame::render`] needs beside the [`crate::scene::Scene`]:
//! the camera, the film, the integrator and where the image goes. Kept apart
//! from the scene so that integrators, geometry and lights see only what rays
//! query, and one scene can be rendered through several views.

use crate::camera::Camera;
use crate::camera::motion::CameraMotion;
use crate::film::{Adaptive, Filter};
use crate::imageio::Display;
use crate::integrators::Integrator;
use crate::math::Ray;
use crate::sampler::{Sampler, SamplerKind};
use std::path::PathBuf;

/// Image size and sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Film {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel.
    pub spp: u32,
    /// Seed of every random stream: same seed, same image.
    pub seed: u64,
    /// How sample positions are drawn.
    pub sampler: SamplerKind,
    /// Layers written beside the beauty pass (`film.aovs`); EXR only.
    pub aovs: AovSet,
    /// Run the denoiser on the image before writing it (`film.denoise`).
    pub denoise: bool,
    /// Adaptive sampling (`film.noise_threshold` above 0): when a pixel
    /// may stop before `spp` samples.
    pub adaptive: Option<Adaptive>,
    /// How the samples are spread over the pixels (`film.allocation`).
    pub allocation: Allocation,
}

/// How a render's `spp × pixels` samples are spread over its pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Allocation {
    /// `spp` in every pixel.
    Even,
    /// Half everywhere, the rest by the noise the first half saw around
    /// each pixel (`crate::film::allocation`); renders of fewer than 32
    /// spp, adaptive or `Stratified` ones and pieces spread evenly.
    #[default]
    ByNoise,
}

/// Camera, film, integrator and output of one render.
#[derive(Clone, Debug)]
pub struct View {
    /// The camera, in world space.
    pub camera: Camera,
    /// Image size and sampling.
    pub film: Film,
    /// Where each camera sample lands around its pixel, and its weight.
    pub filter: Filter,
    /// Exposure, tone map and bit depth of PNG outputs (and the watch page).
    pub display: Display,
    /// The light-transport estimator.
    pub integrator: Integrator,
    /// The scene's `film.output`, resolved against the scene file's folder;
    /// empty when the scene names none.
    pub output: PathBuf,
    /// When something moves while the shutter is open: the interval each
    /// camera sample draws its time in. `None` for a still frame.
    pub shutter: Option<Shutter>,
}

/// The shutter of a frame in which something moves.
#[derive(Clone, Debug)]
pub struct Shutter {
    /// Opening and closing times, in frames (absolute: frame + the
    /// camera's `shutter`).
    pub open: f32,
    /// See `open`.
    pub close: f32,
    /// The camera's keys, when the camera itself moves.
    pub camera: Option<Box<CameraMotion>>,
}

impl View {
    /// The camera ray of one sample of pixel `(x, y)` and the sample's
    /// filter weight: its place in the pixel drawn from the filter (`Box`:
    /// the sampler's two numbers themselves), then the lens. The beauty pass
    /// and the AOV pass both draw here, so the layers see the beauty's rays.
    #[inline(always)]
    pub fn camera_ray(&self, x: u32, y: u32, sampler: &mut Sampler) -> (Ray, f32) {
        let (w, h) = (self.film.width as f32, self.film.height as f32);
        let (offset, weight) = self.filter.sample(sampler.next_vec2());
        let film_pos = glam::Vec2::new((x as f32 + offset.x) / w, (y as f32 + offset.y) / h);
        if let Some(s) = &self.shutter {
            return (moving_ray(&self.camera, s, film_pos, w / h, sampler), weight);
        }
        (self.camera.ray(film_pos, w / h, sampler.next_vec2()), weight)
    }
}

/// The camera ray of a sample of a frame with motion: its time drawn in the
/// shutter ([`Sampler::time`]) and set on this thread's clock for the
/// moving instances, then the camera at that time.
#[inline(never)]
fn moving_ray(still: &Camera, s: &Shutter, film_pos: glam::Vec2, aspect: f32, sampler: &mut Sampler) -> Ray {
    let t = s.open + (s.close - s.open) * sampler.time();
    crate::anim::clock::set(t);
    let camera = s.camera.as_ref().map_or(*still, |c| c.at(t));
    camera.ray(film_pos, aspect, sampler.next_vec2())
}

/// One AOV layer, as `film.aovs` lists them; written beside the beauty
/// pass by `crate::aov`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aov {
    /// Reflectance at the first hit, in [0, 1] (`albedo.R/G/B`).
    Albedo,
    /// World-space shading normal facing the camera (`N.X/Y/Z`).
    Normal,
    /// Distance along the camera ray to the first hit (`Z`).
    Depth,
    /// World-space first-hit position (`P.X/Y/Z`).
    Position,
    /// 1 + the first hit's material index, 0 for no surface (`materialId`).
    MaterialIndex,
    /// 1 + the first hit's object index, 0 for no surface (`objectId`).
    ObjectIndex,
}

impl Aov {
    /// Every layer, in the order `docs/aov.md` lists them.
    pub const ALL: [Aov; 6] = [
        Aov::Albedo,
        Aov::Normal,
        Aov::Depth,
        Aov::Position,
        Aov::MaterialIndex,
        Aov::ObjectIndex,
    ];

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of layers, small and `Copy` so that [`crate::view::Film`] stays so.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AovSet(u8);

impl AovSet {
    /// No layers: the beauty pass only.
    pub const EMPTY: AovSet = AovSet(0);

    /// This set with `aov` added.
    pub fn with(self, aov: Aov) -> Self {
        AovSet(self.0 | aov.bit())
    }

    /// Whether `aov` is in the set.
    pub fn contains(self, aov: Aov) -> bool {
        self.0 & aov.bit() != 0
    }

    /// Whether no layer is asked for.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The layers in the set, in [`Aov::ALL`] order.
    pub fn iter(self) -> impl Iterator<Item = Aov> {
        Aov::ALL.into_iter().filter(move |a| self.contains(*a))
    }
}

impl FromIterator<Aov> for AovSet {
    fn from_iter<I: IntoIterator<Item = Aov>>(iter: I) -> Self {
        iter.into_iter().fold(AovSet::EMPTY, AovSet::with)
    }
}
