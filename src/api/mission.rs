//! `sweep --mission`: the mission-aware station beside every other station at every EU868 data
//! rate, near and far (reference §16).

use super::{sweep_senders, ApiError, SenderSweepReport};
use crate::sim::DEFAULT_BURST;
use crate::sim::{
    ModelChoice, ModelResult, PlanPace, Scenario, SimError, Simulator, StationModel,
    SyntheticChoice,
};
use crate::trajectory::{canberra_flight, fly_plan, inspection_plan, FlightPlan, TRACE_TOLERANCE};
use serde::Serialize;

/// The data rates of the sweep, (SF, bandwidth kHz): EU868 DR6 (SF7 at 250 kHz), then DR5..DR0
/// (SF7..SF12 at 125 kHz), fastest first.
pub const MISSION_RATES: [(i64, f64); 7] = [
    (7, 250.0),
    (7, 125.0),
    (8, 125.0),
    (9, 125.0),
    (10, 125.0),
    (11, 125.0),
    (12, 125.0),
];

/// Gateway distances of the sweep, m: one where nearly every packet arrives, one where SF7 loses
/// a fifth of them.
pub const MISSION_DISTANCES: [f64; 2] = [1000.0, 3000.0];

/// The data rates of the real flight's rows: the paper's, one where packets are a few per
/// minute, and the slowest.
pub const REAL_RATES: [(i64, f64); 3] = [(7, 250.0), (9, 125.0), (12, 125.0)];

/// Seeds the real flight's rows pool at least: the flight is short (162 s), so one seed rests on
/// a handful of packets.
pub const REAL_SEEDS: u32 = 8;

/// The stations compared: the paper's three, the IMM and the mission station.
pub const MISSION_MODELS: &str = "dr,ctra-plus,3d-ctra,imm,mission";

/// The seed of the inspection mission the sweep flies ([`inspection_plan`]).
pub const INSPECTION_SEED: u64 = 1;

/// The inspection mission ([`inspection_plan`], flown by [`fly_plan`]) at one data rate, 1 km:
/// the mission station reading the plan's holds, the same station given the plan without them,
/// and bounded 3D-CTRA.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct HoldRun {
    /// Spreading factor.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// 3D-CTRA with the sweep's prediction.
    pub ctra3d: ModelResult,
    /// The mission station with the plan's holds.
    pub holding: ModelResult,
    /// The mission station with the same plan without its holds: it flies on while the drone
    /// hovers.
    pub flying_on: ModelResult,
}

/// One setting's results.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct MissionRun {
    /// Spreading factor.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Gateway distance, m.
    pub distance: f64,
    /// Each station's result, in [`MISSION_MODELS`]'s order.
    pub results: Vec<ModelResult>,
    /// The mission station with `planPace: "packet"` (the plan's speeds ignored).
    pub packet_pace: Option<ModelResult>,
}

impl MissionRun {
    /// The mission station's result.
    pub fn mission(&self) -> Option<&ModelResult> {
        self.results
            .iter()
            .find(|r| r.model == StationModel::Mission)
    }

    /// The station other than the mission one with the lowest p75 (ignoring stations that
    /// received nothing).
    pub fn best_other(&self) -> Option<&ModelResult> {
        self.results
            .iter()
            .filter(|r| r.model != StationModel::Mission && r.error3d.p75.is_finite())
            .min_by(|a, b| a.error3d.p75.total_cmp(&b.error3d.p75))
    }

    /// Mission p75 over the best other station's p75 (below 1: the mission station is better).
    pub fn ratio(&self) -> Option<f64> {
        Some(self.mission()?.error3d.p75 / self.best_other()?.error3d.p75)
    }
}

/// The output of `sweep --mission`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct MissionSweepReport {
    /// The seed of the first run (drawn when `random` was asked for).
    pub seed: u64,
    /// Seeds pooled in every run.
    pub seeds: u32,
    /// Every setting, distance by distance, fastest data rate first.
    pub runs: Vec<MissionRun>,
    /// The real Canberra flight with the plan traced from its own log, at `REAL_RATES` and 1 km,
    /// pooled over at least `REAL_SEEDS` seeds.
    pub real: Vec<MissionRun>,
    /// Seeds pooled in each of `real`.
    pub real_seeds: u32,
    /// Error-triggered sending with the mission station against periodic sending, also slowed
    /// to the same airtime, over the synthetic set at SF7/250 kHz and 1 km (the drone mirrors the
    /// mission station, plan and all).
    pub senders: SenderSweepReport,
    /// The inspection mission at every rate of [`MISSION_RATES`], 1 km: what reading a plan's
    /// holds is worth.
    pub holds: Vec<HoldRun>,
}

/// Runs `base` over the whole synthetic set (each flight's own plan) with every station of
/// [`MISSION_MODELS`], and the mission station once more pacing by the packet alone
/// ([`PlanPace::Packet`]), at each rate of [`MISSION_RATES`] and distance of [`MISSION_DISTANCES`],
/// with `base`'s prediction for the single-model stations (the mission station falls back to a
/// bounded 3D-CTRA whatever it says). Drone filters run once per payload.
pub fn sweep_mission(sim: &mut Simulator, base: &Scenario) -> Result<MissionSweepReport, ApiError> {
    let mut s = base.clone();
    s.flight = Default::default();
    s.flight.synthetic = Some(SyntheticChoice::All);
    s.station.model = ModelChoice::parse(MISSION_MODELS).map_err(ApiError::Invalid)?;
    let mut runs = Vec::new();
    for &distance in &MISSION_DISTANCES {
        for &(sf, bw) in &MISSION_RATES {
            runs.push(mission_run(sim, &s, sf, bw, distance)?);
        }
    }
    let mut real = s.clone();
    real.flight = Default::default();
    real.flight.sample = Some("canberra".into());
    real.flight.plan = Some(FlightPlan::traced(&canberra_flight(), TRACE_TOLERANCE).to_csv());
    real.run.seeds = real.run.seeds.max(REAL_SEEDS);
    let real_runs = REAL_RATES
        .iter()
        .map(|&(sf, bw)| mission_run(sim, &real, sf, bw, MISSION_DISTANCES[0]))
        .collect::<Result<_, _>>()?;
    let mut senders = s.clone();
    senders.station.model = ModelChoice::one(StationModel::Mission);
    (senders.radio.sf, senders.radio.bw) = MISSION_RATES[0];
    senders.channel.distance = MISSION_DISTANCES[0];
    let senders = sweep_senders(sim, &senders, DEFAULT_BURST)?;
    let plan = inspection_plan(INSPECTION_SEED);
    let mut inspection = s.clone();
    inspection.flight = Default::default();
    inspection.flight.trajectory = Some(
        fly_plan(&plan, "inspection")
            .map_err(SimError::from)?
            .to_csv()
            .into(),
    );
    inspection.flight.trajectory_name = Some("inspection".into());
    let holds = MISSION_RATES
        .iter()
        .map(|&(sf, bw)| hold_run(sim, &inspection, &plan, sf, bw))
        .collect::<Result<_, _>>()?;
    Ok(MissionSweepReport {
        seed: base.run.seed,
        seeds: s.run.seeds.max(1),
        runs,
        real: real_runs,
        real_seeds: real.run.seeds,
        senders,
        holds,
    })
}

/// The inspection mission (`s` flies it, `plan` is its plan) at one rate, 1 km, with and
/// without the plan's holds.
fn hold_run(
    sim: &mut Simulator,
    s: &Scenario,
    plan: &FlightPlan,
    sf: i64,
    bw: f64,
) -> Result<HoldRun, ApiError> {
    let mut s = s.clone();
    s.flight.plan = Some(plan.to_csv());
    s.station.model = ModelChoice::parse("3d-ctra,mission").map_err(ApiError::Invalid)?;
    (s.radio.sf, s.radio.bw, s.channel.distance) = (sf, bw, MISSION_DISTANCES[0]);
    let mut both = sim.run(&s.validate()?)?.results.into_iter();
    s.flight.plan = Some(plan.without_holds().to_csv());
    s.station.model = ModelChoice::one(StationModel::Mission);
    let flying_on = sim.run(&s.validate()?)?.results.pop();
    match (both.next(), both.next(), flying_on) {
        (Some(ctra3d), Some(holding), Some(flying_on)) => Ok(HoldRun {
            sf,
            bw,
            ctra3d,
            holding,
            flying_on,
        }),
        _ => Err(ApiError::Invalid(
            "the inspection mission gave no result".into(),
        )),
    }
}

/// Every station of `s` at one rate and distance, and the mission station pacing by the packet.
fn mission_run(
    sim: &mut Simulator,
    s: &Scenario,
    sf: i64,
    bw: f64,
    distance: f64,
) -> Result<MissionRun, ApiError> {
    let mut s = s.clone();
    (s.radio.sf, s.radio.bw, s.channel.distance) = (sf, bw, distance);
    let report = sim.run(&s.validate()?)?;
    s.station.model = ModelChoice::one(StationModel::Mission);
    s.station.plan_pace = PlanPace::Packet;
    let packet_pace = sim.run(&s.validate()?)?.results.pop();
    Ok(MissionRun {
        sf,
        bw,
        distance,
        results: report.results,
        packet_pace,
    })
}
