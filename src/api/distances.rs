//! `sweep --distances`: every fixed EU868 data rate and both ADR modes, side by side, at each
//! gateway distance.

use super::ApiError;
use crate::lora::{AdrMode, DataRate};
use crate::sim::{ModelResult, Scenario, Simulator};
use serde::Serialize;

/// The most distances one sweep takes (each runs nine whole-set simulations).
pub const MAX_DISTANCES: usize = 100;

/// The distances of the targets, m.
pub const ADR_DISTANCES: [f64; 4] = [1000.0, 3000.0, 5000.0, 7000.0];

/// One row: a fixed data rate or an ADR mode at one distance.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DistanceRun {
    /// Gateway distance, m.
    pub distance: f64,
    /// The fixed data rate (`null` for an ADR row).
    pub dr: Option<u8>,
    /// `off` for a fixed rate, else the ADR mode.
    pub adr: AdrMode,
    /// The data rate an ADR row started at (`null` for a fixed rate).
    pub start: Option<u8>,
    /// Share of packets received (`null` when none was sent).
    pub delivery: f64,
    /// The result.
    pub result: ModelResult,
    /// This row's p75 over the whole flight time against the best fixed rate's at its distance
    /// ([`DistanceSweepReport::best_fixed`]); `null` where no fixed rate has such a p75 there.
    pub p75_vs_best_fixed: Option<VersusBestFixed>,
}

/// A row's whole-flight p75 over the best fixed rate's at the same distance.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct VersusBestFixed {
    /// The best fixed rate's data rate (0–6).
    pub dr: u8,
    /// The ratio; infinite (`null` in JSON) where this row has no whole-flight p75: a quarter of
    /// its flight time or more had no packet.
    pub ratio: f64,
    /// Its 95 % interval from resampling the seeds together for both rows
    /// ([`WholeFlightDraws`](crate::metrics::WholeFlightDraws), `docs/reference.md` §12); an
    /// end of `null` in JSON is infinite; `null` for a single seed or where this row has no p75.
    pub interval: Option<[f64; 2]>,
}

/// The output of `sweep --distances`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DistanceSweepReport {
    /// The seed every run used (drawn when `random` was asked for).
    pub seed: u64,
    /// Every run, distance by distance: DR0..DR6, then `lorawan` and `tracking` from `base`'s
    /// data rate, then both from DR0.
    pub runs: Vec<DistanceRun>,
}

impl DistanceSweepReport {
    /// The fixed data rate of lowest whole-flight p75 at `distance` (time before a flight's
    /// first packet counted as the largest error): the rate an ADR mode is judged against.
    pub fn best_fixed(&self, distance: f64) -> Option<&DistanceRun> {
        self.runs
            .iter()
            .filter(|x| x.distance == distance && x.dr.is_some())
            .filter_map(|x| Some((x, x.result.whole_flight.p75?)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(x, _)| x)
    }

    /// Each row's [`VersusBestFixed`], once every row of its distance has run.
    fn judge(&mut self) {
        let judged: Vec<Option<VersusBestFixed>> = self
            .runs
            .iter()
            .map(|run| {
                let best = self.best_fixed(run.distance)?;
                let best_p75 = best.result.whole_flight.p75?;
                let draws = (
                    &run.result.whole_flight_draws,
                    &best.result.whole_flight_draws,
                );
                let interval = match (run.result.whole_flight.p75, draws) {
                    (Some(_), (Some(mine), Some(theirs))) => mine.p75_ratio_interval(theirs),
                    _ => None,
                };
                Some(VersusBestFixed {
                    dr: best.dr?,
                    ratio: run
                        .result
                        .whole_flight
                        .p75
                        .map_or(f64::INFINITY, |p| p / best_p75),
                    interval,
                })
            })
            .collect();
        for (run, v) in self.runs.iter_mut().zip(judged) {
            run.p75_vs_best_fixed = v;
        }
    }
}

/// Runs `base` (its first model) at each distance with each fixed data rate DR0–DR6 and with
/// both ADR modes, starting from `base`'s SF and bandwidth (an EU868 data rate) and from DR0
/// (SF12, the safe start of a device that knows nothing of its link). Drone filters run once.
pub fn sweep_distances(
    sim: &mut Simulator,
    base: &Scenario,
    distances: &[f64],
) -> Result<DistanceSweepReport, ApiError> {
    // Every distance is checked, and their number bounded, before any run starts.
    if distances.is_empty() || distances.len() > MAX_DISTANCES {
        return Err(ApiError::Invalid(format!(
            "distances: give 1..{MAX_DISTANCES} distances, got {}",
            distances.len()
        )));
    }
    // Named as the list, not as the scenario's own `distance`, which is another setting.
    for &d in distances {
        crate::options::DISTANCE
            .check(d)
            .map_err(|e| ApiError::Invalid(format!("distances: {e}")))?;
    }
    let radio = base.validate()?.radio;
    let given = DataRate::of(radio.sf, radio.bw).ok_or(crate::sim::SimError::AdrStart(
        radio.sf.get(),
        radio.bw.khz(),
    ))?;
    let mut starts = vec![given];
    if given != DataRate::DR0 {
        starts.push(DataRate::DR0);
    }
    let mut runs = Vec::new();
    for &distance in distances {
        let fixed = DataRate::ALL.map(|dr| (dr, AdrMode::Off));
        let adaptive = starts
            .iter()
            .flat_map(|&s| [(s, AdrMode::Lorawan), (s, AdrMode::Tracking)]);
        for (dr, adr) in fixed.into_iter().chain(adaptive) {
            let mut p = base.clone();
            p.channel.distance = distance;
            p.network.adr = adr;
            p.radio.sf = i64::from(dr.sf().get());
            p.radio.bw = dr.bw().khz();
            let mut r = super::simulate(sim, &p)?;
            let result = r.results.swap_remove(0);
            let fixed = adr == AdrMode::Off;
            runs.push(DistanceRun {
                distance,
                dr: fixed.then_some(dr.index()),
                adr,
                start: (!fixed).then_some(dr.index()),
                delivery: result.delivery.delivery_ratio,
                result,
                p75_vs_best_fixed: None,
            });
        }
    }
    let mut report = DistanceSweepReport {
        seed: base.run.seed,
        runs,
    };
    report.judge();
    Ok(report)
}
