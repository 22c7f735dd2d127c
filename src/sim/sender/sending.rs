//! The sending settings `simulate` and `swarm` share, validated in one place.

use super::{new_sender, Sender, SenderKind};
use crate::lora::{DutyCycle, DutyCycleMode, LoraError, MAX_BURST};
use crate::sim::station::{StationModel, StationSetup};
use crate::sim::SimError;
use serde::Serialize;

/// Default error-triggered threshold, m: about twice the on-time p75 of the paper's station at
/// SF7 / 1 km, so packets go when the station is clearly off, not on every wobble.
pub const DEFAULT_THRESHOLD_M: f64 = 2.0;
/// Default heartbeat, s: a lost packet is repaired within 10 s, at 1/5 of the periodic airtime
/// at SF7 / 250 kHz.
pub const DEFAULT_MAX_INTERVAL_S: f64 = 10.0;
/// Default budget capacity, packets (issue: "holds at most K packets' airtime (default 10)").
pub const DEFAULT_BURST: u32 = 10;

/// When a drone sends and which duty-cycle rule bounds it (echoed in reports as `sender`,
/// `threshold`, `maxInterval`, `dutyCycleMode`, `burst`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Sending {
    /// The sending policy.
    pub sender: SenderKind,
    /// Error-triggered threshold, m.
    pub threshold: f64,
    /// Error-triggered heartbeat, s.
    pub max_interval: f64,
    /// The duty-cycle rule.
    pub duty_cycle_mode: DutyCycleMode,
    /// Budget capacity, packets.
    pub burst: u32,
}

impl Default for Sending {
    fn default() -> Self {
        Sending {
            sender: SenderKind::Periodic,
            threshold: DEFAULT_THRESHOLD_M,
            max_interval: DEFAULT_MAX_INTERVAL_S,
            duty_cycle_mode: DutyCycleMode::PerPacket,
            burst: DEFAULT_BURST,
        }
    }
}

impl Sending {
    /// Checks each setting against its range.
    pub fn validate(&self) -> Result<(), SimError> {
        if !(0.0..=10_000.0).contains(&self.threshold) {
            return Err(SimError::Parameter(
                "threshold",
                self.threshold,
                "0..10000 m",
            ));
        }
        if !(self.max_interval > 0.0 && self.max_interval <= 3600.0) {
            return Err(SimError::Parameter(
                "maxInterval",
                self.max_interval,
                "in (0, 3600] s",
            ));
        }
        if !(1..=MAX_BURST).contains(&self.burst) {
            return Err(SimError::Parameter(
                "burst",
                f64::from(self.burst),
                "1..3600 packets",
            ));
        }
        Ok(())
    }

    /// The duty-cycle rule for packets of `time_on_air` s at `duty_cycle`, from `start` s.
    pub fn rule(
        &self,
        duty_cycle: f64,
        time_on_air: f64,
        start: f64,
    ) -> Result<DutyCycle, LoraError> {
        DutyCycle::new(
            self.duty_cycle_mode,
            duty_cycle,
            time_on_air,
            self.burst,
            start,
        )
    }

    /// The drone's sender, mirroring a station of `model` with `setup`; its heartbeat is
    /// `heartbeat` s.
    pub fn sender(
        &self,
        model: StationModel,
        setup: StationSetup,
        heartbeat: f64,
    ) -> Box<dyn Sender> {
        new_sender(self.sender, self.threshold, heartbeat, model, setup)
    }
}
