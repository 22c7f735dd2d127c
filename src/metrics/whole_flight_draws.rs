//! How sure a ratio of two p75s over the whole flight time is ([`WholeFlightError`]): the p75
//! in each bootstrap draw of whole seeds, paired between two runs of the same seeds
//! (`docs/reference.md` §12).
//!
//! Seeds, not flights, are the units drawn: where the drone stays joined from one flight to the
//! next (ADR: `sweep --distances`), each flight starts with the data rate and the network's
//! history the last one left, so the flights of one seed are one run, and drawing them apart
//! would count one run's luck as many.
//!
//! [`WholeFlightError`]: super::WholeFlightError

use super::bootstrap::{draw_weights, Draw, Ranks};
use super::{percentile, sort_total};
use crate::rng::Rng;

/// The p75 over the whole flight time, untracked time counted as larger than any error, in each
/// of the [`RESAMPLES`](super::RESAMPLES) draws of a run's seeds, drawn alike for every run of
/// the same seed and number of seeds.
#[derive(Clone, Debug, PartialEq)]
pub struct WholeFlightDraws {
    /// The seed the draws were made from (the run's own).
    pub seed: u64,
    /// Seeds drawn from.
    pub seeds: usize,
    /// The p75 of each draw, m: infinite where a quarter of the draw's time or more went
    /// untracked, NaN where the draw evaluated nothing.
    pub p75: Vec<f64>,
}

/// One seed's flights: `runs[first..end]`.
pub type SeedSpan = std::ops::Range<usize>;

impl WholeFlightDraws {
    /// The draws of a station whose tracked errors in flight run i are `runs[i]`, ascending,
    /// with `untracked[i]` evaluation times before its first packet; `seeds` gives each seed's
    /// runs, `all` every error of `runs` pooled and ascending, and `seed` draws the resamples.
    /// `None` for fewer than two seeds, or lengths that do not match.
    ///
    /// ```
    /// use loratrack::metrics::WholeFlightDraws;
    /// // Two seeds of one flight each: 1, 2, 3 m tracked and one step untracked in the first.
    /// let (a, b) = ([1.0, 2.0, 3.0], [1.0, 2.0, 3.0, 4.0]);
    /// let all = [1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0];
    /// let d = WholeFlightDraws::of(&[&a, &b], &all, &[1, 0], &[0..1, 1..2], 9).unwrap();
    /// // A draw of the first seed twice leaves a quarter of its time untracked: no p75.
    /// assert!(d.p75.iter().any(|p| p.is_infinite()));
    /// assert!(d.p75.iter().all(|&p| p.is_infinite() || (3.0..=4.0).contains(&p)));
    /// ```
    pub fn of(
        runs: &[&[f64]],
        all: &[f64],
        untracked: &[usize],
        seeds: &[SeedSpan],
        seed: u64,
    ) -> Option<Self> {
        Self::of_ranked(
            runs,
            all,
            Ranks::of(runs, all).as_ref(),
            untracked,
            seeds,
            seed,
        )
    }

    /// [`Self::of`] with the rank table of `runs` and `all` where it fits
    /// ([`station_draws`](super::paired::station_draws) builds it once for these and the
    /// flights' draws).
    pub(super) fn of_ranked(
        runs: &[&[f64]],
        all: &[f64],
        ranks: Option<&Ranks>,
        untracked: &[usize],
        seeds: &[SeedSpan],
        seed: u64,
    ) -> Option<Self> {
        let spans_runs = seeds
            .iter()
            .all(|s| s.start <= s.end && s.end <= runs.len());
        if seeds.len() < 2 || untracked.len() != runs.len() || !spans_runs {
            return None;
        }
        debug_assert_eq!(all.len(), runs.iter().map(|r| r.len()).sum::<usize>());
        let p75 = draw_weights(seeds.len(), Rng::derive(seed, 0x3f1_16b7))
            .into_iter()
            .map(|per_seed| {
                // A seed drawn k times takes each of its flights k times.
                let mut weights = vec![0u32; runs.len()];
                for (span, &w) in seeds.iter().zip(&per_seed) {
                    weights[span.clone()].fill(w);
                }
                let untracked: u64 = untracked
                    .iter()
                    .zip(&weights)
                    .map(|(&u, &w)| u as u64 * u64::from(w))
                    .sum();
                let draw = Draw {
                    runs,
                    weights: &weights,
                    all,
                    ranks,
                };
                p75_with_untracked(&draw, untracked)
            })
            .collect();
        Some(WholeFlightDraws {
            seed,
            seeds: seeds.len(),
            p75,
        })
    }

    /// The 95 % interval of this run's p75 over `other`'s, draw by draw, where a p75 that lies
    /// in the untracked time is larger than any: a draw in which only this run's does gives an
    /// infinite ratio, one in which only `other`'s does a ratio of 0, and one in which both do
    /// (or either evaluated nothing) is left out. `None` where the two were not drawn alike, or
    /// no draw is left.
    ///
    /// ```
    /// use loratrack::metrics::WholeFlightDraws;
    /// let a = WholeFlightDraws { seed: 1, seeds: 3, p75: vec![2.0, 4.0, f64::INFINITY] };
    /// let b = WholeFlightDraws { seed: 1, seeds: 3, p75: vec![1.0, 2.0, 2.0] };
    /// let [lo, hi] = a.p75_ratio_interval(&b).unwrap();
    /// assert_eq!(lo, 2.0);
    /// assert!(hi.is_infinite());
    /// ```
    pub fn p75_ratio_interval(&self, other: &Self) -> Option<[f64; 2]> {
        if (self.seed, self.seeds) != (other.seed, other.seeds) || self.p75.len() != other.p75.len()
        {
            return None;
        }
        let mut ratios: Vec<f64> = self
            .p75
            .iter()
            .zip(&other.p75)
            .filter_map(
                |(&mine, &theirs)| match (mine.is_infinite(), theirs.is_infinite()) {
                    (true, true) => None,
                    (true, false) => Some(f64::INFINITY),
                    (false, true) => Some(0.0),
                    (false, false) => Some(mine / theirs),
                },
            )
            .filter(|r| !r.is_nan())
            .collect();
        if ratios.is_empty() {
            return None;
        }
        sort_total(&mut ratios);
        // Interpolating towards an infinite ratio is infinite too (not ∞ − ∞ = NaN).
        let at = |p: f64| {
            let rank = p / 100.0 * (ratios.len() - 1) as f64;
            if ratios[rank.ceil() as usize].is_infinite() {
                f64::INFINITY
            } else {
                percentile(&ratios, p)
            }
        };
        Some([at(2.5), at(97.5)])
    }
}

/// The draw's p75 over its tracked errors and `untracked` larger ones, as
/// [`WholeFlightError::of_sorted`](super::WholeFlightError::of_sorted) takes it: infinite where
/// it lies among (or leans on) the untracked ones, NaN where there is nothing.
fn p75_with_untracked(draw: &Draw, untracked: u64) -> f64 {
    let tracked = draw.count_at_most(f64::INFINITY);
    let all = tracked + untracked;
    if all == 0 {
        return f64::NAN;
    }
    // The interpolation leans on the sample after the rank's floor wherever the rank is not whole.
    if (0.75 * (all - 1) as f64).ceil() as u64 >= tracked {
        return f64::INFINITY;
    }
    draw.percentile(all, 75.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::WholeFlightError;

    /// Seed k's flights: three runs of errors scaled by the seed, the first `gap` steps of each
    /// untracked.
    fn seeds(n: usize, gap: impl Fn(usize) -> usize) -> (Vec<Vec<f64>>, Vec<usize>, Vec<SeedSpan>) {
        let mut runs = Vec::new();
        let mut untracked = Vec::new();
        let mut spans = Vec::new();
        for k in 0..n {
            let first = runs.len();
            for f in 0..3 {
                let mut run: Vec<f64> = (0..40)
                    .map(|i| (1.0 + k as f64) * (1.0 + f as f64 + f64::from(i) / 10.0))
                    .collect();
                sort_total(&mut run);
                runs.push(run);
                untracked.push(gap(k));
            }
            spans.push(first..runs.len());
        }
        (runs, untracked, spans)
    }

    fn draws(
        runs: &[Vec<f64>],
        untracked: &[usize],
        spans: &[SeedSpan],
        seed: u64,
    ) -> WholeFlightDraws {
        let refs: Vec<&[f64]> = runs.iter().map(Vec::as_slice).collect();
        let mut all = runs.concat();
        sort_total(&mut all);
        WholeFlightDraws::of(&refs, &all, untracked, spans, seed).unwrap()
    }

    #[test]
    fn a_draw_of_every_seed_once_gives_the_pooled_whole_flight_p75() {
        let (runs, untracked, _) = seeds(5, |k| 4 * k);
        let refs: Vec<&[f64]> = runs.iter().map(Vec::as_slice).collect();
        let mut all = runs.concat();
        sort_total(&mut all);
        let draw = Draw {
            runs: &refs,
            weights: &[1; 15],
            all: &all,
            ranks: None,
        };
        let pooled = WholeFlightError::of_sorted(&all, untracked.iter().sum());
        assert_eq!(
            Some(p75_with_untracked(
                &draw,
                untracked.iter().sum::<usize>() as u64
            )),
            pooled.p75
        );
        // Enough untracked time to reach the p75: infinite, as the pooled p75 is `None`.
        let reached = WholeFlightError::of_sorted(&all, 200);
        assert_eq!(reached.p75, None);
        assert!(p75_with_untracked(&draw, 200).is_infinite());
    }

    #[test]
    fn seeds_are_drawn_whole_and_alike_for_runs_of_the_same_seeds() {
        let (runs, untracked, spans) = seeds(6, |_| 0);
        let d = draws(&runs, &untracked, &spans, 3);
        assert_eq!((d.seeds, d.p75.len()), (6, crate::metrics::RESAMPLES));
        // A run whose every error is doubled is twice as high in every draw: drawn alike.
        let doubled: Vec<Vec<f64>> = runs
            .iter()
            .map(|r| r.iter().map(|e| 2.0 * e).collect())
            .collect();
        let twice = draws(&doubled, &untracked, &spans, 3);
        assert_eq!(twice.p75_ratio_interval(&d), Some([2.0, 2.0]));
        // Another seed draws otherwise: not paired.
        assert_eq!(
            twice.p75_ratio_interval(&draws(&runs, &untracked, &spans, 4)),
            None
        );
    }

    #[test]
    fn untracked_time_in_some_seeds_reaches_the_p75_in_some_draws() {
        // Seeds 0 and 1 lose most of their time; a draw that takes them often has no p75.
        let (runs, untracked, spans) = seeds(6, |k| if k < 2 { 150 } else { 0 });
        let d = draws(&runs, &untracked, &spans, 5);
        let infinite = d.p75.iter().filter(|p| p.is_infinite()).count();
        assert!(infinite > 0 && infinite < d.p75.len(), "{infinite}");
        let tracked = draws(&runs, &vec![0; runs.len()], &spans, 5);
        let [lo, hi] = d.p75_ratio_interval(&tracked).unwrap();
        assert!(lo >= 1.0 && hi.is_infinite(), "{lo}..{hi}");
        // Every draw's own p75 infinite but one: the interval ends at infinity, not NaN.
        let mostly = WholeFlightDraws {
            p75: (0..d.p75.len())
                .map(|i| if i == 0 { 2.0 } else { f64::INFINITY })
                .collect(),
            ..d.clone()
        };
        let [lo, hi] = mostly.p75_ratio_interval(&tracked).unwrap();
        assert!(lo.is_infinite() && hi.is_infinite(), "{lo}..{hi}");
    }

    #[test]
    fn fewer_than_two_seeds_or_mismatched_lengths_give_no_draws() {
        let (runs, untracked, spans) = seeds(2, |_| 0);
        let refs: Vec<&[f64]> = runs.iter().map(Vec::as_slice).collect();
        let mut all = runs.concat();
        sort_total(&mut all);
        assert!(WholeFlightDraws::of(&refs, &all, &untracked, &spans[..1], 1).is_none());
        assert!(WholeFlightDraws::of(&refs, &all, &untracked[1..], &spans, 1).is_none());
        assert!(WholeFlightDraws::of(&refs, &all, &untracked, &[0..3, 3..9], 1).is_none());
    }
}
