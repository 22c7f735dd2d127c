//! The sending settings, validated in one place for every run.

use super::{ChannelSense, ErrorTriggered, PayloadChoice, Periodic, Sender, SenderKind};
use crate::lora::{DutyCycle, DutyCycleMode, LoraError};
use crate::options::{BURST, MAX_INTERVAL, THRESHOLD};
use crate::sim::station::{MissionPlan, StationModel, StationSetup};
use crate::sim::SimError;
use serde::{Deserialize, Serialize};

/// Default error-triggered threshold, m: about twice the on-time p75 of the paper's station at
/// SF7 / 1 km, so packets go when the station is clearly off, not on every wobble.
pub const DEFAULT_THRESHOLD_M: f64 = THRESHOLD.default;
/// Default heartbeat, s: a lost packet is repaired within 10 s, at 1/5 of the periodic airtime
/// at SF7 / 250 kHz.
pub const DEFAULT_MAX_INTERVAL_S: f64 = MAX_INTERVAL.default;
/// Default budget capacity, packets ("holds at most K packets' airtime (default 10)").
pub const DEFAULT_BURST: u32 = BURST.default as u32;

/// When a drone sends and which duty-cycle rule bounds it (flat keys `sender`, `threshold`,
/// `maxInterval`, `channelSense`, `dutyCycleMode`, `payload`, `burst`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Sending {
    /// The sending policy.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "When the drone sends: periodic (as often as the duty cycle allows, the paper) or error (when the mirrored station drifts past --threshold)."
        )
    )]
    pub sender: SenderKind,
    /// Error-triggered threshold, m.
    #[cfg_attr(cli, arg(long, default_value_t = THRESHOLD.default, help = THRESHOLD.cli_help(), allow_negative_numbers = true, value_parser = crate::options::number("threshold")))]
    pub threshold: f64,
    /// Error-triggered heartbeat, s.
    #[cfg_attr(cli, arg(long, default_value_t = MAX_INTERVAL.default, help = MAX_INTERVAL.cli_help(), allow_negative_numbers = true, value_parser = crate::options::number("maxInterval")))]
    pub max_interval: f64,
    /// Error-triggered sending: whether the drone listens to its channel and sends less where
    /// it is crowded ([`ChannelSense`]).
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Error-triggered sending: cad (channel activity detection as each uplink starts: the threshold is divided by (1 - b)^2, b the share of recent starts that found another packet of the drone's SF on its channel; a drone alone keeps its threshold) or off (the threshold as set, whatever the crowd). swarm only."
        )
    )]
    pub channel_sense: ChannelSense,
    /// The duty-cycle rule.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Duty-cycle rule: per-packet (off-time of time-on-air / duty-cycle after each packet) or budget (airtime credit over time, up to --burst packets; ETSI EN 300 220 counts over an hour)."
        )
    )]
    pub duty_cycle_mode: DutyCycleMode,
    /// Which payload each packet takes: `full` (the model's own, the paper) or `lean`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = PayloadChoice::cli_help()
        )
    )]
    pub payload: PayloadChoice,
    /// Budget capacity, packets.
    #[cfg_attr(cli, arg(long, default_value_t = DEFAULT_BURST, help = BURST.cli_help(), allow_negative_numbers = true, value_parser = crate::options::whole::<u32>("burst")))]
    pub burst: u32,
}

impl Default for Sending {
    fn default() -> Self {
        Sending {
            sender: SenderKind::Periodic,
            threshold: DEFAULT_THRESHOLD_M,
            max_interval: DEFAULT_MAX_INTERVAL_S,
            channel_sense: ChannelSense::default(),
            duty_cycle_mode: DutyCycleMode::PerPacket,
            payload: PayloadChoice::Full,
            burst: DEFAULT_BURST,
        }
    }
}

impl Sending {
    /// Checks each setting against its limits, and that each one changed from its default
    /// applies: error-triggered sending's with that sender, the budget's burst with the budget.
    pub fn validate(&self) -> Result<(), SimError> {
        THRESHOLD.check(self.threshold)?;
        MAX_INTERVAL.check(self.max_interval)?;
        BURST.check(f64::from(self.burst))?;
        let defaults = Sending::default();
        SimError::unless_read(
            self.sender == SenderKind::Error,
            &[
                ("threshold", self.threshold != defaults.threshold),
                ("maxInterval", self.max_interval != defaults.max_interval),
                ("channelSense", self.channel_sense != defaults.channel_sense),
            ],
            "error-triggered sending's",
            "set `sender` to error",
        )?;
        SimError::unless_read(
            self.duty_cycle_mode == DutyCycleMode::Budget,
            &[("burst", self.burst != defaults.burst)],
            "the budget duty-cycle rule's",
            "set `dutyCycleMode` to budget",
        )?;
        Ok(())
    }

    /// Periodic sending under the per-packet rule with these settings' payload: the sender an
    /// error-triggered one is compared with (its threshold, heartbeat, listening and burst are
    /// none of periodic sending's, which refuses them).
    pub fn periodic(&self) -> Sending {
        Sending {
            payload: self.payload,
            ..Sending::default()
        }
    }

    /// The duty-cycle rule for packets of `time_on_air` s at `duty_cycle`, from time 0: the
    /// [`Flier`](crate::sim::Flier) starts it when its drone first may send.
    pub fn rule(&self, duty_cycle: f64, time_on_air: f64) -> Result<DutyCycle, LoraError> {
        DutyCycle::new(
            self.duty_cycle_mode,
            duty_cycle,
            time_on_air,
            self.burst,
            0.0,
        )
    }

    /// A drone's sender for one flight; an error-triggered one mirrors a fresh station of the
    /// kind the ground runs (`model` with `setup`, and for a mission station the drone's `plan`).
    pub fn sender(
        &self,
        model: StationModel,
        setup: StationSetup,
        plan: Option<&MissionPlan>,
    ) -> Box<dyn Sender> {
        match self.sender {
            SenderKind::Periodic => Box::new(Periodic),
            SenderKind::Error => Box::new(ErrorTriggered::new(
                model,
                setup,
                plan,
                (self.threshold, self.max_interval),
                self.channel_sense,
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn periodic_sending_refuses_the_settings_only_error_triggered_sending_reads() {
        let changed = [
            Sending {
                threshold: 5.0,
                ..Sending::default()
            },
            Sending {
                max_interval: 30.0,
                ..Sending::default()
            },
            Sending {
                channel_sense: ChannelSense::Off,
                ..Sending::default()
            },
        ];
        for sending in changed {
            let e = sending.validate().unwrap_err();
            assert!(matches!(e, SimError::Unused { .. }), "{e}");
            let error = Sending {
                sender: SenderKind::Error,
                ..sending
            };
            assert_eq!(error.validate(), Ok(()));
        }
    }

    #[test]
    fn a_burst_is_refused_without_the_budget_rule() {
        let burst = Sending {
            burst: 4,
            ..Sending::default()
        };
        assert_eq!(burst.validate().unwrap_err().setting(), Some("burst"));
        let budget = Sending {
            duty_cycle_mode: DutyCycleMode::Budget,
            ..burst
        };
        assert_eq!(budget.validate(), Ok(()));
    }

    #[test]
    fn the_periodic_sender_of_error_triggered_settings_keeps_only_their_payload() {
        let error = Sending {
            sender: SenderKind::Error,
            threshold: 5.0,
            max_interval: 30.0,
            channel_sense: ChannelSense::Off,
            duty_cycle_mode: DutyCycleMode::Budget,
            payload: PayloadChoice::Lean,
            burst: 4,
        };
        let periodic = error.periodic();
        assert_eq!(periodic.validate(), Ok(()));
        assert_eq!(
            periodic,
            Sending {
                payload: PayloadChoice::Lean,
                ..Sending::default()
            }
        );
    }
}
