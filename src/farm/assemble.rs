//! Putting pieces back together: crops and tiles are placed, sample splits
//! are added (exact sums, so the order does not matter), and the result is
//! divided by the frame's samples per pixel — the same division the whole
//! render does on the same sums, hence the same bytes. Pieces of a frame
//! spread by noise carry each pixel's count and their two passes' sums
//! apart; the division is then the whole render's two-pass mean.
//!
//! Every problem is found before anything is written, and each names the
//! pieces and the pixels concerned: pieces from different scenes, ronray
//! versions, frame sizes, sample counts or seeds; pieces that hold the same
//! samples of the same pixels (overlaps); pixels whose samples no piece holds
//! (gaps, with the missing tile when the pieces came from `--tile`).

use super::piece::{Piece, PieceMeta, read_piece};
use crate::imageio::SampleSums;
use crate::imageio::{Image, PixelRect};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Why pieces were not assembled: every problem found, one per line.
#[derive(Debug, thiserror::Error)]
#[error("{}", .problems.join("\n"))]
pub struct AssembleError {
    /// Each problem as a sentence naming the pieces and pixels concerned.
    pub problems: Vec<String>,
}

/// At most this many overlaps or gaps are described one by one.
const SHOWN: usize = 8;

/// The piece that writing the assembled frame to `out` would replace (links
/// followed on both sides), if any: `assemble -o` must never destroy its
/// own input.
pub fn output_replaces_piece<'a>(pieces: &'a [PathBuf], out: &Path) -> Option<&'a PathBuf> {
    let target = crate::files::write_target(out);
    pieces.iter().find(|p| crate::files::resolved(p) == target)
}

/// Reads the piece files and assembles them.
pub fn assemble_files(paths: &[PathBuf]) -> Result<(Image, PieceMeta), AssembleError> {
    let mut pieces = Vec::new();
    let mut problems = Vec::new();
    for p in paths {
        match read_piece(p) {
            Ok(piece) => pieces.push((p.display().to_string(), piece)),
            Err(e) => problems.push(e.to_string()),
        }
    }
    if !problems.is_empty() {
        return Err(AssembleError { problems });
    }
    assemble(&pieces)
}

/// Assembles named pieces into the whole frame; returns it with the first
/// piece's metadata (all agree on scene, frame and samples).
pub fn assemble(pieces: &[(String, Piece)]) -> Result<(Image, PieceMeta), AssembleError> {
    let metas: Vec<(&str, &PieceMeta)> = pieces.iter().map(|(n, p)| (n.as_str(), &p.meta)).collect();
    let problems = check(&metas);
    if !problems.is_empty() {
        return Err(AssembleError { problems });
    }
    let first = &pieces[0].1.meta;
    let (w, h) = first.frame;
    let full = PixelRect::full(w, h);
    let mut total = match first.spread {
        Some(f) => SampleSums::new_spread(full, f),
        None => SampleSums::new(full),
    };
    for (_, p) in pieces {
        total.add(&p.sums);
    }
    Ok((total.mean(first.spp), first.clone()))
}

/// Every reason the pieces do not make one frame; empty when they do.
pub fn check(pieces: &[(&str, &PieceMeta)]) -> Vec<String> {
    if pieces.is_empty() {
        return vec!["no pieces given".into()];
    }
    let mut problems = Vec::new();
    disagree(&mut problems, pieces, "ronray versions", |m| {
        format!("version {}", m.version)
    });
    disagree(&mut problems, pieces, "animation frames", |m| {
        match m.animation_frame {
            Some(f) => format!("frame {f}"),
            None => "no animation frame".into(),
        }
    });
    disagree(&mut problems, pieces, "scenes", |m| format!("scene {}", m.scene));
    disagree(&mut problems, pieces, "frame sizes", |m| {
        format!("a {}×{} frame", m.frame.0, m.frame.1)
    });
    disagree(&mut problems, pieces, "sample counts", |m| {
        format!("{} spp", m.spp)
    });
    disagree(&mut problems, pieces, "seeds", |m| format!("seed {}", m.seed));
    disagree(&mut problems, pieces, "sample allocations", |m| match m.spread {
        Some(f) => format!("samples spread by noise after a first pass of {f}"),
        None => "samples spread evenly".into(),
    });
    if !problems.is_empty() {
        // Overlaps and gaps between different frames would only be noise.
        return problems;
    }
    let spp = pieces[0].1.spp;
    for (name, m) in pieces {
        if m.samples.1 > spp {
            problems.push(format!(
                "{name} holds samples {}..{}, past the frame's {spp}",
                m.samples.0, m.samples.1
            ));
        }
    }
    overlaps(&mut problems, pieces);
    gaps(&mut problems, pieces);
    problems
}

/// One problem when `key` differs between pieces, naming the pieces of each
/// value (the first few).
fn disagree(
    problems: &mut Vec<String>,
    pieces: &[(&str, &PieceMeta)],
    what: &str,
    key: impl Fn(&PieceMeta) -> String,
) {
    let mut groups: BTreeMap<String, Vec<&str>> = BTreeMap::new();
    let mut order = Vec::new();
    for (name, m) in pieces {
        let k = key(m);
        if !groups.contains_key(&k) {
            order.push(k.clone());
        }
        groups.entry(k).or_default().push(name);
    }
    if groups.len() < 2 {
        return;
    }
    let parts: Vec<String> = order
        .iter()
        .map(|k| {
            let names = &groups[k];
            let verb = if names.len() == 1 { "has" } else { "have" };
            format!("{} {verb} {k}", list(names))
        })
        .collect();
    problems.push(format!("pieces come from different {what}: {}", parts.join("; ")));
}

/// `a, b, c and 4 more`.
fn list(names: &[&str]) -> String {
    let shown = names.iter().take(3).copied().collect::<Vec<_>>().join(", ");
    match names.len() {
        n if n > 3 => format!("{shown} and {} more", n - 3),
        _ => shown,
    }
}

fn intersect_samples(a: (u32, u32), b: (u32, u32)) -> Option<(u32, u32)> {
    let r = (a.0.max(b.0), a.1.min(b.1));
    (r.0 < r.1).then_some(r)
}

/// Pairs of pieces holding the same samples of the same pixels.
fn overlaps(problems: &mut Vec<String>, pieces: &[(&str, &PieceMeta)]) {
    let mut found = 0;
    for (i, (a, ma)) in pieces.iter().enumerate() {
        for (b, mb) in &pieces[i + 1..] {
            let (Some(r), Some(s)) = (
                ma.rect.intersect(&mb.rect),
                intersect_samples(ma.samples, mb.samples),
            ) else {
                continue;
            };
            found += 1;
            if found <= SHOWN {
                let same = if a == b {
                    " (the same file given twice)"
                } else {
                    ""
                };
                problems.push(format!(
                    "pieces {a} and {b} overlap{same}: both hold samples {}..{} of pixels {r} ({} pixels)",
                    s.0,
                    s.1,
                    r.area()
                ));
            }
        }
    }
    if found > SHOWN {
        problems.push(format!("… and {} more overlapping pairs", found - SHOWN));
    }
}

/// Pixels and samples no piece holds. The samples are cut at every piece's
/// first and last sample; within each cut every piece holds all of it or
/// none, so one coverage mask per cut finds every gap.
fn gaps(problems: &mut Vec<String>, pieces: &[(&str, &PieceMeta)]) {
    let first = pieces[0].1;
    let (w, h) = first.frame;
    let mut cuts: Vec<u32> = vec![0, first.spp];
    for (_, m) in pieces {
        cuts.extend([m.samples.0.min(first.spp), m.samples.1.min(first.spp)]);
    }
    cuts.sort_unstable();
    cuts.dedup();
    // (samples, missing pixels, their bounds), merged across cuts with the
    // same missing pixels.
    let mut missing: Vec<((u32, u32), u64, PixelRect)> = Vec::new();
    let mut covered = vec![false; w as usize * h as usize];
    for s in cuts.windows(2) {
        covered.fill(false);
        for (_, m) in pieces
            .iter()
            .filter(|(_, m)| m.samples.0 <= s[0] && s[1] <= m.samples.1)
        {
            for y in m.rect.y0..m.rect.y1 {
                let row = y as usize * w as usize;
                covered[row + m.rect.x0 as usize..row + m.rect.x1 as usize].fill(true);
            }
        }
        let Some((count, bounds)) = uncovered(&covered, w) else {
            continue;
        };
        match missing.last_mut() {
            Some((samples, c, b)) if samples.1 == s[0] && *c == count && *b == bounds => samples.1 = s[1],
            _ => missing.push(((s[0], s[1]), count, bounds)),
        }
    }
    for ((a, b), count, bounds) in missing.iter().take(SHOWN) {
        let pixels = if *count == bounds.area() {
            format!("pixels {bounds} ({count} pixels)")
        } else {
            format!("{count} pixels within {bounds}")
        };
        let tiles = missing_tiles(pieces, (*a, *b), bounds);
        problems.push(format!("{tiles}no piece holds samples {a}..{b} of {pixels}"));
    }
    if missing.len() > SHOWN {
        problems.push(format!("… and {} more gaps", missing.len() - SHOWN));
    }
}

/// How many pixels are not covered, and their bounding box.
fn uncovered(covered: &[bool], w: u32) -> Option<(u64, PixelRect)> {
    let mut count = 0u64;
    let mut b = PixelRect {
        x0: u32::MAX,
        y0: u32::MAX,
        x1: 0,
        y1: 0,
    };
    for (i, _) in covered.iter().enumerate().filter(|(_, c)| !**c) {
        let (x, y) = (i as u32 % w, i as u32 / w);
        count += 1;
        b = PixelRect {
            x0: b.x0.min(x),
            y0: b.y0.min(y),
            x1: b.x1.max(x + 1),
            y1: b.y1.max(y + 1),
        };
    }
    (count > 0).then_some((count, b))
}

/// `missing tile 3/7: ` when the pieces of these samples came from one
/// `--tile` split and tiles of it over the gap are absent; empty otherwise.
fn missing_tiles(pieces: &[(&str, &PieceMeta)], samples: (u32, u32), gap: &PixelRect) -> String {
    let holding: Vec<&PieceMeta> = pieces
        .iter()
        .map(|(_, m)| *m)
        .filter(|m| intersect_samples(m.samples, samples).is_some())
        .collect();
    let Some(n) = holding.first().and_then(|m| m.tile).map(|t| t.1) else {
        return String::new();
    };
    if holding.iter().any(|m| m.tile.is_none_or(|t| t.1 != n)) {
        return String::new();
    }
    let (w, h) = holding[0].frame;
    let absent: Vec<String> = (0..n)
        .filter(|i| holding.iter().all(|m| m.tile.map(|t| t.0) != Some(*i)))
        .filter(|&i| super::split::tile_rect(i, n, w, h).intersect(gap).is_some())
        .map(|i| format!("{i}/{n}"))
        .collect();
    match absent.len() {
        0 => String::new(),
        1 => format!("missing tile {}: ", absent[0]),
        _ => format!("missing tiles {}: ", absent.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meta(rect: PixelRect, samples: (u32, u32)) -> PieceMeta {
        PieceMeta {
            version: "0.1.0".into(),
            scene: "sha256:aa".into(),
            seed: 0,
            spp: 8,
            samples,
            tile: None,
            frame: (8, 4),
            animation_frame: None,
            rect,
            spread: None,
        }
    }

    fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> PixelRect {
        PixelRect { x0, y0, x1, y1 }
    }

    #[test]
    fn check_accepts_crops_and_sample_splits_that_cover_the_frame_once() {
        let (a, b, c) = (
            meta(rect(0, 0, 8, 2), (0, 8)),
            meta(rect(0, 2, 8, 4), (0, 3)),
            meta(rect(0, 2, 8, 4), (3, 8)),
        );
        assert_eq!(check(&[("a", &a), ("b", &b), ("c", &c)]), Vec::<String>::new());
    }

    #[test]
    fn check_finds_samples_no_piece_holds() {
        let (a, b) = (meta(rect(0, 0, 8, 4), (0, 3)), meta(rect(0, 0, 8, 2), (3, 8)));
        let p = check(&[("a", &a), ("b", &b)]);
        assert_eq!(
            p,
            vec!["no piece holds samples 3..8 of pixels x 0..8, y 2..4 (16 pixels)"]
        );
    }
}
