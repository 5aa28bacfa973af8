//! The pixels of an equirectangular sky map and where a point falls
//! between them: what the sky's radiance lookup (`environment.rs`) and its
//! importance tables (`env_table.rs`) both read, kept apart so neither
//! file imports the other.
//!
//! # Layout
//! Each pixel is 16 bytes: its red, green and blue, then its weight for
//! importance sampling (luminance × sin θ of its row, filled by
//! [`EnvMap::fill_weights`] when the tables are built). A sample reads the
//! four weights around the point it draws and then the radiance of the
//! same four pixels; held in separate arrays they were four cache lines
//! from a map larger than the cache, interleaved they are two (the same
//! lines serve both). On `ground40_sun_2spheres` (a 1440 × 720 map, 21
//! bytes a pixel with the tables) a third of the time was the sky's lookups
//! waiting on memory (perf). The values are the same floats either way.

use crate::math::{Rgb, luminance};
use glam::{Vec2, Vec4};
use rayon::prelude::*;
use std::f32::consts::PI;

/// A linear-RGB equirectangular image, row 0 at the top.
#[derive(Clone, Debug)]
pub struct EnvMap {
    /// Width in pixels (around the horizon).
    pub width: u32,
    /// Height in pixels (pole to pole).
    pub height: u32,
    /// `width·height` pixels, row-major from the top: red, green, blue and
    /// the sampling weight (see the module docs; 0 until
    /// [`EnvMap::fill_weights`]).
    pub texels: Vec<[f32; 4]>,
}

impl EnvMap {
    /// A map from `3·width·height` floats, RGB interleaved, row-major from
    /// the top (weights not yet filled).
    pub fn from_rgb(width: u32, height: u32, rgb: &[f32]) -> Self {
        Self {
            width,
            height,
            texels: rgb.chunks_exact(3).map(|p| [p[0], p[1], p[2], 0.0]).collect(),
        }
    }

    /// The colour channels of every pixel (and the weights, 0 before
    /// [`EnvMap::fill_weights`]) as one slice of floats, for repairs.
    pub fn values_mut(&mut self) -> &mut [f32] {
        self.texels.as_flattened_mut()
    }

    /// Writes each pixel's sampling weight: `luminance × sin θ` of its
    /// colour (negative channels as 0) and its row (θ = πj/(H − 1); 1 for
    /// a map of one row), 0 where that is not finite. Rows in parallel.
    pub fn fill_weights(&mut self) {
        let (w, h) = (self.width as usize, self.height as usize);
        self.texels.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
            let s = if h > 1 {
                (PI * j as f32 / (h - 1) as f32).sin().max(0.0)
            } else {
                1.0
            };
            for px in row.iter_mut() {
                let rgb = Rgb::new(px[0].max(0.0), px[1].max(0.0), px[2].max(0.0));
                let l = luminance(rgb) * s;
                px[3] = if l.is_finite() { l } else { 0.0 };
            }
        });
    }

    /// The sampling weights of the four pixels of footprint `at`, in the
    /// order (i0, j0), (i1, j0), (i0, j1), (i1, j1).
    #[inline]
    pub fn weights(&self, at: &Footprint) -> [f32; 4] {
        let w = self.width as usize;
        let (r0, r1) = (at.j[0] as usize * w, at.j[1] as usize * w);
        let (i0, i1) = (at.i[0] as usize, at.i[1] as usize);
        [
            self.texels[r0 + i0][3],
            self.texels[r0 + i1][3],
            self.texels[r1 + i0][3],
            self.texels[r1 + i1][3],
        ]
    }

    /// Bilinear lookup at `(u, v)` ∈ [0, 1]²: columns centred at `(i + ½)/W`
    /// (wrapping), rows at `j/(H − 1)` (see the module docs).
    ///
    /// Indices go through `i32` (clamped coordinates fit) and each row is
    /// sliced once: the saturating `f32 → usize` casts and twelve bounds
    /// checks were a third of its ~150 instructions (callgrind).
    #[inline]
    pub fn lookup(&self, uv: Vec2) -> Rgb {
        self.bilerp(&self.footprint(uv))
    }

    /// The four pixels around image coordinates `uv` and the place
    /// between them (see [`EnvMap::lookup`] for the grid).
    #[inline]
    pub fn footprint(&self, uv: Vec2) -> Footprint {
        let (w, h) = (self.width as usize, self.height as usize);
        // Columns wrap: left of the first centre blends the last column in.
        let x = (uv.x * w as f32 - 0.5).clamp(-1.0, w as f32 - 0.5);
        let x0 = x.floor();
        let fx = x - x0;
        // x0 ∈ [−1, W − 1]: −1 is the seam, between the last column and the first.
        let xi = x0 as i32;
        let i0 = if xi < 0 { w - 1 } else { xi as usize };
        let i1 = if xi + 1 >= w as i32 { 0 } else { (xi + 1) as usize };
        // Row 0 at the zenith, row H − 1 at the nadir.
        let y = (uv.y * (h - 1) as f32).clamp(0.0, (h - 1) as f32);
        let j0 = (y as i32) as usize;
        let j1 = (j0 + 1).min(h - 1);
        let fy = y - j0 as f32;
        Footprint {
            i: [i0 as u32, i1 as u32],
            j: [j0 as u32, j1 as u32],
            f: Vec2::new(fx, fy),
        }
    }

    /// The image interpolated over footprint `at`.
    #[inline]
    pub fn bilerp(&self, at: &Footprint) -> Rgb {
        let (row0, row1) = (self.row(at.j[0] as usize), self.row(at.j[1] as usize));
        // Four lanes at once; the fourth (the weight) is dropped.
        let px = |row: &[[f32; 4]], i: u32| Vec4::from_array(row[i as usize]);
        let (fx, fy) = (at.f.x, at.f.y);
        let top = px(row0, at.i[0]) * (1.0 - fx) + px(row0, at.i[1]) * fx;
        let bottom = px(row1, at.i[0]) * (1.0 - fx) + px(row1, at.i[1]) * fx;
        Rgb::from_vec4(top * (1.0 - fy) + bottom * fy)
    }

    #[inline]
    fn row(&self, j: usize) -> &[[f32; 4]] {
        let n = self.width as usize;
        &self.texels[j * n..(j + 1) * n]
    }
}

/// Where a point of the map falls between pixel centres: the four pixels
/// around it (columns `i`, rows `j`) and its place between them. The same
/// footprint serves the radiance lookup ([`EnvMap::bilerp`]) and the
/// density ([`super::env_table::EnvTable::pdf_at`]): the importance
/// tables' cells are the lookup's grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Left and right columns (the right wraps across the seam).
    pub i: [u32; 2],
    /// Upper and lower rows.
    pub j: [u32; 2],
    /// Place between them, each in [0, 1].
    pub f: Vec2,
}
