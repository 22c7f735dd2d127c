//! How sure a difference between two stations is: the ratio of their p75s (or p95s), with a 95 %
//! interval from resampling the runs both were scored on together (a paired percentile bootstrap;
//! Efron & Tibshirani 1993, ch. 13; `docs/reference.md` §12).
//!
//! Stations of one run fly the same flights with the same seeds, so much of their errors' spread
//! is shared: a hard flight is hard for every station. Intervals of each station alone carry that
//! shared spread, and asking that they do not overlap misses differences the runs show plainly.
//! Every station of a run is resampled with the same draws (they follow from the seed and the
//! number of runs alone), so each station's p75 in each draw can be computed apart, by whichever
//! worker ran that station, and the draws paired afterwards: the ratio's interval holds only
//! what differs between the stations.

use super::bootstrap::{draw_weights, Draw, Ranks};
use super::whole_flight_draws::{SeedSpan, WholeFlightDraws};
use super::{percentile, sort_total};
use crate::rng::Rng;
use serde::{Deserialize, Serialize};

/// A station's p75 and p95 (m) in each of the [`RESAMPLES`](super::RESAMPLES) bootstrap draws
/// of its runs, drawn alike for every station of the run (the same seed, the same number of
/// runs).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Draws {
    /// The seed the draws were made from (the run's own).
    pub seed: u64,
    /// Runs drawn from (flights × seeds), runs without errors included.
    pub runs: usize,
    /// The p75 of each draw, m; `null` (NaN) where a draw holds none of the station's errors.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "(number | null)[]"))]
    #[serde(deserialize_with = "nan_for_null")]
    pub p75: Vec<f64>,
    /// The p95 of each draw, m, likewise.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "(number | null)[]"))]
    #[serde(deserialize_with = "nan_for_null")]
    pub p95: Vec<f64>,
}

/// Numbers with `null` read as NaN: JSON writes a NaN as `null`, and reading it back must not
/// refuse the draws.
fn nan_for_null<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
    let values: Vec<Option<f64>> = Deserialize::deserialize(d)?;
    Ok(values.into_iter().map(|v| v.unwrap_or(f64::NAN)).collect())
}

impl Draws {
    /// The draws of a station whose errors in run i are `runs[i]`, ascending (run i the same
    /// flight and seed for every station); `seed` draws the resamples. `None` with errors in
    /// fewer than two runs: one run cannot show its own spread.
    ///
    /// ```
    /// use loratrack::metrics::Draws;
    /// // Three runs; the second station's errors are the first's doubled, run by run.
    /// let a: [&[f64]; 3] = [&[1.0, 2.0], &[4.0, 8.0], &[2.0, 3.0]];
    /// let b: [&[f64]; 3] = [&[2.0, 4.0], &[8.0, 16.0], &[4.0, 6.0]];
    /// let (a, b) = (Draws::of(&a, 1).unwrap(), Draws::of(&b, 1).unwrap());
    /// // However the runs are drawn, b's percentiles are twice a's: the shared spread cancels.
    /// assert_eq!(b.p75_ratio_interval(&a), Some([2.0, 2.0]));
    /// assert_eq!(b.p95_ratio_interval(&a), Some([2.0, 2.0]));
    /// ```
    pub fn of(runs: &[&[f64]], seed: u64) -> Option<Self> {
        let mut all: Vec<f64> = runs.iter().flat_map(|r| r.iter().copied()).collect();
        sort_total(&mut all);
        Self::of_ranked(runs, &all, Ranks::of(runs, &all).as_ref(), seed)
    }

    /// [`Self::of`] given every error of `runs` pooled and in ascending order (`f64::total_cmp`)
    /// as `all`, and their rank table where it fits ([`station_draws`] builds it once for these
    /// and the whole-flight draws).
    fn of_ranked(runs: &[&[f64]], all: &[f64], ranks: Option<&Ranks>, seed: u64) -> Option<Self> {
        if runs.iter().filter(|r| !r.is_empty()).count() < 2 {
            return None;
        }
        debug_assert_eq!(all.len(), runs.iter().map(|r| r.len()).sum::<usize>());
        // As the intervals' draws (`bootstrap`): drawn from one stream in order, then computed
        // on every core.
        let draws = draw_weights(runs.len(), Rng::derive(seed, 0x9a1_7ed));
        let stats = crate::parallel::par_map_owned(draws, |weights| {
            let draw = Draw {
                runs,
                weights: &weights,
                all,
                ranks,
            };
            match draw.count_at_most(f64::INFINITY) {
                0 => [f64::NAN; 2],
                n => [draw.percentile(n, 75.0), draw.percentile(n, 95.0)],
            }
        });
        Some(Draws {
            seed,
            runs: runs.len(),
            p75: stats.iter().map(|s| s[0]).collect(),
            p95: stats.iter().map(|s| s[1]).collect(),
        })
    }

    /// The 95 % interval of this station's p75 over `other`'s, draw by draw; `None` where the
    /// two were not drawn alike (another seed or number of runs), or no draw holds both.
    pub fn p75_ratio_interval(&self, other: &Draws) -> Option<[f64; 2]> {
        self.ratio_interval(other, &self.p75, &other.p75)
    }

    /// The 95 % interval of this station's p95 over `other`'s, likewise.
    pub fn p95_ratio_interval(&self, other: &Draws) -> Option<[f64; 2]> {
        self.ratio_interval(other, &self.p95, &other.p95)
    }

    /// The 2.5th to the 97.5th percentile of the ratios `mine[i] / theirs[i]` of the draws that
    /// hold both stations.
    fn ratio_interval(&self, other: &Draws, mine: &[f64], theirs: &[f64]) -> Option<[f64; 2]> {
        if (self.seed, self.runs) != (other.seed, other.runs) || mine.len() != theirs.len() {
            return None;
        }
        let mut ratios: Vec<f64> = mine
            .iter()
            .zip(theirs)
            .map(|(a, b)| a / b)
            .filter(|r| r.is_finite())
            .collect();
        if ratios.is_empty() {
            return None;
        }
        sort_total(&mut ratios);
        Some([percentile(&ratios, 2.5), percentile(&ratios, 97.5)])
    }
}

/// A station's paired draws of its flight runs ([`Draws`]) and of its seeds
/// ([`WholeFlightDraws`]), from one rank table: both resample the same runs and errors (`runs`,
/// each ascending; `all`, every error pooled and ascending), the second with each run's
/// `untracked` evaluation times and `seeds`' spans of runs. `(None, None)` with errors in fewer
/// than two runs.
pub(crate) fn station_draws(
    runs: &[&[f64]],
    all: &[f64],
    untracked: &[usize],
    seeds: &[SeedSpan],
    seed: u64,
) -> (Option<Draws>, Option<WholeFlightDraws>) {
    if runs.iter().filter(|r| !r.is_empty()).count() < 2 {
        return (None, None);
    }
    let ranks = Ranks::of(runs, all);
    (
        Draws::of_ranked(runs, all, ranks.as_ref(), seed),
        WholeFlightDraws::of_ranked(runs, all, ranks.as_ref(), untracked, seeds, seed),
    )
}

/// The ratio of the means of `mine` and `theirs`, one number each per run (a swarm's median
/// drone's p75 per seed under two senders, say), with a 95 % interval from resampling the runs
/// together (the pairs kept whole, [`RESAMPLES`](super::RESAMPLES) draws made from `seed`):
/// `(ratio, [lo, hi])`. `None` for fewer than two pairs, unequal lengths, or a number that is not
/// finite.
///
/// ```
/// use loratrack::metrics::mean_ratio_interval;
/// // Every run's second number is its first doubled: the runs' spread cancels.
/// let (ratio, interval) = mean_ratio_interval(&[2.0, 8.0, 40.0], &[1.0, 4.0, 20.0], 1).unwrap();
/// assert_eq!((ratio, interval), (2.0, [2.0, 2.0]));
/// ```
pub fn mean_ratio_interval(mine: &[f64], theirs: &[f64], seed: u64) -> Option<(f64, [f64; 2])> {
    let finite = |xs: &[f64]| xs.iter().all(|x| x.is_finite());
    if mine.len() != theirs.len() || mine.len() < 2 || !finite(mine) || !finite(theirs) {
        return None;
    }
    let weighted = |xs: &[f64], weights: &[u32]| -> f64 {
        xs.iter().zip(weights).map(|(x, &w)| x * f64::from(w)).sum()
    };
    let mut ratios: Vec<f64> = draw_weights(mine.len(), Rng::derive(seed, 0x3ea_4a71))
        .iter()
        .map(|w| weighted(mine, w) / weighted(theirs, w))
        .filter(|r| r.is_finite())
        .collect();
    let ratio = mine.iter().sum::<f64>() / theirs.iter().sum::<f64>();
    if ratios.is_empty() || !ratio.is_finite() {
        return None;
    }
    sort_total(&mut ratios);
    Some((ratio, [percentile(&ratios, 2.5), percentile(&ratios, 97.5)]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::bootstrap;

    #[test]
    fn mean_ratio_interval_holds_the_ratio_and_narrows_where_the_runs_agree() {
        // Runs of very different difficulty, the first number 0.9x the second in each, give
        // an interval that holds 0.9 and is narrow; the same means with the pairs shuffled
        // apart give a wide one.
        let theirs = [10.0, 100.0, 1000.0, 30.0, 300.0, 3.0, 50.0, 500.0];
        let paired: Vec<f64> = theirs.iter().map(|t| 0.9 * t).collect();
        let (ratio, [lo, hi]) = mean_ratio_interval(&paired, &theirs, 7).unwrap();
        assert!((ratio - 0.9).abs() < 1e-12 && lo <= 0.9 + 1e-12 && hi >= 0.9 - 1e-12);
        assert!(hi - lo < 1e-9, "{lo}..{hi}");
        let mut shuffled = paired.clone();
        shuffled.rotate_left(3);
        let (same, [lo, hi]) = mean_ratio_interval(&shuffled, &theirs, 7).unwrap();
        assert!((same - ratio).abs() < 1e-12);
        assert!(lo < 0.9 && hi > 0.9 && hi - lo > 0.5, "{lo}..{hi}");
    }

    #[test]
    fn mean_ratio_interval_refuses_what_it_cannot_pair() {
        assert_eq!(mean_ratio_interval(&[1.0], &[2.0], 1), None);
        assert_eq!(mean_ratio_interval(&[1.0, 2.0], &[2.0], 1), None);
        assert_eq!(mean_ratio_interval(&[1.0, f64::NAN], &[2.0, 3.0], 1), None);
        assert_eq!(mean_ratio_interval(&[1.0, 2.0], &[0.0, 0.0], 1), None);
    }

    #[test]
    fn mean_ratio_interval_is_the_same_for_the_same_seed() {
        let (a, b) = ([1.0, 2.5, 3.0, 7.0], [1.5, 2.0, 4.0, 6.0]);
        assert_eq!(
            mean_ratio_interval(&a, &b, 3),
            mean_ratio_interval(&a, &b, 3)
        );
    }

    /// Runs of very different difficulty: run k's errors are about 10^(k mod 4) m.
    fn shared_spread(scale: f64, wobble: u64) -> Vec<Vec<f64>> {
        (0..12u64)
            .map(|k| {
                let mut run: Vec<f64> = (0..20u64)
                    .map(|i| {
                        let noise = 1.0 + 0.01 * (((i * 7 + k * 3 + wobble) % 5) as f64 - 2.0);
                        scale * 10f64.powi((k % 4) as i32) * (1.0 + i as f64 / 20.0) * noise
                    })
                    .collect();
                sort_total(&mut run);
                run
            })
            .collect()
    }

    fn refs(runs: &[Vec<f64>]) -> Vec<&[f64]> {
        runs.iter().map(Vec::as_slice).collect()
    }

    fn draws(runs: &[Vec<f64>], seed: u64) -> Draws {
        Draws::of(&refs(runs), seed).unwrap()
    }

    #[test]
    fn a_small_difference_on_shared_runs_is_clear_paired_but_not_by_overlap() {
        let a = shared_spread(1.0, 0);
        let b = shared_spread(1.1, 1);
        // Alone, each station's p75 interval spans the runs' decades: they overlap.
        let (ia, ib) = (
            bootstrap(&refs(&a), 1).unwrap(),
            bootstrap(&refs(&b), 1).unwrap(),
        );
        assert!(ia.p75[1] > ib.p75[0], "{ia:?} {ib:?}");
        let [lo, hi] = draws(&b, 1).p75_ratio_interval(&draws(&a, 1)).unwrap();
        assert!(lo > 1.0 && lo < 1.1 && hi > 1.1 && hi < 1.2, "{lo}..{hi}");
        assert_eq!(draws(&a, 1).runs, 12);
    }

    #[test]
    fn stations_alike_but_for_noise_are_not_told_apart() {
        let a = shared_spread(1.0, 0);
        let b = shared_spread(1.0, 2);
        let [lo, hi] = draws(&a, 3).p75_ratio_interval(&draws(&b, 3)).unwrap();
        assert!(lo < 1.0 && 1.0 < hi, "{lo}..{hi}");
    }

    #[test]
    fn a_run_without_errors_is_drawn_too_and_errors_in_one_run_give_no_draws() {
        let a = shared_spread(1.0, 0);
        let mut b = shared_spread(2.0, 0);
        // A run in which station b heard no packet (one of the easy ones): still drawn, with
        // nothing of b's in it.
        b[4].clear();
        let with_gap = draws(&b, 5);
        assert_eq!(with_gap.runs, 12);
        assert!(with_gap.p75_ratio_interval(&draws(&a, 5)).unwrap()[0] > 1.0);
        // With errors in one run only, a station cannot show its spread.
        let one: Vec<Vec<f64>> = (0..12)
            .map(|k| if k == 0 { a[0].clone() } else { Vec::new() })
            .collect();
        assert!(Draws::of(&refs(&one), 5).is_none());
        // Draws of another number of runs, or of another seed, are other draws: not paired.
        assert!(draws(&a[..5], 5)
            .p75_ratio_interval(&draws(&b, 5))
            .is_none());
        let (a5, b5, b6) = (draws(&a, 5), draws(&b, 5), draws(&b, 6));
        assert_eq!(
            b5.p75_ratio_interval(&a5),
            draws(&b, 5).p75_ratio_interval(&a5)
        );
        assert_ne!(b5.p75, b6.p75);
        assert!(b6.p75_ratio_interval(&a5).is_none());
    }
}
