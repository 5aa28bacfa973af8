//! Cameras: a frame in world space (`eye`, `forward`, `right`, `up`) and a
//! [`Projection`] that turns a film position into a ray.
//!
//! Conventions follow the Mitsuba references: `forward = normalize(target −
//! eye)`, `right = normalize(forward × up)`, `true_up = right × forward`;
//! image x grows toward `right`, row 0 is the top. Each projection's maths
//! lives in its own file: [`perspective`] (pinhole and thin lens, the field
//! of view is the full vertical angle), [`orthographic`] (parallel rays, a
//! view height in scene units) and [`spherical`] (equirectangular, the
//! environment map's own mapping, so a map seen through it comes back as
//! itself).

pub mod motion;
pub mod orthographic;
pub mod perspective;
pub mod spherical;

use crate::math::Ray;
use glam::{Vec2, Vec3A};

/// How film positions become rays; a closed set, dispatched by `match`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Rays through one point (or a thin lens around it); see [`perspective`].
    Perspective,
    /// Parallel rays along `forward` from a rectangle `view_height` tall; see
    /// [`orthographic`].
    Orthographic {
        /// Height of the seen rectangle, in scene units.
        view_height: f32,
    },
    /// Every direction around `eye`, latitude–longitude; see [`spherical`].
    Spherical {
        /// Image height in pixels: rows are centred at `v = j/(H − 1)`, as the
        /// environment map's are.
        rows: u32,
    },
}

/// A camera in world space, with its orthonormal frame precomputed so
/// generating a ray is a few multiply-adds.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    /// Centre of projection (pinhole or lens centre; the centre of the
    /// orthographic rectangle; the spherical camera's viewpoint), in world space.
    pub eye: Vec3A,
    /// Unit view direction, `normalize(target − eye)`.
    pub forward: Vec3A,
    /// Unit image-right direction, `normalize(forward × up)`.
    pub right: Vec3A,
    /// Unit image-up direction, perpendicular to `forward` and `right` (not
    /// necessarily the `up` the scene gave).
    pub up: Vec3A,
    /// tan(fov_y / 2) (perspective only).
    pub tan_half_fov: f32,
    /// Thin-lens aperture radius in scene units; 0 (or less) is a pinhole, with
    /// everything in focus (perspective only).
    pub aperture_radius: f32,
    /// Distance from `eye` along `forward` to the plane in focus, in scene units.
    pub focus_distance: f32,
    /// How film positions become rays.
    pub projection: Projection,
}

impl Camera {
    /// A pinhole camera at `eye` looking at `target`, with `up` the image's rough up
    /// direction and `fov_y_degrees` the full vertical field of view in degrees;
    /// focus distance `|target − eye|`. `up` must not be parallel to the view (the
    /// loader checks it).
    pub fn look_at(eye: Vec3A, target: Vec3A, up: Vec3A, fov_y_degrees: f32) -> Self {
        let forward = (target - eye).normalize();
        let right = forward.cross(up).normalize();
        let true_up = right.cross(forward);
        Self {
            eye,
            forward,
            right,
            up: true_up,
            tan_half_fov: (fov_y_degrees.to_radians() * 0.5).tan(),
            aperture_radius: 0.0,
            focus_distance: (target - eye).length(),
            projection: Projection::Perspective,
        }
    }

    /// The same frame with another projection.
    pub fn with_projection(self, projection: Projection) -> Self {
        Self { projection, ..self }
    }

    /// Ray through film position `film` ∈ `[0, 1]²` (x right, y down; a pixel
    /// filter may reach a little outside) for an image of aspect `width /
    /// height`; `u_lens` samples the aperture.
    #[inline]
    pub fn ray(&self, film: Vec2, aspect: f32, u_lens: Vec2) -> Ray {
        match self.projection {
            Projection::Perspective => perspective::ray(self, film, aspect, u_lens),
            Projection::Orthographic { view_height } => orthographic::ray(self, film, aspect, view_height),
            Projection::Spherical { rows } => spherical::ray(self, film, rows),
        }
    }
}
