//! Participating media: what fills the space between surfaces (fog, smoke,
//! the inside of wax), for the volumetric part of the path tracer
//! (`integrators/vol_path.rs`).
//!
//! # Units
//! Coefficients are per scene unit (1/length): a ray crossing a distance d
//! of a medium of extinction σ_t keeps exp(−σ_t d) of its radiance (per RGB
//! channel); σ_s of it is scattered per unit length, σ_a absorbed. The
//! phase function ([`HenyeyGreenstein`]) is a density over directions
//! (1/sr).
//!
//! # Where media live
//! The scene's global medium (if any) is where the camera is and fills all
//! space outside media shapes. A closed shape may hold a medium inside; its
//! outside is the global medium unless it names another one. Crossing such
//! a shape's surface into it (against its outward normal) enters the inside
//! medium, out of it enters the outside medium. A shape without a medium
//! does not change the medium a ray is in (a glass sphere in fog has fog
//! inside, as in Mitsuba). A medium shape without a material is an
//! index-matched (null) boundary: invisible to light, it only changes the
//! medium. Nested media are declared, not inferred: a shape inside another
//! medium shape names that medium as its `outside`.
//!
//! | file | holds |
//! |---|---|
//! | `homogeneous.rs` | constant coefficients: closed-form free flights and transmittance |
//! | `grid.rs` | a density grid: delta tracking and ratio tracking with a majorant |
//! | `phase.rs` | Henyey–Greenstein |
//! | `vol.rs` | Mitsuba's `.vol` grid files |

pub mod grid;
pub mod homogeneous;
pub mod phase;
pub mod vol;

pub use grid::Grid;
pub use homogeneous::Homogeneous;
pub use phase::HenyeyGreenstein;

use crate::math::Ray;
use glam::{Vec2, Vec3A};

/// "No medium": vacuum.
pub const NO_MEDIUM: u32 = u32::MAX;

/// The outcome of tracking a ray through a medium up to the surface ahead.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision {
    /// Distance of the scattering event along the ray, or `None` when the
    /// ray reaches the surface (or leaves to infinity) unscattered.
    pub t: Option<f32>,
    /// What the path throughput is multiplied by: transmittance (and σ_s
    /// at a scattering event) over the sampling density.
    pub weight: Vec3A,
}

/// A medium: a closed set, forwarded by `match`.
#[derive(Clone, Debug, PartialEq)]
pub enum Medium {
    /// Constant coefficients.
    Homogeneous(Homogeneous),
    /// A density grid.
    Grid(Box<Grid>),
}

impl Medium {
    /// The next collision along `ray` (unit direction) before `t_max`.
    /// `rand` gives uniform numbers: two for a homogeneous medium, as many
    /// as the tracking takes in a grid.
    #[inline]
    pub fn sample(&self, ray: &Ray, t_max: f32, rand: &mut impl FnMut() -> f32) -> Collision {
        match self {
            Medium::Homogeneous(h) => {
                let u = Vec2::new(rand(), rand());
                h.sample(t_max, u)
            }
            Medium::Grid(g) => g.sample(ray, t_max, rand),
        }
    }

    /// Transmittance along `ray` over `(0, t_max)`: exact in a homogeneous
    /// medium, an unbiased estimate (ratio tracking) in a grid.
    #[inline]
    pub fn transmittance(&self, ray: &Ray, t_max: f32, rand: &mut impl FnMut() -> f32) -> Vec3A {
        match self {
            Medium::Homogeneous(h) => h.transmittance(t_max),
            Medium::Grid(g) => Vec3A::splat(g.transmittance(ray, t_max, rand)),
        }
    }

    /// The phase function.
    #[inline]
    pub fn phase(&self) -> HenyeyGreenstein {
        match self {
            Medium::Homogeneous(h) => h.phase,
            Medium::Grid(g) => g.phase,
        }
    }
}

/// What crossing an object's surface does to the medium a ray is in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Boundary {
    /// The medium inside (behind the outward normal), or [`NO_MEDIUM`].
    pub inside: u32,
    /// The medium outside, or [`NO_MEDIUM`].
    pub outside: u32,
    /// An index-matched surface: light passes it unchanged.
    pub null: bool,
}

impl Boundary {
    /// The medium a ray leaving the surface along `w` is in (`ng` the
    /// outward geometric normal).
    #[inline]
    pub fn toward(&self, w: Vec3A, ng: Vec3A) -> u32 {
        if w.dot(ng) < 0.0 {
            self.inside
        } else {
            self.outside
        }
    }
}

/// The scene's media: the runtime table `Scene::media` holds when a scene
/// declares any (none otherwise, so surface-only scenes pay nothing).
#[derive(Clone, Debug, PartialEq)]
pub struct Media {
    /// Indexed by [`Boundary::inside`] / `outside` and `camera`.
    pub media: Vec<Medium>,
    /// The global medium, where the camera is, or [`NO_MEDIUM`].
    pub camera: u32,
    /// Boundaries by object id (`Scene::objects`); `None` for objects that
    /// leave the medium unchanged.
    pub boundaries: Vec<Option<Boundary>>,
    /// Whether any boundary is null: shadow rays then go through surfaces.
    pub any_null: bool,
}

impl Media {
    /// The boundary of object `id`, if it has one.
    #[inline]
    pub fn boundary(&self, id: u32) -> Option<Boundary> {
        self.boundaries.get(id as usize).copied().flatten()
    }

    /// The medium of index `i`, or `None` for [`NO_MEDIUM`].
    #[inline]
    pub fn get(&self, i: u32) -> Option<&Medium> {
        self.media.get(i as usize)
    }
}
