//! The plan of one frame, made once from the view and a [`Request`] before
//! anything renders: which pixels and samples, how the samples are spread
//! ([`Sampling`]), whether the caustic light tracer runs, which AOV layers
//! and whether to denoise. The tile loop, the writer, the CLI, watch mode and
//! the farm read it; none of them decides these again.
//!
//! A part of the samples is added to other parts' exact sums, which needs
//! counts fixed before any piece renders: only a whole frame is adaptive
//! (a pixel's count depends on its own samples) or light traced (the splats
//! land anywhere in the frame, so pieces could not add up), and only a
//! whole frame has layers or is denoised. A piece is spread by noise as the
//! whole frame is: it renders the frame's first pass itself, which fixes
//! every pixel's count, so its sums add up to the whole render's bytes.
//! Watch passes spread evenly.

use crate::camera::Projection;
use crate::film::{Adaptive, FilterKind, Spread};
use crate::imageio::PixelRect;
use crate::integrators::{Integrator, caustic};
use crate::sampler::SamplerKind;
use crate::scene::Scene;
use crate::view::{Allocation, AovSet, View};

/// What part of a frame to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Request {
    /// Every pixel, every sample: an image of means.
    Whole,
    /// Samples `samples.0..samples.1` of the pixels in `rect` (a farm piece,
    /// or a sample split): exact sums, to be added to other pieces' sums.
    Piece {
        /// The pixels, inside the film.
        rect: PixelRect,
        /// First sample and one past the last.
        samples: (u32, u32),
    },
    /// Watch mode's pass `k` (0-based) of [`pass_targets`]: the samples from
    /// the previous pass's target to this one's, of every pixel.
    Pass {
        /// Which pass.
        k: usize,
    },
}

/// Cumulative sample counts after each watch pass: 1, 2, 4, … and finally
/// `spp`, so a first image comes quickly and no sample is rendered twice.
pub fn pass_targets(spp: u32) -> Vec<u32> {
    let mut targets: Vec<u32> = std::iter::successors(Some(1u32), |&n| n.checked_mul(2))
        .take_while(|&n| n < spp)
        .collect();
    targets.push(spp.max(1));
    targets
}

/// How samples are spread over the pixels: the sampling policy the tile
/// loop runs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Sampling {
    /// Samples `first..first + count` of every pixel.
    Even {
        /// The first sample.
        first: u32,
        /// How many.
        count: u32,
    },
    /// Up to `spp` samples a pixel, each pixel stopping once its noise is
    /// below the threshold (`film.noise_threshold`).
    Adaptive(Adaptive),
    /// Two passes: part everywhere, the rest by the noise the first saw
    /// (`film.allocation: ByNoise`).
    Spread(Spread),
}

/// The caustic light-tracing pass of a whole frame ([`super::caustics`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LightTrace {
    /// Light paths to trace.
    pub paths: u64,
    /// The longest specular chain they follow.
    pub max_chain: u32,
    /// The path tracer's depth (segments from the camera; `u32::MAX`:
    /// unlimited), which bounds a delta light's paths past their first
    /// surface (`caustic::bounce`).
    pub max_depth: u32,
}

/// A frame's plan: see the module doc.
#[derive(Clone, Copy, Debug)]
pub struct Plan {
    /// What was asked for.
    pub request: Request,
    /// The pixels rendered.
    pub rect: PixelRect,
    /// The whole frame's pixels.
    pub frame: PixelRect,
    /// Samples `samples.0..samples.1` of each pixel (at most, when adaptive
    /// or spread).
    pub samples: (u32, u32),
    /// How the samples are spread.
    pub sampling: Sampling,
    /// The caustic light-tracing pass, when it runs.
    pub light_trace: Option<LightTrace>,
    /// The integrator as the tiles run it: the view's, told whether the
    /// light tracer takes its caustics. Decided here so that the tile loop
    /// never changes it.
    pub integrator: Integrator,
    /// AOV layers written beside the beauty pass.
    pub layers: AovSet,
    /// Whether the beauty pass is denoised before it is written.
    pub denoise: bool,
    /// True when the scene asks for adaptive sampling and this request
    /// cannot have it (a piece or a pass): worth a note.
    pub adaptive_ignored: bool,
    /// True when a whole frame would light trace its caustics and this
    /// piece path traces them: the assembled frame is not `render`'s bytes.
    pub light_trace_skipped: bool,
    /// True when the skipped light tracing would have drawn a point, spot or directional
    /// light's caustics, which the path tracer cannot find.
    pub point_caustics_skipped: bool,
}

/// A request the view cannot honour.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PlanError {
    /// Layers or denoising asked of a piece.
    #[error(
        "AOV layers and denoising need the whole frame (pieces carry only the beauty pass's sums); render without --crop, --pixels, --tile and --samples"
    )]
    LayersNeedWholeFrame,
    /// Denoising asked of a build without the denoiser.
    #[error("--denoise: {}; {}", crate::denoise::NOT_BUILT, crate::denoise::HOW_TO_ENABLE)]
    DenoiserNotBuilt,
    /// A piece outside the film, or a sample range outside `0..spp`.
    #[error("pixels {rect} and samples {}..{} are not inside a {width}×{height}, {spp} spp frame", samples.0, samples.1)]
    OutsideFrame {
        /// The pixels asked for.
        rect: PixelRect,
        /// The samples asked for.
        samples: (u32, u32),
        /// The film's width.
        width: u32,
        /// The film's height.
        height: u32,
        /// The film's samples per pixel.
        spp: u32,
    },
}

impl Plan {
    /// The plan of a whole frame: layers and denoising as the film says.
    pub fn whole(scene: &Scene, view: &View) -> Plan {
        let f = view.film;
        let full = PixelRect::full(f.width, f.height);
        Self::build(scene, view, Request::Whole, full, (0, f.spp), f.denoise)
    }

    /// The plan of `request`; `denoise` adds denoising to what the film
    /// asks (`--denoise`).
    pub fn new(scene: &Scene, view: &View, request: Request, denoise: bool) -> Result<Plan, PlanError> {
        let f = view.film;
        let full = PixelRect::full(f.width, f.height);
        let (rect, samples) = match request {
            Request::Whole => (full, (0, f.spp)),
            Request::Piece { rect, samples } => (rect, samples),
            Request::Pass { k } => {
                let targets = pass_targets(f.spp);
                let end = targets.get(k).copied().unwrap_or(f.spp);
                let first = k
                    .checked_sub(1)
                    .and_then(|j| targets.get(j))
                    .copied()
                    .unwrap_or(0);
                (full, (first, end))
            }
        };
        if !full.contains(&rect) || samples.0 > samples.1 || samples.1 > f.spp {
            return Err(PlanError::OutsideFrame {
                rect,
                samples,
                width: f.width,
                height: f.height,
                spp: f.spp,
            });
        }
        if denoise && !crate::denoise::AVAILABLE {
            return Err(PlanError::DenoiserNotBuilt);
        }
        let denoise = denoise || f.denoise;
        if matches!(request, Request::Piece { .. }) && (denoise || !f.aovs.is_empty()) {
            return Err(PlanError::LayersNeedWholeFrame);
        }
        Ok(Self::build(scene, view, request, rect, samples, denoise))
    }

    fn build(
        scene: &Scene,
        view: &View,
        request: Request,
        rect: PixelRect,
        samples: (u32, u32),
        denoise: bool,
    ) -> Plan {
        let f = view.film;
        // Only a render of every sample of every pixel may vary the counts
        // or splat light paths anywhere: the others' sums must add up.
        // (A piece that happens to cover the frame is still a piece.)
        let whole = request == Request::Whole;
        let piece = matches!(request, Request::Piece { .. });
        let sampling = match (whole, piece, f.adaptive, spread(view)) {
            (true, _, Some(a), _) => Sampling::Adaptive(a),
            (true, _, None, Some(s)) | (_, true, None, Some(s)) => Sampling::Spread(s),
            _ => Sampling::Even {
                first: samples.0,
                count: samples.1 - samples.0,
            },
        };
        let traced = light_trace(scene, view);
        let light_trace = traced.filter(|_| whole);
        let integrator = match view.integrator {
            Integrator::Path(p) if light_trace.is_some() => Integrator::Path(crate::integrators::Path {
                split_caustics: true,
                ..p
            }),
            i => i,
        };
        // Layers and denoising are written only with a whole frame's image;
        // watch passes write the beauty pass alone.
        let image = whole;
        Plan {
            request,
            rect,
            frame: PixelRect::full(f.width, f.height),
            samples,
            sampling,
            light_trace,
            integrator,
            layers: if image { f.aovs } else { AovSet::EMPTY },
            denoise: image && denoise,
            adaptive_ignored: f.adaptive.is_some() && !matches!(sampling, Sampling::Adaptive(_)),
            light_trace_skipped: piece && traced.is_some(),
            point_caustics_skipped: piece
                && traced.is_some()
                && scene
                    .caustics
                    .as_ref()
                    .is_some_and(|c| c.from_points(&scene.lights)),
        }
    }

    /// What a user splitting a frame must know, as notes: where this piece
    /// differs from or costs more than its share of `render`.
    pub fn piece_notes(&self, view: &View) -> Vec<String> {
        let Request::Piece { rect, .. } = self.request else {
            return Vec::new();
        };
        let mut notes = Vec::new();
        if self.adaptive_ignored {
            notes.push(
                "film.noise_threshold is ignored for pieces: their exact sums add up across machines only when every pixel takes every sample; the assembled frame is not what `render` writes".to_string(),
            );
        }
        if self.point_caustics_skipped {
            notes.push(
                "this scene's caustics are light traced in a whole render and path traced in pieces, and the path tracer cannot find a point, spot or directional light's: the assembled frame lacks them; `integrator: Path(caustics: PathOnly)` leaves them out of whole renders too".to_string(),
            );
        } else if self.light_trace_skipped {
            notes.push(
                "this scene's caustics are light traced in a whole render and path traced in pieces: the assembled frame has the same expected value but not the bytes `render` writes".to_string(),
            );
        }
        let f = view.film;
        if let Sampling::Spread(s) = self.sampling
            && rect.area() < u64::from(f.width) * u64::from(f.height)
        {
            notes.push(format!(
                "samples are spread by noise (film.allocation: ByNoise), so this piece first renders the whole frame's first pass ({} of {} spp) to place them as `render` does; `film.allocation: Even` (or `--set film.allocation=Even`) spares each piece that pass",
                s.first, s.spp
            ));
        }
        notes
    }

    /// Whether this renders exact sums to be added up (a piece or a pass)
    /// rather than an image of means.
    pub fn keeps_sums(&self) -> bool {
        match self.request {
            Request::Whole => false,
            Request::Piece { .. } | Request::Pass { .. } => true,
        }
    }

    /// What was rendered, for the summary line: size, samples and how they
    /// were spread; `samples_taken` is the render's count.
    pub fn describe(&self, view: &View, samples_taken: u64) -> String {
        let f = view.film;
        let pixels = (u64::from(f.width) * u64::from(f.height)).max(1);
        let mean = samples_taken as f64 / pixels as f64;
        if let Request::Piece { rect, samples } = self.request {
            return format!(
                "piece: pixels {rect}, samples {}..{} of a {}×{}, {} spp frame",
                samples.0, samples.1, f.width, f.height, f.spp
            );
        }
        match self.sampling {
            Sampling::Adaptive(_) => format!(
                "{}×{}, adaptive: {mean:.1} spp on average, at most {}",
                f.width, f.height, f.spp
            ),
            Sampling::Spread(_) => format!(
                "{}×{}, {} spp spread by noise: {mean:.1} on average",
                f.width, f.height, f.spp
            ),
            Sampling::Even { .. } => format!("{}×{}, {} spp", f.width, f.height, f.spp),
        }
    }
}

/// The spread of a whole frame's samples by noise (`film.allocation:
/// ByNoise`), `None` when every pixel takes `spp`: below 32 spp, with
/// adaptive sampling, or with the `Stratified` sampler (whose strata are laid
/// out for exactly `spp`).
fn spread(view: &View) -> Option<Spread> {
    let f = view.film;
    match f.allocation {
        Allocation::ByNoise if f.adaptive.is_none() && f.sampler != SamplerKind::Stratified => {
            Spread::new(f.spp)
        }
        Allocation::ByNoise | Allocation::Even => None,
    }
}

/// Light paths per camera sample the caustic light tracer takes. Its own
/// noise is small: on `cornell_specular` (256², 128 spp, two seeds) the
/// noise off the light is 0.0387 without it and 0.0309, 0.0307, 0.0306,
/// 0.0306 with 1/32, 1/16, 1/8, 1/4 light paths a sample; 1/16 costs 4% more
/// instructions (callgrind, 64², 64 spp: 1.393 against 1.336 G), 3% more
/// rays.
pub const LIGHT_PATHS_PER_SAMPLE: f64 = 0.0625;

/// The light-tracing pass of a whole frame for caustics seen directly
/// (`integrator: Path(caustics: LightTracing)`, the default); `None` when
/// the scene has no perfect mirror or smooth glass lit by a rectangle or
/// sphere light, the camera is not a pinhole, the filter is not `Box`, or it
/// would take 2³² light paths or more.
fn light_trace(scene: &Scene, view: &View) -> Option<LightTrace> {
    let Integrator::Path(p) = view.integrator else {
        return None;
    };
    let pinhole = view.camera.projection == Projection::Perspective && view.camera.aperture_radius <= 0.0;
    if !(p.light_trace_caustics && scene.caustics.is_some() && pinhole && view.filter.kind == FilterKind::Box)
    {
        return None;
    }
    let samples = view.film.width as f64 * view.film.height as f64 * view.film.spp as f64;
    let paths = (samples * LIGHT_PATHS_PER_SAMPLE).ceil();
    // `ExactSum::mean` divides by a u32.
    (paths >= 1.0 && paths <= u32::MAX as f64).then_some(LightTrace {
        paths: paths as u64,
        max_chain: caustic::max_chain(p.max_depth),
        max_depth: p.max_depth,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_targets_double_up_to_the_scene_spp() {
        assert_eq!(pass_targets(1), vec![1]);
        assert_eq!(pass_targets(8), vec![1, 2, 4, 8]);
        assert_eq!(pass_targets(64), vec![1, 2, 4, 8, 16, 32, 64]);
        assert_eq!(pass_targets(100), vec![1, 2, 4, 8, 16, 32, 64, 100]);
        assert_eq!(pass_targets(u32::MAX).last(), Some(&u32::MAX));
    }
}
