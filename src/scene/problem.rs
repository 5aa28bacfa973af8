//! One semantic problem found while validating or building a scene.

/// A mistake in a scene file, located by its path inside the scene
/// (`objects[3].material`); the loader turns the path into file:line:col.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// Dotted path with `[i]` for sequence elements and `.name` for map keys:
    /// `objects[3].material`, `materials.floor.albedo`.
    pub path: String,
    pub message: String,
    /// The likely fix, phrased as advice ("did you mean `white`?").
    pub help: Option<String>,
}

impl Problem {
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            path: path.into(),
            message: message.into(),
            help: None,
        }
    }

    pub fn help(mut self, help: impl Into<String>) -> Self {
        self.help = Some(help.into());
        self
    }
}

/// Closest candidate by edit distance, if it is close enough to be a typo.
/// A candidate that starts with what was typed (`fov` → `fov_y_degrees`)
/// also counts.
pub fn suggest<'a>(found: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let candidates: Vec<&'a str> = candidates.into_iter().collect();
    if found.len() >= 3
        && let Some(c) = candidates.iter().find(|c| c.starts_with(found))
    {
        return Some(c);
    }
    candidates
        .into_iter()
        .map(|c| (strsim::damerau_levenshtein(found, c), c))
        .filter(|&(d, c)| d <= 2.max(c.len() / 3))
        .min_by_key(|&(d, _)| d)
        .map(|(_, c)| c)
}
