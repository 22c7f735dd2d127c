//! `sweep --senders`: the trade-off between airtime and tracking error of error-triggered sending,
//! under both duty-cycle rules, against the paper's periodic sender.

use super::ApiError;
use crate::lora::DutyCycleMode;
use crate::sim::{ModelResult, Scenario, SenderKind, Sending, Simulator};
use serde::Serialize;

/// Thresholds of the trade-off curve, m.
pub const SENDER_THRESHOLDS: [f64; 8] = [0.5, 1.0, 1.5, 2.0, 3.0, 5.0, 7.5, 10.0];

/// One point of the curve: a threshold under one duty-cycle rule.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SenderPoint {
    /// Error threshold, m.
    pub threshold: f64,
    /// The duty-cycle rule.
    pub duty_cycle_mode: DutyCycleMode,
    /// Budget capacity, packets.
    pub burst: u32,
    /// Airtime as a share of the periodic sender's.
    pub airtime_share: f64,
    /// p75 / periodic p75.
    pub p75_ratio: f64,
    /// p95 / periodic p95.
    pub p95_ratio: f64,
    /// The periodic sender slowed to the same airtime: its duty cycle scaled by
    /// `airtime_share`, so it sends every interval / share.
    pub equal_airtime: ModelResult,
    /// p75 / the equal-airtime periodic p75: below 1 the error-triggered sender tracks better
    /// for the same airtime.
    pub p75_vs_equal: f64,
    /// p95 / the equal-airtime periodic p95.
    pub p95_vs_equal: f64,
    /// The full result.
    pub result: ModelResult,
}

/// The output of `sweep --senders`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SenderSweepReport {
    /// The seed every run used (drawn when `random` was asked for).
    pub seed: u64,
    /// Spreading factor, bandwidth (kHz) and gateway distance (m) of every run.
    pub setting: (i64, f64, f64),
    /// The periodic sender under the per-packet rule (the paper).
    pub periodic: ModelResult,
    /// Error-triggered sending at each threshold, per-packet rule then budget.
    pub points: Vec<SenderPoint>,
}

/// Runs `base` (its first model) with the periodic sender, then with the error-triggered sender
/// at each of [`SENDER_THRESHOLDS`] under the per-packet rule and under a budget of `burst`
/// packets, each beside the periodic sender slowed to its airtime (the duty cycle times its
/// airtime share). Drone filters run once; every other run reuses them. The error-triggered
/// sender takes its heartbeat, listening and payload from `base.sending` (whose sender may be
/// either); the periodic one its payload.
pub fn sweep_senders(
    sim: &mut Simulator,
    base: &Scenario,
    burst: u32,
) -> Result<SenderSweepReport, ApiError> {
    let mut run = |sending: Sending, duty_cycle: f64| -> Result<ModelResult, ApiError> {
        let mut p = base.clone();
        p.sending = sending;
        p.radio.duty_cycle = duty_cycle;
        let mut r = super::simulate(sim, &p)?;
        Ok(r.results.swap_remove(0))
    };
    let periodic_sending = base.sending.periodic();
    let duty_cycle = base.radio.duty_cycle;
    let periodic = run(periodic_sending, duty_cycle)?;
    let mut points = Vec::new();
    for (mode, k) in [
        (DutyCycleMode::PerPacket, 1),
        (DutyCycleMode::Budget, burst),
    ] {
        for threshold in SENDER_THRESHOLDS {
            let sending = Sending {
                sender: SenderKind::Error,
                threshold,
                duty_cycle_mode: mode,
                // The per-packet rule has no burst (it is the budget's with one packet).
                burst: if mode == DutyCycleMode::Budget {
                    k
                } else {
                    periodic_sending.burst
                },
                ..base.sending
            };
            let result = run(sending, duty_cycle)?;
            let airtime_share = result.airtime / periodic.airtime;
            let equal_airtime = run(periodic_sending, duty_cycle * airtime_share)?;
            points.push(SenderPoint {
                threshold,
                duty_cycle_mode: mode,
                burst: k,
                airtime_share,
                p75_ratio: result.error3d.p75 / periodic.error3d.p75,
                p95_ratio: result.error3d.p95 / periodic.error3d.p95,
                p75_vs_equal: result.error3d.p75 / equal_airtime.error3d.p75,
                p95_vs_equal: result.error3d.p95 / equal_airtime.error3d.p95,
                equal_airtime,
                result,
            });
        }
    }
    Ok(SenderSweepReport {
        seed: base.run.seed,
        setting: (base.radio.sf, base.radio.bw, base.channel.distance),
        periodic,
        points,
    })
}

/// The settings whose equal-airtime comparison docs/senders.md tabulates: (spreading factor,
/// bandwidth kHz, gateway distance m) — the paper's fastest rate and a slow one, near and far.
pub const SENDER_SETTINGS: [(i64, f64, f64); 4] = [
    (7, 250.0, 1000.0),
    (7, 250.0, 3000.0),
    (9, 125.0, 1000.0),
    (9, 125.0, 3000.0),
];

/// [`sweep_senders`] with `base` moved to `sf` / `bw` kHz / `distance` m, and the heartbeat at
/// least [`HEARTBEAT_INTERVALS`] duty-cycle intervals there (a heartbeat must not be shorter
/// than the interval, and one much closer to it leaves the sender nothing to decide).
pub fn sweep_senders_at(
    sim: &mut Simulator,
    base: &Scenario,
    burst: u32,
    (sf, bw, distance): (i64, f64, f64),
) -> Result<SenderSweepReport, ApiError> {
    let mut p = base.clone();
    (p.radio.sf, p.radio.bw, p.channel.distance) = (sf, bw, distance);
    // The interval is the periodic sender's: the base may carry error-triggered settings.
    let periodic = Scenario {
        sending: p.sending.periodic(),
        ..p.clone()
    };
    let v = periodic.validate()?;
    let (radio, _) = v.drone_radio(&v.radio, v.models[0])?;
    let interval = radio.current().interval;
    p.sending.max_interval = p.sending.max_interval.max(HEARTBEAT_INTERVALS * interval);
    sweep_senders(sim, &p, burst)
}

/// How many duty-cycle intervals [`sweep_senders_at`]'s heartbeat spans at least: 5, about
/// what the default 10 s heartbeat is at SF7 / 250 kHz (2.06 s).
pub const HEARTBEAT_INTERVALS: f64 = 5.0;
