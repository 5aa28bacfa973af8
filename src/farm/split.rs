//! Which part of a frame one render covers: `--crop`, `--pixels`,
//! `--tile I/N` (with `auto` reading the index from the scheduler) and
//! `--samples A..B`, parsed from the command line and resolved against the
//! film.

use crate::imageio::PixelRect;

/// The pixels a render covers, as the command line says it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Region {
    /// Every pixel (no `--crop`, `--pixels` or `--tile`).
    Whole,
    /// Fractions of the image in pbrt's order: x0, x1, y0, y1.
    Crop([f64; 4]),
    /// Pixel bounds, ends excluded.
    Pixels(PixelRect),
    /// Tile `index` of a `count`-tile split ([`tile_rect`]).
    Tile {
        /// Which tile.
        index: TileIndex,
        /// How many tiles the frame is split into.
        count: u32,
    },
}

/// The tile of `--tile I/N`: given, or read from the scheduler's variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TileIndex {
    /// `--tile I/N`.
    Given(u32),
    /// `--tile auto/N`: from [`INDEX_VARIABLES`].
    Auto,
}

/// What `--tile auto/N` reads, in this order: the variable, who sets it, and
/// the number its first task gets (GNU parallel counts from 1).
pub const INDEX_VARIABLES: [(&str, &str, u32); 3] = [
    ("SLURM_ARRAY_TASK_ID", "a Slurm job array", 0),
    ("JOB_COMPLETION_INDEX", "a Kubernetes indexed Job", 0),
    ("PARALLEL_SEQ", "GNU parallel", 1),
];

/// A part of a frame, resolved against the film: pixels, samples
/// `samples.0..samples.1`, and the tile it is when it came from `--tile`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PieceSpec {
    /// The pixels, inside the film.
    pub rect: PixelRect,
    /// Samples `samples.0..samples.1` of every pixel.
    pub samples: (u32, u32),
    /// `(I, N)` for `--tile`.
    pub tile: Option<(u32, u32)>,
}

fn numbers<T: std::str::FromStr>(s: &str, n: usize, what: &str) -> Result<Vec<T>, String> {
    let v: Vec<T> = s
        .split(',')
        .map(|p| p.trim().parse::<T>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("`{s}` is not {what}"))?;
    if v.len() != n {
        return Err(format!("`{s}` is not {what}"));
    }
    Ok(v)
}

/// `x0,x1,y0,y1`, fractions of the image with 0 ≤ x0 < x1 ≤ 1 (pbrt's
/// `--cropwindow`).
pub fn parse_crop(s: &str) -> Result<[f64; 4], String> {
    let what = "x0,x1,y0,y1 (four fractions of the image, e.g. 0,0.5,0,0.5)";
    let v = numbers::<f64>(s, 4, what)?;
    let ok = |a: f64, b: f64| (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) && a < b;
    if !ok(v[0], v[1]) || !ok(v[2], v[3]) {
        return Err(format!(
            "crop `{s}` must have 0 ≤ x0 < x1 ≤ 1 and 0 ≤ y0 < y1 ≤ 1 (pbrt's order: x0,x1,y0,y1)"
        ));
    }
    Ok([v[0], v[1], v[2], v[3]])
}

/// `x0,y0,x1,y1`, pixel bounds with the ends excluded.
pub fn parse_pixels(s: &str) -> Result<PixelRect, String> {
    let v = numbers::<u32>(s, 4, "x0,y0,x1,y1 (pixel bounds, ends excluded, e.g. 0,0,32,32)")?;
    let r = PixelRect {
        x0: v[0],
        y0: v[1],
        x1: v[2],
        y1: v[3],
    };
    if r.is_empty() {
        return Err(format!("pixels `{s}` cover nothing: need x0 < x1 and y0 < y1"));
    }
    Ok(r)
}

/// `I/N` or `auto/N`, with I < N.
pub fn parse_tile(s: &str) -> Result<(TileIndex, u32), String> {
    let what = || format!("`{s}` is not I/N or auto/N (e.g. 3/8)");
    let (i, n) = s.split_once('/').ok_or_else(what)?;
    let n: u32 = n.trim().parse().map_err(|_| what())?;
    if n == 0 {
        return Err(format!("`{s}`: a split needs at least one tile"));
    }
    let index = match i.trim() {
        "auto" => TileIndex::Auto,
        i => {
            let i: u32 = i.parse().map_err(|_| what())?;
            if i >= n {
                return Err(format!(
                    "tile {i} of {n} does not exist: tiles count from 0 to {}",
                    n - 1
                ));
            }
            TileIndex::Given(i)
        }
    };
    Ok((index, n))
}

/// `A..B`: samples A to B−1 of every pixel.
pub fn parse_samples(s: &str) -> Result<(u32, u32), String> {
    let what = || format!("`{s}` is not A..B (samples A to B−1, e.g. 0..64)");
    let (a, b) = s.split_once("..").ok_or_else(what)?;
    let (a, b): (u32, u32) = (
        a.trim().parse().map_err(|_| what())?,
        b.trim().parse().map_err(|_| what())?,
    );
    if a >= b {
        return Err(format!("samples `{s}` are empty: need A < B"));
    }
    Ok((a, b))
}

/// The tile index from the first of [`INDEX_VARIABLES`] that is set, and
/// the variable's name.
pub fn auto_index(env: &dyn Fn(&str) -> Option<String>) -> Result<(u32, &'static str), String> {
    for (var, who, first) in INDEX_VARIABLES {
        if let Some(v) = env(var) {
            let n: u32 = v
                .trim()
                .parse()
                .map_err(|_| format!("{var}=`{v}` is not a whole number"))?;
            let i = n
                .checked_sub(first)
                .ok_or_else(|| format!("{var}={n}, but {who} counts from {first}"))?;
            return Ok((i, var));
        }
    }
    let names: Vec<_> = INDEX_VARIABLES
        .iter()
        .map(|(v, who, _)| format!("{v} ({who})"))
        .collect();
    Err(format!(
        "--tile auto/N takes the tile from {}, and none is set; give the index instead (--tile 0/N)",
        names.join(", ")
    ))
}

/// Tile `index` of a `count`-tile split of a `width` × `height` frame:
/// horizontal bands of whole rows, band i holding rows ⌊i·h/N⌋ to
/// ⌊(i+1)·h/N⌋ − 1. Full rows keep each task's work alike (a band crosses
/// the whole picture), and any N up to the height splits exactly.
pub fn tile_rect(index: u32, count: u32, width: u32, height: u32) -> PixelRect {
    let row = |i: u32| (i as u64 * height as u64 / count as u64) as u32;
    PixelRect {
        x0: 0,
        y0: row(index),
        x1: width,
        y1: row(index + 1),
    }
}

/// A crop window's pixels as pbrt-v4 computes them: ⌈w·x0⌉..⌈w·x1⌉ ×
/// ⌈h·y0⌉..⌈h·y1⌉, so crops that share an edge share no pixel.
pub fn crop_rect(crop: [f64; 4], width: u32, height: u32) -> PixelRect {
    let at = |f: f64, size: u32| ((size as f64 * f).ceil() as u32).min(size);
    PixelRect {
        x0: at(crop[0], width),
        x1: at(crop[1], width),
        y0: at(crop[2], height),
        y1: at(crop[3], height),
    }
}

/// Resolves the command line's region and samples against a film of
/// `width` × `height` pixels and `spp` samples.
pub fn resolve(
    region: Region,
    samples: Option<(u32, u32)>,
    (width, height, spp): (u32, u32, u32),
    env: &dyn Fn(&str) -> Option<String>,
) -> Result<PieceSpec, String> {
    let full = PixelRect::full(width, height);
    let mut tile = None;
    let rect = match region {
        Region::Whole => full,
        Region::Crop(c) => crop_rect(c, width, height),
        Region::Pixels(r) => r,
        Region::Tile { index, count } => {
            let index = match index {
                TileIndex::Given(i) => i,
                TileIndex::Auto => auto_index(env)?.0,
            };
            if index >= count {
                return Err(format!(
                    "tile {index} of {count} does not exist: tiles count from 0 to {}",
                    count - 1
                ));
            }
            if count > height {
                return Err(format!(
                    "{count} tiles are more than the frame's {height} rows; use at most {height}"
                ));
            }
            tile = Some((index, count));
            tile_rect(index, count, width, height)
        }
    };
    if !full.contains(&rect) {
        return Err(format!("pixels {rect} are outside the {width}×{height} frame"));
    }
    if rect.is_empty() {
        return Err(format!("the crop covers no pixel of the {width}×{height} frame"));
    }
    let samples = samples.unwrap_or((0, spp));
    if samples.1 > spp {
        return Err(format!(
            "samples {}..{} go past the scene's {spp} samples per pixel; set the total with --spp",
            samples.0, samples.1
        ));
    }
    Ok(PieceSpec { rect, samples, tile })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_split_every_row_exactly_once() {
        for (h, n) in [(64, 7), (64, 4), (10, 10), (1, 1), (97, 13)] {
            let mut next = 0;
            for i in 0..n {
                let r = tile_rect(i, n, 5, h);
                assert_eq!(r.y0, next, "tile {i}/{n} of {h} rows starts at {}", r.y0);
                assert!(!r.is_empty(), "tile {i}/{n} of {h} rows is empty");
                next = r.y1;
            }
            assert_eq!(next, h, "{n} tiles of {h} rows end at row {next}");
        }
    }

    #[test]
    fn crop_windows_that_share_an_edge_share_no_pixel() {
        let left = crop_rect([0.0, 1.0 / 3.0, 0.0, 1.0], 64, 64);
        let right = crop_rect([1.0 / 3.0, 1.0, 0.0, 1.0], 64, 64);
        assert_eq!((left.x1, right.x0), (22, 22));
        assert_eq!(right.x1, 64);
    }

    #[test]
    fn piece_arguments_parse_and_explain_mistakes() {
        assert_eq!(parse_tile("3/8"), Ok((TileIndex::Given(3), 8)));
        assert_eq!(parse_tile("auto/4"), Ok((TileIndex::Auto, 4)));
        assert!(parse_tile("8/8").unwrap_err().contains("from 0 to 7"));
        assert_eq!(parse_samples("16..32"), Ok((16, 32)));
        assert!(parse_samples("4..4").unwrap_err().contains("empty"));
        assert!(parse_crop("0,0.5,0.5,0.2").unwrap_err().contains("y0 < y1"));
        assert!(parse_pixels("0,0,0,8").unwrap_err().contains("cover nothing"));
    }

    #[test]
    fn auto_index_reads_the_schedulers_variables() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| pairs.iter().find(|(n, _)| *n == k).map(|(_, v)| v.to_string())
        };
        assert_eq!(
            auto_index(&env(&[("SLURM_ARRAY_TASK_ID", "2")])),
            Ok((2, "SLURM_ARRAY_TASK_ID"))
        );
        assert_eq!(
            auto_index(&env(&[("JOB_COMPLETION_INDEX", "0")])).map(|r| r.0),
            Ok(0)
        );
        assert_eq!(
            auto_index(&env(&[("PARALLEL_SEQ", "1")])).map(|r| r.0),
            Ok(0),
            "GNU parallel counts from 1"
        );
        let none = auto_index(&env(&[])).unwrap_err();
        assert!(
            none.contains("SLURM_ARRAY_TASK_ID") && none.contains("PARALLEL_SEQ"),
            "{none}"
        );
    }

    #[test]
    fn resolve_refuses_pieces_outside_the_film() {
        let env = |_: &str| None;
        let r = resolve(
            Region::Pixels(parse_pixels("0,0,80,8").unwrap()),
            None,
            (64, 64, 4),
            &env,
        );
        assert!(r.unwrap_err().contains("outside the 64×64 frame"));
        let s = resolve(Region::Whole, Some((0, 8)), (64, 64, 4), &env);
        assert!(s.unwrap_err().contains("scene's 4 samples"));
        let t = resolve(
            Region::Tile {
                index: TileIndex::Given(1),
                count: 4,
            },
            None,
            (64, 64, 4),
            &env,
        );
        assert_eq!(
            t.map(|p| (p.rect, p.samples, p.tile)),
            Ok((
                PixelRect {
                    x0: 0,
                    y0: 16,
                    x1: 64,
                    y1: 32
                },
                (0, 4),
                Some((1, 4))
            ))
        );
    }
}
