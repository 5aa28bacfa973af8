//! `ronray bench --scenes DIR`: renders the scenes that have a reference in
//! DIR and prints, per scene, sampler and spp, the speed (samples and rays
//! per second, wall and CPU time) and the error against the reference
//! (whole image and off the light pixels), so the figures of a
//! ronray-against-Mitsuba table are one command away.
//!
//! DIR holds `<name>_ref.exr` (or `.pfm`) references and, optionally,
//! `<name>_emitter_mask.png` (255 where a pixel sees a light), for example
//! Mitsuba 3 renders of ronray's reference scenes. Each reference is matched to a ronray scene
//! `<name>.ron` looked up first in DIR, then in `--ronray-scenes` (default
//! `scenes`), where `cornell_diffuse` is also found as `cornell.ron`.
//! References without a ronray twin are listed as skipped. The renderer-
//! neutral JSON beside the references is not read: the shipped twins are
//! written from it by hand and checked against the references by
//! `tests/reference.rs`.

use super::RenderSettings;
use crate::frame::{RenderOptions, render_whole};
use crate::imageio::{Image, compare, read_image};
use crate::load::{Overrides, load_with};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// `println!` that ignores a closed pipe (`ronray bench … | head`).
macro_rules! out {
    ($($arg:tt)*) => {
        super::print_out(&format!("{}\n", format_args!($($arg)*)))
    };
}

/// Other names under which a reference's ronray twin is shipped.
const ALIASES: &[(&str, &str)] = &[("cornell_diffuse", "cornell")];

/// What `bench --scenes` renders.
pub struct SceneBench<'a> {
    /// Folder of `<name>_ref.exr` references.
    pub refs: &'a Path,
    /// Folder of ronray scenes to match them with.
    pub scenes: &'a Path,
    /// Samples per pixel to render each scene at.
    pub spp: &'a [u32],
    /// Samplers (scene-file names, e.g. `Independent`, `Sobol`); empty: the scene's own.
    pub samplers: &'a [String],
    /// Threads, seed and `--set` overrides.
    pub settings: &'a RenderSettings,
    /// `--root DIR`: inputs outside it are refused.
    pub root: Option<&'a Path>,
}

/// A reference image found in the folder, its mask, and the scene to render.
struct Case {
    name: String,
    reference: Image,
    /// Pixels to leave out of the "off the light" error.
    light: Option<Vec<bool>>,
    scene: Option<PathBuf>,
}

/// Runs the benchmark; the error says which file could not be read.
pub fn run(b: &SceneBench) -> Result<(), String> {
    let cases = find_cases(b.refs, b.scenes)?;
    if cases.is_empty() {
        return Err(format!(
            "no `<name>_ref.exr` or `<name>_ref.pfm` in {}",
            b.refs.display()
        ));
    }
    let threads = b.settings.threads;
    let samplers: Vec<Option<&str>> = if b.samplers.is_empty() {
        vec![None]
    } else {
        b.samplers.iter().map(|s| Some(s.as_str())).collect()
    };
    // The binary timed, so a table names its build (`tools/pgo-build.sh`).
    out!(
        "ronray {}; load before: {}",
        super::VERSION,
        super::bench::load_average()
    );
    out!("| scene | sampler | spp | s | CPU s | Msamples/s | Mrays/s | RMSE | RMSE off light |");
    out!("|---|---|---|---|---|---|---|---|---|");
    for case in &cases {
        let Some(scene) = &case.scene else {
            out!(
                "| {} | no ronray scene in {} or {} | | | | | | | |",
                case.name,
                b.refs.display(),
                b.scenes.display()
            );
            continue;
        };
        for sampler in &samplers {
            for &spp in b.spp {
                let mut sets = b.settings.sets.clone();
                if let Some(s) = sampler {
                    sets.push(format!("film.sampler={s}"));
                }
                let o = Overrides {
                    spp: Some(spp),
                    size: Some((case.reference.width, case.reference.height)),
                    seed: b.settings.seed,
                    sets,
                    root: b.root.map(Path::to_path_buf),
                    ..Default::default()
                };
                let loaded = load_with(scene, &o).map_err(|e| format!("{}: {e}", scene.display()))?;
                let opts = RenderOptions {
                    threads,
                    ..Default::default()
                };
                let (wall, cpu) = (Instant::now(), super::bench::cpu_seconds());
                let (img, stats) = render_whole(&loaded.scene, &loaded.view, &opts);
                let (secs, cpu_s) = (wall.elapsed().as_secs_f64(), super::bench::cpu_seconds() - cpu);
                let err = |skip: Option<&[bool]>| compare(&img, &case.reference, skip).map(|c| c.rmse);
                let whole = err(None)?;
                let off = case.light.as_deref().map(|m| err(Some(m))).transpose()?;
                // With adaptive sampling `spp` is the most a pixel takes;
                // the mean is what the time bought.
                let spp_cell = match loaded.view.film.adaptive {
                    Some(_) => format!(
                        "{spp} (adaptive, mean {:.1})",
                        stats.samples as f64 / (u64::from(img.width) * u64::from(img.height)).max(1) as f64
                    ),
                    None => spp.to_string(),
                };
                out!(
                    "| {} | {} | {spp_cell} | {secs:.2} | {cpu_s:.2} | {:.3} | {:.3} | {whole:.5} | {} |",
                    case.name,
                    sampler.map_or_else(
                        || format!("{:?} (scene)", loaded.view.film.sampler),
                        str::to_string
                    ),
                    stats.samples as f64 / secs / 1e6,
                    stats.rays as f64 / secs / 1e6,
                    off.map_or_else(|| "no mask".to_string(), |e| format!("{e:.5}"))
                );
            }
        }
    }
    out!("load after: {}", super::bench::load_average());
    Ok(())
}

/// The references in `refs`, sorted by name, each with its mask and ronray scene.
fn find_cases(refs: &Path, scenes: &Path) -> Result<Vec<Case>, String> {
    let entries = std::fs::read_dir(refs).map_err(|e| format!("cannot read {}: {e}", refs.display()))?;
    let mut names: Vec<(String, PathBuf)> = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        let file = path.file_name().and_then(|f| f.to_str()).unwrap_or_default();
        // Prefer the EXR when both formats are there.
        for ext in ["_ref.exr", "_ref.pfm"] {
            if let Some(name) = file.strip_suffix(ext)
                && !names
                    .iter()
                    .any(|(n, p)| n == name && p.extension().is_some_and(|e| e == "exr"))
            {
                names.retain(|(n, _)| n != name);
                names.push((name.to_string(), path.clone()));
            }
        }
    }
    names.sort();
    names
        .into_iter()
        .map(|(name, path)| {
            let reference = read_image(&path).map_err(|e| format!("{}: {e}", path.display()))?;
            let mask_path = refs.join(format!("{name}_emitter_mask.png"));
            let light = if mask_path.exists() {
                let m = read_image(&mask_path).map_err(|e| format!("{}: {e}", mask_path.display()))?;
                if (m.width, m.height) != (reference.width, reference.height) {
                    return Err(format!(
                        "{}: mask size differs from the reference",
                        mask_path.display()
                    ));
                }
                // 8-bit grey decoded to linear: 128 is about 0.22 (`ronray diff --mask`'s rule).
                Some(m.pixels.iter().map(|p| p.x >= 0.2).collect())
            } else {
                None
            };
            let scene = twin(&name, refs, scenes);
            Ok(Case {
                name,
                reference,
                light,
                scene,
            })
        })
        .collect()
}

/// The ronray scene for reference `name`: `<name>.ron` (or an alias) in `refs`, then in `scenes`.
fn twin(name: &str, refs: &Path, scenes: &Path) -> Option<PathBuf> {
    let alias = ALIASES.iter().find(|(n, _)| *n == name).map(|(_, a)| *a);
    [refs, scenes]
        .iter()
        .flat_map(|dir| {
            std::iter::once(name)
                .chain(alias)
                .map(move |n| dir.join(format!("{n}.ron")))
        })
        .find(|p| p.is_file())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn twin_finds_aliases_and_prefers_the_reference_folder() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR"));
        let scenes = root.join("scenes");
        assert_eq!(
            twin("cornell_diffuse", Path::new("/nonexistent"), &scenes),
            Some(scenes.join("cornell.ron"))
        );
        assert_eq!(
            twin("cornell_dof", Path::new("/nonexistent"), &scenes),
            Some(scenes.join("cornell_dof.ron"))
        );
        assert_eq!(twin("no_such_scene", Path::new("/nonexistent"), &scenes), None);
    }
}
