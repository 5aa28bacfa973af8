//! The CPU features this binary was compiled to use, checked against the
//! CPU it runs on. `.cargo/config.toml` compiles for x86-64-v3 (AVX2, FMA),
//! and a build for the machine itself (`RUSTFLAGS="-C target-cpu=native"`,
//! `CPU=native tools/pgo-build.sh`) may use AVX-512: such a binary copied to
//! an older machine (a render-farm node, say) would die on its first such
//! instruction with a bare "Illegal instruction". `main` asks
//! [`missing_features`] first and says what is missing and how to rebuild.

/// The instruction-set extensions this binary was compiled for that the
/// running CPU lacks; empty when it can run here. Only x86-64 levels are
/// checked (other architectures: always empty).
///
/// Kept out of line and free of anything but detection calls and a
/// small `Vec`, so it runs before any AVX-512 code: an AVX-512 build on an
/// AVX2 machine reports here. It is still compiled at the build's level,
/// so an x86-64-v3 build on a CPU without AVX at all may fault in it.
#[inline(never)]
pub fn missing_features() -> Vec<&'static str> {
    #[allow(unused_mut)]
    let mut missing = Vec::new();
    #[cfg(target_arch = "x86_64")]
    {
        macro_rules! check {
            ($($f:tt),*) => {
                $(
                    if cfg!(target_feature = $f) && !std::arch::is_x86_feature_detected!($f) {
                        missing.push($f);
                    }
                )*
            };
        }
        check!(
            "sse3", "ssse3", "sse4.1", "sse4.2", "popcnt", "avx", "avx2", "fma", "bmi1", "bmi2", "lzcnt",
            "movbe", "f16c", "avx512f", "avx512cd", "avx512bw", "avx512dq", "avx512vl"
        );
    }
    missing
}

/// Asks the CPU for the cache line holding `p`, ahead of a load that will
/// need it (the traversal's next nodes, a sky map's table entry). `p` need
/// not be a valid address: a prefetch never faults, and nothing is read.
/// A no-op on other architectures.
#[inline(always)]
pub(crate) fn prefetch_line(p: *const u8) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE is part of x86-64; a prefetch never faults.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(p.cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = p;
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Tests run on the machine that compiled them: nothing can be missing
    /// (and the macro's `cfg!` sees the features the build enabled).
    #[test]
    fn the_build_machine_has_every_feature_compiled_for() {
        assert_eq!(missing_features(), Vec::<&str>::new());
        #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
        assert!(std::arch::is_x86_feature_detected!("avx2"));
    }
}
