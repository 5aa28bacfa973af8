//! Arbitrary output variables: first-hit layers written beside the beauty
//! pass (albedo, shading normal, depth, position, material index) and fed to
//! the denoiser.
//!
//! They come from their own pass ([`render_aovs`]) that traces the same
//! camera rays as the beauty pass (same sampler stream per pixel and sample)
//! but only to the first hit, so the beauty render loop is untouched and
//! costs nothing more when no layer is asked for. Each pixel's samples are
//! reduced in sample order on one thread, so the layers are identical
//! whatever the thread count.

mod albedo;
mod exr;
mod layers;
mod pass;

pub use crate::view::{Aov, AovSet};
pub use albedo::first_hit_albedo;
pub use exr::write_exr_layers;
pub use layers::AovLayers;
pub use pass::render_aovs;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_holds_exactly_what_was_added() {
        let s: AovSet = [Aov::Depth, Aov::Albedo, Aov::Depth].into_iter().collect();
        assert_eq!(s.iter().collect::<Vec<_>>(), vec![Aov::Albedo, Aov::Depth]);
        assert!(!s.contains(Aov::Normal) && !s.is_empty());
        assert!(AovSet::EMPTY.is_empty());
    }
}
