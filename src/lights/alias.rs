//! Walker's alias method (Vose's construction): one uniform number picks an
//! entry of a discrete distribution in O(1), whatever its size. Emissive
//! meshes pick a triangle by area with it, and sky maps a cell
//! (`env_table.rs`, through [`fill_bins`] and [`pick`] on flat arrays of
//! [`Bin`]s, one table per row).
//!
//! Vose, "A linear algorithm for generating random numbers with a given
//! distribution", IEEE TSE 1991; pbrt-v4 §A.1.4
//! (<https://pbr-book.org/4ed/Sampling_Algorithms/The_Alias_Method>).

/// One bin: keep its own entry with probability `keep`, else go to `alias`.
#[derive(Clone, Copy, Debug)]
pub struct Bin {
    keep: f32,
    alias: u32,
}

/// A placeholder until [`fill_bins`] writes every bin.
impl Default for Bin {
    fn default() -> Self {
        Bin { keep: 1.0, alias: 0 }
    }
}

/// Fills `bins` with the alias table of `scaled`: each entry's probability
/// times the entry count (they sum to the count; every one finite and
/// ≥ 0). Consumes `scaled`.
pub fn fill_bins(mut scaled: Vec<f64>, bins: &mut [Bin]) {
    debug_assert_eq!(scaled.len(), bins.len());
    let n = bins.len();
    // Bins below 1 are filled up from bins above.
    let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| scaled[i] < 1.0);
    while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
        small.pop();
        bins[s] = Bin {
            keep: scaled[s] as f32,
            alias: l as u32,
        };
        // The large entry gives away what the small one lacked.
        scaled[l] -= 1.0 - scaled[s];
        if scaled[l] < 1.0 {
            large.pop();
            small.push(l);
        }
    }
    // What is left is 1 up to rounding.
    for i in small.into_iter().chain(large) {
        bins[i] = Bin {
            keep: 1.0,
            alias: i as u32,
        };
    }
}

/// The entry of the table `bins` (not empty) for `u` ∈ [0, 1), and `u`
/// remapped to a fresh uniform number in [0, 1) (the part of `u` the
/// choice did not use): one load, no search.
#[inline]
pub fn pick(bins: &[Bin], u: f32) -> (usize, f32) {
    let n = bins.len();
    debug_assert!(n > 0, "sampling an empty alias table");
    let x = u * n as f32;
    let i = (x as usize).min(n - 1);
    let frac = (x - i as f32).clamp(0.0, 1.0);
    let b = bins[i];
    // Both outcomes' numbers, then one choice: the comparison goes either
    // way at random, so no branch is left for it to mispredict (no change
    // in time measured on `env_spheres`, where the entry's load is what
    // waits). The same operations, and numbers, as the branch.
    let keep = frac < b.keep;
    let k = if keep { i } else { b.alias as usize };
    let (num, den) = if keep {
        (frac, b.keep)
    } else {
        (frac - b.keep, 1.0 - b.keep)
    };
    (k, (num / den).min(1.0 - f32::EPSILON / 2.0))
}

/// A discrete distribution over `0..n` sampled in constant time; 8 bytes per entry
/// plus 4 for its probability.
#[derive(Clone, Debug, Default)]
pub struct AliasTable {
    bins: Vec<Bin>,
    /// Normalised probability of each entry.
    pmf: Vec<f32>,
}

impl AliasTable {
    /// The distribution proportional to `weights` (≥ 0, finite). All zero (or
    /// empty) gives the uniform distribution over the entries.
    pub fn new(weights: &[f32]) -> Self {
        let n = weights.len();
        let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
        let pmf: Vec<f32> = if total > 0.0 {
            weights
                .iter()
                .map(|&w| (w.max(0.0) as f64 / total) as f32)
                .collect()
        } else {
            vec![1.0 / n.max(1) as f32; n]
        };
        // Scaled probabilities n·p.
        let scaled: Vec<f64> = pmf.iter().map(|&p| p as f64 * n as f64).collect();
        let mut bins = vec![Bin::default(); n];
        fill_bins(scaled, &mut bins);
        Self { bins, pmf }
    }

    /// An entry for `u` ∈ [0, 1), its probability, and `u` remapped to a fresh
    /// uniform number in [0, 1) (the part of `u` the choice did not use).
    #[inline]
    pub fn sample(&self, u: f32) -> (usize, f32, f32) {
        let (k, rest) = pick(&self.bins, u);
        (k, self.pmf[k], rest)
    }

    /// Probability of entry `i`.
    #[inline]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf[i]
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.bins.len()
    }

    /// Whether the table has no entries.
    pub fn is_empty(&self) -> bool {
        self.bins.is_empty()
    }

    /// Heap bytes of the table.
    pub fn bytes(&self) -> usize {
        self.bins.len() * std::mem::size_of::<Bin>() + self.pmf.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alias_table_frequencies_follow_the_weights() {
        let w = [1.0, 0.0, 3.0, 0.5, 5.5];
        let t = AliasTable::new(&w);
        let n = 200_000;
        let mut counts = [0u32; 5];
        let mut rest_sum = 0.0f64;
        for k in 0..n {
            let (i, p, rest) = t.sample((k as f32 + 0.5) / n as f32);
            assert!((p - t.pmf(i)).abs() < 1e-7);
            assert!((0.0..1.0).contains(&rest), "remapped {rest}");
            rest_sum += rest as f64;
            counts[i] += 1;
        }
        for (i, &c) in counts.iter().enumerate() {
            let want = w[i] / 10.0;
            let got = c as f32 / n as f32;
            assert!((got - want).abs() < 1e-3, "entry {i}: {got} vs {want}");
        }
        assert!(
            (rest_sum / n as f64 - 0.5).abs() < 1e-3,
            "remapped numbers are uniform"
        );
    }

    /// A number at the very top of the last bin (`u = 1`, just outside the
    /// documented range) stays in it: every bin [`fill_bins`] writes names
    /// an entry that exists, its own when it keeps everything.
    #[test]
    fn the_top_of_the_last_bin_stays_in_it() {
        for n in [1usize, 7, 512] {
            let mut bins = vec![Bin::default(); n];
            fill_bins(vec![1.0; n], &mut bins);
            let (k, rest) = pick(&bins, 1.0);
            assert_eq!(k, n - 1, "{n} bins");
            assert!((0.0..1.0).contains(&rest), "{n} bins: rest {rest}");
        }
    }

    #[test]
    fn alias_table_of_zeros_is_uniform() {
        let t = AliasTable::new(&[0.0, 0.0]);
        assert_eq!(t.pmf(0), 0.5);
        assert_eq!(t.sample(0.75).0, 1);
    }
}
