//! Piece files: one part of a frame, as an OpenEXR file that any EXR viewer
//! opens and that `ronray assemble` puts back together exactly.
//!
//! - **Windows**: the data window is the piece's pixels, the display window
//!   the whole frame, so a viewer shows the piece in place.
//! - **Channels**: `R`, `G`, `B` (32-bit float) hold the mean over the
//!   piece's samples: for a piece with all of the frame's samples, the very
//!   values the whole render has at those pixels. `sum0.R` … `sum3.B`
//!   (32-bit unsigned) hold each channel's exact sample sum
//!   ([`crate::math::ExactSum`]) as four little-endian words, which is what
//!   assembling adds up. A piece of a frame spread by noise
//!   (`spread=` below) adds `late0.R` … `late3.B`, the sums of the samples
//!   past the first pass (the sum channels then hold the first pass's), and
//!   `count` (32-bit unsigned), each pixel's number of samples in the piece.
//! - **Metadata**: one string-vector attribute `ronray` with `version=`,
//!   `scene=` (the scene content hash), `samples=A..B`, `spp=`, `seed=`,
//!   for `--tile` pieces `tile=I/N`, and for a frame spread by noise
//!   `spread=F` (its first pass's samples per pixel). One attribute rather than six: the
//!   `exr` crate keeps extra attributes in a hash map whose order changes
//!   from run to run, and a single one keeps piece files byte-reproducible.

use super::PieceError;
use crate::imageio::SampleSums;
use crate::imageio::sample_sums::SpreadSums;
use crate::imageio::{PixelRect, write_atomic};
use crate::math::ExactSum;
use exr::prelude::{self as x, AttributeValue, ReadChannels, ReadLayers, Text, WritableImage};
use std::path::Path;

/// What a piece holds, beside its pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PieceMeta {
    /// ronray's version (`CARGO_PKG_VERSION`) that rendered it.
    pub version: String,
    /// [`super::scene_hash`] of the scene.
    pub scene: String,
    /// The scene's seed (`film.seed`).
    pub seed: u64,
    /// The frame's samples per pixel.
    pub spp: u32,
    /// Samples `samples.0..samples.1` of every pixel of `rect`.
    pub samples: (u32, u32),
    /// `(I, N)` for tile I of an N-tile split (`--tile`).
    pub tile: Option<(u32, u32)>,
    /// The whole frame, width × height.
    pub frame: (u32, u32),
    /// The animation frame drawn (`--frame`), for scenes with an
    /// `animation`; pieces of different ones never assemble.
    pub animation_frame: Option<i32>,
    /// The piece's pixels (its EXR data window).
    pub rect: PixelRect,
    /// For a frame spread by noise (`film.allocation: ByNoise`), the
    /// samples per pixel of its first pass; samples `A..B` then stand for
    /// `A·n/spp..B·n/spp` of a pixel that takes `n`.
    pub spread: Option<u32>,
}

impl PieceMeta {
    /// Whether `other` is the same piece of the same frame (what `--resume`
    /// asks before skipping a render).
    pub fn same_work(&self, other: &PieceMeta) -> bool {
        let key = |m: &PieceMeta| {
            (
                m.version.clone(),
                m.scene.clone(),
                m.seed,
                m.spp,
                m.samples,
                m.frame,
                m.animation_frame,
                m.rect,
                m.spread,
            )
        };
        key(self) == key(other)
    }

    fn to_lines(&self) -> Vec<String> {
        let mut v = vec![
            format!("version={}", self.version),
            format!("scene={}", self.scene),
            format!("samples={}..{}", self.samples.0, self.samples.1),
            format!("spp={}", self.spp),
            format!("seed={}", self.seed),
        ];
        if let Some((i, n)) = self.tile {
            v.push(format!("tile={i}/{n}"));
        }
        if let Some(f) = self.animation_frame {
            v.push(format!("animation_frame={f}"));
        }
        if let Some(first) = self.spread {
            v.push(format!("spread={first}"));
        }
        v
    }

    fn from_lines(lines: &[String], frame: (u32, u32), rect: PixelRect) -> Result<Self, String> {
        let get = |k: &str| {
            lines
                .iter()
                .find_map(|l| l.strip_prefix(k).and_then(|r| r.strip_prefix('=')))
                .ok_or_else(|| format!("its `ronray` attribute has no `{k}=`"))
        };
        let bad = |k: &str, v: &str| format!("its `ronray` attribute has a bad `{k}={v}`");
        let num = |k: &str| get(k).and_then(|v| v.parse::<u64>().map_err(|_| bad(k, v)));
        let samples = get("samples")?;
        let samples = super::split::parse_samples(samples).map_err(|_| bad("samples", samples))?;
        let tile = match get("tile") {
            Ok(t) => Some(match super::split::parse_tile(t) {
                Ok((super::TileIndex::Given(i), n)) => (i, n),
                _ => return Err(bad("tile", t)),
            }),
            Err(_) => None,
        };
        let spread = match get("spread") {
            Ok(v) => Some(v.parse::<u32>().map_err(|_| bad("spread", v))?),
            Err(_) => None,
        };
        Ok(PieceMeta {
            version: get("version")?.to_string(),
            scene: get("scene")?.to_string(),
            seed: num("seed")?,
            spp: u32::try_from(num("spp")?).map_err(|_| bad("spp", get("spp").unwrap_or("")))?,
            samples,
            tile,
            frame,
            animation_frame: match get("animation_frame") {
                Ok(f) => Some(f.parse().map_err(|_| bad("animation_frame", f))?),
                Err(_) => None,
            },
            rect,
            spread,
        })
    }
}

/// A piece as read back: what it is and its exact sums.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// What the piece is.
    pub meta: PieceMeta,
    /// The exact sample sums of its pixels.
    pub sums: SampleSums,
}

/// The sum channels' names: word `w` of channel `c` of the sums called
/// `prefix` (`sum`, `late`).
fn sum_channel(prefix: &str, w: usize, c: usize) -> String {
    format!("{prefix}{w}.{}", ["R", "G", "B"][c])
}

/// Adds twelve channels holding `sums`' words, named `prefix`.
fn push_sums(channels: &mut Vec<x::AnyChannel<x::FlatSamples>>, prefix: &str, sums: &[ExactSum]) {
    let words: Vec<[[u32; 4]; 3]> = sums.iter().map(ExactSum::to_words).collect();
    for w in 0..4 {
        for c in 0..3 {
            let v = words.iter().map(|p| p[c][w]).collect();
            channels.push(x::AnyChannel::new(
                sum_channel(prefix, w, c).as_str(),
                x::FlatSamples::U32(v),
            ));
        }
    }
}

/// Writes a piece atomically. PNG and other formats are refused: 8-bit
/// pieces cannot be merged exactly.
pub fn write_piece(path: &Path, meta: &PieceMeta, sums: &SampleSums) -> Result<(), PieceError> {
    let err = |reason: String| PieceError {
        path: path.to_path_buf(),
        reason,
    };
    if !is_exr(path) {
        return Err(err(
            "a piece of a frame must be an .exr file: PNG pieces are 8-bit and cannot be merged exactly"
                .into(),
        ));
    }
    debug_assert_eq!(meta.rect, sums.rect);
    if meta.spread != sums.spread.as_ref().map(|s| s.first) {
        return Err(err(
            "its metadata and its sums disagree on spreading by noise".into()
        ));
    }
    let mean = sums.piece_mean(meta.samples.1 - meta.samples.0);
    let mut channels: Vec<x::AnyChannel<x::FlatSamples>> = (0..3)
        .map(|c| {
            let v = mean.pixels.iter().map(|p| p[c]).collect();
            x::AnyChannel::new(["R", "G", "B"][c], x::FlatSamples::F32(v))
        })
        .collect();
    push_sums(&mut channels, "sum", &sums.sums);
    if let Some(spread) = &sums.spread {
        push_sums(&mut channels, "late", &spread.late);
        channels.push(x::AnyChannel::new(
            "count",
            x::FlatSamples::U32(spread.counts.clone()),
        ));
    }
    let r = meta.rect;
    let mut attributes = x::LayerAttributes {
        layer_position: x::Vec2(r.x0 as i32, r.y0 as i32),
        software_name: Some(Text::new_or_panic(format!("ronray {}", meta.version))),
        ..Default::default()
    };
    attributes.other.insert(
        Text::new_or_panic("ronray"),
        AttributeValue::TextVector(meta.to_lines().iter().map(Text::new_or_panic).collect()),
    );
    let layer = x::Layer::new(
        (r.width() as usize, r.height() as usize),
        attributes,
        x::Encoding::SMALL_LOSSLESS,
        x::AnyChannels::sort(channels.into()),
    );
    let mut image = x::Image::from_layer(layer);
    image.attributes.display_window =
        x::IntegerBounds::new((0, 0), (meta.frame.0 as usize, meta.frame.1 as usize));
    write_atomic(path, |w| image.write().to_buffered(w).map_err(|e| e.to_string()))
        .map_err(|e| err(e.to_string()))
}

fn is_exr(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// The frame, the piece's pixels and its `ronray` lines, from a header.
fn describe(
    display: x::IntegerBounds,
    position: x::Vec2<i32>,
    size: x::Vec2<usize>,
    attributes: &x::LayerAttributes,
) -> Result<PieceMeta, String> {
    let lines = match attributes.other.get(&Text::new_or_panic("ronray")) {
        Some(AttributeValue::TextVector(v)) => v.iter().map(|t| t.to_string()).collect::<Vec<_>>(),
        _ => {
            return Err(
                "not a piece of a frame: it has no `ronray` attribute (pieces are written by \
                        `ronray render` with --crop, --pixels, --tile or --samples)"
                    .into(),
            );
        }
    };
    if display.position != x::Vec2(0, 0) || position.0 < 0 || position.1 < 0 {
        return Err("its display window does not start at (0, 0) or its data window is outside it".into());
    }
    // A frame is an image ronray could render, checked before any size is
    // narrowed or added: a header may claim anything.
    let max = crate::load::validate::MAX_RESOLUTION as usize;
    if display.size.0.max(display.size.1) > max {
        return Err(format!(
            "its display window is {}×{}, above the limit of {max} pixels a side",
            display.size.0, display.size.1
        ));
    }
    let frame = (display.size.0 as u32, display.size.1 as u32);
    let (x0, y0) = (position.0 as usize, position.1 as usize);
    if x0.saturating_add(size.0) > display.size.0 || y0.saturating_add(size.1) > display.size.1 {
        return Err(format!(
            "its data window (x {x0}..{}, y {y0}..{}) is outside its {}×{} display window",
            x0.saturating_add(size.0),
            y0.saturating_add(size.1),
            frame.0,
            frame.1
        ));
    }
    let rect = PixelRect {
        x0: x0 as u32,
        y0: y0 as u32,
        x1: (x0 + size.0) as u32,
        y1: (y0 + size.1) as u32,
    };
    PieceMeta::from_lines(&lines, frame, rect)
}

/// A FIFO or a device named as a piece would block or never end: only
/// regular files are read (`metadata` does not open the file).
fn regular(path: &Path) -> Result<(), String> {
    match std::fs::metadata(path) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(_) => Err("not a regular file (a piece is an .exr file)".into()),
        Err(e) => Err(e.to_string()),
    }
}

/// How many times its file size a piece's channels may take once decoded:
/// deflate cannot pass ~1,032×, so only a corrupt header reaches this (as
/// for sky maps, `MAX_EXR_RATIO` in `src/load/light.rs`).
const MAX_PIECE_RATIO: u64 = 16_384;

/// What the header of the piece at `path` claims, checked before the
/// decoder allocates it: every channel of every layer at 4 bytes a sample,
/// within the memory available and [`MAX_PIECE_RATIO`] times the file's
/// size. A 1 KB file claiming 16384² pixels of 40 channels asked for 43 GB.
fn check_size(path: &Path) -> Result<(), String> {
    let file_len = std::fs::metadata(path).map_err(|e| e.to_string())?.len();
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    let mut bytes = 0u64;
    for h in meta.headers.iter() {
        let pixels = h.layer_size.width() as u64 * h.layer_size.height() as u64;
        bytes = bytes.saturating_add(pixels.saturating_mul(4 * h.channels.list.len() as u64));
    }
    if bytes > MAX_PIECE_RATIO.saturating_mul(file_len.max(1)) {
        return Err(format!(
            "its header claims {} MB of samples but the file holds {file_len} bytes: truncated or corrupt",
            bytes >> 20
        ));
    }
    if let Some(free) = crate::memory::available()
        && bytes > free
    {
        return Err(format!(
            "its samples need {} MB, more than the {} MB of memory available",
            bytes >> 20,
            free >> 20
        ));
    }
    Ok(())
}

/// Reads only a piece's header.
pub fn read_piece_meta(path: &Path) -> Result<PieceMeta, PieceError> {
    let err = |reason: String| PieceError {
        path: path.to_path_buf(),
        reason,
    };
    regular(path).map_err(err)?;
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| err(e.to_string()))?;
    let h = meta.headers.first().ok_or_else(|| err("no layer".into()))?;
    describe(
        h.shared_attributes.display_window,
        h.own_attributes.layer_position,
        h.layer_size,
        &h.own_attributes,
    )
    .map_err(err)
}

/// Reads a piece: its metadata and exact sums.
pub fn read_piece(path: &Path) -> Result<Piece, PieceError> {
    let err = |reason: String| PieceError {
        path: path.to_path_buf(),
        reason,
    };
    if !is_exr(path) {
        return Err(err(
            "pieces are .exr files written by `ronray render`; PNG pieces cannot be merged exactly".into(),
        ));
    }
    regular(path).map_err(err)?;
    check_size(path).map_err(err)?;
    let image = x::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_file(path)
        .map_err(|e| err(e.to_string()))?;
    let layer = &image.layer_data;
    let meta = describe(
        image.attributes.display_window,
        layer.attributes.layer_position,
        layer.size,
        &layer.attributes,
    )
    .map_err(err)?;
    let n = meta.rect.area() as usize;
    let channel = |name: &str| -> Result<&[u32], String> {
        let c = layer
            .channel_data
            .list
            .iter()
            .find(|c| c.name == Text::new_or_panic(name))
            .ok_or_else(|| format!("channel `{name}` is missing"))?;
        match &c.sample_data {
            x::FlatSamples::U32(v) if v.len() == n => Ok(v.as_slice()),
            _ => Err(format!("channel `{name}` is not {n} 32-bit words")),
        }
    };
    let read_sums = |prefix: &str| -> Result<Vec<ExactSum>, String> {
        let mut words = vec![[[0u32; 4]; 3]; n];
        for w in 0..4 {
            for c in 0..3 {
                let v = channel(&sum_channel(prefix, w, c))?;
                for (p, &x) in words.iter_mut().zip(v) {
                    p[c][w] = x;
                }
            }
        }
        Ok(words.into_iter().map(ExactSum::from_words).collect())
    };
    let spread = match meta.spread {
        Some(first) => Some(SpreadSums {
            first,
            late: read_sums("late").map_err(err)?,
            counts: channel("count").map_err(err)?.to_vec(),
        }),
        None => None,
    };
    let sums = SampleSums {
        rect: meta.rect,
        sums: read_sums("sum").map_err(err)?,
        spread,
    };
    Ok(Piece { meta, sums })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    fn piece() -> (PieceMeta, SampleSums) {
        let rect = PixelRect {
            x0: 3,
            y0: 2,
            x1: 8,
            y1: 6,
        };
        let meta = PieceMeta {
            version: "0.1.0".into(),
            scene: "sha256:00ff".into(),
            seed: 7,
            spp: 16,
            samples: (4, 12),
            tile: Some((1, 3)),
            frame: (10, 9),
            animation_frame: Some(-12),
            rect,
            spread: None,
        };
        let mut sums = SampleSums::new(rect);
        for (i, s) in sums.sums.iter_mut().enumerate() {
            s.add_sample(Rgb::new(i as f32, 1e-7 * i as f32, 3.0e5));
        }
        (meta, sums)
    }

    #[test]
    fn piece_files_round_trip_metadata_and_exact_sums() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("p.exr");
        let (meta, sums) = piece();
        write_piece(&path, &meta, &sums).expect("write");
        let back = read_piece(&path).expect("read");
        assert_eq!(back.meta, meta);
        assert_eq!(back.sums, sums);
        assert_eq!(read_piece_meta(&path).expect("header"), meta);
        let again = dir.path().join("q.exr");
        write_piece(&again, &meta, &sums).expect("write again");
        assert!(
            std::fs::read(&path).ok() == std::fs::read(&again).ok(),
            "two writes of one piece differ in bytes"
        );
    }

    #[test]
    fn non_pieces_are_refused_with_the_reason() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (meta, sums) = piece();
        let png = write_piece(&dir.path().join("p.png"), &meta, &sums).unwrap_err();
        assert!(png.reason.contains("cannot be merged exactly"), "{png}");
        let plain = dir.path().join("plain.exr");
        crate::imageio::write_image(&crate::imageio::Image::new(4, 4), &plain).expect("write");
        let e = read_piece(&plain).unwrap_err();
        assert!(e.reason.contains("no `ronray` attribute"), "{e}");
    }
}
