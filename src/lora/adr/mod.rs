//! Adaptive data rate: the network chooses the drone's data rate and transmit power from the
//! uplinks it hears, and tells the drone in a downlink (LoRaWAN 1.0.3 §5.3 `LinkADRReq`).
//!
//! * [`AdrDevice`]: the drone's side: applies commands, and backs off on its own when it hears
//!   nothing (`ADR_ACK_LIMIT`, `ADR_ACK_DELAY`).
//! * [`LorawanAdr`]: Semtech's recommended network-server algorithm, as the ns-3 `lorawan`
//!   module implements it: margin of the best recent SNR, 3 dB steps, DR5 at most.
//! * [`TrackingAdr`]: ours: the data rate with the smallest expected cost in the age of the
//!   station's newest packet, from the delivery it estimates for each rate over the long run and,
//!   through a fade, for the next frame.

mod device;
mod lorawan;
mod tracking;

pub use device::{AckLimits, AdrDevice, UplinkFrame, ADR_ACK_DELAY, ADR_ACK_LIMIT};
pub use lorawan::{LorawanAdr, LORAWAN_ADR_MAX_DR};
pub use tracking::{
    expected_age_cost, tracking_ack_limits, TrackingAdr, ERROR_GROWTH, TRACKING_HYSTERESIS,
    TRACKING_WINDOW,
};

use super::{DataRate, LoraError};
use serde::{Deserialize, Serialize};

/// Which network-side ADR runs (`--adr`): [`LorawanAdr`] or [`TrackingAdr`]. The variants' docs
/// are `--adr`'s help, in a CLI user's words.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum AdrMode {
    /// The data rate stays where `--sf`/`--bw` put it (the paper).
    #[default]
    Off,
    /// LoRaWAN's network-server ADR (Semtech's algorithm, as ns-3 runs it):
    /// once --adr-history uplinks have arrived, each whole 3 dB of margin over --adr-margin raises
    /// the data rate (to DR5 at most), then lowers the power; only the device's own back-off slows
    /// it. Built for delivery and battery, not tracking.
    Lorawan,
    /// Ours: the network picks the data rate whose packets keep the station's newest packet
    /// youngest, from each rate's delivery estimated on the received frames, and slows it
    /// through a fade it sees coming (docs/beyond-the-paper.md, "Adaptive data rate").
    Tracking,
}

impl AdrMode {
    /// The CLI/JS name.
    pub fn name(self) -> &'static str {
        match self {
            AdrMode::Off => "off",
            AdrMode::Lorawan => "lorawan",
            AdrMode::Tracking => "tracking",
        }
    }
}

impl core::str::FromStr for AdrMode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim().to_ascii_lowercase().as_str() {
            "off" => Ok(AdrMode::Off),
            "lorawan" => Ok(AdrMode::Lorawan),
            "tracking" => Ok(AdrMode::Tracking),
            other => Err(format!(
                "unknown adr '{other}' (expected off, lorawan or tracking)"
            )),
        }
    }
}

/// Transmit-power steps of `LinkADRReq`, dB (Semtech's recommended algorithm; EU868 TXPower
/// indices are 2 dB apart, the algorithm moves 3 dB per margin step).
pub const TX_POWER_STEP_DB: f64 = 3.0;
/// The largest power reduction ADR may ask for, dB: EU868 allows down to MaxEIRP − 14 dB; four
/// 3 dB steps stay inside it.
pub const MAX_POWER_REDUCTION_DB: f64 = 12.0;
/// Default device margin of [`LorawanAdr`], dB (Semtech's recommended algorithm; The Things Stack
/// uses 15).
pub const DEFAULT_ADR_MARGIN_DB: f64 = crate::options::ADR_MARGIN.default;
/// Default number of uplinks whose best SNR [`LorawanAdr`] uses (Semtech, The Things Stack).
pub const DEFAULT_ADR_HISTORY: usize = crate::options::ADR_HISTORY.default as usize;
/// The gateway's downlink power, dBm (EU868 RX1 in the 1 % sub-band: 14 dBm ERP).
pub const GATEWAY_TX_POWER_DBM: f64 = 14.0;
/// The device opens its first receive window this long after an uplink ends, s (LoRaWAN
/// `RECEIVE_DELAY1`).
pub const RECEIVE_DELAY1_S: f64 = 1.0;

/// ADR settings.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct AdrParams {
    /// Which algorithm.
    pub mode: AdrMode,
    /// [`LorawanAdr`]'s device margin, dB.
    pub margin_db: f64,
    /// [`LorawanAdr`]'s history length, uplinks.
    pub history: usize,
}

impl Default for AdrParams {
    fn default() -> Self {
        AdrParams {
            mode: AdrMode::Off,
            margin_db: DEFAULT_ADR_MARGIN_DB,
            history: DEFAULT_ADR_HISTORY,
        }
    }
}

impl AdrParams {
    /// Checks the margin and the history against their limits ([`crate::options`]).
    pub fn validate(&self) -> Result<(), LoraError> {
        crate::options::ADR_MARGIN.check(self.margin_db)?;
        crate::options::ADR_HISTORY.check(self.history as f64)?;
        Ok(())
    }
}

/// What the network knows of one received uplink.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UplinkReport {
    /// The frame counter (counts every uplink, so gaps are lost frames).
    pub fcnt: u32,
    /// Its data rate.
    pub dr: DataRate,
    /// The device's power reduction below its maximum, dB.
    pub power_reduction_db: f64,
    /// Received power, dBm.
    pub rssi_dbm: f64,
    /// SNR, dB ([`snr_db`](super::snr_db)).
    pub snr_db: f64,
    /// The frame's `ADRACKReq` bit: the server answers it with a downlink, command or not.
    pub adr_ack_req: bool,
    /// The drone's speed its payload reports, m/s: the server decodes every uplink, and
    /// [`TrackingAdr`] reads from it how far the drone flies between frames.
    pub speed_mps: f64,
    /// Per EU868 data rate (index = DR), the chance that a frame of this device at that rate
    /// overlaps another device's frame at its SF, from the traffic the server hears (pure
    /// ALOHA; 0 for a lone device). [`TrackingAdr`] reads a lost frame as either lost in this
    /// crowd or below the sensitivity.
    pub crowd_loss: [f64; 7],
}

/// A `LinkADRReq`: the data rate and power the device should use from its next uplink.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkAdrReq {
    /// Data rate.
    pub dr: DataRate,
    /// Power reduction below the maximum, dB (0, 3, …, 12).
    pub power_reduction_db: f64,
}

/// A network server's ADR: sees every received uplink, may answer with a command.
pub trait AdrNetwork {
    /// Called for each uplink the gateway received; returns the command to send in the downlink
    /// after it, if the device should change.
    fn on_uplink(&mut self, up: &UplinkReport) -> Option<LinkAdrReq>;

    /// Whether the network keeps its answers out of RX2 where the other devices would lose
    /// frames while the gateway sends there: a half-duplex gateway hears nothing during RX2's
    /// SF12 frame (over a second), and a command can wait for RX1 after a later uplink. LoRaWAN
    /// network servers answer in RX2 whenever RX1 is not free (`false`, the default).
    fn spares_the_gateway(&self) -> bool {
        false
    }
}
