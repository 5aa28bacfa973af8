//! The one table of image formats: what each file extension is and what it
//! can carry. The loader (`film.output`), the frame wing's output rule
//! (`crate::frame::output`), the writer and the reader all ask it, so adding
//! a format is one variant here plus its encoder and decoder.
//!
//! It sits in `imageio/` rather than in the frame wing because the loader
//! checks `film.output` against it and the loader never imports the frame
//! wing (`tests/architecture.rs`).

use std::path::Path;

/// An image file format ronray writes and reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OutputFormat {
    /// 8- or 16-bit sRGB, exposed and tone mapped (`film.exposure`, `film.tonemap`).
    Png,
    /// OpenEXR, linear 32-bit float; the only one with extra layers and exact sums.
    Exr,
    /// Portable float map, linear 32-bit float.
    Pfm,
    /// Radiance RGBE, linear.
    Hdr,
}

impl OutputFormat {
    /// Every format, in the order messages list them.
    pub const ALL: [OutputFormat; 4] = [
        OutputFormat::Png,
        OutputFormat::Exr,
        OutputFormat::Pfm,
        OutputFormat::Hdr,
    ];

    /// The file extension, lower case, without the dot.
    pub fn extension(self) -> &'static str {
        match self {
            OutputFormat::Png => "png",
            OutputFormat::Exr => "exr",
            OutputFormat::Pfm => "pfm",
            OutputFormat::Hdr => "hdr",
        }
    }

    /// Whether pixels are stored as linear radiance (not tone mapped).
    pub fn linear(self) -> bool {
        match self {
            OutputFormat::Png => false,
            OutputFormat::Exr | OutputFormat::Pfm | OutputFormat::Hdr => true,
        }
    }

    /// Whether it can hold AOV layers beside the beauty pass (`film.aovs`).
    pub fn carries_layers(self) -> bool {
        match self {
            OutputFormat::Exr => true,
            OutputFormat::Png | OutputFormat::Pfm | OutputFormat::Hdr => false,
        }
    }

    /// Whether it can hold a piece of a frame: exact per-pixel sums that add
    /// up across machines (`ronray assemble`).
    pub fn carries_pieces(self) -> bool {
        match self {
            OutputFormat::Exr => true,
            OutputFormat::Png | OutputFormat::Pfm | OutputFormat::Hdr => false,
        }
    }

    /// The format of extension `ext` (any case, without the dot).
    pub fn from_extension(ext: &str) -> Option<OutputFormat> {
        Self::ALL
            .into_iter()
            .find(|f| f.extension().eq_ignore_ascii_case(ext))
    }

    /// The format `path`'s extension names.
    pub fn of_path(path: &Path) -> Option<OutputFormat> {
        path.extension()
            .and_then(|e| e.to_str())
            .and_then(Self::from_extension)
    }

    /// "`.png`, `.exr`, `.pfm` or `.hdr`": every extension, for messages.
    pub fn choices() -> String {
        let names: Vec<String> = Self::ALL.iter().map(|f| format!(".{}", f.extension())).collect();
        or_list(&names)
    }

    /// How to end a file name, grouped by what the pixels are: "end it in
    /// `.png` (sRGB, tone mapped), or `.exr`, `.pfm` or `.hdr` (linear float)".
    pub fn advice() -> String {
        let group = |linear: bool| -> Vec<String> {
            Self::ALL
                .iter()
                .filter(|f| f.linear() == linear)
                .map(|f| format!("`.{}`", f.extension()))
                .collect()
        };
        format!(
            "end it in {} (sRGB, tone mapped), or {} (linear float)",
            or_list(&group(false)),
            or_list(&group(true))
        )
    }
}

/// "a", "a or b", "a, b or c".
fn or_list(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_table_names_each_extension_once_in_any_case() {
        for f in OutputFormat::ALL {
            assert_eq!(OutputFormat::from_extension(f.extension()), Some(f));
            assert_eq!(
                OutputFormat::from_extension(&f.extension().to_uppercase()),
                Some(f)
            );
        }
        assert_eq!(OutputFormat::from_extension("jpg"), None);
        assert_eq!(
            OutputFormat::of_path(Path::new("a/b.EXR")),
            Some(OutputFormat::Exr)
        );
        assert_eq!(OutputFormat::of_path(Path::new("noext")), None);
    }

    #[test]
    fn format_messages_list_every_extension() {
        assert_eq!(OutputFormat::choices(), ".png, .exr, .pfm or .hdr");
        assert_eq!(
            OutputFormat::advice(),
            "end it in `.png` (sRGB, tone mapped), or `.exr`, `.pfm` or `.hdr` (linear float)"
        );
    }
}
