//! Mitsuba's `.vol` grid files (version 3, float32, one channel), so the
//! same file feeds both renderers.
//!
//! Layout, little endian: `'V' 'O' 'L'`, u8 version 3, i32 encoding 1
//! (float32), i32 xres, yres, zres, i32 channels (1), six f32 (the bounding
//! box, which Mitsuba ignores when the scene places the grid, as here), then
//! xres·yres·zres f32 values, x fastest.
//!
//! Hostile files: the header's sizes are checked against [`MAX_VOXELS`] and
//! against the file's length before anything is allocated; values must be
//! finite and ≥ 0.

use thiserror::Error;

/// Most values a grid may hold (2²⁴: 64 MB of f32, a 256³ grid).
pub const MAX_VOXELS: u64 = 1 << 24;
/// Bytes before the values.
const HEADER: usize = 48;

/// Why a `.vol` file was refused.
#[derive(Debug, Error, PartialEq)]
#[allow(missing_docs)] // each variant's message is its doc
pub enum VolError {
    #[error("not a Mitsuba .vol file (it does not start with `VOL` and version 3)")]
    Magic,
    #[error("the file ends inside its header ({0} bytes)")]
    Short(usize),
    #[error("encoding {0} is not supported (only 1, float32)")]
    Encoding(i32),
    #[error("{0} channels: only single-channel density grids are supported")]
    Channels(i32),
    #[error("grid size {0}×{1}×{2} is empty or above {MAX_VOXELS} values")]
    Size(i32, i32, i32),
    #[error("the header claims {expected} bytes of values but the file holds {found}")]
    Length { expected: u64, found: u64 },
    #[error("value {index} is {value}: densities must be finite and ≥ 0")]
    Value { index: usize, value: f32 },
}

/// A parsed grid: sizes along x, y, z and the values, x fastest.
#[derive(Debug, PartialEq)]
pub struct VolGrid {
    /// Values along x, y, z.
    pub res: [u32; 3],
    /// The values, x fastest.
    pub values: Vec<f32>,
}

/// The grid in `bytes` (a whole `.vol` file).
pub fn parse_vol(bytes: &[u8]) -> Result<VolGrid, VolError> {
    if bytes.len() < 4 || &bytes[..3] != b"VOL" || bytes[3] != 3 {
        return Err(VolError::Magic);
    }
    if bytes.len() < HEADER {
        return Err(VolError::Short(bytes.len()));
    }
    let int = |at: usize| i32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    let encoding = int(4);
    if encoding != 1 {
        return Err(VolError::Encoding(encoding));
    }
    let (x, y, z) = (int(8), int(12), int(16));
    let channels = int(20);
    if channels != 1 {
        return Err(VolError::Channels(channels));
    }
    let count = (x > 0 && y > 0 && z > 0)
        .then(|| x as u64 * y as u64 * z as u64)
        .filter(|&n| n <= MAX_VOXELS)
        .ok_or(VolError::Size(x, y, z))?;
    let found = (bytes.len() - HEADER) as u64;
    if found != count * 4 {
        return Err(VolError::Length {
            expected: count * 4,
            found,
        });
    }
    let mut values = Vec::with_capacity(count as usize);
    for (index, c) in bytes[HEADER..].chunks_exact(4).enumerate() {
        let value = f32::from_le_bytes([c[0], c[1], c[2], c[3]]);
        if !(value.is_finite() && value >= 0.0) {
            return Err(VolError::Value { index, value });
        }
        values.push(value);
    }
    Ok(VolGrid {
        res: [x as u32, y as u32, z as u32],
        values,
    })
}

/// The bytes of a `.vol` file holding `grid` with header box
/// `(min, max)`: what tests and tools write.
pub fn write_vol(res: [u32; 3], values: &[f32], min: [f32; 3], max: [f32; 3]) -> Vec<u8> {
    let mut out = b"VOL\x03".to_vec();
    for i in [1, res[0] as i32, res[1] as i32, res[2] as i32, 1] {
        out.extend_from_slice(&i.to_le_bytes());
    }
    for f in min.iter().chain(&max).chain(values) {
        out.extend_from_slice(&f.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vol_round_trips() {
        let values: Vec<f32> = (0..24).map(|i| i as f32 * 0.5).collect();
        let bytes = write_vol([2, 3, 4], &values, [0.0; 3], [1.0; 3]);
        let g = parse_vol(&bytes).expect("parses");
        assert_eq!(g.res, [2, 3, 4]);
        assert_eq!(g.values, values);
    }

    /// A header claiming a huge grid is refused before any allocation, as
    /// are a truncated file, negative or NaN values and wrong magic.
    #[test]
    fn vol_refuses_hostile_headers() {
        let mut bytes = write_vol([2, 2, 2], &[1.0; 8], [0.0; 3], [1.0; 3]);
        assert_eq!(parse_vol(&bytes[..40]), Err(VolError::Short(40)));
        assert!(matches!(
            parse_vol(&bytes[..bytes.len() - 4]),
            Err(VolError::Length { .. })
        ));
        bytes[8..12].copy_from_slice(&100_000i32.to_le_bytes());
        assert!(matches!(parse_vol(&bytes), Err(VolError::Length { .. })));
        bytes[12..16].copy_from_slice(&100_000i32.to_le_bytes());
        assert_eq!(parse_vol(&bytes), Err(VolError::Size(100_000, 100_000, 2)));
        let bad = write_vol([2, 1, 1], &[1.0, -2.0], [0.0; 3], [1.0; 3]);
        assert!(matches!(parse_vol(&bad), Err(VolError::Value { index: 1, .. })));
        let nan = write_vol([1, 1, 1], &[f32::NAN], [0.0; 3], [1.0; 3]);
        assert!(matches!(parse_vol(&nan), Err(VolError::Value { index: 0, .. })));
        assert_eq!(parse_vol(b"PNG\x03rest"), Err(VolError::Magic));
    }
}
