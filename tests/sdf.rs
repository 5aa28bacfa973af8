//! Implicit surfaces in scenes: SDF shapes checked against analytic and
//! tessellated twins, and the shipped SDF scenes round-tripped. Their golden
//! images are checked with every other shipped scene's by `ronray check`
//! (`tests/check.rs`, goldens in `scenes/golden/`).

use crate::common;

mod geometry;
mod mandelbulb;
mod torus;
mod validation;

use common::root;
pub use common::{load_in as scene_in, load_text as scene};
use ronray::imageio::Image;
use ronray::load::{Loaded, Overrides, load_with};
use std::path::Path;

/// Renders `scene` at `seed`; every pixel must be finite.
pub fn render_seed(scene: &mut Loaded, seed: u64) -> Image {
    scene.view.film.seed = seed;
    common::render_loaded(scene)
}

#[test]
fn sdf_scenes_round_trip_through_ron() {
    for name in ["sdf_shapes", "mandelbulb"] {
        let loaded = load_with(&root().join(format!("scenes/{name}.ron")), &Overrides::default()).unwrap();
        let text = ron::ser::to_string_pretty(&loaded.desc, Default::default()).unwrap();
        let again = ronray::load::pipeline::parse(Path::new("again.ron"), &text)
            .unwrap_or_else(|r| panic!("{name} does not parse back:\n{}\n{text}", r.render(false)));
        assert_eq!(again, loaded.desc, "{name} changed in the round trip");
    }
}
