//! `simulate` and `sweep --paper` (reference §9).

use super::ApiError;
use crate::sim::{
    ModelChoice, ModelResult, Prediction, Scenario, SimReport, Simulator, StationModel,
    SyntheticChoice,
};
use serde::Serialize;

/// Runs one simulation. Pass the same [`Simulator`] to later calls to reuse its caches.
pub fn simulate(sim: &mut Simulator, p: &Scenario) -> Result<SimReport, ApiError> {
    simulate_with_progress(sim, p, &mut |_, _| {})
}

/// [`simulate`], reporting `progress(done, total)` as flights complete.
pub fn simulate_with_progress(
    sim: &mut Simulator,
    p: &Scenario,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<SimReport, ApiError> {
    let cfg = p.validate()?;
    Ok(sim.run_with_progress(&cfg, progress)?)
}

/// [`simulate_with_progress`], where `progress` also says whether to go on: `false` stops the
/// run before its next flight with [`SimError::Stopped`](crate::sim::SimError::Stopped)
/// ([`Simulator::run_stoppable`]).
pub fn simulate_stoppable(
    sim: &mut Simulator,
    p: &Scenario,
    progress: &mut dyn FnMut(usize, usize) -> bool,
) -> Result<SimReport, ApiError> {
    let cfg = p.validate()?;
    Ok(sim.run_stoppable(&cfg, progress)?)
}

/// One point of the sweep grid.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SweepRun {
    /// Spreading factor.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bandwidth_khz: f64,
    /// Gateway distance, m.
    pub distance: f64,
    /// The station's prediction.
    pub prediction: Prediction,
    /// Per model.
    pub results: Vec<ModelResult>,
}

/// The output of `sweep`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SweepReport {
    /// Flight time per run, s.
    pub flight_time: f64,
    /// Seed used.
    pub seed: u64,
    /// MAC overhead, bytes (the paper: 0).
    pub overhead: usize,
    /// The grid.
    pub runs: Vec<SweepRun>,
}

impl SweepReport {
    /// The predictions the sweep ran, in order.
    pub fn predictions(&self) -> Vec<Prediction> {
        let mut out: Vec<Prediction> = Vec::new();
        for run in &self.runs {
            if !out.contains(&run.prediction) {
                out.push(run.prediction);
            }
        }
        out
    }
}

/// Spreading factors of the paper's Figs. "error for different values of d".
pub const PAPER_SFS: [i64; 2] = [7, 8];
/// Distances of the same figures, m.
pub const PAPER_DISTANCES: [f64; 3] = [1000.0, 2000.0, 3000.0];

/// The paper's grid: SF 7 and 8 at 250 kHz, d = 1, 2, 3 km, over the whole synthetic set, with
/// no LoRaWAN overhead (as in its Table II) and every other setting at the paper's defaults, for
/// each of `predictions` and each station in `models` (the paper: its three models, the paper's
/// prediction). The drone filters run once per model; every other run reuses them.
pub fn sweep_paper(
    sim: &mut Simulator,
    seed: u64,
    predictions: &[Prediction],
    models: &ModelChoice,
) -> Result<SweepReport, ApiError> {
    let mut runs = Vec::new();
    let mut flight_time = 0.0;
    for &prediction in predictions {
        for sf in PAPER_SFS {
            for distance in PAPER_DISTANCES {
                let mut p = Scenario::default();
                p.flight.synthetic = Some(SyntheticChoice::All);
                p.station.model = models.clone();
                p.station.prediction = prediction;
                p.radio.sf = sf;
                p.radio.bw = 250.0;
                p.radio.overhead = 0;
                p.channel.distance = distance;
                p.run.seed = seed;
                let r = simulate(sim, &p)?;
                flight_time = r.config.flight_time;
                runs.push(SweepRun {
                    sf,
                    bandwidth_khz: 250.0,
                    distance,
                    prediction,
                    results: r.results,
                });
            }
        }
    }
    Ok(SweepReport {
        flight_time,
        seed,
        overhead: 0,
        runs,
    })
}

/// p75 of `model` in a sweep run (for the reproduction document).
pub fn p75(run: &SweepRun, model: StationModel) -> f64 {
    run.results
        .iter()
        .find(|r| r.model == model)
        .map_or(f64::NAN, |r| r.error3d.p75)
}
