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
    /// The full result.
    pub result: ModelResult,
}

/// The output of `sweep --senders`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SenderSweepReport {
    /// The seed every run used (drawn when `random` was asked for).
    pub seed: u64,
    /// The periodic sender under the per-packet rule (the paper).
    pub periodic: ModelResult,
    /// Error-triggered sending at each threshold, per-packet rule then budget.
    pub points: Vec<SenderPoint>,
}

/// Runs `base` (its first model) with the periodic sender, then with the error-triggered sender
/// at each of [`SENDER_THRESHOLDS`] under the per-packet rule and under a budget of `burst`
/// packets. Drone filters run once; every other run reuses them.
pub fn sweep_senders(
    sim: &mut Simulator,
    base: &Scenario,
    burst: u32,
) -> Result<SenderSweepReport, ApiError> {
    let mut run = |sending: Sending| -> Result<ModelResult, ApiError> {
        let mut p = base.clone();
        p.sending = sending;
        let mut r = super::simulate(sim, &p)?;
        Ok(r.results.swap_remove(0))
    };
    let periodic = run(Sending {
        sender: SenderKind::Periodic,
        duty_cycle_mode: DutyCycleMode::PerPacket,
        ..base.sending
    })?;
    let mut points = Vec::new();
    for (mode, k) in [
        (DutyCycleMode::PerPacket, 1),
        (DutyCycleMode::Budget, burst),
    ] {
        for threshold in SENDER_THRESHOLDS {
            let result = run(Sending {
                sender: SenderKind::Error,
                threshold,
                duty_cycle_mode: mode,
                burst: k,
                ..base.sending
            })?;
            points.push(SenderPoint {
                threshold,
                duty_cycle_mode: mode,
                burst: k,
                airtime_share: result.airtime / periodic.airtime,
                p75_ratio: result.error3d.p75 / periodic.error3d.p75,
                p95_ratio: result.error3d.p95 / periodic.error3d.p95,
                result,
            });
        }
    }
    Ok(SenderSweepReport {
        seed: base.run.seed,
        periodic,
        points,
    })
}
