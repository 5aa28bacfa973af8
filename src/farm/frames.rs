//! Frames of an animation on the command line: `--frame N|auto`,
//! `--frames A..B`, and the `{frame}` field of an output name.

/// What `--frame` names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameArg {
    /// That frame.
    Given(i32),
    /// The scene's first frame plus the scheduler's job index (as `--tile
    /// auto/N` reads it).
    Auto,
}

/// Parses `--frame`: a whole number or `auto`.
pub fn parse_frame(s: &str) -> Result<FrameArg, String> {
    match s.trim() {
        "auto" => Ok(FrameArg::Auto),
        t => t
            .parse()
            .map(FrameArg::Given)
            .map_err(|_| format!("`{s}` is not a frame number or `auto`")),
    }
}

/// Parses `--frames A..B` (or `A..=B`): frames A to B, both included.
pub fn parse_frames(s: &str) -> Result<(i32, i32), String> {
    let bad = || format!("`{s}` is not a range of frames `A..B` (both included), e.g. `1..48`");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let b = b.strip_prefix('=').unwrap_or(b);
    let (a, b): (i32, i32) = (
        a.trim().parse().map_err(|_| bad())?,
        b.trim().parse().map_err(|_| bad())?,
    );
    if a > b {
        return Err(format!("`{s}` runs backwards: the first frame is after the last"));
    }
    Ok((a, b))
}

/// Whether an output name has a `{frame}` or `{frame:0N}` field.
pub fn has_field(name: &str) -> bool {
    field(name).is_some()
}

/// The first `{frame}` / `{frame:0N}` field: its byte range and width.
fn field(name: &str) -> Option<(std::ops::Range<usize>, usize)> {
    let start = name.find("{frame")?;
    let rest = &name[start + 6..];
    let end = rest.find('}')?;
    let width = match &rest[..end] {
        "" => 0,
        spec => spec
            .strip_prefix(':')?
            .parse::<usize>()
            .ok()
            .filter(|w| *w <= 16)?,
    };
    Some((start..start + 6 + end + 1, width))
}

/// `name` with every `{frame}` field replaced by `frame`, zero-padded to
/// the field's width (`out_{frame:04}.exr` → `out_0007.exr`).
pub fn fill(name: &str, frame: i32) -> String {
    let mut out = name.to_string();
    // Each pass replaces one field; a name has few.
    for _ in 0..64 {
        let Some((range, width)) = field(&out) else {
            break;
        };
        let number = if frame < 0 {
            format!(
                "-{:0width$}",
                frame.unsigned_abs(),
                width = width.saturating_sub(1)
            )
        } else {
            format!("{frame:0width$}")
        };
        out.replace_range(range, &number);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_arguments_parse_and_explain_mistakes() {
        assert_eq!(parse_frame("7"), Ok(FrameArg::Given(7)));
        assert_eq!(parse_frame("auto"), Ok(FrameArg::Auto));
        assert!(parse_frame("seven").is_err());
        assert_eq!(parse_frames("3..5"), Ok((3, 5)));
        assert_eq!(parse_frames("3..=5"), Ok((3, 5)));
        assert!(parse_frames("5..3").unwrap_err().contains("backwards"));
        assert!(parse_frames("0..1000000000000").is_err());
    }

    #[test]
    fn frame_fields_fill_with_padding() {
        assert_eq!(fill("out_{frame:04}.exr", 7), "out_0007.exr");
        assert_eq!(fill("f{frame}/{frame:3}.png", 12), "f12/012.png");
        assert_eq!(fill("still.png", 3), "still.png");
        assert!(has_field("a_{frame:04}.exr") && !has_field("a_{frames}.exr") && !has_field("a.exr"));
    }
}
