//! How drones get on the air besides the duty cycle: their clocks and random delays (and,
//! in a swarm, the schedule they keep). `docs/reference.md` §13.

use crate::options as opt;
use crate::sim::clock::Timing;
use crate::sim::schedule::Schedule;
use crate::sim::SimError;
use serde::{Deserialize, Serialize};

/// Clocks, delays and the swarm's schedule (flat keys `jitter`, `clockDrift`, `schedule`).
/// Unset clock values take the command's default: a swarm's drones drift and jitter as real
/// ones do; `simulate` keeps the paper's exact timing.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(not(target_arch = "wasm32"), derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct AccessSettings {
    /// The longest random delay before each uplink, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(not(target_arch = "wasm32"), arg(long, help = opt::JITTER.cli_help(), allow_negative_numbers = true))]
    pub jitter: Option<f64>,
    /// The largest clock error, ppm.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(not(target_arch = "wasm32"), arg(long, help = opt::CLOCK_DRIFT.cli_help(), allow_negative_numbers = true))]
    pub clock_drift: Option<f64>,
    /// How a swarm's drones share the air: `aloha` or `slotted`.
    #[cfg_attr(
        not(target_arch = "wasm32"),
        arg(
            long,
            value_enum,
            default_value = "aloha",
            help = "How a swarm's drones share the air: aloha (each sends when its duty cycle allows, after its random delay) or slotted (a slot each in a frame on GPS time; no two drones on one SF and channel overlap). swarm only; not with --adr."
        )
    )]
    pub schedule: Schedule,
}

impl AccessSettings {
    /// Checks each setting given against its limits.
    pub fn validate(&self) -> Result<(), SimError> {
        if let Some(j) = self.jitter {
            opt::JITTER.check(j)?;
        }
        if let Some(d) = self.clock_drift {
            opt::CLOCK_DRIFT.check(d)?;
        }
        Ok(())
    }

    /// The timing of a swarm's drones: as given, else the defaults of [`opt::JITTER`] and
    /// [`opt::CLOCK_DRIFT`].
    pub fn swarm_timing(&self) -> Timing {
        Timing {
            clock_drift_ppm: self.clock_drift.unwrap_or(opt::CLOCK_DRIFT.default),
            jitter: self.jitter.unwrap_or(opt::JITTER.default),
        }
    }

    /// The timing of `simulate`'s drone: as given, else the paper's exact timing.
    pub fn single_timing(&self) -> Timing {
        Timing {
            clock_drift_ppm: self.clock_drift.unwrap_or(0.0),
            jitter: self.jitter.unwrap_or(0.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_swarm_drifts_and_jitters_by_default_and_simulate_keeps_the_papers_timing() {
        let a = AccessSettings::default();
        assert!(a.single_timing().is_exact());
        assert!(!a.swarm_timing().is_exact());
        let zero = AccessSettings {
            jitter: Some(0.0),
            clock_drift: Some(0.0),
            ..Default::default()
        };
        assert!(zero.swarm_timing().is_exact());
    }

    #[test]
    fn refuses_a_negative_jitter() {
        let a = AccessSettings {
            jitter: Some(-1.0),
            ..Default::default()
        };
        assert!(a.validate().is_err());
    }
}
