//! Open Image Denoise (`--features denoise`): the Cornell box at 16 spp,
//! denoised with its albedo and normal layers, has less than half the raw
//! render's error against Mitsuba's reference; the raw 256 spp error is
//! printed beside it. Without the feature (the
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
    fn denoising_the_cornell_box_at_16_spp_more_than_halves_its_error() {
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
        // Measured on OIDN 2.5.1: denoised 16 spp is 0.37× the raw 16 spp
        // error off the light, but still above raw 256 spp (0.0089 against
        // 0.0059), so the "beats 256 spp" is reported, not asserted.
        let (d16, r16) = (rmse(&clean, Some(&off_light)), rmse(&noisy, Some(&off_light)));
        assert!(
            d16 < 0.5 * r16,
            "off the light, denoised 16 spp RMSE {d16:.5} is not below half the raw {r16:.5}"
        );
    }
}

#[cfg(not(feature = "denoise"))]
#[test]
fn denoising_the_cornell_box_at_16_spp_more_than_halves_its_error() {
    common::skip_or_fail(
        "denoising_the_cornell_box_at_16_spp_more_than_halves_its_error",
        "ronray was built without the `denoise` feature",
        "run `eval \"$(scripts/fetch-oidn.sh)\"; cargo test --features denoise --test denoise`",
    );
}
