//! Listen-before-talk: the alternative to the duty cycle that ETSI EN 300 220-2 (V3.2.1, §4.4.2)
//! allows in the 863–870 MHz band, and that AS923 devices in Japan use (ARIB STD-T108).
//! `docs/reference.md` §15.
//!
//! Before each uplink a device listens on its channel; it transmits only if the channel is
//! quieter than a threshold, and otherwise tries another channel (adaptive frequency agility) or
//! backs off for a random time. In exchange for listening, ETSI allows up to 100 s of
//! transmission per hour per 200 kHz of spectrum, with at least 100 ms off after each
//! transmission on a channel. A listener hears only what reaches it: a drone too far from
//! another to hear it may still collide with it at the gateway (the hidden-node problem).

use serde::{Deserialize, Serialize};

/// How a device earns the right to transmit (`--access`). Listening lasts [`LISTEN_S`] and
/// hears a channel busy above [`THRESHOLD_DBM`]; the variants' docs are `--access`'s help.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum ChannelAccess {
    /// The plan's duty cycle (the paper).
    #[default]
    DutyCycle,
    /// Listen before each uplink (5 ms; busy above −80 dBm), and keep ETSI's 100 s of airtime
    /// per hour.
    Lbt,
}

impl ChannelAccess {
    /// The CLI/JS name: `duty-cycle` or `lbt`.
    pub fn name(self) -> &'static str {
        match self {
            ChannelAccess::DutyCycle => "duty-cycle",
            ChannelAccess::Lbt => "lbt",
        }
    }
}

/// How long a device listens before transmitting, s (ARIB STD-T108's carrier sense, and
/// LoRaMac-node's `AS923_CARRIER_SENSE_TIME` of 5 ms; ETSI asks at least 160 µs).
pub const LISTEN_S: f64 = 0.005;

/// The received power above which a channel is busy, dBm (LoRaMac-node's
/// `AS923_RSSI_FREE_TH`, ARIB STD-T108's −80 dBm).
pub const THRESHOLD_DBM: f64 = -80.0;

/// The most a device may transmit per hour per 200 kHz with listen-before-talk, s (ETSI EN
/// 300 220-2 V3.2.1 Table 9).
pub const MAX_ON_TIME_PER_HOUR_S: f64 = 100.0;

/// The shortest silence after each transmission on a channel, s (ETSI EN 300 220-2).
pub const MIN_OFF_TIME_S: f64 = 0.1;

/// The duty cycle ETSI's hourly limit amounts to, spread evenly: 100 / 3600 ≈ 2.8 %, almost
/// three times EU868's 1 %. (A 125 kHz channel is within one 200 kHz slice.)
pub fn duty_cycle() -> f64 {
    MAX_ON_TIME_PER_HOUR_S / 3600.0
}

/// The longest random backoff after finding every channel busy, s: ten of the device's own
/// packets, so that slow SFs wait longer, as their neighbours' packets last longer.
pub fn max_backoff(time_on_air: f64) -> f64 {
    10.0 * time_on_air
}

/// Whether a listener receiving `rx_dbm` finds the channel busy.
pub fn busy(rx_dbm: f64) -> bool {
    rx_dbm > THRESHOLD_DBM
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--access lbt`'s help is the variant's doc, written with the numbers for a CLI user.
    #[cfg(cli)]
    #[test]
    fn the_cli_help_states_the_listening_the_code_does() {
        let value = clap::ValueEnum::to_possible_value(&ChannelAccess::Lbt).unwrap();
        let help = value.get_help().unwrap().to_string();
        let said = format!("{} ms; busy above −{} dBm", LISTEN_S * 1e3, -THRESHOLD_DBM);
        assert!(help.contains(&said), "{help}");
    }

    #[test]
    fn lbt_allows_almost_three_times_the_airtime_of_eu868s_one_percent() {
        assert!((duty_cycle() / 0.01 - 2.78).abs() < 0.01);
        // Even the shortest LoRa packet (SF7/500 kHz, a few ms) waits over 100 ms at 2.8 %.
        assert!(0.005 / duty_cycle() > MIN_OFF_TIME_S);
    }

    #[test]
    fn a_channel_is_busy_only_above_the_threshold() {
        assert!(busy(-79.0));
        assert!(!busy(-80.0));
        assert!(!busy(-120.0));
    }
}
