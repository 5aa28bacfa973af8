//! What a render will cost in memory, asked before anything is allocated.
//!
//! The largest film the loader accepts (16384²) needs about 18 GiB: on a
//! smaller machine the allocation would abort the process (or wake the
//! kernel's OOM killer) after the scene was loaded. Commands compare
//! [`film_bytes`] with what the machine has (`MemAvailable` in
//! `/proc/meminfo`) or with `--max-memory`, and refuse with both figures.

/// Bytes per pixel of a one-shot render: the film of linear RGB
/// (`Rgb` = `Vec3A`, 16 bytes), the finished tiles' pixels on their way
/// into it (up to a film's worth while tiles are gathered), the encoder's
/// copy (8-bit or float RGB, at most 12 bytes), and what a render spread
/// by noise keeps between its passes (`film/allocation.rs`: the first
/// pass's mean and variance, 16 bytes, then the variances, weights and
/// counts, 12). The caustic light tracer's exact sums (48 bytes, beside the
/// film's 16, after the tiles are gathered) stay below that.
const RENDER_BYTES_PER_PIXEL: u64 = 16 + 16 + 12 + 16 + 12;
/// Extra bytes per pixel of progressive rendering (watch mode): exact sums
/// of every pixel (3 × i128) kept between passes, and one pass's sums.
const PROGRESSIVE_BYTES_PER_PIXEL: u64 = 2 * 48;

/// Estimated peak memory of rendering a `width × height` film, in bytes
/// (the scene's own memory — meshes, textures, BVHs — is already allocated
/// when this is asked, and is not counted).
pub fn film_bytes(width: u32, height: u32, progressive: bool) -> u64 {
    let per_pixel = RENDER_BYTES_PER_PIXEL
        + if progressive {
            PROGRESSIVE_BYTES_PER_PIXEL
        } else {
            0
        };
    u64::from(width) * u64::from(height) * per_pixel
}

/// `MemAvailable` of `/proc/meminfo`, in bytes: memory the machine can
/// give without swapping. `None` where it cannot be read (not Linux).
pub fn available() -> Option<u64> {
    parse_meminfo(&std::fs::read_to_string("/proc/meminfo").ok()?)
}

fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let mut words = line.split_whitespace().skip(1);
    let n: u64 = words.next()?.parse().ok()?;
    match words.next() {
        Some("kB") | None => n.checked_mul(1024),
        Some(_) => None,
    }
}

/// A render refused because it would not fit.
#[derive(Debug, thiserror::Error)]
#[error("{}", describe(self))]
pub struct MemoryError {
    /// The film's size.
    pub size: (u32, u32),
    /// The estimate, in bytes.
    pub needed: u64,
    /// What it was compared with, in bytes.
    pub limit: u64,
    /// Whether `limit` is the machine's `MemAvailable` (else `--max-memory`).
    pub machine: bool,
}

fn describe(e: &MemoryError) -> String {
    let gib = |b: u64| b as f64 / f64::from(1u32 << 30);
    let (w, h) = e.size;
    let limit = if e.machine {
        format!("this machine has {:.1} GiB available", gib(e.limit))
    } else {
        format!("--max-memory is {:.1} GiB", gib(e.limit))
    };
    format!(
        "a {w}×{h} render needs about {:.1} GiB of memory and {limit}; render smaller (--size) or in pieces (--tile), or raise the limit with --max-memory GIB",
        gib(e.needed)
    )
}

/// Refuses a `width × height` render whose estimate is above `limit`
/// bytes, or, without one, above what the machine has available.
pub fn check_film(width: u32, height: u32, progressive: bool, limit: Option<u64>) -> Result<(), MemoryError> {
    let needed = film_bytes(width, height, progressive);
    let (limit, machine) = match limit {
        Some(l) => (l, false),
        None => match available() {
            Some(a) => (a, true),
            None => return Ok(()),
        },
    };
    if needed <= limit {
        return Ok(());
    }
    Err(MemoryError {
        size: (width, height),
        needed,
        limit,
        machine,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn meminfo_gives_available_bytes() {
        let text = "MemTotal:       16000000 kB\nMemFree:  100 kB\nMemAvailable:    8000000 kB\n";
        assert_eq!(parse_meminfo(text), Some(8_000_000 * 1024));
        assert_eq!(parse_meminfo("MemTotal: 1 kB\n"), None);
    }

    #[test]
    fn the_largest_film_is_refused_on_a_small_machine() {
        let four_gib = 4 << 30;
        let e = check_film(16384, 16384, false, Some(four_gib)).expect_err("too large");
        let msg = e.to_string();
        assert!(
            msg.contains("16384×16384") && msg.contains("GiB") && msg.contains("--max-memory"),
            "{msg}"
        );
        assert!(check_film(64, 64, true, Some(four_gib)).is_ok());
    }
}
