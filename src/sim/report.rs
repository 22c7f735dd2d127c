//! The JSON shapes of `simulate` and `sweep` (SPEC §8): a contract, changed only additively.

use super::sender::Sending;
use super::station::{Prediction, StationModel};
use crate::lora::AdrMode;
use crate::metrics::{Boxplot, Summary};
use serde::Serialize;
use std::collections::BTreeMap;

/// Echo of the settings, plus what the run covered.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct RunConfig {
    /// Flight(s) simulated.
    pub trajectory: String,
    /// Number of flights.
    pub flights: usize,
    /// Seconds of flight simulated (all flights).
    pub flight_time: f64,
    /// Stations run.
    pub models: Vec<StationModel>,
    /// The station's prediction between packets: `paper` or `bounded`.
    pub prediction: Prediction,
    /// When the drone sends: `sender` (`periodic` or `error`), `threshold`, `maxInterval`,
    /// `dutyCycleMode` (`per-packet` or `budget`), `burst`.
    #[serde(flatten)]
    pub sending: Sending,
    /// Adaptive data rate: `off`, `lorawan` or `tracking`.
    pub adr: AdrMode,
    /// LoRaWAN ADR's device margin, dB.
    pub adr_margin: f64,
    /// LoRaWAN ADR's history, uplinks.
    pub adr_history: usize,
    /// Spreading factor (with ADR: the one the drone starts at).
    pub sf: u8,
    /// Bandwidth, kHz.
    pub bandwidth_khz: f64,
    /// Gateway distance, m.
    pub distance: f64,
    /// Seed.
    pub seed: u64,
    /// MAC overhead, bytes.
    pub overhead: usize,
    /// Coding rate index.
    pub cr: u8,
    /// Duty cycle.
    pub duty_cycle: f64,
    /// Transmit power, dBm.
    pub tx_power: f64,
    /// Path-loss exponent.
    pub path_loss_exponent: f64,
    /// Shadowing sigma, dB.
    pub shadowing: f64,
    /// Gateway height, m.
    pub gateway_height: f64,
    /// Sensor rate, Hz.
    pub sensor_rate: f64,
    /// Station step T, s.
    pub step: f64,
    /// Tilt decay per step.
    pub eta: f64,
    /// Tilt decay per second, eta^(1/T).
    pub eta_per_second: f64,
    /// Process noise scale.
    pub q: f64,
    /// Gateway sensitivity for this SF and bandwidth, dBm.
    pub sensitivity_dbm: f64,
    /// Range where the mean received power meets the sensitivity, m.
    pub range_m: f64,
}

/// Per-axis and 3D boxplots.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Boxplots {
    /// 3D error.
    pub error3d: Boxplot,
    /// |x error|.
    pub error_x: Boxplot,
    /// |y error|.
    pub error_y: Boxplot,
    /// |z error|.
    pub error_z: Boxplot,
}

impl Boxplots {
    /// Boxplots of the four error samples, each already in ascending order.
    pub fn of_sorted(e3: &[f64], ex: &[f64], ey: &[f64], ez: &[f64]) -> Self {
        Boxplots {
            error3d: Boxplot::of_sorted(e3),
            error_x: Boxplot::of_sorted(ex),
            error_y: Boxplot::of_sorted(ey),
            error_z: Boxplot::of_sorted(ez),
        }
    }
}

/// One model's outcome.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ModelResult {
    /// The station: `dr`, `ctra-plus`, `3d-ctra` or `imm`.
    pub model: StationModel,
    /// Payload, bytes.
    pub payload_bytes: usize,
    /// Time on air of one packet (payload + overhead), s (with ADR: at the starting data rate).
    pub time_on_air: f64,
    /// Interval between transmissions under the duty cycle, s (with ADR: at the starting data
    /// rate).
    pub interval: f64,
    /// Packets sent.
    pub packets_sent: usize,
    /// Total time on air of the packets sent over all flights, s.
    pub airtime: f64,
    /// Packets received.
    pub packets_received: usize,
    /// 3D error, m.
    pub error3d: Summary,
    /// |x error|, m.
    pub error_x: Summary,
    /// |y error|, m.
    pub error_y: Summary,
    /// |z error|, m.
    pub error_z: Summary,
    /// Boxplot statistics of the same samples.
    pub boxplot: Boxplots,
    /// Covariance repairs in the drone filter (0 in a healthy run).
    pub filter_recoveries: u64,
    /// Fraction of evaluated steps whose true position lay inside the station's 95 % position
    /// ellipsoid (chi-square, 3 degrees of freedom); a consistent station scores near 0.95,
    /// an overconfident one lower. `null` when nothing was evaluated.
    pub coverage95: f64,
    /// The packets sent at each data rate (one entry without ADR), slowest rate first.
    pub data_rate_use: Vec<DataRateUse>,
    /// IMM only: the mean probability of each member over the evaluated steps.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub model_probability: Option<BTreeMap<&'static str, f64>>,
}

/// One model's time series over the first flight (for plots).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct ModelSeries {
    /// The station.
    pub model: StationModel,
    /// Evaluation times, s.
    pub t: Vec<f64>,
    /// 3D error at each time, m.
    pub error3d: Vec<f64>,
    /// The station's own 95 % bound on that error at each time (the longest semi-axis of its
    /// 95 % position ellipsoid), m.
    pub bound95: Vec<f64>,
    /// Estimated x, y, z at each time, m.
    pub x: Vec<f64>,
    /// See `x`.
    pub y: Vec<f64>,
    /// See `x`.
    pub z: Vec<f64>,
    /// Arrival times of received packets, s.
    pub arrivals: Vec<f64>,
    /// Send times of lost packets, s.
    pub lost: Vec<f64>,
    /// The EU868 data rate of each received packet (`null` for an SF/bandwidth that is none).
    pub arrival_dr: Vec<Option<u8>>,
    /// The data rate of each lost packet.
    pub lost_dr: Vec<Option<u8>>,
}

/// How many packets went at one data rate.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DataRateUse {
    /// EU868 data rate index (`null` when the SF and bandwidth form none, e.g. SF8 at 500 kHz).
    pub dr: Option<u8>,
    /// Spreading factor.
    pub sf: u8,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Packets sent at it.
    pub packets: usize,
    /// Of those, received.
    pub received: usize,
    /// Time on air of one packet at it, s.
    pub time_on_air: f64,
}

/// Ground truth and every model's estimates over the first flight.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct Series {
    /// The flight.
    pub flight: String,
    /// Truth sample times, s (decimated to at most a few thousand points).
    pub t: Vec<f64>,
    /// True x, m.
    pub x: Vec<f64>,
    /// True y, m.
    pub y: Vec<f64>,
    /// True z, m.
    pub z: Vec<f64>,
    /// Gateway position x, y, z, m.
    pub gateway: [f64; 3],
    /// Per model.
    pub models: Vec<ModelSeries>,
}

/// The output of `simulate`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SimReport {
    /// Settings and coverage.
    pub config: RunConfig,
    /// One entry per model.
    pub results: Vec<ModelResult>,
    /// Time series of the first flight, when asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub series: Option<Series>,
}
