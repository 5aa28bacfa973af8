//! Open Image Denoise (`--features denoise`): the Cornell box at 16 spp,
//! denoised with its albedo and normal layers, is closer to Mitsuba's
//! reference than the raw render at 256 spp. Without the feature (the
//! default build) it says "skipped", or fails under RONRAY_REQUIRE_TOOLS=1;
//! CI runs it with the feature (`.ci/run`).

mod common;

#[cfg(feature = "denoise")]
mod with_oidn {
    use super::common::{report, root};
    use ronray::aov::{AovSet, render_aovs};
    use ronray::imageio::{Image, compare, read_image};
    use ronray::load::{Loaded, Overrides, load_with};
    use ronray::render::render;
    use std::time::Instant;

    fn cornell(spp: u32) -> (Loaded, Image) {
        let o = Overrides {
            spp: Some(spp),
            size: Some((64, 64)),
            seed: Some(1),
            ..Default::default()
        };
        let l = load_with(&root().join("scenes/cornell.ron"), &o).expect("cornell loads");
        let img = render(&l.scene, &l.view, &Default::default()).0;
        (l, img)
    }

    #[test]
    fn denoised_cornell_at_16_spp_beats_the_raw_render_at_256_spp() {
        let fixture = |f: &str| read_image(&root().join("tests/fixtures/refs").join(f)).expect("fixture");
        let reference = fixture("cornell_diffuse_64.pfm");
        // As tests/reference.rs: the light's own pixels (radiance ~17, their
        // edges a coin flip per sample) are judged apart.
        let off_light: Vec<bool> = fixture("cornell_diffuse_mask_64.pfm")
            .pixels
            .iter()
            .map(|p| p.x > 0.5)
            .collect();
        let (l, noisy) = cornell(16);
        let layers = render_aovs(&l.scene, &l.view, AovSet::EMPTY, None);
        let t = Instant::now();
        let clean = ronray::denoise::denoise(&noisy, &layers).expect("OIDN denoises");
        let secs = t.elapsed().as_secs_f64();
        let (_, raw) = cornell(256);
        let rmse = |a: &Image, skip: Option<&[bool]>| compare(a, &reference, skip).expect("same size").rmse;
        for (label, skip) in [
            ("all pixels", None),
            ("off the light", Some(off_light.as_slice())),
        ] {
            report(&format!(
                "denoise: Cornell 64² vs Mitsuba ({label}), RMSE raw 16 spp {:.5}, denoised 16 spp {:.5}, raw 256 spp {:.5}",
                rmse(&noisy, skip),
                rmse(&clean, skip),
                rmse(&raw, skip)
            ));
        }
        report(&format!("denoise: OIDN took {secs:.3} s (wall, loaded machine)"));
        assert!(
            clean.pixels.iter().all(|p| p.is_finite()),
            "denoised image is not finite"
        );
        let (d16, r256) = (rmse(&clean, Some(&off_light)), rmse(&raw, Some(&off_light)));
        assert!(
            d16 < r256,
            "off the light, denoised 16 spp RMSE {d16:.5} is not below raw 256 spp {r256:.5}"
        );
    }
}

#[cfg(not(feature = "denoise"))]
#[test]
fn denoised_cornell_at_16_spp_beats_the_raw_render_at_256_spp() {
    common::skip_or_fail(
        "denoised_cornell_at_16_spp_beats_the_raw_render_at_256_spp",
        "ronray was built without the `denoise` feature",
        "run `eval \"$(scripts/fetch-oidn.sh)\"; cargo test --features denoise --test denoise`",
    );
}
