//! Simulation options: the `simulate` parameters of SPEC §8–9 and their validation.

use super::sender::{
    SenderKind, Sending, DEFAULT_BURST, DEFAULT_MAX_INTERVAL_S, DEFAULT_THRESHOLD_M,
};
use super::station::{Prediction, StationModel};
use super::SimError;
use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};
use crate::lora::{
    AdrMode, AdrParams, Channel, ChannelParams, DutyCycleMode, LoraParams, DEFAULT_ADR_HISTORY,
    DEFAULT_ADR_MARGIN_DB, LORAWAN_OVERHEAD_BYTES, MIN_DUTY_CYCLE,
};
use serde::{Deserialize, Serialize};

/// The largest seed: 2^53 − 1, so that a seed round-trips through a JavaScript number (and the
/// page's URL) unchanged.
pub const MAX_SEED: u64 = (1 << 53) - 1;

/// A fresh seed in 0..=[`MAX_SEED`] from the operating system's generator (getrandom; Web
/// Crypto in WebAssembly), for runs that should differ, yet can be repeated from the seed they
/// report.
pub fn random_seed() -> Result<u64, String> {
    getrandom::u64()
        .map(|v| v & MAX_SEED)
        .map_err(|e| format!("no random seed available: {e}"))
}

/// A seed as a number, or `"random"` for [`random_seed`].
fn seed_or_random<'de, D: serde::Deserializer<'de>>(d: D) -> Result<u64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Raw {
        Number(u64),
        Text(String),
    }
    match Raw::deserialize(d).map_err(|_| {
        serde::de::Error::custom("seed must be a whole number 0..2^53-1 or \"random\"")
    })? {
        Raw::Number(n) => Ok(n),
        Raw::Text(t) if t.trim().eq_ignore_ascii_case("random") => {
            random_seed().map_err(serde::de::Error::custom)
        }
        Raw::Text(t) => Err(serde::de::Error::custom(format!(
            "seed must be a whole number 0..2^53-1 or \"random\", got '{}'",
            t.chars().take(20).collect::<String>()
        ))),
    }
}

/// `--synthetic all` or `--synthetic N` (1..=30).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
#[serde(untagged)]
pub enum SyntheticChoice {
    /// The whole set of 30 flights.
    All,
    /// One flight, 1..=30.
    One(usize),
}

impl SyntheticChoice {
    fn from_number(n: f64) -> Result<Self, String> {
        if n.fract() == 0.0 && (1.0..=30.0).contains(&n) {
            Ok(SyntheticChoice::One(n as usize))
        } else {
            Err(format!(
                "synthetic must be 'all' or a flight number 1..30, got {n:?}"
            ))
        }
    }

    /// Parses `all` or a flight number 1..30.
    pub fn parse(text: &str) -> Result<Self, String> {
        let t = text.trim();
        if t.eq_ignore_ascii_case("all") {
            return Ok(SyntheticChoice::All);
        }
        match t.parse::<f64>() {
            Ok(n) => Self::from_number(n),
            Err(_) => Err(format!(
                "synthetic must be 'all' or a flight number 1..30, got '{}'",
                t.chars().take(40).collect::<String>()
            )),
        }
    }
}

impl<'de> Deserialize<'de> for SyntheticChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Choice;
        impl serde::de::Visitor<'_> for Choice {
            type Value = SyntheticChoice;
            fn expecting(&self, f: &mut core::fmt::Formatter) -> core::fmt::Result {
                f.write_str("'all' or a flight number 1..30")
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Self::Value, E> {
                SyntheticChoice::parse(s).map_err(E::custom)
            }
            fn visit_f64<E: serde::de::Error>(self, n: f64) -> Result<Self::Value, E> {
                SyntheticChoice::from_number(n).map_err(E::custom)
            }
            fn visit_i64<E: serde::de::Error>(self, n: i64) -> Result<Self::Value, E> {
                self.visit_f64(n as f64)
            }
            fn visit_u64<E: serde::de::Error>(self, n: u64) -> Result<Self::Value, E> {
                self.visit_f64(n as f64)
            }
        }
        d.deserialize_any(Choice)
    }
}

/// `--model`: the stations to compare, as `all` (the paper's three models) or a comma list of
/// `dr`, `ctra-plus`, `3d-ctra` and `imm` (also a JSON array of those names).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ModelChoice(Vec<StationModel>);

impl ModelChoice {
    /// The paper's three models.
    pub fn all() -> Self {
        ModelChoice(StationModel::PAPER.to_vec())
    }

    /// One station.
    pub fn one(model: impl Into<StationModel>) -> Self {
        ModelChoice(vec![model.into()])
    }

    /// The stations to run, in the order given, each once.
    pub fn models(&self) -> &[StationModel] {
        &self.0
    }

    /// Parses `all` or a comma list.
    pub fn parse(text: &str) -> Result<Self, String> {
        if text.trim().eq_ignore_ascii_case("all") {
            return Ok(Self::all());
        }
        Self::from_names(text.split(','))
    }

    fn from_names<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<Self, String> {
        let mut models = Vec::new();
        for name in names {
            let m = name.trim().parse::<StationModel>().map_err(|_| {
                format!("unknown model '{}' (expected dr, ctra-plus, 3d-ctra, imm, a comma list of them, or all)", name.trim())
            })?;
            if !models.contains(&m) {
                models.push(m);
            }
        }
        if models.is_empty() {
            return Err("model: name at least one of dr, ctra-plus, 3d-ctra, imm, or all".into());
        }
        Ok(ModelChoice(models))
    }
}

impl Default for ModelChoice {
    fn default() -> Self {
        Self::all()
    }
}

impl<'de> Deserialize<'de> for ModelChoice {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Text(String),
            List(Vec<String>),
        }
        let raw = Raw::deserialize(d).map_err(|_| {
            serde::de::Error::custom(
                "model must be a name, a comma list of names, or an array of names",
            )
        })?;
        match raw {
            Raw::Text(t) => ModelChoice::parse(&t),
            Raw::List(v) => ModelChoice::from_names(v.iter().map(String::as_str)),
        }
        .map_err(serde::de::Error::custom)
    }
}

/// The input of `simulate` (SPEC §8–9): the CLI's long options in camelCase. Exactly one of
/// `trajectory` (CSV text), `synthetic` or `sample` chooses the flight. Defaults are the paper's
/// (SF7, 250 kHz, 1000 m, all models, Table I noise, eta 0.9) with the LoRaWAN overhead of 13
/// bytes; set `overhead: 0` for the paper's raw-LoRa airtimes.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields, default)]
pub struct SimParams {
    /// CSV text of a flight (the CLI reads `--trajectory FILE` into this).
    pub trajectory: Option<String>,
    /// A name for the CSV flight, shown in reports.
    pub trajectory_name: Option<String>,
    /// Synthetic flight(s).
    pub synthetic: Option<SyntheticChoice>,
    /// A bundled real flight: `canberra`.
    pub sample: Option<String>,
    /// Which station(s): `all`, or a comma list of `dr`, `ctra-plus`, `3d-ctra`, `imm`.
    pub model: ModelChoice,
    /// The station's prediction between packets: `paper` (default) or `bounded`.
    pub prediction: Prediction,
    /// When the drone sends: `periodic` (default) or `error`.
    pub sender: SenderKind,
    /// Error-triggered sending: the drift between the mirrored station and the drone's own
    /// estimate that triggers a packet, m.
    pub threshold: f64,
    /// Error-triggered sending: the longest silence, s (a heartbeat repairs lost packets).
    pub max_interval: f64,
    /// The duty-cycle rule: `per-packet` (default) or `budget`.
    pub duty_cycle_mode: DutyCycleMode,
    /// Budget rule: the most packets' airtime the credit can hold.
    pub burst: u32,
    /// Adaptive data rate: `off` (default), `lorawan` or `tracking`.
    pub adr: AdrMode,
    /// LoRaWAN ADR's device margin, dB.
    pub adr_margin: f64,
    /// LoRaWAN ADR's history, uplinks.
    pub adr_history: usize,
    /// Spreading factor 7..12 (with ADR: the start).
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Horizontal distance from the flight's first point to the gateway, m.
    pub distance: f64,
    /// Seed of every random draw (sensor noise, transmission offset, shadowing); `"random"` draws
    /// one from the operating system ([`random_seed`]), which the report's `config.seed` gives.
    #[serde(deserialize_with = "seed_or_random")]
    pub seed: u64,
    /// MAC overhead, bytes (LoRaWAN 13; the paper's Table II: 0).
    pub overhead: usize,
    /// Coding rate index 1..4.
    pub cr: i64,
    /// Duty-cycle limit, fraction.
    pub duty_cycle: f64,
    /// Transmit power, dBm.
    pub tx_power: f64,
    /// Path-loss exponent.
    pub path_loss_exponent: f64,
    /// Shadowing standard deviation, dB (0: off).
    pub shadowing: f64,
    /// Gateway antenna height, m.
    pub gateway_height: f64,
    /// Drone sensor and filter rate, Hz.
    pub sensor_rate: f64,
    /// Station prediction step T, s.
    pub step: f64,
    /// Tilt-rate decay per station step.
    pub eta: f64,
    /// Process noise q of Q = q·I.
    pub q: f64,
    /// Include time series (error over time, trajectories) of the first flight.
    pub series: bool,
}

impl Default for SimParams {
    fn default() -> Self {
        let ch = ChannelParams::default();
        SimParams {
            trajectory: None,
            trajectory_name: None,
            synthetic: None,
            sample: None,
            model: ModelChoice::all(),
            prediction: Prediction::Paper,
            sender: SenderKind::Periodic,
            threshold: DEFAULT_THRESHOLD_M,
            max_interval: DEFAULT_MAX_INTERVAL_S,
            duty_cycle_mode: DutyCycleMode::PerPacket,
            burst: DEFAULT_BURST,
            adr: AdrMode::Off,
            adr_margin: DEFAULT_ADR_MARGIN_DB,
            adr_history: DEFAULT_ADR_HISTORY,
            sf: 7,
            bw: 250.0,
            distance: 1000.0,
            seed: 1,
            overhead: LORAWAN_OVERHEAD_BYTES,
            cr: 1,
            duty_cycle: 0.01,
            tx_power: ch.tx_power_dbm,
            path_loss_exponent: ch.path_loss_exponent,
            shadowing: ch.shadowing_sigma_db,
            gateway_height: ch.gateway_height,
            sensor_rate: 10.0,
            step: 0.1,
            eta: 0.9,
            q: PAPER_Q,
            series: false,
        }
    }
}

/// Where the flight comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum TrajectorySource {
    /// CSV text and a name.
    Csv(String, String),
    /// Synthetic set or one flight of it.
    Synthetic(SyntheticChoice),
    /// A bundled sample by name.
    Sample(String),
}

/// Validated simulation settings.
#[derive(Clone, Debug, PartialEq)]
pub struct SimConfig {
    /// The flight(s).
    pub source: TrajectorySource,
    /// Stations to run.
    pub models: Vec<StationModel>,
    /// Paper or bounded prediction.
    pub prediction: Prediction,
    /// When the drone sends, under which duty-cycle rule.
    pub sending: Sending,
    /// Radio settings (with ADR: the start).
    pub radio: LoraParams,
    /// Adaptive data rate.
    pub adr: AdrParams,
    /// Link budget.
    pub channel: Channel,
    /// MAC overhead, bytes.
    pub overhead: usize,
    /// Duty cycle, fraction.
    pub duty_cycle: f64,
    /// Gateway distance, m.
    pub distance: f64,
    /// Seed.
    pub seed: u64,
    /// Sensor rate, Hz.
    pub sensor_rate: f64,
    /// Station step, s.
    pub step: f64,
    /// Tilt decay per step.
    pub eta: f64,
    /// Process noise scale.
    pub q: f64,
    /// Measurement variances (paper Table I).
    pub r_diagonal: [f64; 9],
    /// Whether to return time series.
    pub series: bool,
}

fn check(name: &'static str, v: f64, ok: bool, allowed: &'static str) -> Result<(), SimError> {
    if ok && v.is_finite() {
        Ok(())
    } else {
        Err(SimError::Parameter(name, v, allowed))
    }
}

impl SimParams {
    /// The sending settings.
    pub fn sending(&self) -> Sending {
        Sending {
            sender: self.sender,
            threshold: self.threshold,
            max_interval: self.max_interval,
            duty_cycle_mode: self.duty_cycle_mode,
            burst: self.burst,
        }
    }

    /// Validates every option.
    pub fn validate(&self) -> Result<SimConfig, SimError> {
        let chosen = [
            self.trajectory.is_some(),
            self.synthetic.is_some(),
            self.sample.is_some(),
        ];
        let source = match (self.trajectory.clone(), self.synthetic, self.sample.clone()) {
            (Some(text), None, None) => TrajectorySource::Csv(
                text,
                self.trajectory_name
                    .clone()
                    .unwrap_or_else(|| "uploaded CSV".into()),
            ),
            (None, Some(s), None) => TrajectorySource::Synthetic(s),
            (None, None, Some(name)) => TrajectorySource::Sample(name),
            _ => {
                let n = chosen.iter().filter(|c| **c).count();
                return Err(SimError::Source(if n == 0 {
                    "choose a flight: trajectory (CSV), synthetic (all or 1..30) or sample (canberra)".into()
                } else {
                    "choose only one of trajectory, synthetic and sample".into()
                }));
            }
        };
        let radio = LoraParams::from_settings(self.sf, self.bw, self.cr)?;
        let adr = AdrParams {
            mode: self.adr,
            margin_db: self.adr_margin,
            history: self.adr_history,
        };
        adr.validate()?;
        if adr.mode != AdrMode::Off && crate::lora::DataRate::of(radio.sf, radio.bw).is_none() {
            return Err(SimError::AdrStart(radio.sf.get(), radio.bw.khz()));
        }
        let channel = Channel::new(ChannelParams {
            tx_power_dbm: self.tx_power,
            path_loss_exponent: self.path_loss_exponent,
            shadowing_sigma_db: self.shadowing,
            gateway_height: self.gateway_height,
            ..ChannelParams::default()
        })?;
        check(
            "distance",
            self.distance,
            (0.0..=100_000.0).contains(&self.distance),
            "0..100000 m",
        )?;
        check(
            "dutyCycle",
            self.duty_cycle,
            (MIN_DUTY_CYCLE..=1.0).contains(&self.duty_cycle),
            "0.0001..1 (0.01 %..100 %)",
        )?;
        check(
            "sensorRate",
            self.sensor_rate,
            (0.1..=1000.0).contains(&self.sensor_rate),
            "0.1..1000 Hz",
        )?;
        check(
            "step",
            self.step,
            (0.001..=10.0).contains(&self.step),
            "0.001..10 s",
        )?;
        check(
            "eta",
            self.eta,
            (0.0..=1.0).contains(&self.eta),
            "in [0, 1]",
        )?;
        check("q", self.q, self.q > 0.0 && self.q <= 1e3, "in (0, 1000]")?;
        let sending = self.sending();
        sending.validate()?;
        if self.seed > MAX_SEED {
            return Err(SimError::Seed(self.seed));
        }
        if self.overhead > 255 {
            return Err(SimError::Parameter(
                "overhead",
                self.overhead as f64,
                "0..255 bytes",
            ));
        }
        Ok(SimConfig {
            source,
            models: self.model.models().to_vec(),
            prediction: self.prediction,
            sending,
            radio,
            adr,
            channel,
            overhead: self.overhead,
            duty_cycle: self.duty_cycle,
            distance: self.distance,
            seed: self.seed,
            sensor_rate: self.sensor_rate,
            step: self.step,
            eta: self.eta,
            q: self.q,
            r_diagonal: PAPER_R_DIAGONAL,
            series: self.series,
        })
    }
}
