//! How sure a statistic is: 95 % intervals of the error statistics by resampling whole runs
//! (each flight of each seed), the percentile bootstrap of Efron & Tibshirani (1993, ch. 13).
//!
//! The samples inside one run are strongly correlated (the error grows between packets and
//! falls at each one), so they are not resampled one by one; the runs are, which keeps every
//! run's own structure (`docs/reference.md` §12).

use super::{percentile, sort_total};
use crate::rng::Rng;
use serde::Serialize;

/// Resamples per interval: enough for the 2.5 and 97.5 percentiles to move by a small fraction
/// of the interval's width between seeds, and cheap (a whole-set run adds a few milliseconds).
pub const RESAMPLES: usize = 400;

/// 95 % intervals `[lo, hi]` of each statistic of a pooled 3D error, m, and the runs they rest on.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Intervals {
    /// Independent runs resampled (flights × seeds).
    pub runs: usize,
    /// Of the mean.
    pub mean: [f64; 2],
    /// Of the median.
    pub p50: [f64; 2],
    /// Of the 75th percentile.
    pub p75: [f64; 2],
    /// Of the 95th percentile.
    pub p95: [f64; 2],
    /// Of the largest error.
    pub max: [f64; 2],
}

impl Intervals {
    /// Whether `self`'s p75 interval lies wholly below `other`'s: a clear difference.
    pub fn p75_clearly_below(&self, other: &Intervals) -> bool {
        self.p75[1] < other.p75[0]
    }
}

/// The 95 % intervals of the statistics of `runs` pooled, each run's samples in ascending order;
/// `None` with fewer than two runs that have samples (one run cannot show its own spread).
///
/// ```
/// use loratrack::metrics::bootstrap;
/// let a = [1.0, 2.0, 3.0];
/// let b = [2.0, 4.0, 6.0];
/// let c = [1.5, 2.5, 9.0];
/// let ci = bootstrap(&[&a[..], &b[..], &c[..]], 7).unwrap();
/// assert!(ci.p75[0] <= ci.p75[1] && ci.max[1] == 9.0);
/// ```
pub fn bootstrap(runs: &[&[f64]], seed: u64) -> Option<Intervals> {
    if runs.iter().filter(|r| !r.is_empty()).count() < 2 {
        return None;
    }
    let mut all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
    sort_total(&mut all);
    bootstrap_sorted(runs, &all, seed)
}

/// [`bootstrap`] given every sample of `runs` pooled and in ascending order (`f64::total_cmp`)
/// as `all`: a caller that has already sorted the pooled errors for their summary does not
/// sort them again.
pub(crate) fn bootstrap_sorted(runs: &[&[f64]], all: &[f64], seed: u64) -> Option<Intervals> {
    let runs: Vec<&[f64]> = runs.iter().copied().filter(|r| !r.is_empty()).collect();
    if runs.len() < 2 {
        return None;
    }
    debug_assert_eq!(all.len(), runs.iter().map(|r| r.len()).sum::<usize>());
    let sums: Vec<f64> = runs.iter().map(|r| r.iter().sum()).collect();
    let ranks = Ranks::of(&runs, all);
    // The draws' weights come from one stream, in order; the draws are then independent, and
    // natively run on every core (a sweep's single station scored them on one).
    let draws = draw_weights(runs.len(), Rng::derive(seed, 0xb00_757a));
    let ranks = ranks.as_ref();
    let per_draw = crate::parallel::par_map_owned(draws, |weights| {
        Draw {
            runs: &runs,
            weights: &weights,
            all,
            ranks,
        }
        .statistics(&sums)
    });
    let mut stats: [Vec<f64>; 5] = Default::default();
    for draw in per_draw {
        for (s, v) in stats.iter_mut().zip(draw) {
            s.push(v);
        }
    }
    let [mean, p50, p75, p95, max] = stats.map(|mut s| {
        sort_total(&mut s);
        [percentile(&s, 2.5), percentile(&s, 97.5)]
    });
    Some(Intervals {
        runs: runs.len(),
        mean,
        p50,
        p75,
        p95,
        max,
    })
}

/// [`RESAMPLES`] draws of `runs` runs with replacement, from `rng`'s stream in order: how many
/// times each draw takes each run.
pub(super) fn draw_weights(runs: usize, mut rng: Rng) -> Vec<Vec<u32>> {
    (0..RESAMPLES)
        .map(|_| {
            let mut weights = vec![0u32; runs];
            for _ in 0..runs {
                let pick = (rng.uniform() * runs as f64) as usize;
                weights[pick.min(runs - 1)] += 1;
            }
            weights
        })
        .collect()
}

/// At most this many entries (4 bytes each) in a [`Ranks`] table: the whole synthetic set with
/// one seed fits every candidate (0.8 million entries); more runs keep every 2nd, 4th, …
const RANKS_BUDGET: usize = 4_000_000;

/// For every `stride`-th candidate `all[m]` and each run i, how many of the run's samples are at
/// most `all[m]`: a draw's count at such a candidate is one weighted sum instead of a binary
/// search in every run (the same integers, tested). An order statistic is bracketed between two
/// rows of the table and found within the bracket by the searches: log₂ stride of them instead of
/// log₂ of every sample.
pub(super) struct Ranks {
    runs: usize,
    stride: usize,
    rows: usize,
    counts: Vec<u32>,
}

impl Ranks {
    /// The table, with the smallest stride (a power of two) that keeps it within
    /// [`RANKS_BUDGET`]; `None` when no stride does, a run is longer than `u32` counts, or a
    /// sample is not finite (a NaN breaks the merge's order).
    pub(super) fn of(runs: &[&[f64]], all: &[f64]) -> Option<Self> {
        Self::with_budget(runs, all, RANKS_BUDGET)
    }

    fn with_budget(runs: &[&[f64]], all: &[f64], budget: usize) -> Option<Self> {
        let finite =
            all.first().is_some_and(|v| v.is_finite()) && all.last().is_some_and(|v| v.is_finite());
        if !finite || all.len() > u32::MAX as usize || runs.is_empty() || runs.len() > budget {
            return None;
        }
        let mut stride = 1;
        while (all.len() - 1) / stride + 1 > budget / runs.len() {
            stride *= 2;
        }
        let rows = (all.len() - 1) / stride + 1;
        // Row by row, each run's merge resumed where it stopped: the table (up to 16 MB) is
        // written in order. Filled run by run, each run touched one entry in every row, a cache
        // line per entry, and building it was 8 % of `npm run reproduce` (perf).
        let mut counts = vec![0u32; rows * runs.len()];
        let mut merged = vec![0usize; runs.len()];
        for (row, out) in counts.chunks_exact_mut(runs.len()).enumerate() {
            let v = all[row * stride];
            for ((j, run), count) in merged.iter_mut().zip(runs).zip(out) {
                while *j < run.len() && run[*j] <= v {
                    *j += 1;
                }
                *count = *j as u32;
            }
        }
        Some(Ranks {
            runs: runs.len(),
            stride,
            rows,
            counts,
        })
    }

    /// The samples of a draw with `weights` that are at most the candidate of `row`.
    fn count(&self, row: usize, weights: &[u32]) -> u64 {
        self.counts[row * self.runs..(row + 1) * self.runs]
            .iter()
            .zip(weights)
            .map(|(&c, &w)| u64::from(c) * u64::from(w))
            .sum()
    }

    /// The candidates `[lo, hi]` among which the first with more than `k` samples of the draw at
    /// or below it lies, from the table alone (the last candidate, `last`, has all n > k).
    fn bracket(&self, k: u64, weights: &[u32], last: usize) -> (usize, usize) {
        if self.count(self.rows - 1, weights) <= k {
            return ((self.rows - 1) * self.stride + 1, last);
        }
        let (mut lo, mut hi) = (0, self.rows - 1);
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.count(mid, weights) > k {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        let start = if lo == 0 {
            0
        } else {
            (lo - 1) * self.stride + 1
        };
        (start, lo * self.stride)
    }
}

/// One bootstrap draw: each run taken `weights[i]` times.
pub(super) struct Draw<'a> {
    pub(super) runs: &'a [&'a [f64]],
    pub(super) weights: &'a [u32],
    /// Every sample of every run, ascending (the candidates for an order statistic).
    pub(super) all: &'a [f64],
    /// The candidates' ranks in each run, when they fit in memory.
    pub(super) ranks: Option<&'a Ranks>,
}

impl Draw<'_> {
    /// The draw's mean, p50, p75, p95 and maximum; `sums` holds each run's sum.
    fn statistics(&self, sums: &[f64]) -> [f64; 5] {
        let n = self.count_at_most(f64::INFINITY);
        let sum: f64 = self
            .weights
            .iter()
            .zip(sums)
            .map(|(&w, s)| w as f64 * s)
            .sum();
        let max = self
            .runs
            .iter()
            .zip(self.weights)
            .filter(|&(_, &w)| w > 0)
            .map(|(r, _)| r[r.len() - 1])
            .fold(f64::NEG_INFINITY, f64::max);
        [
            sum / n as f64,
            self.percentile(n, 50.0),
            self.percentile(n, 75.0),
            self.percentile(n, 95.0),
            max,
        ]
    }

    /// How many samples of the draw are at most `v`.
    pub(super) fn count_at_most(&self, v: f64) -> u64 {
        self.runs
            .iter()
            .zip(self.weights)
            .filter(|&(_, &w)| w > 0)
            .map(|(r, &w)| u64::from(w) * r.partition_point(|x| *x <= v) as u64)
            .sum()
    }

    /// The `k`-th smallest sample of the draw (0-based), by bisection over the sorted candidates:
    /// the smallest candidate with more than `k` samples at or below it.
    fn order_statistic(&self, k: u64) -> f64 {
        let last = self.all.len() - 1;
        let (mut lo, mut hi) = match self.ranks {
            Some(r) => r.bracket(k, self.weights, last),
            None => (0, last),
        };
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.count_at_most(self.all[mid]) > k {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        self.all[lo]
    }

    /// The `p`-th percentile of the draw's `n` samples, interpolated as [`percentile`] does.
    pub(super) fn percentile(&self, n: u64, p: f64) -> f64 {
        let rank = p / 100.0 * (n - 1) as f64;
        let lo = rank.floor() as u64;
        let a = self.order_statistic(lo);
        let b = self.order_statistic((lo + 1).min(n - 1));
        a + (rank - lo as f64) * (b - a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sorted(mut v: Vec<f64>) -> Vec<f64> {
        v.sort_unstable_by(f64::total_cmp);
        v
    }

    #[test]
    fn a_draw_of_every_run_once_gives_the_pooled_percentiles() {
        let a = sorted(vec![3.0, 1.0, 7.0, 2.0]);
        let b = sorted(vec![5.0, 0.5, 4.0]);
        let runs = [&a[..], &b[..]];
        let mut all: Vec<f64> = a.iter().chain(&b).copied().collect();
        all.sort_unstable_by(f64::total_cmp);
        let draw = Draw {
            runs: &runs,
            weights: &[1, 1],
            all: &all,
            ranks: None,
        };
        for p in [0.0, 50.0, 75.0, 95.0, 100.0] {
            assert_eq!(draw.percentile(7, p), percentile(&all, p), "p{p}");
        }
        // Taking the second run twice counts its samples twice.
        let twice = Draw {
            runs: &runs,
            weights: &[0, 2],
            all: &all,
            ranks: None,
        };
        assert_eq!(twice.count_at_most(4.0), 4);
        assert_eq!(twice.order_statistic(5), 5.0);
    }

    #[test]
    fn the_rank_table_gives_the_searches_order_statistics() {
        // Runs with ties inside and across them, of different lengths.
        let runs: Vec<Vec<f64>> = (0..7)
            .map(|k| {
                sorted(
                    (0..40 + 3 * k)
                        .map(|i| f64::from((i * 7 + k * 3) % 23))
                        .collect(),
                )
            })
            .collect();
        let refs: Vec<&[f64]> = runs.iter().map(Vec::as_slice).collect();
        let all = sorted(runs.concat());
        // Every candidate, then (a small budget) every 2nd, 4th, … with searches in the brackets.
        for budget in [RANKS_BUDGET, 7 * 100, 7 * 20, 7 * 3, 7] {
            let table = Ranks::with_budget(&refs, &all, budget).unwrap();
            assert!(table.counts.len() <= budget);
            for weights in [
                [1, 1, 1, 1, 1, 1, 1],
                [0, 3, 0, 2, 1, 0, 1],
                [7, 0, 0, 0, 0, 0, 0],
            ] {
                let draw = |ranks| Draw {
                    runs: &refs,
                    weights: &weights,
                    all: &all,
                    ranks,
                };
                let (with, without) = (draw(Some(&table)), draw(None));
                let n = without.count_at_most(f64::INFINITY);
                for k in 0..n {
                    assert_eq!(
                        with.order_statistic(k),
                        without.order_statistic(k),
                        "budget {budget}, k {k}"
                    );
                }
            }
        }
        // Not finite, or more runs than the budget: no table.
        assert!(Ranks::of(&refs, &[f64::NAN]).is_none());
        assert!(Ranks::with_budget(&refs, &all, 6).is_none());
    }

    #[test]
    fn one_run_has_no_interval() {
        let a = [1.0, 2.0];
        assert!(bootstrap(&[&a[..]], 1).is_none());
        assert!(bootstrap(&[&a[..], &[][..]], 1).is_none());
    }

    #[test]
    fn runs_alike_give_a_narrow_interval_and_runs_apart_a_wide_one() {
        let grid = |scale: f64| sorted((0..200).map(|i| scale * f64::from(i) / 200.0).collect());
        let alike: Vec<Vec<f64>> = (0..10).map(|k| grid(1.0 + 0.01 * f64::from(k))).collect();
        let apart: Vec<Vec<f64>> = (0..10).map(|k| grid(1.0 + f64::from(k))).collect();
        fn refs(v: &[Vec<f64>]) -> Vec<&[f64]> {
            v.iter().map(Vec::as_slice).collect()
        }
        let narrow = bootstrap(&refs(&alike), 1).unwrap();
        let wide = bootstrap(&refs(&apart), 1).unwrap();
        let width = |c: &Intervals| c.p75[1] - c.p75[0];
        assert!(width(&narrow) < 0.05, "{narrow:?}");
        assert!(width(&wide) > 1.0, "{wide:?}");
        assert_eq!(narrow.runs, 10);
        // The pooled p75 of the runs lies inside its interval.
        let pooled = sorted(alike.concat());
        let p75 = percentile(&pooled, 75.0);
        assert!(narrow.p75[0] <= p75 && p75 <= narrow.p75[1]);
    }

    #[test]
    fn the_same_seed_gives_the_same_interval() {
        let runs: Vec<Vec<f64>> = (1..6).map(|k| sorted(vec![f64::from(k); 5])).collect();
        let refs: Vec<&[f64]> = runs.iter().map(Vec::as_slice).collect();
        assert_eq!(bootstrap(&refs, 3), bootstrap(&refs, 3));
    }

    #[test]
    fn separated_intervals_are_a_clear_difference() {
        let low = Intervals {
            runs: 2,
            mean: [0.0; 2],
            p50: [0.0; 2],
            p75: [1.0, 2.0],
            p95: [0.0; 2],
            max: [0.0; 2],
        };
        let high = Intervals {
            p75: [2.5, 3.0],
            ..low
        };
        let overlapping = Intervals {
            p75: [1.5, 3.0],
            ..low
        };
        assert!(low.p75_clearly_below(&high));
        assert!(!low.p75_clearly_below(&overlapping));
    }
}
