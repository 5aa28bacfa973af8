//! The integrator: its checks and the runtime [`Integrator`] it builds.

use super::validate::{Checker, MAX_DEPTH, MAX_LIGHT_SAMPLES, MAX_RR_DEPTH, MAX_SPLITS};
use crate::desc::{CausticsDesc, IntegratorDesc};
use crate::integrators::{Direct, Integrator, Path as PathTracer, Whitted};

impl Checker {
    pub(super) fn integrator(&mut self, i: &IntegratorDesc) {
        let samples = |v: &mut Self, n: u32| {
            if n == 0 || n > MAX_LIGHT_SAMPLES {
                v.push(
                    "integrator.light_samples",
                    format!("{n} light samples is outside 1..={MAX_LIGHT_SAMPLES}"),
                    "use 1–64 shadow rays per area light",
                );
            }
        };
        match i {
            IntegratorDesc::Direct { light_samples } => samples(self, *light_samples),
            IntegratorDesc::Whitted {
                max_depth,
                light_samples,
            } => {
                samples(self, *light_samples);
                if *max_depth > MAX_DEPTH {
                    self.push(
                        "integrator.max_depth",
                        format!("max_depth {max_depth} is above {MAX_DEPTH}"),
                        "a handful of specular bounces is enough; 5 is typical",
                    );
                }
            }
            IntegratorDesc::Path {
                max_depth,
                rr_depth,
                splits,
                ..
            } => {
                if *splits == 0 || *splits > MAX_SPLITS {
                    self.push(
                        "integrator.splits",
                        format!("{splits} paths per camera sample is outside 1..={MAX_SPLITS}"),
                        "1 (the default) traces one path per camera sample; 2 suits rooms lit mostly indirectly",
                    );
                }
                if *max_depth == 0 || *max_depth < -1 {
                    self.push(
                        "integrator.max_depth",
                        format!("max_depth {max_depth} is neither −1 nor ≥ 1"),
                        "it counts path segments: 1 = emitters only, 2 = direct lighting, 8 is typical, −1 = unlimited",
                    );
                }
                if *rr_depth > MAX_RR_DEPTH {
                    self.push(
                        "integrator.rr_depth",
                        format!("rr_depth {rr_depth} is above {MAX_RR_DEPTH}"),
                        "Russian roulette is what ends long paths cheaply; 5 is typical",
                    );
                }
            }
        }
    }
}

/// The integrator of a checked scene. `split_caustics` starts false: the
/// frame's plan decides whether a light tracer takes the caustics.
pub(super) fn build_integrator(i: &IntegratorDesc) -> Integrator {
    match *i {
        IntegratorDesc::Direct { light_samples } => Integrator::Direct(Direct { light_samples }),
        IntegratorDesc::Whitted {
            max_depth,
            light_samples,
        } => Integrator::Whitted(Whitted {
            max_depth,
            light_samples,
        }),
        IntegratorDesc::Path {
            max_depth,
            rr_depth,
            caustics,
            splits,
            ..
        } => Integrator::Path(PathTracer {
            max_depth: u32::try_from(max_depth).unwrap_or(u32::MAX),
            rr_depth,
            light_trace_caustics: caustics == CausticsDesc::LightTracing,
            split_caustics: false,
            splits: splits.clamp(1, MAX_SPLITS),
        }),
    }
}
