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
mod layers;
mod pass;

pub use albedo::first_hit_albedo;
pub use layers::AovLayers;
pub use pass::render_aovs;

/// One AOV layer (the runtime twin of [`crate::desc::AovDesc`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aov {
    /// Reflectance at the first hit, in [0, 1] (`albedo.R/G/B`).
    Albedo,
    /// World-space shading normal facing the camera (`N.X/Y/Z`).
    Normal,
    /// Distance along the camera ray to the first hit (`Z`).
    Depth,
    /// World-space first-hit position (`P.X/Y/Z`).
    Position,
    /// 1 + the first hit's material index, 0 for no surface (`materialId`).
    MaterialIndex,
}

impl Aov {
    /// Every layer, in the order they are listed in the README.
    pub const ALL: [Aov; 5] = [
        Aov::Albedo,
        Aov::Normal,
        Aov::Depth,
        Aov::Position,
        Aov::MaterialIndex,
    ];

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// A set of layers, small and `Copy` so that [`crate::view::Film`] stays so.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AovSet(u8);

impl AovSet {
    /// No layers: the beauty pass only.
    pub const EMPTY: AovSet = AovSet(0);

    /// This set with `aov` added.
    pub fn with(self, aov: Aov) -> Self {
        AovSet(self.0 | aov.bit())
    }

    /// Whether `aov` is in the set.
    pub fn contains(self, aov: Aov) -> bool {
        self.0 & aov.bit() != 0
    }

    /// Whether no layer is asked for.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The layers in the set, in [`Aov::ALL`] order.
    pub fn iter(self) -> impl Iterator<Item = Aov> {
        Aov::ALL.into_iter().filter(move |a| self.contains(*a))
    }
}

impl FromIterator<Aov> for AovSet {
    fn from_iter<I: IntoIterator<Item = Aov>>(iter: I) -> Self {
        iter.into_iter().fold(AovSet::EMPTY, AovSet::with)
    }
}

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
