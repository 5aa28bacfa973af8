//! The pixels of an equirectangular sky map and where a point falls
//! between them: what the sky's radiance lookup (`environment.rs`) and its
//! importance tables (`env_table.rs`) both read, kept apart so neither
//! file imports the other.

use crate::math::Rgb;
use glam::Vec2;

/// A linear-RGB equirectangular image, row 0 at the top.
#[derive(Clone, Debug)]
pub struct EnvMap {
    /// Width in pixels (around the horizon).
    pub width: u32,
    /// Height in pixels (pole to pole).
    pub height: u32,
    /// `3·width·height` floats, RGB interleaved, row-major from the top.
    pub rgb: Vec<f32>,
}

impl EnvMap {
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
        let px = |row: &[f32], i: u32| {
            let p = &row[3 * i as usize..3 * i as usize + 3];
            Rgb::new(p[0], p[1], p[2])
        };
        let (fx, fy) = (at.f.x, at.f.y);
        let top = px(row0, at.i[0]) * (1.0 - fx) + px(row0, at.i[1]) * fx;
        let bottom = px(row1, at.i[0]) * (1.0 - fx) + px(row1, at.i[1]) * fx;
        top * (1.0 - fy) + bottom * fy
    }

    #[inline]
    fn row(&self, j: usize) -> &[f32] {
        let n = 3 * self.width as usize;
        &self.rgb[j * n..(j + 1) * n]
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
