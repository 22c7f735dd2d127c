//! How drones get on the air: the regional plan and what limits their sending (a duty cycle,
//! or an interval where the plan has none, and a network's fair use), their clocks and random
//! delays, and in a swarm the schedule they keep. `docs/reference.md` §13, §14.

use crate::lora::{lbt, ChannelAccess, FairUse, Region};
use crate::options as opt;
use crate::sim::clock::Timing;
use crate::sim::schedule::Schedule;
use crate::sim::SimError;
use serde::{Deserialize, Serialize};

/// The plan, the sending limits, clocks, delays and the swarm's schedule (flat keys `region`,
/// `interval`, `fairUse`, `jitter`, `clockDrift`, `schedule`). Unset clock values take the
/// command's default: a swarm's drones drift and jitter as real ones do; `simulate` keeps the
/// paper's exact timing.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct AccessSettings {
    /// The regional plan.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "LoRaWAN regional plan (RP002-1.0.4): eu868 (duty cycle; raw LoRa at any SF/bandwidth allowed, as the paper), us915 (DR0-DR4, 400 ms dwell, no duty cycle: --interval), au915 (DR2-DR6, 400 ms dwell, --interval), as923 (DR2-DR6, 400 ms dwell, 1 % duty cycle), in865 (DR0-DR5, --interval)."
        )
    )]
    pub region: Region,
    /// Where the plan has no duty cycle: seconds between uplink starts.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(cli, arg(long, help = opt::INTERVAL.cli_help(), allow_negative_numbers = true, value_parser = opt::number("interval")))]
    pub interval: Option<f64>,
    /// How a drone earns the right to send: the plan's duty cycle, or listen-before-talk.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "How a drone earns the right to send: duty-cycle (the plan's), or lbt (listen 5 ms before each uplink, send only below -80 dBm, else try another channel or back off; ETSI's 100 s of airtime per hour). Plans with a duty cycle only (eu868, as923)."
        )
    )]
    pub access: ChannelAccess,
    /// A network's fair-use policy: `off` or `ttn`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Fair-use policy on top of the plan: off, or ttn (The Things Network: 30 s of airtime per day, spread evenly)."
        )
    )]
    pub fair_use: FairUse,
    /// The longest random delay before each uplink, s.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(cli, arg(long, help = opt::JITTER.cli_help(), allow_negative_numbers = true, value_parser = opt::number("jitter")))]
    pub jitter: Option<f64>,
    /// The largest clock error, ppm.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(cli, arg(long, help = opt::CLOCK_DRIFT.cli_help(), allow_negative_numbers = true, value_parser = opt::number("clockDrift")))]
    pub clock_drift: Option<f64>,
    /// How a swarm's drones share the air: `aloha` or `slotted`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "How a swarm's drones share the air: aloha (each sends when its duty cycle allows, after its random delay) or slotted (a slot each in a frame on GPS time; no two drones on one SF and channel overlap). swarm only; not with --adr."
        )
    )]
    pub schedule: Schedule,
}

impl AccessSettings {
    /// Checks each setting given against its limits, and that `duty_cycle` (the `dutyCycle`
    /// setting) applies: a plan without a duty cycle, or listen-before-talk, would ignore it.
    pub fn validate(&self, duty_cycle: f64) -> Result<(), SimError> {
        let changed = duty_cycle != opt::DUTY_CYCLE.default;
        if self.region.duty_cycle().is_none() {
            if self.access == ChannelAccess::Lbt {
                return Err(SimError::Source(format!(
                    "`access` lbt replaces a duty cycle; {} has none (its sending interval is `interval`)",
                    self.region.label()
                )));
            }
            if changed {
                return Err(SimError::Source(format!(
                    "{} has no duty cycle: set `interval` instead of `dutyCycle`",
                    self.region.label()
                )));
            }
        }
        if self.access == ChannelAccess::Lbt && changed {
            return Err(SimError::Source(
                "`dutyCycle` does not apply with `access` lbt (ETSI's 100 s of airtime per hour)"
                    .into(),
            ));
        }
        if let Some(i) = self.interval {
            opt::INTERVAL.check(i)?;
            if self.region.duty_cycle().is_some() {
                return Err(SimError::Source(format!(
                    "`interval` is for plans without a duty cycle; {} limits sending by its duty cycle (`dutyCycle`)",
                    self.region.label()
                )));
            }
        }
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

    /// The duty cycle a drone's rule enforces for packets of `time_on_air` s: the plan's
    /// (`duty_cycle`, the setting) or, where the plan has none, time on air / `interval`; never
    /// above what the fair-use policy leaves. An interval shorter than the time on air is refused.
    pub fn duty_cycle_for(&self, duty_cycle: f64, time_on_air: f64) -> Result<f64, SimError> {
        let plan = match self.region.duty_cycle() {
            Some(_) if self.access == ChannelAccess::Lbt => lbt::duty_cycle(),
            Some(_) => duty_cycle,
            None => {
                let interval = self.interval.unwrap_or(opt::INTERVAL.default);
                if interval < time_on_air {
                    return Err(SimError::Parameter(
                        "interval",
                        interval,
                        "at least the time on air of every drone's frame",
                    ));
                }
                time_on_air / interval
            }
        };
        Ok(plan.min(self.fair_use.duty_cycle()))
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
        assert!(a.validate(0.01).is_err());
    }
}
