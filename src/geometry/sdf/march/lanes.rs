//! The estimate march of a lone power-8 Mandelbulb, four points per SIMD
//! evaluation ([`Sdf::local_distance_x4`]).
//!
//! Why: one estimate is a long chain of dependent square roots and
//! divisions, so a scalar march waits on it at every step; four lanes cost
//! about the latency of one. Lane 0 is the point the scalar march would
//! visit next; lanes 1–3 continue with steps *guessed* from the ratio of
//! the last two distances (a ray approaching or leaving a surface sees
//! them shrink or grow by a near-constant factor, `1 ∓ ω cos α`), a little
//! short of it. A guessed step counts only if it is no longer than the step
//! the estimate at its start allows (`ω d`, and the interval's end), so the
//! lanes taken are a valid sphere-tracing march, step for step no longer
//! than the scalar one's; the first refused lane and those after it are
//! dropped and the march goes on from the last lane taken, by the step its
//! estimate allows. Every point taken goes through the same tests as in
//! [`super::trace`] and [`super::occluded`] (hit threshold, overshoot,
//! ball past the end), so hits agree within the threshold; the points
//! visited differ, so hits move within it and the fractal's sub-pixel
//! detail shades a little differently (measured in `docs/benchmarks.md`).

use super::{MarchParams, SdfTrace, bisect};
use crate::geometry::sdf::tree::Sdf;
use crate::math::Ray;

/// Guessed distances are this fraction of the extrapolated ones: a guess a
/// little short is taken, one a little long is wasted with the lanes after it.
/// With [`FIRST_RATIO`], chosen by counting SIMD rounds (the march's latency)
/// on `scenes/mandelbulb.ron` at 512×512: 8.00 M rounds at (0.85 compounded
/// per lane, 0.5), 7.53 M here; 0.95 wastes lanes (8.75 M).
const SHORTFALL: f32 = 0.8;
/// Distance ratio assumed before two distances are known.
const FIRST_RATIO: f32 = 0.7;
/// The first round's guessed distance at the start, in hit thresholds, and
/// its growth from lane to lane (a ray leaving a surface): 8.26 M rounds
/// and first estimates → 8.06 M on `scenes/mandelbulb.ron` at 512×512,
/// against a scalar first estimate.
const FIRST_GUESS: f32 = 16.0;
const FIRST_GROWTH: f32 = 2.0;
/// Range of the extrapolated ratio (a ray leaving a surface head-on sees
/// `1 + ω`; one reaching a flat one, `1 − ω`).
const RATIO_RANGE: (f32, f32) = (1.0 / 64.0, 2.0);

/// What a visited point decides: the march ends, or may step on by at most
/// this distance along the ray.
enum Visit {
    Done(SdfTrace),
    Step(f32),
}

/// [`super::trace`] for a distance estimate with lanes
/// ([`Sdf::has_lanes`]); `local` is the ray in the tree's local space.
pub(super) fn trace(
    sdf: &Sdf,
    local: &Ray,
    (t_start, t_end): (f32, f32),
    inv_len: f32,
    params: &MarchParams,
) -> SdfTrace {
    let omega = params.estimate_step;
    // Along-ray distances are `t · len`: a multiplication per point, not a
    // division.
    let len = inv_len.recip();
    walk(
        sdf,
        local,
        (t_start, 1.0),
        (inv_len, omega),
        (params.max_steps, params.eps_at(t_start * len)),
        |t, d, side, step_in, steps| {
            let eps = params.eps_at(t * len);
            if d.abs() < eps {
                return Visit::Done(SdfTrace {
                    hit: Some(t.clamp(t_start, t_end)),
                    steps,
                });
            }
            if d < 0.0 {
                // Overshot: bisect the step that led here down to eps.
                let (outside, steps) = bisect(
                    sdf,
                    local,
                    side,
                    (t - step_in * inv_len, t),
                    eps * inv_len,
                    (steps, params.max_steps),
                );
                return Visit::Done(SdfTrace {
                    hit: Some(outside.clamp(t_start, t_end)),
                    steps,
                });
            }
            if t + d * inv_len > t_end {
                return Visit::Done(SdfTrace { hit: None, steps });
            }
            Visit::Step((d * omega).min((t_end - t) * len))
        },
    )
}

/// [`super::occluded`]'s backward march for a distance estimate with lanes.
pub(super) fn occluded(
    sdf: &Sdf,
    local: &Ray,
    (t_start, t_end): (f32, f32),
    inv_len: f32,
    params: &MarchParams,
) -> SdfTrace {
    let omega = params.estimate_step;
    let len = inv_len.recip();
    walk(
        sdf,
        local,
        (t_end, -1.0),
        (inv_len, omega),
        (params.max_steps, params.eps_at(t_end * len)),
        |t, d, _, _, steps| {
            if d < params.eps_at(t * len) {
                return Visit::Done(SdfTrace { hit: Some(t), steps });
            }
            let ball = d * omega;
            if t - ball * inv_len < t_start {
                return Visit::Done(SdfTrace { hit: None, steps });
            }
            Visit::Step(ball)
        },
    )
}

/// Marches from `t0` in direction `dir` (±1 along the ray), calling `visit`
/// at each point taken with `(t, d, side, step_in, steps)`: the distance
/// `d` signed so that the start is outside (`side` is that sign), and the
/// step that led to `t`. Guessed steps are `omega` times guessed distances.
fn walk(
    sdf: &Sdf,
    local: &Ray,
    (t0, dir): (f32, f32),
    (inv_len, omega): (f32, f32),
    (max_steps, eps_at_start): (u32, f32),
    mut visit: impl FnMut(f32, f32, f32, f32, u32) -> Visit,
) -> SdfTrace {
    // No distance yet to extrapolate from: the first round has lane 0 at
    // `t0` and guesses a start [`FIRST_GUESS`] thresholds from a surface,
    // moving away from it. A wrong guess costs nothing but its lanes.
    let (mut t, mut step, mut steps) = (t0, 0.0f32, 0u32);
    let mut d = FIRST_GUESS * eps_at_start;
    let mut ratio = FIRST_GROWTH;
    let mut d_before = d;
    let mut side = 0.0f32;
    loop {
        // Lane 0 steps as the scalar march would; lanes 1–3 guess.
        let mut ts = [t + dir * step * inv_len; 4];
        let mut steps_in = [step; 4];
        let mut guess = d * SHORTFALL;
        for j in 1..4 {
            guess *= ratio;
            steps_in[j] = omega * guess;
            ts[j] = ts[j - 1] + dir * steps_in[j] * inv_len;
        }
        let ds = sdf.local_distance_x4(ts.map(|t| local.at(t)));
        for j in 0..4 {
            if steps >= max_steps {
                return SdfTrace {
                    hit: None,
                    steps: max_steps,
                };
            }
            steps += 1;
            if steps == 1 {
                // Started inside: march toward the exit.
                side = if ds[0] < 0.0 { -1.0 } else { 1.0 };
            }
            let dj = ds[j] * side;
            match visit(ts[j], dj, side, steps_in[j], steps) {
                Visit::Done(r) => return r,
                Visit::Step(s) => {
                    (d_before, t, d, step) = (d, ts[j], dj, s);
                    if j == 3 || steps_in[j + 1] > s {
                        break;
                    }
                }
            }
        }
        // One division a round: only the last two points taken guess on
        // (after the first point alone, a plain guess).
        ratio = if steps == 1 {
            FIRST_RATIO
        } else {
            (d / d_before).clamp(RATIO_RANGE.0, RATIO_RANGE.1)
        };
    }
}
