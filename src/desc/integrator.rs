//! The integrator a scene file describes: how light transport is
//! estimated.

use serde::{Deserialize, Serialize};

/// How light transport is estimated.
#[derive(Clone, Debug, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
#[serde(deny_unknown_fields)]
pub enum IntegratorDesc {
    /// Emission plus one bounce of light: hard shadows from point lights,
    /// soft shadows from area lights with `light_samples` shadow rays per
    /// area light per camera sample.
    Direct {
        /// Shadow rays per area light per camera sample, 1 to 4096 (default 1): more
        /// gives smoother soft shadows at proportional cost.
        #[serde(default = "one")]
        #[schemars(range(min = 1, max = 4096))]
        light_samples: u32,
    },
    /// Direct lighting at diffuse and glossy surfaces, perfect reflection and
    /// refraction at mirrors and glass, up to `max_depth` specular bounces.
    Whitted {
        /// Most specular bounces (mirror reflections and glass refractions) followed
        /// from a camera ray, at most 64 (default 5).
        #[serde(default = "whitted_depth")]
        #[schemars(range(min = 0, max = 64))]
        max_depth: u32,
        /// Shadow rays per area light at each diffuse or glossy hit, 1 to 4096
        /// (default 1).
        #[serde(default = "one")]
        #[schemars(range(min = 1, max = 4096))]
        light_samples: u32,
    },
    /// Path tracing with next-event estimation and MIS. `max_depth` counts
    /// path segments as Mitsuba does (2 = direct lighting only); −1 means
    /// unlimited. Russian roulette starts after `rr_depth` segments.
    Path {
        /// Longest path in segments (default 8): 1 sees only emitters, 2 is direct
        /// lighting, −1 is unlimited (Russian roulette still ends paths).
        #[serde(default = "path_depth")]
        #[schemars(range(min = -1))]
        max_depth: i32,
        /// Path segments before Russian roulette may end a path (default 5); lower is
        /// faster and noisier, never biased.
        #[serde(default = "rr_depth")]
        #[schemars(range(min = 0, max = 1024))]
        rr_depth: u32,
        /// How the light for next-event estimation is chosen.
        #[serde(default)]
        light_selection: LightSelectionDesc,
        /// How caustics seen directly (light focused onto a surface by perfect
        /// mirrors and smooth glass) are found (default `LightTracing`).
        #[serde(default)]
        caustics: CausticsDesc,
        /// Paths per camera sample, 1 to 16 (default 1, one path per camera
        /// sample, as Mitsuba traces): at its first diffuse or glossy surface a
        /// camera sample's path takes its one light sample, then goes on along
        /// this many BSDF samples, each weighted 1/splits (path splitting). The
        /// camera ray, first hit and light sample are shared, so the indirect
        /// light costs less per path; `spp` still counts camera samples.
        #[serde(default = "path_splits")]
        #[schemars(range(min = 1, max = 16))]
        splits: u32,
    },
}

/// How the path tracer finds caustics seen directly: light reaching a
/// diffuse or glossy surface the camera sees through perfect mirrors and
/// smooth glass.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq, Eq)]
pub enum CausticsDesc {
    /// Also from the light's side: a render of the whole frame traces paths
    /// from its rectangle and sphere lights toward its mirrors and glass and
    /// joins the surfaces they reach to the camera, for the caustics the
    /// camera sees directly. Far less noise there, the same image in
    /// expectation. Scenes without a perfect mirror or smooth glass surface,
    /// pinhole-less cameras, filters other than `Box`, farm pieces and watch
    /// passes render exactly as with `PathOnly`.
    #[default]
    LightTracing,
    /// Only by BSDF sampling from the camera's side (Mitsuba's `path`).
    PathOnly,
}

/// How next-event estimation picks the one light it samples at each path
/// vertex.
#[derive(Clone, Copy, Debug, Default, Deserialize, Serialize, schemars::JsonSchema, PartialEq)]
pub enum LightSelectionDesc {
    /// In proportion to emitted power.
    Power,
    /// Every light equally likely.
    Uniform,
    /// By a light tree: in proportion to what each light can send to the
    /// shading point (its irradiance there from its intensity, distance,
    /// extent and orientation), so scenes of many lights spend their shadow
    /// rays on the near ones that face the point. The sky is weighed by
    /// what it sends to the point that BSDF sampling would not find alone
    /// (all of a small sun's irradiance, none of a constant sky's), not by
    /// its power through the scene, and a tenth of the picks stay uniform
    /// over all lights, so no light is starved where the estimate is wrong.
    /// With one light of finite extent and no sky it is `Power`: there is
    /// nothing to choose.
    #[default]
    Tree,
}

fn one() -> u32 {
    1
}
fn whitted_depth() -> u32 {
    5
}
fn path_depth() -> i32 {
    8
}
fn rr_depth() -> u32 {
    5
}
fn path_splits() -> u32 {
    1
}

impl Default for IntegratorDesc {
    fn default() -> Self {
        IntegratorDesc::Direct { light_samples: 1 }
    }
}
