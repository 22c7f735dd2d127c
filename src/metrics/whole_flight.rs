use serde::Serialize;

/// The 3D error over the whole flight time, not only the time after the first packet arrived.
///
/// A station is scored every T from its first packet on ([`Summary`](super::Summary) of
/// `error3d`), so where packets are scarce (SF11–12, long range, a data rate too fast for its
/// link) a flight's first seconds or minutes, or a whole flight without a packet, leave no
/// sample, and the summary describes only the time a packet had arrived: a rate that reaches
/// the station in one flight out of ten can show a smaller p75 than one that reaches it in
/// every flight. Here every evaluation time counts: one without any packet yet counts as an
/// error larger than every other, so a percentile exists only when less of the time than its
/// complement went untracked (docs/reference.md §12).
///
/// ```
/// use loratrack::WholeFlightError;
/// // Four tracked steps, one before the first packet: the p75 over five steps is the fourth
/// // smallest error; the p95 would lie in the untracked step.
/// let e = WholeFlightError::of_sorted(&[1.0, 2.0, 3.0, 4.0], 1);
/// assert_eq!(e.tracked, 0.8);
/// assert_eq!(e.p75, Some(4.0));
/// assert_eq!(e.p95, None);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct WholeFlightError {
    /// Share of the evaluation times (every T over the flights) at which the station had
    /// received a packet, 0–1 (`null` when there were none at all).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub tracked: f64,
    /// Median over the whole flight time, m (`null` when half of it or more was untracked).
    pub p50: Option<f64>,
    /// 75th percentile over the whole flight time, m (`null` when a quarter or more was
    /// untracked).
    pub p75: Option<f64>,
    /// 95th percentile over the whole flight time, m (`null` when 5 % or more was untracked).
    pub p95: Option<f64>,
    /// Whether the untracked time is worth saying beside the errors: `tracked` in whole percent
    /// is below [`TRACKED_IN_FULL_PERCENT`] (or nothing was evaluated). The CLI's line under its
    /// table and the page's notes follow it, so that both say it for the same runs.
    pub partly_tracked: bool,
}

/// The share of the flight time, in whole percent as the page shows it, from which the errors
/// are said to cover the flight ([`WholeFlightError::partly_tracked`]): below it, a reader is told
/// how much of the flight the statistics leave out (docs/reference.md §12).
pub const TRACKED_IN_FULL_PERCENT: f64 = 95.0;

impl WholeFlightError {
    /// From the ascending errors of the tracked evaluation times and the number of `untracked`
    /// ones, by the same interpolation as [`percentile`](super::percentile) over all of them.
    pub fn of_sorted(sorted: &[f64], untracked: usize) -> Self {
        let all = sorted.len() + untracked;
        let tracked = if all == 0 {
            f64::NAN
        } else {
            sorted.len() as f64 / all as f64
        };
        WholeFlightError {
            tracked,
            p50: percentile_tracked(sorted, all, 50.0),
            p75: percentile_tracked(sorted, all, 75.0),
            p95: percentile_tracked(sorted, all, 95.0),
            partly_tracked: tracked.is_nan() || (100.0 * tracked).round() < TRACKED_IN_FULL_PERCENT,
        }
    }
}

/// The `p`-th percentile of `all` values of which `sorted` are the smallest and the rest are
/// larger than any number; `None` when it lies among (or leans on) the rest.
fn percentile_tracked(sorted: &[f64], all: usize, p: f64) -> Option<f64> {
    let n = sorted.len();
    if n == 0 {
        return None;
    }
    let rank = (p / 100.0).clamp(0.0, 1.0) * (all - 1) as f64;
    let lo = rank.floor() as usize;
    let frac = rank - lo as f64;
    match (sorted.get(lo), sorted.get(lo + 1)) {
        (Some(&a), _) if frac == 0.0 => Some(a),
        (Some(&a), Some(&b)) => Some(a + frac * (b - a)),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::percentile;

    #[test]
    fn with_every_step_tracked_it_is_the_ordinary_percentile() {
        let sorted: Vec<f64> = (1..=37).map(|k| f64::from(k).sqrt()).collect();
        let e = WholeFlightError::of_sorted(&sorted, 0);
        assert_eq!(e.tracked, 1.0);
        assert_eq!(e.p50, Some(percentile(&sorted, 50.0)));
        assert_eq!(e.p75, Some(percentile(&sorted, 75.0)));
        assert_eq!(e.p95, Some(percentile(&sorted, 95.0)));
    }

    #[test]
    fn untracked_time_raises_every_percentile_and_hides_those_it_reaches() {
        let sorted: Vec<f64> = (1..=70).map(f64::from).collect();
        let tracked = WholeFlightError::of_sorted(&sorted, 0);
        let e = WholeFlightError::of_sorted(&sorted, 30);
        assert!((e.tracked - 0.7).abs() < 1e-12);
        assert!(e.p50.unwrap() > tracked.p50.unwrap());
        assert_eq!(e.p75, None);
        assert_eq!(e.p95, None);
        // Half of 100 steps: rank 49.5 of 0..99 between the 50th and 51st smallest.
        assert_eq!(e.p50, Some(50.5));
    }

    #[test]
    fn the_untracked_time_is_worth_saying_below_95_percent_as_shown() {
        let share =
            |tracked: usize| WholeFlightError::of_sorted(&vec![1.0; tracked], 1000 - tracked);
        assert!(share(620).partly_tracked);
        assert!(share(944).partly_tracked);
        // 94.6 % reads as 95 %: not said, so no note or line ever says "95 %" of the flight.
        assert!(!share(946).partly_tracked);
        assert!(!share(984).partly_tracked);
        assert!(!share(1000).partly_tracked);
        // Nothing evaluated: nothing covered.
        assert!(WholeFlightError::of_sorted(&[], 0).partly_tracked);
    }

    #[test]
    fn nothing_tracked_has_no_percentile() {
        let e = WholeFlightError::of_sorted(&[], 12);
        assert_eq!((e.tracked, e.p50, e.p75), (0.0, None, None));
        assert!(WholeFlightError::of_sorted(&[], 0).tracked.is_nan());
    }
}
