//! One settings type for every run: [`Scenario`], made of small sub-structs (flight, station,
//! sending, radio, channel, network, drone, swarm, run). `simulate` and `swarm` take it, the CLI
//! flattens its sub-structs into its options (clap), the WebAssembly boundary reads it from a flat
//! camelCase JSON object (serde), and reports echo it. Numeric defaults and limits come from
//! [`crate::options`]; [`Scenario::validate`] checks every field before any work starts.
//!
//! The keys are flat on the wire (`{"sf": 9, "adr": "lorawan", "gateways": [...]}`), as they
//! always were; the sub-structs only group them in Rust. Reference: `docs/reference.md` §6.

mod access;
mod choices;
mod command_line;
mod gateways;

pub use access::AccessSettings;
pub use command_line::{CliCommand, FLIGHT_FILE, PLAN_FILE};

pub use choices::{
    parse_seed, random_seed, ModelChoice, SyntheticChoice, TrajectorySource, MAX_SEED,
};
use gateways::check_default_height;
pub use gateways::{validate_sites, GatewaySite};

use super::drone::Sensing;
use super::radio::{DroneRadio, Frame};
use super::sender::{LeanPayload, PayloadChoice, SenderKind, Sending};
use super::station::{
    Bounds, DroneCovariances, HeadingNoise, MissionPlan, PlanPace, Prediction, StationModel,
    StationSetup,
};
use super::streams::DroneStreams;
use super::SimError;
use crate::filter::PAPER_R_DIAGONAL;
use crate::lora::{
    time_on_air, AdrMode, AdrParams, Channel, ChannelParams, DataRate, InterferenceModel,
    LoraParams, Region, RegionError, ShadowingModel,
};
use crate::models::ModelKind;
use crate::options as opt;
use crate::trajectory::{
    parse_plan_as, Cornering, FlightPlan, Trajectory, VehicleChoice, TRACE_TOLERANCE,
};
use choices::seed_or_random;
use serde::de::IgnoredAny;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::sync::Arc;

#[cfg(cli)]
fn on_off(text: &str) -> Result<bool, String> {
    match text.trim().to_ascii_lowercase().as_str() {
        "on" | "true" => Ok(true),
        "off" | "false" => Ok(false),
        _ => Err(format!(
            "expected on or off, got '{}'",
            text.chars().take(20).collect::<String>()
        )),
    }
}

/// The name of a CSV flight given without one.
pub const DEFAULT_CSV_NAME: &str = "uploaded CSV";
/// The name of a flown plan given without its own (`plan_name`).
pub const DEFAULT_PLAN_NAME: &str = "flown plan";

/// Which flight(s) the drones fly: exactly one of CSV text, synthetic flights or a bundled
/// sample, a plan alone (flown), or none in a swarm (each drone then chains synthetic flights
/// for `duration`).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct FlightSettings {
    /// CSV text of a flight (the CLI reads `--trajectory FILE` into this); input only, not
    /// echoed (the JS API's `SimulateParams` adds it to the generated type). Shared, not
    /// copied, by the settings' clones, the source and the simulator's cache: a 10⁶-row
    /// flight's text is tens of megabytes.
    #[serde(default, skip_serializing)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(skip))]
    pub trajectory: Option<Arc<str>>,
    /// A name for the CSV flight, shown in reports; input only.
    #[serde(default, skip_serializing)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(skip))]
    pub trajectory_name: Option<String>,
    /// Synthetic flight(s): `all` or 1..30.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[cfg_attr(
        all(test, not(target_arch = "wasm32")),
        ts(type = "number | 'all'", optional)
    )]
    pub synthetic: Option<SyntheticChoice>,
    /// A bundled real flight: `canberra`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    pub sample: Option<String>,
    /// The drone's mission plan for a CSV or sample flight, as text: a CSV of `x,y,z[,speed[,hold]]`,
    /// a QGroundControl `.plan` or a waypoint list (the CLI reads `--plan FILE` into this;
    /// reference §16); input only, not echoed (the JS API's `SimulateParams` adds it to the
    /// generated type). The synthetic flights carry their own. Without a flight the drone flies
    /// the plan ([`fly_plan`](crate::fly_plan): stopping at every waypoint, no wind), the
    /// mission station's best case.
    #[serde(default, skip_serializing)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(skip))]
    pub plan: Option<String>,
    /// The plan's file name, for the command line that reruns these settings
    /// ([`Scenario::command_line`]); input only.
    #[serde(default, skip_serializing)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(skip))]
    pub plan_name: Option<String>,
}

/// The ground station.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct StationSettings {
    /// Which station(s): `all`, or a comma list of `dr`, `ctra-plus`, `3d-ctra`, `imm`,
    /// `mission`.
    #[cfg_attr(
        cli,
        arg(long, default_value = "all", value_parser = ModelChoice::parse,
            help = "Station model(s): dr, ctra-plus, 3d-ctra, imm (IMM over the three), mission (along the drone's plan: the synthetic flights' own, or --plan), a comma list, or all (the paper's three). A swarm runs one station: all means 3d-ctra.")
    )]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelChoice"))]
    pub model: ModelChoice,
    /// The station's prediction between packets: `paper` (default) or `bounded`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Station prediction between packets: paper (constant a and omega, as published) or bounded (speed and pitch limits, the acceleration fades, overdue manoeuvres decay)."
        )
    )]
    pub prediction: Prediction,
    /// The bounded station's direct noise on heading and pitch: `fixed` (default) or `adaptive`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Bounded station's noise on heading and pitch, the unscented mean's hedge against unseen turns: fixed (q) or adaptive (0, 1 or 3 x q, whichever forecast the flight's packets best once five are scored). Needs --prediction bounded."
        )
    )]
    pub heading_noise: HeadingNoise,
    /// Station prediction step T, s.
    #[cfg_attr(cli, arg(long, default_value_t = opt::STEP.default, help = opt::STEP.cli_help(), allow_negative_numbers = true, value_parser = opt::number("step")))]
    pub step: f64,
    /// Tilt-rate decay per station step.
    #[cfg_attr(cli, arg(long, default_value_t = opt::ETA.default, help = opt::ETA.cli_help(), allow_negative_numbers = true, value_parser = opt::number("eta")))]
    pub eta: f64,
    /// How the mission station paces the drone along its plan.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Mission station: pace along the plan by the plan's leg speeds (plan: the packet's speed gives way to them) or by the packet's speed alone (packet: for a drone that does not keep its plan's timing)."
        )
    )]
    pub plan_pace: PlanPace,
    /// The mission station's off-plan distance, m.
    #[cfg_attr(cli, arg(long, default_value_t = opt::PLAN_TOLERANCE.default, help = opt::PLAN_TOLERANCE.cli_help(), allow_negative_numbers = true, value_parser = opt::number("planTolerance")))]
    pub plan_tolerance: f64,
}

impl Default for StationSettings {
    fn default() -> Self {
        StationSettings {
            model: ModelChoice::all(),
            prediction: Prediction::Paper,
            heading_noise: HeadingNoise::Fixed,
            step: opt::STEP.default,
            eta: opt::ETA.default,
            plan_pace: PlanPace::Plan,
            plan_tolerance: opt::PLAN_TOLERANCE.default,
        }
    }
}

/// The drone's radio.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct RadioSettings {
    /// Spreading factor 7..12 (with ADR: the start).
    #[cfg_attr(cli, arg(long, default_value_t = opt::SF.default as i64, help = opt::SF.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<i64>("sf")))]
    pub sf: i64,
    /// Bandwidth, kHz.
    #[cfg_attr(cli, arg(long, default_value_t = opt::BW.default, help = opt::BW.cli_help(), allow_negative_numbers = true, value_parser = opt::number("bw")))]
    pub bw: f64,
    /// Coding rate index 1..4.
    #[cfg_attr(cli, arg(long, default_value_t = opt::CR.default as i64, help = opt::CR.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<i64>("cr")))]
    pub cr: i64,
    /// MAC overhead, bytes (LoRaWAN 13; the paper's Table II: 0).
    #[cfg_attr(cli, arg(long, default_value_t = opt::OVERHEAD.default as usize, help = opt::OVERHEAD.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<usize>("overhead")))]
    pub overhead: usize,
    /// Duty-cycle limit, fraction.
    #[cfg_attr(cli, arg(long, default_value_t = opt::DUTY_CYCLE.default, help = opt::DUTY_CYCLE.cli_help(), allow_negative_numbers = true, value_parser = opt::number("dutyCycle")))]
    pub duty_cycle: f64,
    /// Transmit power, dBm.
    #[cfg_attr(cli, arg(long, default_value_t = opt::TX_POWER.default, help = opt::TX_POWER.cli_help(), allow_negative_numbers = true, value_parser = opt::number("txPower")))]
    pub tx_power: f64,
}

impl Default for RadioSettings {
    fn default() -> Self {
        RadioSettings {
            sf: opt::SF.default as i64,
            bw: opt::BW.default,
            cr: opt::CR.default as i64,
            overhead: opt::OVERHEAD.default as usize,
            duty_cycle: opt::DUTY_CYCLE.default,
            tx_power: opt::TX_POWER.default,
        }
    }
}

/// The channel between drones and gateways.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct ChannelSettings {
    /// simulate: distance from the flight's first point to the default gateway (refused where
    /// `gateways` are listed, which replace it); swarm: every drone's starting distance from the
    /// centre, m.
    #[cfg_attr(cli, arg(long, default_value_t = opt::DISTANCE.default, help = opt::DISTANCE.cli_help(), allow_negative_numbers = true, value_parser = opt::number("distance")))]
    pub distance: f64,
    /// Path-loss exponent.
    #[cfg_attr(cli, arg(long, default_value_t = opt::PATH_LOSS_EXPONENT.default, help = opt::PATH_LOSS_EXPONENT.cli_help(), allow_negative_numbers = true, value_parser = opt::number("pathLossExponent")))]
    pub path_loss_exponent: f64,
    /// Shadowing standard deviation, dB (0: off).
    #[cfg_attr(cli, arg(long, default_value_t = opt::SHADOWING.default, help = opt::SHADOWING.cli_help(), allow_negative_numbers = true, value_parser = opt::number("shadowing")))]
    pub shadowing: f64,
    /// Whether shadowing varies along the drone's path (the default) or is fixed in space.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Shadowing: path (each frame continues the last over the metres flown, with a fresh draw) or field (fixed in space: runs that differ only in when they send meet the same fades)."
        )
    )]
    pub shadowing_model: ShadowingModel,
    /// Antenna height of every gateway not given its own, m.
    #[cfg_attr(cli, arg(long, default_value_t = opt::GATEWAY_HEIGHT.default, help = opt::GATEWAY_HEIGHT.cli_help(), allow_negative_numbers = true, value_parser = opt::number("gatewayHeight")))]
    pub gateway_height: f64,
}

impl Default for ChannelSettings {
    fn default() -> Self {
        ChannelSettings {
            distance: opt::DISTANCE.default,
            path_loss_exponent: opt::PATH_LOSS_EXPONENT.default,
            shadowing: opt::SHADOWING.default,
            shadowing_model: ShadowingModel::Path,
            gateway_height: opt::GATEWAY_HEIGHT.default,
        }
    }
}

/// Gateways, channels, reception rules and the network server's ADR.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct NetworkSettings {
    /// The gateways; empty for the one default gateway (simulate: `distance` m east of the
    /// flight's first point; swarm: at the centre).
    #[cfg_attr(
        cli,
        arg(long = "gateway", value_name = "E,N[,H]", value_parser = GatewaySite::parse, allow_hyphen_values = true,
            help = "A gateway at E metres east and N north of the origin (simulate: the flight's first point; swarm: the centre), antenna H metres high [default: --gateway-height]; repeat for more (1..16, each coordinate within 100 km). Without it: one gateway, simulate at (--distance, 0), swarm at the centre.")
    )]
    pub gateways: Vec<GatewaySite>,
    /// Uplink channels: 1, or the plan's (the default, when unset).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    #[cfg_attr(cli, arg(long, help = opt::CHANNELS.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<u8>("channels")))]
    pub channels: Option<u8>,
    /// Same-SF capture at 6 dB (off: every same-SF overlap is fatal).
    #[cfg_attr(
        cli,
        arg(long, default_value = "on", value_parser = on_off, value_name = "on|off", action = clap::ArgAction::Set,
            help = "Same-SF capture: the stronger packet survives 6 dB above the others (off: every overlap is fatal). swarm only.")
    )]
    pub capture: bool,
    /// Inter-SF interference by the rejection matrix (off: SFs are orthogonal).
    #[cfg_attr(
        cli,
        arg(long, default_value = "on", value_parser = on_off, value_name = "on|off", action = clap::ArgAction::Set,
            help = "Inter-SF interference by the rejection matrix of ns-3's lorawan module (off: SFs are orthogonal). swarm only.")
    )]
    pub inter_sf: bool,
    /// Adaptive data rate: `off`, `lorawan` or `tracking`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Adaptive data rate: off (fixed --sf/--bw, the paper), lorawan (the network server's ADR from the best SNR across gateways) or tracking (the rate with the least expected squared error: the time mean of the newest packet's age⁴). ADR starts at --sf/--bw, an EU868 data rate."
        )
    )]
    pub adr: AdrMode,
    /// LoRaWAN ADR's device margin, dB.
    #[cfg_attr(cli, arg(long, default_value_t = opt::ADR_MARGIN.default, help = opt::ADR_MARGIN.cli_help(), allow_negative_numbers = true, value_parser = opt::number("adrMargin")))]
    pub adr_margin: f64,
    /// LoRaWAN ADR's history, uplinks.
    #[cfg_attr(cli, arg(long, default_value_t = opt::ADR_HISTORY.default as usize, help = opt::ADR_HISTORY.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<usize>("adrHistory")))]
    pub adr_history: usize,
}

impl Default for NetworkSettings {
    fn default() -> Self {
        NetworkSettings {
            gateways: Vec::new(),
            channels: None,
            capture: true,
            inter_sf: true,
            adr: AdrMode::Off,
            adr_margin: opt::ADR_MARGIN.default,
            adr_history: opt::ADR_HISTORY.default as usize,
        }
    }
}

/// The drone's sensors and filter.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DroneSettings {
    /// Sensor and filter rate, Hz.
    #[cfg_attr(cli, arg(long, default_value_t = opt::SENSOR_RATE.default, help = opt::SENSOR_RATE.cli_help(), allow_negative_numbers = true, value_parser = opt::number("sensorRate")))]
    pub sensor_rate: f64,
    /// Process noise q of Q = q·I (drone and station).
    #[cfg_attr(cli, arg(long, default_value_t = opt::Q.default, help = opt::Q.cli_help(), allow_negative_numbers = true, value_parser = opt::number("q")))]
    pub q: f64,
    /// The vehicle: `auto` (default: a QGroundControl `.plan`'s `vehicleType` or a CSV plan's
    /// `# vehicle:` line, else a multicopter), `multicopter` or `fixed-wing`.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = vehicle_help()
        )
    )]
    pub vehicle: VehicleChoice,
}

/// `--vehicle`'s help, with the top speed a bounded station holds each vehicle to
/// ([`Bounds::for_vehicle`]).
#[cfg(cli)]
fn vehicle_help() -> String {
    let top = |vehicle| Bounds::for_vehicle(vehicle).v_max;
    format!(
        "The vehicle, for how a plan is flown and followed and the top speed a bounded station \
         holds the drone to: auto (a QGroundControl .plan's vehicleType or a CSV plan's line \
         '{mark} fixed-wing', else a multicopter), multicopter (up to {} m/s) or fixed-wing (a \
         plane: wide turns at its speed, no holds, up to {} m/s).",
        top(Cornering::Multicopter),
        top(Cornering::FixedWing),
        mark = crate::VEHICLE_MARK,
    )
}

impl Default for DroneSettings {
    fn default() -> Self {
        DroneSettings {
            sensor_rate: opt::SENSOR_RATE.default,
            q: opt::Q.default,
            vehicle: VehicleChoice::Auto,
        }
    }
}

/// How a swarm is laid out (`swarm` only).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[cfg_attr(cli, derive(clap::ValueEnum))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub enum SfPlan {
    /// SF7..SF12 in turn (drone i gets SF 7 + i mod 6), the paper's suggestion for up to 72
    /// drones; of these, those at which the plan carries the station's frame at the bandwidth
    /// (a data rate, its payload limit, the dwell time: US915 at 125 kHz SF7..SF10 for DR's
    /// 9-byte payload, SF7..SF9 for the 12-byte one) and, where the plan has no duty cycle, whose
    /// frame fits in the interval set; the report's `sfLimit` says which rule left SFs out.
    #[default]
    Spread,
    /// Every drone at `sf`.
    Fixed,
}

/// The swarm's size and layout (`swarm` only; `simulate` flies one drone).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SwarmSettings {
    /// Number of drones.
    #[cfg_attr(cli, arg(long, default_value_t = opt::DRONES.default as usize, help = opt::DRONES.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<usize>("drones")))]
    pub drones: usize,
    /// Seconds of chained synthetic flight per drone (when no flight is chosen).
    #[cfg_attr(cli, arg(long, default_value_t = opt::DURATION.default, help = opt::DURATION.cli_help(), allow_negative_numbers = true, value_parser = opt::number("duration")))]
    pub duration: f64,
    /// How SFs are shared out.
    #[cfg_attr(
        cli,
        arg(
            long,
            value_enum,
            default_value_t,
            help = "Spreading factors: spread (SF7..SF12 in turn, a sixth of the swarm each; where a data rate is needed, outside EU868 or with --adr, those whose data rate at --bw carries the station's frame: with --adr at 250 kHz SF7 alone; where the plan has no duty cycle, those whose frame fits in --interval; the header says why it dealt fewer) or fixed (everyone at --sf)."
        )
    )]
    pub sf_plan: SfPlan,
}

impl Default for SwarmSettings {
    fn default() -> Self {
        SwarmSettings {
            drones: opt::DRONES.default as usize,
            duration: opt::DURATION.default,
            sf_plan: SfPlan::Spread,
        }
    }
}

/// The seed and what to return.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(cli, derive(clap::Args))]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct RunSettings {
    /// Seed of every random draw; `"random"` draws one ([`random_seed`]), which the echo gives.
    #[serde(deserialize_with = "seed_or_random")]
    #[cfg_attr(
        cli,
        arg(long, default_value = "1", value_name = "N|random", value_parser = parse_seed, allow_negative_numbers = true,
            help = "Seed of all random draws (sensor noise, layout, channels, shadowing), 0..2^53-1, or random for a fresh one (reported, so the run can be repeated).")
    )]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number"))]
    pub seed: u64,
    /// How many seeds `simulate` runs (`seed`, `seed + 1`, …), pooled, with 95 % intervals
    /// (`docs/reference.md` §12); a swarm runs one.
    #[cfg_attr(cli, arg(long, default_value_t = opt::SEEDS.default as u32, help = opt::SEEDS.cli_help(), allow_negative_numbers = true, value_parser = opt::whole::<u32>("seeds")))]
    pub seeds: u32,
    /// Include time series of the first flight (simulate).
    #[cfg_attr(
        cli,
        arg(
            long,
            help = "Include time series of the first flight (error over time, trajectories) in the JSON."
        )
    )]
    pub series: bool,
}

impl Default for RunSettings {
    fn default() -> Self {
        RunSettings {
            seed: opt::SEED.default as u64,
            seeds: opt::SEEDS.default as u32,
            series: false,
        }
    }
}

/// Everything a run needs, for `simulate` (one drone) and `swarm` (many).
///
/// ```
/// use loratrack::Scenario;
/// let s = Scenario::from_json(r#"{"synthetic": 1, "sf": 9, "gateways": [{"east": 1000, "north": 0}]}"#).unwrap();
/// assert_eq!(s.radio.sf, 9);
/// assert!(Scenario::from_json(r#"{"spreadingFactor": 9}"#).unwrap().validate().is_err());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase", default)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Scenario {
    /// Which flight(s).
    #[serde(flatten)]
    pub flight: FlightSettings,
    /// The station.
    #[serde(flatten)]
    pub station: StationSettings,
    /// When the drones send, under which duty-cycle rule.
    #[serde(flatten)]
    pub sending: Sending,
    /// The radio.
    #[serde(flatten)]
    pub radio: RadioSettings,
    /// The channel.
    #[serde(flatten)]
    pub channel: ChannelSettings,
    /// Gateways, channels, reception rules, ADR.
    #[serde(flatten)]
    pub network: NetworkSettings,
    /// Sensors and filter.
    #[serde(flatten)]
    pub drone: DroneSettings,
    /// Clocks, delays and schedules.
    #[serde(flatten)]
    pub access: AccessSettings,
    /// Swarm size and layout.
    #[serde(flatten)]
    pub swarm: SwarmSettings,
    /// Seed, series.
    #[serde(flatten)]
    pub run: RunSettings,
    /// Keys no sub-struct knows (a misspelt setting); refused by [`Scenario::validate`].
    #[serde(flatten, skip_serializing)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(skip))]
    pub unknown: BTreeMap<String, IgnoredAny>,
}

/// A validated [`Scenario`] and what it implies.
#[derive(Clone, Debug, PartialEq)]
pub struct Validated {
    /// The settings, as given (with a drawn seed in place of `random`).
    pub settings: Scenario,
    /// The flight(s), if chosen.
    pub source: Option<TrajectorySource>,
    /// Stations to run, in order.
    pub models: Vec<StationModel>,
    /// Radio settings (with ADR: the start).
    pub radio: LoraParams,
    /// Link budget.
    pub channel: Channel,
    /// Adaptive data rate.
    pub adr: AdrParams,
    /// Reception rules.
    pub interference: InterferenceModel,
    /// Measurement variances (paper Table I).
    pub r_diagonal: [f64; 9],
    /// Uplink channels: 1, or the plan's.
    pub channels: u8,
    /// The drone's mission plan as given (`plan`); the synthetic flights' own are traced per
    /// flight ([`Validated::mission_plan`]).
    pub plan: Option<FlightPlan>,
}

impl Scenario {
    /// Reads a flat camelCase JSON object (the JS API's and the `--json` echo's shape).
    pub fn from_json(text: &str) -> Result<Self, String> {
        serde_json::from_str(text).map_err(|e| e.to_string())
    }

    /// A copy with the settings of `changes` (a flat JSON object, as from JS) applied on top;
    /// CSV text is kept unless `changes` gives another.
    ///
    /// ```
    /// use loratrack::Scenario;
    /// let s = Scenario::default().with(&serde_json::json!({"sf": 9, "adr": "lorawan"})).unwrap();
    /// assert_eq!((s.radio.sf, s.network.adr.name()), (9, "lorawan"));
    /// ```
    #[cfg(not(target_arch = "wasm32"))]
    pub fn with(&self, changes: &serde_json::Value) -> Result<Self, String> {
        let mut v = serde_json::to_value(self).map_err(|e| e.to_string())?;
        if let (Some(map), Some(add)) = (v.as_object_mut(), changes.as_object()) {
            for (k, x) in add {
                map.insert(k.clone(), x.clone());
            }
        } else {
            return Err("settings must be a JSON object".into());
        }
        let mut out: Scenario = serde_json::from_value(v).map_err(|e| e.to_string())?;
        if changes.get("trajectory").is_none() {
            out.flight.trajectory = self.flight.trajectory.clone();
            out.flight.trajectory_name = self.flight.trajectory_name.clone();
        }
        if changes.get("plan").is_none() {
            out.flight.plan = self.flight.plan.clone();
            out.flight.plan_name = self.flight.plan_name.clone();
        }
        Ok(out)
    }

    /// Uplink channels: as given, else the regional plan's.
    pub fn channels(&self) -> u8 {
        self.network.channels(self.access.region)
    }

    /// Refuses a key no setting has (a misspelt one), which would otherwise be ignored.
    fn known_keys(&self) -> Result<(), SimError> {
        match self.unknown.keys().next() {
            Some(key) => Err(SimError::Source(format!(
                "unknown setting '{}' (see `loratrack simulate --help` or limits())",
                key.chars().take(40).collect::<String>()
            ))),
            None => Ok(()),
        }
    }

    /// Checks every setting before any work: the first problem, naming the field, the value
    /// and what is accepted.
    pub fn validate(&self) -> Result<Validated, SimError> {
        self.known_keys()?;
        // The settings kept with the run give their CSV text to the source (the echo in every
        // report clones these settings).
        let mut settings = self.clone();
        let source = settings.flight.take_source(self.drone.vehicle)?;
        let (r, c, n) = (&self.radio, &self.channel, &self.network);
        r.validate()?;
        c.validate()?;
        let channels = n.validate(self.access.region)?;
        check_default_height(&n.gateways, c.gateway_height)?;
        settings.network.channels = Some(channels);
        self.drone.validate()?;
        self.station.validate()?;
        let vehicle = self.drone.vehicle.flying(&source)?;
        self.drone.vehicle.check_read(&source, &self.station)?;
        let plan = settings.flight.take_plan(&source, &self.station, vehicle)?;
        self.sending.validate()?;
        self.access.validate(r.duty_cycle)?;
        self.swarm.validate()?;
        self.run.validate()?;
        let radio = LoraParams::from_settings(r.sf, r.bw, r.cr)?;
        let adr = AdrParams {
            mode: n.adr,
            margin_db: n.adr_margin,
            history: n.adr_history,
        };
        if adr.mode != AdrMode::Off && self.access.region != Region::Eu868 {
            return Err(SimError::Source(format!(
                "`adr` runs EU868's data rates; {} has its own (choose a data rate with `sf` and `bw`)",
                self.access.region.label()
            )));
        }
        if adr.mode != AdrMode::Off && DataRate::of(radio.sf, radio.bw).is_none() {
            return Err(SimError::AdrStart(radio.sf.get(), radio.bw.khz()));
        }
        let channel = Channel::new(ChannelParams {
            tx_power_dbm: r.tx_power,
            path_loss_exponent: c.path_loss_exponent,
            shadowing_sigma_db: c.shadowing,
            shadowing_model: c.shadowing_model,
            gateway_height: c.gateway_height,
            ..ChannelParams::default()
        })?;
        Ok(Validated {
            settings,
            source,
            models: self.station.model.models().to_vec(),
            radio,
            channel,
            adr,
            interference: InterferenceModel {
                capture: n.capture,
                inter_sf: n.inter_sf,
            },
            r_diagonal: PAPER_R_DIAGONAL,
            channels,
            plan,
        })
    }
}

impl FlightSettings {
    /// The plan, read and taken out of the settings (one copy, like the CSV text). Refused with
    /// synthetic flights, which carry their own, and beside a logged flight where nothing reads
    /// it; a mission station needs one.
    fn take_plan(
        &mut self,
        source: &Option<TrajectorySource>,
        station: &StationSettings,
        vehicle: Option<Cornering>,
    ) -> Result<Option<FlightPlan>, SimError> {
        let synthetic = matches!(source, Some(TrajectorySource::Synthetic(_)));
        Self::check_plan_read(source, station, vehicle, self.plan.is_some())?;
        let plan = match self.plan.take() {
            Some(_) if synthetic => return Err(SimError::Source(
                "the synthetic flights carry their own plans: `plan` goes with `trajectory` or `sample`"
                    .into(),
            )),
            Some(text) => Some(parse_plan_as(&text, vehicle)?),
            None => None,
        };
        if plan.is_none() && source.is_some() && !synthetic && station.model.runs_mission() {
            return Err(SimError::Source(
                "the mission station needs the plan the drone flies: give `plan` (a CSV of x,y,z[,speed[,hold]] or a QGroundControl .plan), or fly the synthetic flights, which carry their own"
                    .into(),
            ));
        }
        Ok(plan)
    }

    /// Refuses a plan given beside a logged flight (a CSV log or the Canberra flight) where
    /// nothing reads it: only a mission station follows it there, and otherwise only a bounded
    /// station over a CSV log reads its vehicle (a plane's top speed, [`Validated::vehicle`]
    /// with `vehicle` auto). Without this, `--plan` named in the header and the command line
    /// would run the numbers of no plan. A plan alone is the flight; the synthetic flights
    /// refuse one ([`Self::take_plan`]).
    fn check_plan_read(
        source: &Option<TrajectorySource>,
        station: &StationSettings,
        vehicle: Option<Cornering>,
        given: bool,
    ) -> Result<(), SimError> {
        let csv_log = match source {
            Some(TrajectorySource::Csv(..)) => true,
            Some(TrajectorySource::Sample(_)) => false,
            _ => return Ok(()),
        };
        let reads_vehicle =
            csv_log && vehicle.is_none() && station.prediction == Prediction::Bounded;
        SimError::unless_read(
            station.model.runs_mission() || reads_vehicle,
            &[("plan", given)],
            "read over a logged flight by the mission station alone (and, over a CSV log with `vehicle` auto, by a bounded station for the drone's top speed)",
            "add mission to `model`",
        )
    }

    /// The chosen flight(s), taking the CSV text out of the settings: a plan alone is flown
    /// ([`TrajectorySource::Plan`]); `None` when nothing is chosen, an error when more than one
    /// flight is.
    pub fn take_source(
        &mut self,
        vehicle: VehicleChoice,
    ) -> Result<Option<TrajectorySource>, SimError> {
        Ok(
            match (self.trajectory.take(), self.synthetic, self.sample.clone()) {
                (None, None, None) => self.plan.as_deref().map(|text| {
                    let name = match self.plan_name.as_deref() {
                        Some(n) if !n.trim().is_empty() => format!("{n} (flown)"),
                        _ => DEFAULT_PLAN_NAME.into(),
                    };
                    TrajectorySource::Plan(text.into(), name, vehicle.given())
                }),
                (Some(text), None, None) => Some(TrajectorySource::Csv(
                    text,
                    self.trajectory_name
                        .clone()
                        .unwrap_or_else(|| DEFAULT_CSV_NAME.into()),
                )),
                (None, Some(s), None) => Some(TrajectorySource::Synthetic(s)),
                (None, None, Some(name)) => Some(TrajectorySource::Sample(name)),
                _ => {
                    return Err(SimError::Source(
                        "choose only one of `trajectory`, `synthetic` and `sample`".into(),
                    ))
                }
            },
        )
    }
}

impl VehicleChoice {
    /// The vehicle set for `source`'s flight, or `None` to take the plan file's; refuses a plane
    /// over the bundled flights (and a swarm's chained synthetic flights), which are multicopters.
    fn flying(self, source: &Option<TrajectorySource>) -> Result<Option<Cornering>, SimError> {
        let bundled = matches!(
            source,
            None | Some(TrajectorySource::Synthetic(_) | TrajectorySource::Sample(_))
        );
        match self.given() {
            Some(Cornering::FixedWing) if bundled => Err(SimError::Source(
                "`vehicle` fixed-wing describes a plane's own flight or plan (`trajectory` or `plan`): the synthetic flights and the Canberra flight are multicopters"
                    .into(),
            )),
            given => Ok(given),
        }
    }

    /// Refuses a vehicle set where nothing reads it: a flown plan is flown as it, a mission
    /// station follows its plan as it, and a bounded station holds the drone to its top speed
    /// ([`Validated::vehicle`]); the paper's stations over a logged or synthetic flight read
    /// none of that, though the header would name the vehicle.
    fn check_read(
        self,
        source: &Option<TrajectorySource>,
        station: &StationSettings,
    ) -> Result<(), SimError> {
        let flown = matches!(source, Some(TrajectorySource::Plan(..)));
        SimError::unless_read(
            flown
                || station.prediction == Prediction::Bounded
                || station.model.runs_mission(),
            &[("vehicle", self.given().is_some())],
            "read only where a plan is flown or followed or a bounded station holds the drone to its top speed",
            "set `prediction` to bounded, or add mission to `model`",
        )
    }
}

// Each section's limits (declared in `options.rs`), in the order `Scenario::validate` checks
// them: the first problem is the one reported.
impl RadioSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::SF.check(self.sf as f64)?;
        opt::BW.check(self.bw)?;
        opt::CR.check(self.cr as f64)?;
        opt::OVERHEAD.check(self.overhead as f64)?;
        opt::DUTY_CYCLE.check(self.duty_cycle)?;
        opt::TX_POWER.check(self.tx_power)?;
        Ok(())
    }
}

impl ChannelSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::DISTANCE.check(self.distance)?;
        opt::PATH_LOSS_EXPONENT.check(self.path_loss_exponent)?;
        opt::SHADOWING.check(self.shadowing)?;
        opt::GATEWAY_HEIGHT.check(self.gateway_height)?;
        // Without shadowing there are no fades to place along the path or in space.
        SimError::unless_read(
            self.shadowing > 0.0,
            &[(
                "shadowingModel",
                self.shadowing_model != ShadowingModel::Path,
            )],
            "a shadowing's (where its fades vary), and a shadowing of 0 dB has none",
            "set `shadowing` above 0",
        )
    }
}

impl NetworkSettings {
    /// Uplink channels under `region`'s plan: as given, else the plan's.
    fn channels(&self, region: Region) -> u8 {
        self.channels.unwrap_or(region.channels())
    }

    /// The uplink channels under `region`'s plan, checked: 1, or the plan's (the default).
    fn validate(&self, region: Region) -> Result<u8, SimError> {
        validate_sites(&self.gateways)?;
        let channels = self.channels(region);
        opt::CHANNELS.check(f64::from(channels))?;
        if channels != 1 && channels != region.channels() {
            return Err(SimError::Source(format!(
                "channels must be 1 or {}'s {}, got {channels}",
                region.label(),
                region.channels()
            )));
        }
        opt::ADR_MARGIN.check(self.adr_margin)?;
        opt::ADR_HISTORY.check(self.adr_history as f64)?;
        let defaults = NetworkSettings::default();
        SimError::unless_read(
            self.adr == AdrMode::Lorawan,
            &[
                ("adrMargin", self.adr_margin != defaults.adr_margin),
                ("adrHistory", self.adr_history != defaults.adr_history),
            ],
            "LoRaWAN ADR's",
            "set `adr` to lorawan",
        )?;
        Ok(channels)
    }
}

impl DroneSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::SENSOR_RATE.check(self.sensor_rate)?;
        opt::Q.check(self.q)?;
        Ok(())
    }
}

impl StationSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::STEP.check(self.step)?;
        opt::ETA.check(self.eta)?;
        opt::PLAN_TOLERANCE.check(self.plan_tolerance)?;
        let models = self.model.models();
        SimError::unless_read(
            models.iter().any(|m| m.sent_model() == ModelKind::Ctra3d),
            &[("eta", self.eta != opt::ETA.default)],
            "3D-CTRA's (and the IMM's and the mission station's, which run it)",
            "add 3d-ctra to `model`",
        )?;
        SimError::unless_read(
            self.model.runs_mission(),
            &[
                (
                    "planTolerance",
                    self.plan_tolerance != opt::PLAN_TOLERANCE.default,
                ),
                ("planPace", self.plan_pace != PlanPace::default()),
            ],
            "the mission station's",
            "add mission to `model`",
        )?;
        // The paper's station has no hedge to choose (its q is the drone's, on every component).
        if self.heading_noise == HeadingNoise::Adaptive && self.prediction != Prediction::Bounded {
            return Err(SimError::Source(
                "`headingNoise` adaptive is a bounded station's: set `prediction` to bounded"
                    .into(),
            ));
        }
        Ok(())
    }
}

impl SwarmSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::DRONES.check(self.drones as f64)?;
        opt::DURATION.check(self.duration)?;
        Ok(())
    }
}

impl RunSettings {
    fn validate(&self) -> Result<(), SimError> {
        opt::SEED
            .check(self.seed as f64)
            .map_err(|_| SimError::Seed(self.seed))?;
        opt::SEEDS.check(f64::from(self.seeds))?;
        // Repeats run seed, seed + 1, …: the last must be a seed too.
        if self.seed + u64::from(self.seeds.max(1)) - 1 > MAX_SEED {
            return Err(SimError::Seeds {
                first: self.seed,
                count: self.seeds,
            });
        }
        Ok(())
    }
}

impl Validated {
    /// The settings.
    pub fn s(&self) -> &Scenario {
        &self.settings
    }

    /// The sending settings.
    pub fn sending(&self) -> &Sending {
        &self.settings.sending
    }

    /// The one station a swarm runs: the only one named, or 3D-CTRA (the paper's best) for
    /// `all`, as the trade-off sweeps read it.
    pub fn swarm_station(&self) -> Result<StationModel, SimError> {
        match self.models.as_slice() {
            [StationModel::Mission] => Err(SimError::Source(
                "a swarm runs no mission station: its drones fly without one plan each (name dr, ctra-plus, 3d-ctra or imm)"
                    .into(),
            )),
            [one] => Ok(*one),
            _ if self.settings.station.model == ModelChoice::all() => {
                Ok(StationModel::Single(ModelKind::Ctra3d))
            }
            _ => Err(SimError::Source(
                "a swarm runs one station: name one model (dr, ctra-plus, 3d-ctra or imm)".into(),
            )),
        }
    }

    /// `model`'s station setup from the run's `base`: a mission station's fallback is bounded
    /// 3D-CTRA, which resets to the drone filter's settled covariance whatever `prediction` says
    /// (computed here when `base` has none).
    pub fn setup_for(&self, model: StationModel, base: StationSetup) -> StationSetup {
        match (model, base.drone_covariance) {
            (StationModel::Mission, None) => StationSetup {
                drone_covariance: Some(self.drone_covariances()),
                ..base
            },
            _ => base,
        }
    }

    /// The drone's sensors and filter, drawing its noise from `streams`.
    pub fn sensing(&self, streams: DroneStreams) -> Sensing {
        let s = &self.settings;
        Sensing {
            rate: s.drone.sensor_rate,
            q: s.drone.q,
            r_diagonal: self.r_diagonal,
            streams,
        }
    }

    /// The payload rule of a drone filtering with `model`: `None` sends its own payload (the
    /// paper, or a DR drone, which has no field to leave out).
    pub fn lean_payload(&self, model: ModelKind) -> Option<LeanPayload> {
        if self.settings.sending.payload == PayloadChoice::Full || model == ModelKind::Dr {
            return None;
        }
        let p = self.drone_covariances().of::<9>(model);
        Some(LeanPayload::new(
            model,
            core::array::from_fn(|i| p[(6 + i, 6 + i)].sqrt()),
        ))
    }

    fn drone_covariances(&self) -> DroneCovariances {
        let s = &self.settings;
        DroneCovariances::new(1.0 / s.drone.sensor_rate, s.drone.q, &self.r_diagonal)
    }

    /// The plan a mission station follows over `flight` (`None` for any other `model`): a
    /// synthetic flight's own ([`FlightPlan::traced`]), else the one given (a plane's along its
    /// arcs, [`MissionPlan::followed`]).
    pub fn mission_plan(&self, model: StationModel, flight: &Trajectory) -> Option<MissionPlan> {
        if model != StationModel::Mission {
            return None;
        }
        let plan = match &self.source {
            Some(TrajectorySource::Synthetic(_)) => FlightPlan::traced(flight, TRACE_TOLERANCE),
            _ => MissionPlan::followed(self.plan.clone()?),
        };
        let plan = match self.settings.station.plan_pace {
            PlanPace::Plan => plan,
            PlanPace::Packet => plan.without_speeds(),
        };
        Some(MissionPlan {
            start: MissionPlan::start_on(&plan, flight),
            plan,
            tolerance: self.settings.station.plan_tolerance,
        })
    }

    /// The vehicle the drone is: as set (`vehicle`), else its plan's, else a multicopter
    /// ([`VehicleChoice`]).
    pub fn vehicle(&self) -> Cornering {
        let plan = self.plan.as_ref().map(FlightPlan::cornering);
        self.settings
            .drone
            .vehicle
            .given()
            .or(plan)
            .unwrap_or_default()
    }

    /// The station of every drone whose packets come every `interval` s (its data rate's
    /// duty-cycle interval), bounded for the vehicle ([`Self::vehicle`],
    /// [`Bounds::for_vehicle`]). A bounded station resets to the drone filter's settled
    /// covariance ([`DroneCovariances`], computed here: about 2 ms, so build one setup and copy
    /// it).
    pub fn station_setup(&self, interval: f64) -> StationSetup {
        let s = &self.settings;
        let drone_covariance =
            (s.station.prediction == Prediction::Bounded).then(|| self.drone_covariances());
        StationSetup {
            prediction: s.station.prediction,
            bounds: Bounds {
                heading_noise: s.station.heading_noise,
                ..Bounds::for_vehicle(self.vehicle())
            },
            step: s.station.step,
            eta: s.station.eta,
            q: s.drone.q,
            r_diagonal: self.r_diagonal,
            interval,
            error_triggered: s.sending.sender == SenderKind::Error,
            drone_covariance,
        }
    }

    /// The gateways: as given, or the one default gateway `east` m east of the origin (simulate:
    /// `distance`, east of the flight's first point; swarm: 0, at the centre).
    pub fn sites(&self, east: f64) -> Vec<GatewaySite> {
        let given = &self.settings.network.gateways;
        if given.is_empty() {
            vec![GatewaySite {
                east,
                north: 0.0,
                height: None,
            }]
        } else {
            given.clone()
        }
    }

    /// The duty cycle the rule of a drone whose frames take `time_on_air` s enforces (the
    /// plan's, or time on air / interval, within fair use).
    pub fn duty_cycle_for(&self, time_on_air: f64) -> Result<f64, SimError> {
        let s = &self.settings;
        s.access.duty_cycle_for(s.radio.duty_cycle, time_on_air)
    }

    /// The radio of a drone at `radio` sending `model`'s payload (plus the overhead), once the
    /// plan carries its frame (data rate, payload limit, dwell time; reference §14), with the
    /// duty cycle its rule enforces.
    pub fn drone_radio(
        &self,
        radio: &LoraParams,
        model: StationModel,
    ) -> Result<(DroneRadio, f64), SimError> {
        let s = &self.settings;
        let payload = model.payload_bytes();
        let toa = time_on_air(radio, payload + s.radio.overhead)?.time_on_air;
        s.access
            .region
            .check(radio.sf.get(), radio.bw, payload, toa)
            .map_err(|e| {
                SimError::Source(match e {
                    RegionError::NoDataRate { .. } | RegionError::Barred { .. } => e.to_string(),
                    _ => format!(
                        "{} sends {payload} bytes (+{} overhead): {e}; choose a faster data rate{}",
                        model.label(),
                        s.radio.overhead,
                        smaller_payloads(payload),
                    ),
                })
            })?;
        let duty_cycle = self.duty_cycle_for(toa)?;
        let r = DroneRadio::new(radio, payload + s.radio.overhead, duty_cycle, self.adr.mode)?;
        Ok((r, duty_cycle))
    }

    /// Whether error-triggered sending's heartbeat fits the data rate of `frame`: a heartbeat
    /// shorter than its duty-cycle interval could never be kept. The error names the data rate
    /// (a swarm with spread SFs needs SF12's).
    pub fn check_heartbeat(&self, frame: &Frame) -> Result<(), SimError> {
        let s = self.sending();
        if s.sender == SenderKind::Error && s.max_interval < frame.interval {
            return Err(SimError::Heartbeat {
                max_interval: s.max_interval,
                sf: frame.sf.get(),
                bw_khz: frame.bw.khz(),
                interval: frame.interval,
            });
        }
        Ok(())
    }
}

/// The stations whose payload is smaller than `bytes`, as a refusal's second remedy: ", or a
/// station with a smaller payload (DR: 9 bytes, CTRA+: 11)"; empty where none is (DR's).
fn smaller_payloads(bytes: usize) -> String {
    let smaller: Vec<String> = ModelKind::ALL
        .iter()
        .filter(|m| m.payload_bytes() < bytes)
        .enumerate()
        .map(|(i, m)| match i {
            0 => format!("{}: {} bytes", m.label(), m.payload_bytes()),
            _ => format!("{}: {}", m.label(), m.payload_bytes()),
        })
        .collect();
    if smaller.is_empty() {
        String::new()
    } else {
        format!(
            " or a station with a smaller payload ({})",
            smaller.join(", ")
        )
    }
}
