//! Channel sensing: an error-triggered drone that hears how crowded its channel is sends less
//! there (reference §4, "A drone that listens").

use serde::{Deserialize, Serialize};

/// Whether an error-triggered drone listens to its channel as each uplink starts
/// (`--channel-sense`, JS `channelSense`; what it hears and the threshold it implies:
/// [`ChannelLoad`], [`ChannelLoad::threshold`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum ChannelSense {
    /// It does not listen: its threshold is the one set.
    Off,
    /// Channel activity detection (CAD), which LoRa radios such as the SX1276 run in a few
    /// symbols: as each uplink starts the drone learns whether another packet of its spreading
    /// factor is on air on its channel and loud enough for it to detect, keeps a running share
    /// of busy starts and divides its threshold by the chance that a packet gets through at
    /// that load. The default: a drone alone never hears another packet, so its threshold stays
    /// the one set, and in a crowd of 72 on one SF7 channel the default 2 m threshold then beats
    /// periodic sending (0.93× the median drone's p75 over 16 seeds, against 0.99× not
    /// listening). A threshold already on the crowd's scale (40 m with a 60 s heartbeat and a
    /// budget there) is raised too far (1.10× not listening's p75): docs/beyond-the-paper.md,
    /// "When to send".
    #[default]
    Cad,
}

/// How far each sensed uplink start moves the busy share: about the last ten uplinks count.
pub const SENSE_GAIN: f64 = 0.1;

/// The least chance of success a threshold is divided by: at most a 20-fold threshold, so that a
/// channel heard busy at every start still leaves the drone a threshold, not silence until its
/// heartbeat.
pub const MIN_SUCCESS: f64 = 0.05;

/// The share of a drone's recent uplink starts that found its channel busy, and the threshold
/// it implies.
///
/// Under pure ALOHA a packet gets through when no other packet starts within one packet time
/// before or after it: with G packets on air on average, e^(−2G), the square of e^(−G), the
/// chance that the channel is free at a moment (Abramson 1970). So a busy share b seen at the
/// starts gives a success chance of about (1 − b)², and a threshold of θ / (1 − b)²: a drone that
/// hears a crowd waits for a larger drift before it sends, which also leaves the channel freer
/// for the others. A drone alone never hears a packet: its threshold stays θ.
///
/// ```
/// use loratrack::ChannelLoad;
/// let mut load = ChannelLoad::default();
/// assert_eq!(load.threshold(2.0), 2.0);
/// for _ in 0..100 {
///     load.sensed(true);
///     load.sensed(false);
/// }
/// // Busy at about half the starts: a quarter's chance of success, four times the threshold.
/// assert!((load.threshold(2.0) - 8.0).abs() < 1.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ChannelLoad {
    busy: f64,
}

impl ChannelLoad {
    /// An uplink started on a channel that was `busy`.
    pub fn sensed(&mut self, busy: bool) {
        let seen = if busy { 1.0 } else { 0.0 };
        self.busy += SENSE_GAIN * (seen - self.busy);
    }

    /// The share of recent uplink starts that found the channel busy, 0…1.
    pub fn busy_share(&self) -> f64 {
        self.busy
    }

    /// `threshold` (m) divided by the chance of success at the load heard, (1 − b)², at least
    /// [`MIN_SUCCESS`].
    pub fn threshold(&self, threshold: f64) -> f64 {
        let free = 1.0 - self.busy;
        threshold / (free * free).max(MIN_SUCCESS)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_drone_that_never_hears_a_packet_keeps_its_threshold() {
        let mut load = ChannelLoad::default();
        for _ in 0..50 {
            load.sensed(false);
        }
        assert_eq!(load.busy_share(), 0.0);
        assert_eq!(load.threshold(2.0), 2.0);
    }

    #[test]
    fn a_busy_channel_raises_the_threshold_by_alohas_chance_of_success_up_to_twentyfold() {
        let mut load = ChannelLoad::default();
        load.sensed(true);
        assert!((load.busy_share() - SENSE_GAIN).abs() < 1e-12);
        assert!((load.threshold(2.0) - 2.0 / (0.9 * 0.9)).abs() < 1e-12);
        for _ in 0..500 {
            load.sensed(true);
        }
        assert!(load.busy_share() > 0.99);
        assert!((load.threshold(2.0) - 2.0 / MIN_SUCCESS).abs() < 1e-9);
    }

    #[test]
    fn the_busy_share_forgets_old_starts() {
        let mut load = ChannelLoad::default();
        for _ in 0..100 {
            load.sensed(true);
        }
        for _ in 0..50 {
            load.sensed(false);
        }
        assert!(load.busy_share() < 0.01, "{}", load.busy_share());
    }
}
