//! The path loop computes on no denormal floats. An x86 operation with a
//! denormal operand or result takes a microcode assist of a hundred cycles
//! or more; LLVM had packed the concentric map's point into a register
//! whose upper lanes were left over from earlier work and ran the arithmetic
//! on all four lanes, and leftover integer bits read as denormals: 40% of
//! the Cornell box's diffuse bounces took assists, 4–5% of its wall time in
//! alternated pairs (`src/math/sampling.rs`). MXCSR's sticky flags record any such operation
//! on the thread, so the test runs camera samples of the shipped reference
//! twins on its own thread and reads them.

#![cfg(target_arch = "x86_64")]

use ronray::integrators::Counters;
use ronray::sampler::{Sampler, SamplerKind};
use std::path::Path;

/// MXCSR's denormal-operand (DE) and underflow (UE) flags.
const DENORMAL_FLAGS: u32 = 0x2 | 0x10;

fn mxcsr() -> u32 {
    let mut v = 0u32;
    // SAFETY: stores the 32-bit MXCSR into `v`, which is writable.
    unsafe { std::arch::asm!("stmxcsr [{}]", in(reg) &mut v, options(nostack)) };
    v
}

/// Clears the six sticky exception flags, leaving every mode bit as it is.
fn clear_flags() {
    let v = mxcsr() & !0x3f;
    // SAFETY: loads MXCSR with its own mode bits and the flags cleared.
    unsafe { std::arch::asm!("ldmxcsr [{}]", in(reg) &v, options(nostack, readonly)) };
}

#[test]
fn reference_twins_render_without_denormal_arithmetic() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in [
        "cornell",
        "cornell_dof",
        "cornell_specular",
        "emissive_shapes",
        "env_spheres",
    ] {
        let l = ronray::load::load(&dir.join(format!("{name}.ron"))).expect("shipped scene loads");
        let (w, h) = (l.view.film.width, l.view.film.height);
        let mut counters = Counters::default();
        let mut sum = 0.0f32;
        clear_flags();
        for y in (0..h).step_by(8) {
            for x in (0..w).step_by(8) {
                for i in 0..4 {
                    let mut s = Sampler::new(SamplerKind::Independent, x, y, i, 4, 7);
                    let (ray, _) = l.view.camera_ray(x, y, &mut s);
                    let li = l.view.integrator.li(&l.scene, &ray, &mut s, &mut counters);
                    sum += std::hint::black_box(li).max_element();
                }
            }
        }
        let flags = mxcsr() & DENORMAL_FLAGS;
        assert!(sum > 0.0, "{name}: the samples saw light");
        assert_eq!(
            flags, 0,
            "{name}: the path loop operated on denormal floats (MXCSR flags {flags:#x})"
        );
    }
}
