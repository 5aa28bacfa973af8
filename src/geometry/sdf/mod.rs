//! Implicit surfaces: signed distance functions (SDFs) built from primitives,
//! fractals and CSG operators, rendered by sphere tracing.
//!
//! Why sphere tracing: an SDF `d(p)` tells how far the nearest surface is, so
//! a ray may advance by `d` without crossing it (Hart 1996, "Sphere tracing: a
//! geometric method for the antialiased ray tracing of implicit surfaces",
//! <https://doi.org/10.1007/s003710050084>). That needs only `d ≤` the true
//! distance (a *bound*); a distance *estimate* (fractals) may overshoot and is
//! marched with a safety factor.
//!
//! The distance formulas are Íñigo Quilez's:
//! primitives <https://iquilezles.org/articles/distfunctions/>,
//! smooth minimum <https://iquilezles.org/articles/smin/>,
//! tetrahedral normals <https://iquilezles.org/articles/normalsSDF/>,
//! Mandelbulb <https://iquilezles.org/articles/mandelbulb/>,
//! Menger sponge <https://iquilezles.org/articles/menger/>.
//!
//! Stages: the loader maps its scene types onto [`SdfNode`]s, checks them
//! with [`validate()`], then builds an [`Sdf`]; the renderer uses [`trace`],
//! [`occluded`], [`normal`] and [`Sdf::bounds`] (for the BVH).

pub mod bounding_sphere;
pub mod bounds;
pub mod fast_ln;
pub mod fractal;
pub mod mandelbulb_x4;
pub mod march;
pub mod node;
pub mod primitives;
pub mod tree;
pub mod validate;

pub use march::{MarchParams, SdfTrace, normal, occluded, trace};
pub use node::SdfNode;
pub use tree::Sdf;
pub use validate::{validate, validate_node};
