//! One function per command: parse options into the API's parameter struct, run, format.

use clap::{Args, Subcommand};
use loratrack::api::{self, ApiError};
use loratrack::{
    AdrMode, DutyCycleMode, LdroMode, ModelChoice, ModelKind, ModelResult, Prediction, SenderKind,
    SfPlan, SimParams, Simulator, SwarmParams, SyntheticChoice, MAX_CSV_BYTES,
};
use serde::Serialize;

#[derive(Subcommand)]
pub enum Command {
    /// Time on air and 1 % duty-cycle interval of one LoRa packet (Semtech SX1276 formula).
    Airtime(AirtimeArgs),
    /// Noise-free propagation of a state with one motion model (closed form, SPEC §3).
    Predict(PredictArgs),
    /// Quantise a state into the model's 9/11/12-byte payload (SPEC §5).
    Encode(EncodeArgs),
    /// Decode a payload back into a state (SPEC §5).
    Decode(DecodeArgs),
    /// Simulate tracking over LoRa: drone UKF, duty-cycled packets, channel, station predictor.
    Simulate(Box<SimulateArgs>),
    /// The paper's grid: SF 7/8, 250 kHz, d = 1/2/3 km, all models, whole synthetic set.
    Sweep(SweepArgs),
    /// Many drones, one gateway: collisions (capture, inter-SF, 8 demodulators) and every drone's tracking error.
    Swarm(Box<SwarmArgs>),
}

#[derive(Args)]
pub struct SwarmArgs {
    /// Number of drones, 1..500, each flying synthetic flights back to back from a random start at --distance from the gateway, in a random direction.
    #[arg(long, default_value_t = 12)]
    drones: usize,
    /// Seconds of flight per drone, 10..3600.
    #[arg(long, default_value_t = 600.0)]
    duration: f64,
    /// Horizontal distance of every drone's starting point from the gateway, metres (0..100000).
    #[arg(long, default_value_t = 1000.0, allow_negative_numbers = true)]
    distance: f64,
    /// 1 (one channel) or 3 (EU868 868.1/868.3/868.5 MHz, a random one per packet; the 1 % duty cycle covers all three).
    #[arg(long, default_value_t = 3)]
    channels: u8,
    /// Spreading factors: spread (SF7..SF12 in turn, a sixth of the swarm each) or fixed (everyone at --sf).
    #[arg(long, value_enum, default_value = "spread")]
    sf_plan: SfPlanArg,
    /// Spreading factor of the fixed plan, 7..12.
    #[arg(long, default_value_t = 7, allow_negative_numbers = true)]
    sf: i64,
    /// Bandwidth in kHz: 125, 250 or 500.
    #[arg(long, default_value_t = 125.0)]
    bw: f64,
    /// Station model: dr, ctra-plus, 3d-ctra or imm.
    #[arg(long, default_value = "3d-ctra")]
    model: String,
    /// Station prediction between packets: paper or bounded.
    #[arg(long, value_enum, default_value = "paper")]
    prediction: PredictionArg,
    #[command(flatten)]
    sending: SendingArgs,
    /// Same-SF capture: the stronger packet survives 6 dB above the others (off: every overlap is fatal).
    #[arg(long, value_enum, default_value = "on")]
    capture: OnOff,
    /// Inter-SF interference by the rejection matrix of ns-3's lorawan module (off: SFs are orthogonal).
    #[arg(long, value_enum, default_value = "on")]
    inter_sf: OnOff,
    /// Log-normal shadowing standard deviation in dB (0..20; 0 turns it off).
    #[arg(long, default_value_t = 4.0, allow_negative_numbers = true)]
    shadowing: f64,
    /// MAC overhead in bytes: 13 for LoRaWAN, 0 as in the paper's Table II.
    #[arg(long, default_value_t = 13)]
    overhead: usize,
    /// Seed of all random draws (layout, sensor noise, channels, shadowing), 0..2^53-1.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    #[command(flatten)]
    out: Output,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SfPlanArg {
    Spread,
    Fixed,
}

#[derive(Clone, Copy, PartialEq, clap::ValueEnum)]
enum OnOff {
    On,
    Off,
}

#[derive(Args)]
pub struct SimulateArgs {
    /// A flight as CSV: header with t,x,y,z (s, m, ENU) and optional vx,vy,vz / ax,ay,az; a regular file of at most 64 MiB.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["synthetic", "sample"])]
    trajectory: Option<std::path::PathBuf>,
    /// The canonical synthetic set: `all` (30 flights, 44 min) or one flight 1..30.
    #[arg(long, value_name = "all|1..30", conflicts_with = "sample")]
    synthetic: Option<String>,
    /// A bundled real flight: canberra (ArduCopter log171, CC BY-SA 3.0).
    #[arg(long, value_name = "NAME")]
    sample: Option<String>,
    /// Station model(s): dr, ctra-plus, 3d-ctra, imm (IMM over the three), a comma list, or all (the paper's three).
    #[arg(long, default_value = "all")]
    model: String,
    /// Station prediction between packets: paper (constant a and omega, as published) or bounded (speed and pitch limits, overdue manoeuvres decay).
    #[arg(long, value_enum, default_value = "paper")]
    prediction: PredictionArg,
    #[command(flatten)]
    sending: SendingArgs,
    /// Adaptive data rate: off (fixed --sf/--bw, the paper), lorawan (the network server's ADR: best SNR of --adr-history uplinks, --adr-margin, 3 dB steps; the device backs off after 64+32 silent uplinks) or tracking (the rate with the least expected squared packet age). ADR starts at --sf/--bw, which must be an EU868 data rate.
    #[arg(long, value_enum, default_value = "off")]
    adr: AdrArg,
    /// LoRaWAN ADR: device margin, dB (0..30; Semtech 10, The Things Stack 15).
    #[arg(long, default_value_t = loratrack::DEFAULT_ADR_MARGIN_DB)]
    adr_margin: f64,
    /// LoRaWAN ADR: uplinks whose best SNR decides (1..100; Semtech and The Things Stack 20).
    #[arg(long, default_value_t = loratrack::DEFAULT_ADR_HISTORY)]
    adr_history: usize,
    /// Spreading factor, 7..12.
    #[arg(long, default_value_t = 7, allow_negative_numbers = true)]
    sf: i64,
    /// Bandwidth in kHz: 125, 250 or 500.
    #[arg(long, default_value_t = 250.0)]
    bw: f64,
    /// Horizontal distance from the flight's first point to the gateway, metres (0..100000).
    #[arg(long, default_value_t = 1000.0, allow_negative_numbers = true)]
    distance: f64,
    /// Seed of all random draws (sensor noise, transmission offset, shadowing), 0..2^53-1, or `random` for a fresh one (reported in the output, so the run can be repeated).
    #[arg(long, default_value = "1", value_name = "N|random")]
    seed: String,
    /// MAC overhead in bytes added to each payload: 13 for LoRaWAN, 0 as in the paper's Table II.
    #[arg(long, default_value_t = 13)]
    overhead: usize,
    /// The paper's preset: no LoRaWAN overhead (same as --overhead 0).
    #[arg(long, conflicts_with = "overhead")]
    paper: bool,
    /// Coding rate n of 4/(4+n): 1..4.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    cr: i64,
    /// Duty-cycle limit as a fraction (0.0001..1).
    #[arg(long, default_value_t = 0.01)]
    duty_cycle: f64,
    /// Transmit power, dBm (-30..30).
    #[arg(long, default_value_t = 14.0, allow_negative_numbers = true)]
    tx_power: f64,
    /// Path-loss exponent of the log-distance model (1.5..6).
    #[arg(long, default_value_t = 3.76)]
    path_loss_exponent: f64,
    /// Log-normal shadowing standard deviation in dB (0..20; 0 turns it off).
    #[arg(long, default_value_t = 4.0, allow_negative_numbers = true)]
    shadowing: f64,
    /// Gateway antenna height, metres (0..1000).
    #[arg(long, default_value_t = 15.0)]
    gateway_height: f64,
    /// Drone sensor and filter rate, Hz (0.1..1000; flight time x (rate + 1/step) is limited to 1,000,000 filter steps).
    #[arg(long, default_value_t = 10.0)]
    sensor_rate: f64,
    /// Station prediction step T, seconds (0.001..10).
    #[arg(long, default_value_t = 0.1)]
    step: f64,
    /// Tilt-rate decay per station step, 0..1 (paper: 0.9).
    #[arg(long, default_value_t = 0.9, allow_negative_numbers = true)]
    eta: f64,
    /// Process noise q of Q = q I per second, (0, 1000] (paper: 0.1).
    #[arg(long, default_value_t = 0.1)]
    q: f64,
    /// Include time series of the first flight (error over time, trajectories) in the JSON.
    #[arg(long)]
    series: bool,
    #[command(flatten)]
    out: Output,
}

/// When the drone sends and the duty-cycle rule (simulate).
#[derive(Args)]
pub struct SendingArgs {
    /// When the drone sends: periodic (as often as the duty cycle allows, the paper) or error (when the mirrored station drifts past --threshold).
    #[arg(long, value_enum, default_value = "periodic")]
    sender: SenderArg,
    /// Error-triggered sending: the drift in metres between the station's belief and the drone's own estimate that triggers a packet (0..10000).
    #[arg(long, default_value_t = loratrack::DEFAULT_THRESHOLD_M, allow_negative_numbers = true)]
    threshold: f64,
    /// Error-triggered sending: the longest silence in seconds, a heartbeat that repairs lost packets (at least the duty-cycle interval, at most 3600).
    #[arg(long, default_value_t = loratrack::DEFAULT_MAX_INTERVAL_S, allow_negative_numbers = true)]
    max_interval: f64,
    /// Duty-cycle rule: per-packet (off-time of time-on-air / duty-cycle after each packet) or budget (airtime credit over time, up to --burst packets; ETSI EN 300 220 counts over an hour).
    #[arg(long, value_enum, default_value = "per-packet")]
    duty_cycle_mode: DutyCycleModeArg,
    /// Budget rule: the most packets' airtime the credit holds (1..3600; 1 is per-packet).
    #[arg(long, default_value_t = loratrack::DEFAULT_BURST)]
    burst: u32,
}

impl SendingArgs {
    fn sender(&self) -> SenderKind {
        match self.sender {
            SenderArg::Periodic => SenderKind::Periodic,
            SenderArg::Error => SenderKind::Error,
        }
    }

    fn duty_cycle_mode(&self) -> DutyCycleMode {
        match self.duty_cycle_mode {
            DutyCycleModeArg::PerPacket => DutyCycleMode::PerPacket,
            DutyCycleModeArg::Budget => DutyCycleMode::Budget,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum AdrArg {
    Off,
    Lorawan,
    Tracking,
}

impl From<AdrArg> for AdrMode {
    fn from(a: AdrArg) -> Self {
        match a {
            AdrArg::Off => AdrMode::Off,
            AdrArg::Lorawan => AdrMode::Lorawan,
            AdrArg::Tracking => AdrMode::Tracking,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum SenderArg {
    Periodic,
    Error,
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum DutyCycleModeArg {
    PerPacket,
    Budget,
}

#[derive(Args)]
#[group(required = true, multiple = false)]
pub struct SweepKind {
    /// The paper's grid: SF 7/8, 250 kHz, d = 1/2/3 km, whole synthetic set, no LoRaWAN overhead.
    #[arg(long)]
    paper: bool,
    /// Swarms of 1..500 drones: collision rate (beside the ALOHA formula) and median per-drone p75 for 1 and 3 channels, SF7 for all and spread SFs, periodic and error-triggered sending (300 s per drone, 3D-CTRA, --prediction).
    #[arg(long)]
    swarm: bool,
    /// The airtime / error trade-off of error-triggered sending (thresholds 0.5..10 m, per-packet and budget rules) against periodic sending, on the whole synthetic set at --sf/--bw/--distance, no LoRaWAN overhead, for the first model of --model (3d-ctra when --model is all).
    #[arg(long)]
    senders: bool,
    /// Fixed data rates DR0..DR6 and both ADR modes (starting at --sf/--bw) at each distance, m, comma-separated (e.g. 1000,3000,5000,7000), on the whole synthetic set, no LoRaWAN overhead, for the first model of --model (3d-ctra when --model is all).
    #[arg(long, value_delimiter = ',', value_name = "M,M,...")]
    distances: Option<Vec<f64>>,
}

#[derive(Args)]
pub struct SweepArgs {
    #[command(flatten)]
    kind: SweepKind,
    /// --senders: spreading factor; --distances: the one ADR starts at.
    #[arg(long, default_value_t = 7, allow_negative_numbers = true)]
    sf: i64,
    /// --senders: bandwidth, kHz; --distances: the one ADR starts at.
    #[arg(long, default_value_t = 250.0)]
    bw: f64,
    /// --senders: gateway distance, m.
    #[arg(long, default_value_t = 1000.0, allow_negative_numbers = true)]
    distance: f64,
    /// --senders: the budget rule's capacity in packets.
    #[arg(long, default_value_t = loratrack::DEFAULT_BURST)]
    burst: u32,
    /// Seed of all random draws.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Station model(s): dr, ctra-plus, 3d-ctra, imm, a comma list, or all (the paper's three).
    #[arg(long, default_value = "all")]
    model: String,
    /// Station prediction(s), comma-separated: paper, bounded.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "paper")]
    prediction: Vec<PredictionArg>,
    /// Print the paper-reproduction document (Markdown) instead of a table.
    #[arg(long, conflicts_with = "json")]
    markdown: bool,
    #[command(flatten)]
    out: Output,
}

/// A model and one of its states (predict, encode).
#[derive(Args)]
pub struct ModelState {
    /// Motion model: dr (x y z theta phi v), ctra-plus (+ a omega) or 3d-ctra (+ a omega psi).
    #[arg(long)]
    model: ModelKind,
    /// State, comma-separated, SPEC §2 order and units (m, rad, m/s, m/s^2, rad/s), e.g. 0,0,0,0,0,1,1,1. Ranges: x y z ±1e7 m, theta phi ±1000 rad, v a ±1000, omega psi ±100 rad/s.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    state: Vec<f64>,
}

/// The codec's shared origin (encode, decode).
#[derive(Args)]
pub struct Origin {
    /// Origin x,y,z in metres (ENU) that both ends agree on; positions travel relative to it [0,0,0].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    origin: Option<Vec<f64>>,
}

impl Origin {
    fn get(&self) -> Result<Option<[f64; 3]>, ApiError> {
        self.origin
            .as_ref()
            .map(|v| {
                <[f64; 3]>::try_from(v.as_slice()).map_err(|_| {
                    ApiError::Invalid(format!("--origin needs 3 numbers x,y,z, got {}", v.len()))
                })
            })
            .transpose()
    }
}

#[derive(Args)]
pub struct PredictArgs {
    #[command(flatten)]
    input: ModelState,
    /// Time to propagate over, seconds (0..86400).
    #[arg(long, allow_hyphen_values = true)]
    dt: f64,
    /// Propagate in steps of this many seconds, multiplying psi by eta after each (the station's predictor).
    #[arg(long, allow_hyphen_values = true)]
    step: Option<f64>,
    /// Tilt-rate decay per step, 0..1 (paper: 0.9); needs --step.
    #[arg(long, allow_hyphen_values = true)]
    eta: Option<f64>,
    #[command(flatten)]
    out: Output,
}

#[derive(Args)]
pub struct EncodeArgs {
    #[command(flatten)]
    input: ModelState,
    #[command(flatten)]
    origin: Origin,
    #[command(flatten)]
    out: Output,
}

#[derive(Args)]
pub struct DecodeArgs {
    /// Motion model: dr, ctra-plus or 3d-ctra (fixes the payload size: 9, 11 or 12 bytes).
    #[arg(long)]
    model: ModelKind,
    /// Payload as hex digits (9, 11 or 12 bytes for dr, ctra-plus, 3d-ctra).
    #[arg(long)]
    hex: String,
    #[command(flatten)]
    origin: Origin,
    #[command(flatten)]
    out: Output,
}

fn numbers(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x}"))
        .collect::<Vec<_>>()
        .join(",")
}

/// Output format shared by every command.
#[derive(Args)]
pub struct Output {
    /// Print one JSON object instead of text.
    #[arg(long, global = true)]
    json: bool,
}

#[derive(Args)]
pub struct AirtimeArgs {
    /// Spreading factor, 7..12.
    #[arg(long, allow_negative_numbers = true)]
    sf: i64,
    /// Bandwidth in kHz: 125, 250 or 500.
    #[arg(long)]
    bw: f64,
    /// Application payload in bytes (loratrack's payloads: 9 DR, 11 CTRA+, 12 3D-CTRA).
    #[arg(long)]
    payload: usize,
    /// MAC overhead in bytes added to the payload: 13 for LoRaWAN, 0 for raw LoRa (the paper's Table II).
    #[arg(long, default_value_t = 13)]
    overhead: usize,
    /// Coding rate n of 4/(4+n): 1..4.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    cr: i64,
    /// Preamble length in symbols.
    #[arg(long, default_value_t = 8, allow_negative_numbers = true)]
    preamble: i64,
    /// Implicit header mode (no PHY header; LoRaWAN uplinks use explicit).
    #[arg(long)]
    implicit_header: bool,
    /// Payload CRC off (LoRaWAN uplinks have it on).
    #[arg(long)]
    no_crc: bool,
    /// Low data rate optimisation: auto (on when a symbol lasts over 16 ms), on or off.
    #[arg(long, value_enum, default_value = "auto")]
    ldro: Ldro,
    /// Duty-cycle limit as a fraction, 0.0001..1 (EU868 868.0–868.6 MHz: 0.01).
    #[arg(long, default_value_t = 0.01)]
    duty_cycle: f64,
    #[command(flatten)]
    out: Output,
}

#[derive(Clone, Copy, PartialEq, clap::ValueEnum)]
enum PredictionArg {
    Paper,
    Bounded,
}

impl From<PredictionArg> for Prediction {
    fn from(p: PredictionArg) -> Self {
        match p {
            PredictionArg::Paper => Prediction::Paper,
            PredictionArg::Bounded => Prediction::Bounded,
        }
    }
}

#[derive(Clone, Copy, clap::ValueEnum)]
enum Ldro {
    Auto,
    On,
    Off,
}

impl From<Ldro> for LdroMode {
    fn from(l: Ldro) -> Self {
        match l {
            Ldro::Auto => LdroMode::Auto,
            Ldro::On => LdroMode::On,
            Ldro::Off => LdroMode::Off,
        }
    }
}

/// Runs a command; `Ok` is what to print, `Err` the error message.
pub fn run(cmd: Command) -> Result<String, String> {
    match cmd {
        Command::Airtime(a) => airtime(a),
        Command::Predict(a) => predict(a),
        Command::Encode(a) => encode(a),
        Command::Decode(a) => decode(a),
        Command::Simulate(a) => simulate(*a),
        Command::Sweep(a) => sweep(a),
        Command::Swarm(a) => swarm(*a),
    }
    .map_err(|e| e.to_string())
}

fn json<T: Serialize>(value: &T) -> String {
    serde_json::to_string_pretty(value).unwrap_or_else(|e| format!("{{\"error\":\"{e}\"}}"))
}

fn airtime(a: AirtimeArgs) -> Result<String, ApiError> {
    let params = api::AirtimeParams {
        sf: a.sf,
        bw: a.bw,
        payload: a.payload,
        overhead: a.overhead,
        cr: a.cr,
        preamble: a.preamble,
        implicit_header: a.implicit_header,
        no_crc: a.no_crc,
        ldro: a.ldro.into(),
        duty_cycle: a.duty_cycle,
    };
    let r = api::airtime(&params)?;
    if a.out.json {
        return Ok(json(&r));
    }
    Ok(format!(
        "time on air      {:.3} ms\nsymbol time      {:.3} ms\npayload symbols  {}\nPHY payload      {} B\nLDRO             {}\nmin interval     {:.3} s (duty cycle {})\nTTN fair use     {} packets/day (30 s of airtime; not enforced)",
        r.time_on_air * 1e3,
        r.symbol_time * 1e3,
        r.payload_symbols,
        r.phy_payload_bytes,
        if r.low_data_rate_optimize { "on" } else { "off" },
        r.min_interval,
        a.duty_cycle,
        r.ttn_packets_per_day
    ))
}

fn predict(a: PredictArgs) -> Result<String, ApiError> {
    let r = api::predict(&api::PredictParams {
        model: a.input.model,
        state: a.input.state,
        dt: a.dt,
        step: a.step,
        eta: a.eta,
    })?;
    Ok(if a.out.json {
        json(&r)
    } else {
        format!("{} {}", r.model, numbers(&r.state))
    })
}

fn encode(a: EncodeArgs) -> Result<String, ApiError> {
    let r = api::encode(&api::EncodeParams {
        model: a.input.model,
        state: a.input.state,
        origin: a.origin.get()?,
    })?;
    if a.out.json {
        return Ok(json(&r));
    }
    let note = if r.saturated.is_empty() {
        String::new()
    } else {
        format!("\nsaturated: {}", r.saturated.join(", "))
    };
    Ok(format!("{}{note}", r.hex))
}

fn decode(a: DecodeArgs) -> Result<String, ApiError> {
    let r = api::decode(&api::DecodeParams {
        model: a.model,
        hex: a.hex,
        origin: a.origin.get()?,
    })?;
    Ok(if a.out.json {
        json(&r)
    } else {
        format!("{} {}", r.model, numbers(&r.state))
    })
}

/// Reads a CSV flight: a regular file of at most [`MAX_CSV_BYTES`], so that a device, a FIFO or
/// a huge file is refused at once instead of filling memory or blocking.
fn read_flight(path: &std::path::Path) -> Result<String, ApiError> {
    use std::io::Read;
    let cannot =
        |e: std::io::Error| ApiError::Invalid(format!("cannot read {}: {e}", path.display()));
    let meta = std::fs::metadata(path).map_err(cannot)?;
    if !meta.is_file() {
        return Err(ApiError::Invalid(format!(
            "{} is not a regular file (give a CSV file)",
            path.display()
        )));
    }
    let too_large = |bytes: u64| {
        ApiError::Invalid(format!(
            "{} is {:.1} MiB; at most {} MiB is read",
            path.display(),
            bytes as f64 / 1048576.0,
            MAX_CSV_BYTES >> 20
        ))
    };
    if meta.len() > MAX_CSV_BYTES as u64 {
        return Err(too_large(meta.len()));
    }
    let mut text = String::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_CSV_BYTES as u64 + 1)
        .read_to_string(&mut text)
        .map_err(cannot)?;
    if text.len() > MAX_CSV_BYTES {
        return Err(too_large(text.len() as u64));
    }
    Ok(text)
}

/// `--seed N` or `--seed random`.
fn parse_seed(text: &str) -> Result<u64, ApiError> {
    if text.trim().eq_ignore_ascii_case("random") {
        return loratrack::random_seed().map_err(ApiError::Invalid);
    }
    text.trim().parse().map_err(|_| {
        ApiError::Invalid(format!(
            "seed must be a whole number 0..2^53-1 or 'random', got '{}'",
            text.chars().take(20).collect::<String>()
        ))
    })
}

fn simulate(a: SimulateArgs) -> Result<String, ApiError> {
    let trajectory = a.trajectory.as_deref().map(read_flight).transpose()?;
    let params = SimParams {
        trajectory,
        trajectory_name: a.trajectory.as_ref().map(|p| p.display().to_string()),
        synthetic: a
            .synthetic
            .as_deref()
            .map(|s| SyntheticChoice::parse(s).map_err(ApiError::Invalid))
            .transpose()?,
        sample: a.sample,
        model: ModelChoice::parse(&a.model).map_err(ApiError::Invalid)?,
        prediction: a.prediction.into(),
        sender: a.sending.sender(),
        threshold: a.sending.threshold,
        max_interval: a.sending.max_interval,
        duty_cycle_mode: a.sending.duty_cycle_mode(),
        burst: a.sending.burst,
        adr: a.adr.into(),
        adr_margin: a.adr_margin,
        adr_history: a.adr_history,
        sf: a.sf,
        bw: a.bw,
        distance: a.distance,
        seed: parse_seed(&a.seed)?,
        overhead: if a.paper { 0 } else { a.overhead },
        cr: a.cr,
        duty_cycle: a.duty_cycle,
        tx_power: a.tx_power,
        path_loss_exponent: a.path_loss_exponent,
        shadowing: a.shadowing,
        gateway_height: a.gateway_height,
        sensor_rate: a.sensor_rate,
        step: a.step,
        eta: a.eta,
        q: a.q,
        series: a.series,
    };
    let r = api::simulate(&mut Simulator::new(), &params)?;
    if a.out.json {
        return Ok(json(&r));
    }
    let c = &r.config;
    Ok(format!(
        "{} ({} flight{}, {:.0} s), SF{} / {} kHz, gateway at {} m, overhead {} B, seed {}\n{}",
        c.trajectory,
        c.flights,
        if c.flights == 1 { "" } else { "s" },
        c.flight_time,
        c.sf,
        c.bandwidth_khz,
        c.distance,
        c.overhead,
        c.seed,
        results_table(&r.results)
    ))
}

fn results_table(results: &[ModelResult]) -> String {
    let mut out = String::from(
        "model     interval  received   mean    p50    p75    p95    max  cover95  (3D error, m)\n",
    );
    for m in results {
        out += &format!(
            "{:<9} {:>7.2}s {:>5}/{:<5} {:>6.2} {:>6.2} {:>6.2} {:>6.2} {:>6.1} {:>7.3}\n",
            m.model.label(),
            m.interval,
            m.packets_received,
            m.packets_sent,
            m.error3d.mean,
            m.error3d.p50,
            m.error3d.p75,
            m.error3d.p95,
            m.error3d.max,
            m.coverage95
        );
        if let Some(p) = &m.model_probability {
            let parts: Vec<String> = p.iter().map(|(k, v)| format!("{k} {v:.2}")).collect();
            out += &format!("          mean model probability: {}\n", parts.join(", "));
        }
    }
    out.trim_end().to_string()
}

fn sweep(a: SweepArgs) -> Result<String, ApiError> {
    let model = ModelChoice::parse(&a.model).map_err(ApiError::Invalid)?;
    let predictions: Vec<Prediction> = a.prediction.iter().map(|&p| p.into()).collect();
    if a.kind.senders {
        return sweep_senders(&a, model, predictions[0]);
    }
    if a.kind.swarm {
        return sweep_swarm(&a, predictions[0]);
    }
    if let Some(distances) = &a.kind.distances {
        return sweep_distances(&a, model, predictions[0], distances);
    }
    let r = api::sweep_paper(&mut Simulator::new(), a.seed, &predictions, &model)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.markdown {
        return Ok(crate::reproduction::markdown(&r));
    }
    let mut out = format!(
        "paper sweep: synthetic set ({:.0} s), 250 kHz, no LoRaWAN overhead, seed {}\n",
        r.flight_time, r.seed
    );
    for run in &r.runs {
        out += &format!(
            "\nSF{} d = {} m, {} prediction\n{}\n",
            run.sf,
            run.distance,
            run.prediction.name(),
            results_table(&run.results)
        );
    }
    Ok(out.trim_end().to_string())
}

/// The one station a trade-off sweep runs: `all` (the default) means the paper's best, 3D-CTRA.
fn one_station(model: ModelChoice) -> ModelChoice {
    if model == ModelChoice::all() {
        ModelChoice::one(ModelKind::Ctra3d)
    } else {
        ModelChoice::one(model.models()[0])
    }
}

/// The base of a trade-off sweep: the whole synthetic set, one station, no LoRaWAN overhead.
fn trade_off_base(a: &SweepArgs, model: ModelChoice, prediction: Prediction) -> SimParams {
    SimParams {
        synthetic: Some(SyntheticChoice::All),
        model: one_station(model),
        prediction,
        sf: a.sf,
        bw: a.bw,
        distance: a.distance,
        seed: a.seed,
        overhead: 0,
        ..SimParams::default()
    }
}

fn sweep_distances(
    a: &SweepArgs,
    model: ModelChoice,
    prediction: Prediction,
    distances: &[f64],
) -> Result<String, ApiError> {
    let base = trade_off_base(a, model, prediction);
    let r = api::sweep_distances(&mut Simulator::new(), &base, distances)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.markdown {
        return Ok(crate::reproduction::distances_markdown(&r, &base));
    }
    Ok(crate::reproduction::distances_table(&r))
}

fn sweep_senders(
    a: &SweepArgs,
    model: ModelChoice,
    prediction: Prediction,
) -> Result<String, ApiError> {
    let base = trade_off_base(a, model, prediction);
    let r = api::sweep_senders(&mut Simulator::new(), &base, a.burst)?;
    if a.out.json {
        return Ok(json(&r));
    }
    if a.markdown {
        return Ok(crate::reproduction::senders_markdown(&r, &base));
    }
    Ok(crate::reproduction::senders_table(&r))
}

fn swarm(a: SwarmArgs) -> Result<String, ApiError> {
    let params = SwarmParams {
        drones: a.drones,
        duration: a.duration,
        distance: a.distance,
        channels: a.channels,
        sf_plan: match a.sf_plan {
            SfPlanArg::Spread => SfPlan::Spread,
            SfPlanArg::Fixed => SfPlan::Fixed,
        },
        sf: a.sf,
        bw: a.bw,
        model: a.model.clone(),
        prediction: a.prediction.into(),
        sender: a.sending.sender(),
        threshold: a.sending.threshold,
        max_interval: a.sending.max_interval,
        duty_cycle_mode: a.sending.duty_cycle_mode(),
        burst: a.sending.burst,
        capture: a.capture == OnOff::On,
        inter_sf: a.inter_sf == OnOff::On,
        shadowing: a.shadowing,
        overhead: a.overhead,
        seed: a.seed,
    };
    let r = api::swarm(&params)?;
    if a.out.json {
        return Ok(json(&r));
    }
    let silent = r.drones.iter().filter(|d| d.error3d.count == 0).count();
    Ok(format!(
        "{} drones x {:.0} s at {} m, {} channel{}, {:?} SFs, capture {}, inter-SF {}, seed {}\n\
         packets sent        {}\n\
         collision rate      {:.4}  (ALOHA theory for periodic senders: {:.4})\n\
         delivery ratio      {:.4}\n\
         below sensitivity   {}\n\
         no demodulator      {}\n\
         3D error (pooled)   mean {:.2}  p75 {:.2}  p95 {:.2} m; median drone p75 {:.2} m\n\
         drones that received nothing: {}",
        r.config.drones,
        r.config.duration,
        r.config.distance,
        r.config.channels,
        if r.config.channels == 1 { "" } else { "s" },
        r.config.sf_plan,
        if r.config.capture { "on" } else { "off" },
        if r.config.inter_sf { "on" } else { "off" },
        r.config.seed,
        r.packets_sent,
        r.collision_rate,
        r.collision_rate_theory,
        r.delivery_ratio,
        r.packets_below_sensitivity,
        r.packets_no_demodulator,
        r.error3d.mean,
        r.error3d.p75,
        r.error3d.p95,
        r.median_drone_p75,
        silent
    ))
}

/// Drone counts of `sweep --swarm`.
const SWARM_SIZES: [usize; 7] = [1, 12, 36, 72, 150, 300, 500];

fn sweep_swarm(a: &SweepArgs, prediction: Prediction) -> Result<String, ApiError> {
    let mut rows = Vec::new();
    for channels in [1u8, 3] {
        for plan in [SfPlan::Fixed, SfPlan::Spread] {
            for sender in [SenderKind::Periodic, SenderKind::Error] {
                for drones in SWARM_SIZES {
                    let p = SwarmParams {
                        drones,
                        channels,
                        sf_plan: plan,
                        sf: 7,
                        sender,
                        prediction,
                        duration: 300.0,
                        distance: a.distance,
                        seed: a.seed,
                        ..SwarmParams::default()
                    };
                    rows.push(api::swarm(&p)?);
                }
            }
        }
    }
    if a.out.json {
        return Ok(json(&rows));
    }
    Ok(crate::reproduction::swarm_markdown(&rows, a.markdown))
}
