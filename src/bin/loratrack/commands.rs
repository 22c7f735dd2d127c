//! One function per command: parse options into the API's parameter struct, run, format (`sweep`,
//! which runs grids of them for the generated documents, in sweep.rs).

use crate::doc_cells::pooled_seeds;
use crate::progress::Progress;
use clap::{Args, Subcommand};
use loratrack::api::{self, ApiError};
use loratrack::options as opt;
use loratrack::{
    AccessSettings, ChannelSettings, DroneSettings, FlightSettings, LdroMode, ModelKind,
    ModelResult, NetworkSettings, RadioSettings, RunSettings, Scenario, Sending, SimReport,
    Simulator, StationSettings, SwarmReport, SwarmSettings, SyntheticChoice, FEW_PACKETS,
    MAX_CSV_BYTES,
};
use serde::Serialize;

#[derive(Subcommand)]
pub enum Command {
    /// Time on air of one LoRa packet (Semtech SX1276 formula) and the shortest interval between packets under the plan (1 % duty cycle unless --duty-cycle).
    Airtime(AirtimeArgs),
    /// Noise-free propagation of a state with one motion model (closed form, reference §3).
    Predict(PredictArgs),
    /// Quantise a state into the model's 9/11/12-byte payload (reference §5).
    Encode(EncodeArgs),
    /// Decode a payload back into a state (reference §5).
    Decode(DecodeArgs),
    /// Simulate tracking over LoRa: drone UKF, duty-cycled packets, channel, station predictor.
    Simulate(Box<SimulateArgs>),
    /// The grids the docs are made from: the paper's (--paper), swarms (--swarm), senders, payloads,
    /// data rates and ADR by distance (--distances), the mission station.
    Sweep(crate::sweep::SweepArgs),
    /// Many drones sharing the gateways (one unless --gateway): collisions (capture, inter-SF, 8 demodulators) and every drone's tracking error.
    Swarm(Box<SwarmArgs>),
}

/// Which flight(s): a CSV file, synthetic flights or a bundled sample (simulate needs one;
/// a swarm without one chains synthetic flights for --duration).
#[derive(Args)]
pub struct FlightArgs {
    /// A flight as CSV: header with t,x,y,z (s, m, ENU), or a GPS log's t,lat,lon,alt (degrees, m; read in metres from its first row), and optional vx,vy,vz / ax,ay,az; a regular file of at most 64 MiB.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["synthetic", "sample"])]
    trajectory: Option<std::path::PathBuf>,
    /// The canonical synthetic set: `all` (30 flights, 44 min) or one flight 1..30.
    #[arg(long, value_name = "all|1..30", conflicts_with = "sample", value_parser = SyntheticChoice::parse)]
    synthetic: Option<SyntheticChoice>,
    /// A bundled real flight: canberra (ArduCopter log171, CC BY-SA 3.0).
    #[arg(long, value_name = "NAME")]
    sample: Option<String>,
    /// The drone's mission plan for --model mission with --trajectory or --sample: a CSV of x,y,z[,speed[,hold]] (m, the flight's frame; speed m/s on the leg to that waypoint, which may be empty; hold s at the waypoint), a QGroundControl .plan (its home is the frame's origin) or a QGC WPL waypoint list, Mission Planner's .waypoints (its item 0 is). The synthetic flights carry their own. Alone, without a flight, the drone flies the plan as a multicopter's autopilot does: each leg at its speed (5 m/s where none is given; slower where it climbs over 2.5 m/s or descends over 1.5 m/s), speeding up and braking at 2 m/s², through each waypoint it does not hold at on an arc within 2 m of it (at most 4 m/s² sideways), stopping where it holds, doubles back or ends, each hold as planned, each loiter's turns round its circle (at most 20°/s), a return to launch and a landing as ArduPilot's Copter flies them (up to 15 m first, 5 s over home, down at 0.5 m/s below 10 m); a fixed-wing .plan circles its timed loiters and delays instead of holding (60 m where no radius is given) and turns through a waypoint at its speed on an arc begun up to 90 m before it and climbs out toward its first waypoint, as ArduPlane does; no wind (the mission station's best case; at most 40000 s).
    #[arg(long, value_name = "FILE", conflicts_with = "synthetic")]
    plan: Option<std::path::PathBuf>,
}

impl FlightArgs {
    fn settings(&self) -> Result<FlightSettings, ApiError> {
        Ok(FlightSettings {
            trajectory: self
                .trajectory
                .as_deref()
                .map(read_flight)
                .transpose()?
                .map(Into::into),
            trajectory_name: self.trajectory.as_ref().map(|p| p.display().to_string()),
            synthetic: self.synthetic,
            sample: self.sample.clone(),
            plan: self.plan.as_deref().map(read_flight).transpose()?,
            plan_name: self.plan.as_ref().map(|p| p.display().to_string()),
        })
    }
}

/// Every setting a run takes besides the flight and the swarm's layout: the sub-structs of
/// [`Scenario`], flattened into options (defaults and limits from `loratrack::options`).
#[derive(Args)]
pub struct ScenarioArgs {
    #[command(flatten)]
    station: StationSettings,
    #[command(flatten)]
    sending: Sending,
    #[command(flatten)]
    radio: RadioSettings,
    #[command(flatten)]
    channel: ChannelSettings,
    #[command(flatten)]
    network: NetworkSettings,
    #[command(flatten)]
    drone: DroneSettings,
    #[command(flatten)]
    access: AccessSettings,
    #[command(flatten)]
    run: RunSettings,
}

impl ScenarioArgs {
    fn scenario(self, flight: FlightSettings, swarm: SwarmSettings) -> Scenario {
        Scenario {
            flight,
            station: self.station,
            sending: self.sending,
            radio: self.radio,
            channel: self.channel,
            network: self.network,
            drone: self.drone,
            access: self.access,
            swarm,
            run: self.run,
            unknown: Default::default(),
        }
    }
}

#[derive(Args)]
pub struct SwarmArgs {
    #[command(flatten)]
    flight: FlightArgs,
    #[command(flatten)]
    swarm: SwarmSettings,
    #[command(flatten)]
    scenario: ScenarioArgs,
    #[command(flatten)]
    out: Output,
}

#[derive(Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    flight: FlightArgs,
    #[command(flatten)]
    scenario: ScenarioArgs,
    /// The paper's preset: no LoRaWAN overhead (same as --overhead 0).
    #[arg(long, conflicts_with = "overhead")]
    paper: bool,
    #[command(flatten)]
    out: Output,
}

/// A model and one of its states (predict, encode).
#[derive(Args)]
pub struct ModelState {
    /// Motion model: dr (x y z theta phi v), ctra-plus (+ a omega) or 3d-ctra (+ a omega psi).
    #[arg(long)]
    model: ModelKind,
    /// State, comma-separated, reference §2 order and units (m, rad, m/s, m/s^2, rad/s), e.g. 0,0,0,0,0,1,1,1. Ranges: x y z ±1e7 m, theta phi ±1000 rad, v a ±1000, omega psi ±100 rad/s.
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
    #[arg(long, allow_hyphen_values = true, value_parser = opt::number("dt"))]
    dt: f64,
    /// Propagate in steps of this many seconds, multiplying psi by eta after each (the station's predictor).
    #[arg(long, allow_hyphen_values = true, value_parser = opt::number("step"))]
    step: Option<f64>,
    /// Tilt-rate decay per step, 0..1 (paper: 0.9); needs --step.
    #[arg(long, allow_hyphen_values = true, value_parser = opt::number("eta"))]
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
    pub(crate) json: bool,
}

#[derive(Args)]
pub struct AirtimeArgs {
    /// Spreading factor, 7..12.
    #[arg(long, allow_negative_numbers = true, value_parser = opt::whole::<i64>("sf"))]
    sf: i64,
    /// Bandwidth in kHz: 125, 250 or 500.
    #[arg(long)]
    bw: f64,
    /// Application payload in bytes (loratrack's payloads: 9 DR, 11 CTRA+, 12 3D-CTRA).
    #[arg(long, allow_negative_numbers = true, value_parser = opt::whole::<usize>("payload"))]
    payload: usize,
    /// MAC overhead in bytes added to the payload: 13 for LoRaWAN, 0 for raw LoRa (the paper's Table II).
    #[arg(long, default_value_t = opt::OVERHEAD.default as usize, allow_negative_numbers = true, value_parser = opt::whole::<usize>("overhead"))]
    overhead: usize,
    /// Coding rate n of 4/(4+n): 1..4.
    #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = opt::whole::<i64>("cr"))]
    cr: i64,
    /// Preamble length in symbols.
    #[arg(long, default_value_t = 8, allow_negative_numbers = true, value_parser = opt::whole::<i64>("preamble"))]
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
    #[arg(long, default_value_t = opt::DUTY_CYCLE.default, allow_negative_numbers = true, value_parser = opt::number("dutyCycle"))]
    duty_cycle: f64,
    /// Regional plan: its data rate for this SF and bandwidth, and whether it carries the packet.
    #[arg(long, value_enum, default_value = "eu868")]
    region: loratrack::Region,
    #[arg(long, help = opt::INTERVAL.cli_help(), allow_negative_numbers = true, value_parser = opt::number("interval"))]
    interval: Option<f64>,
    /// duty-cycle, or lbt (ETSI's 100 s of airtime per hour).
    #[arg(long, value_enum, default_value = "duty-cycle")]
    access: loratrack::ChannelAccess,
    /// off, or ttn (30 s of airtime per day).
    #[arg(long, value_enum, default_value = "off")]
    fair_use: loratrack::FairUse,
    #[command(flatten)]
    out: Output,
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

/// Runs a command; `Ok` is what to print, `Err` why it could not.
pub fn run(cmd: Command) -> Result<String, ApiError> {
    match cmd {
        Command::Airtime(a) => airtime(a),
        Command::Predict(a) => predict(a),
        Command::Encode(a) => encode(a),
        Command::Decode(a) => decode(a),
        Command::Simulate(a) => simulate(*a),
        Command::Sweep(a) => crate::sweep::sweep(a),
        Command::Swarm(a) => swarm(*a),
    }
}

/// The plural ending of a count's noun: "" for one, "s" otherwise ("1 packet", "3 packets").
pub(crate) fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

pub(crate) fn json<T: Serialize>(value: &T) -> String {
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
        region: a.region,
        interval: a.interval,
        access: a.access,
        fair_use: a.fair_use,
    };
    let r = api::airtime(&params)?;
    if a.out.json {
        return Ok(json(&r));
    }
    // The plan refuses a data rate it lacks or a frame over its dwell time (no data rate then);
    // at a data rate it has, only an interval shorter than the frame, which the interval line says.
    let (rate, interval) = match (r.data_rate, &r.refused) {
        (None, Some(why)) => (format!("refused: {why}"), None),
        (Some(dr), Some(why)) => (format!("{} DR{dr}", a.region.label()), Some(why)),
        (Some(dr), None) => (format!("{} DR{dr}", a.region.label()), None),
        (None, None) => (
            format!("raw LoRa (no {} data rate)", a.region.label()),
            None,
        ),
    };
    let interval = match interval {
        Some(why) => format!("refused: {why}"),
        None => format!(
            "{:.3} s ({})",
            r.min_interval,
            limit_text(&params.access(), a.duty_cycle)
        ),
    };
    Ok(format!(
        "time on air      {:.3} ms\nsymbol time      {:.3} ms\npayload symbols  {}\nPHY payload      {} B\nLDRO             {}\ndata rate        {rate}\nmin interval     {interval}\nTTN fair use     {} packets/day (30 s of airtime; {})",
        r.time_on_air * 1e3,
        r.symbol_time * 1e3,
        r.payload_symbols,
        r.phy_payload_bytes,
        if r.low_data_rate_optimize { "on" } else { "off" },
        r.ttn_packets_per_day,
        if a.fair_use == loratrack::FairUse::Ttn { "applied to the interval" } else { "not enforced; --fair-use ttn applies it" }
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
    // Each saturated field with the range it was held to: `v (0–25.5 m/s)`.
    let ranged: Vec<String> = loratrack::FIELDS
        .iter()
        .filter(|f| r.saturated.contains(&f.name))
        .map(|f| format!("{} ({})", f.name, f.range_words()))
        .collect();
    let note = if ranged.is_empty() {
        String::new()
    } else {
        format!("\nsaturated: {}", ranged.join(", "))
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

/// Reads a CSV flight (or a plan): a regular file of at most [`MAX_CSV_BYTES`], so that a device, a FIFO or
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
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .map_err(cannot)?
        .take(MAX_CSV_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(cannot)?;
    if bytes.len() > MAX_CSV_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|e| {
        // Say where: the line and the byte, so the file can be mended.
        let at = e.utf8_error().valid_up_to();
        let line = e.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        ApiError::Invalid(format!(
            "{}: line {line}, byte offset {at}: not UTF-8 text (save the CSV as UTF-8)",
            path.display()
        ))
    })
}

fn simulate(a: SimulateArgs) -> Result<String, ApiError> {
    let mut params = a
        .scenario
        .scenario(a.flight.settings()?, SwarmSettings::default());
    if a.paper {
        params.radio.overhead = 0;
    }
    let mut progress = Progress::on_stderr("simulate");
    let r = api::simulate_with_progress(&mut Simulator::new(), &params, &mut |done, total| {
        progress.update(done, total)
    })?;
    drop(progress);
    if a.out.json {
        return Ok(json(&r));
    }
    let c = &r.config;
    Ok(format!(
        "{} ({} flight{}, {:.0} s{}), SF{} / {} kHz ({}){}, overhead {} B, {}\n{}{}\n{}\n{}",
        c.trajectory,
        c.flights,
        plural(c.flights),
        c.flight_time,
        vehicle_text(c.plan_cornering, c.settings.drone.vehicle),
        c.settings.radio.sf,
        c.bandwidth_khz,
        plan_text(c),
        adr_text(&c.settings.network),
        c.settings.radio.overhead,
        pooled_seeds(c.settings.run.seed, c.settings.run.seeds),
        policy_text(&c.settings, false),
        settings_line(&c.settings, &[]),
        results_table(&r.results),
        network_lines(&r)
    ))
}

/// The vehicle a plan is flown and followed as (`config.planCornering`), for the first line:
/// `, plan as a plane`; without a plan, `, a plane` where `--vehicle fixed-wing` says so.
fn vehicle_text(
    plan: Option<loratrack::Cornering>,
    vehicle: loratrack::VehicleChoice,
) -> &'static str {
    use loratrack::Cornering;
    match (plan, vehicle.given()) {
        (Some(Cornering::Multicopter), _) => ", plan as a multicopter",
        (Some(Cornering::FixedWing), _) => ", plan as a plane",
        (None, Some(Cornering::FixedWing)) => ", a plane",
        (None, _) => "",
    }
}

/// The station's prediction and the drone's sending in words, the second line of the text
/// output: two runs that differ only in these must not print alike. `stations: bounded
/// prediction; error-triggered sending (2 m, heartbeat 10 s, listening to its channel), an
/// off-time per packet`. Whether the drone listens is said of a `swarm`'s drones alone: a drone
/// alone never hears another's frame (`simulate` refuses `--channel-sense off`).
fn policy_text(s: &loratrack::Scenario, swarm: bool) -> String {
    let (station, send) = (&s.station, &s.sending);
    let adaptive = station.prediction == loratrack::Prediction::Bounded
        && station.heading_noise == loratrack::HeadingNoise::Adaptive;
    let sender = match send.sender {
        loratrack::SenderKind::Periodic => "periodic sending".to_string(),
        loratrack::SenderKind::Error => format!(
            "error-triggered sending ({} m, heartbeat {} s{})",
            send.threshold,
            send.max_interval,
            match send.channel_sense {
                _ if !swarm => "",
                loratrack::ChannelSense::Cad => ", listening to its channel",
                loratrack::ChannelSense::Off => ", not listening",
            }
        ),
    };
    let region = s.access.region;
    let rule = match (send.duty_cycle_mode, region.duty_cycle()) {
        // Where the plan has no duty cycle the off-time is the interval set.
        (loratrack::DutyCycleMode::PerPacket, None) => format!(
            "every {} s (the interval set; {} has no duty cycle)",
            s.access
                .interval
                .unwrap_or(loratrack::options::INTERVAL.default),
            region.label()
        ),
        (loratrack::DutyCycleMode::PerPacket, Some(_)) => "an off-time per packet".to_string(),
        (loratrack::DutyCycleMode::Budget, _) => {
            format!(
                "a duty-cycle budget of {} packet{}",
                send.burst,
                plural(send.burst as usize)
            )
        }
    };
    let payload = match send.payload {
        loratrack::PayloadChoice::Full => "",
        loratrack::PayloadChoice::Lean => ", lean payloads",
    };
    format!(
        "stations: {} prediction{}; {sender}, {rule}{payload}",
        station.prediction.name(),
        if adaptive {
            ", adaptive heading noise"
        } else {
            ""
        },
    )
}

/// The settings the lines above do not word that differ from their defaults, named and in the
/// units of the options table: `\nsettings: Tx power 10 dBm, Sensor rate 3 Hz, shadowing fixed
/// in space`, or nothing. The numeric ones are the table's `listed_when_changed` (the page's
/// captions list the same, `format.ts advanced`) but `worded`, those the caller's lines already
/// give. Two runs that differ only in them must not print alike.
fn settings_line(s: &loratrack::Scenario, worded: &[&str]) -> String {
    let (now, default) = match (
        serde_json::to_value(s),
        serde_json::to_value(loratrack::Scenario::default()),
    ) {
        (Ok(now), Ok(default)) => (now, default),
        _ => return String::new(),
    };
    let mut named: Vec<String> = opt::OPTIONS
        .iter()
        .filter(|o| o.listed_when_changed && !worded.contains(&o.key))
        .filter(|o| now[o.key] != default[o.key])
        .filter_map(|&o| Some((now[o.key].as_f64()?, o)))
        .map(|(v, o)| match o.key {
            "cr" => format!("{} 4/{}", o.label, 4.0 + v),
            _ if o.unit.is_empty() => format!("{} {}", o.label, opt::as_given(v)),
            _ => format!("{} {} {}", o.label, opt::as_given(v), o.unit),
        })
        .collect();
    if s.channel.shadowing_model == loratrack::ShadowingModel::Field {
        named.push("shadowing fixed in space".into());
    }
    if s.station.plan_pace == loratrack::PlanPace::Packet {
        named.push("pace along the plan from the packet's speed".into());
    }
    if named.is_empty() {
        String::new()
    } else {
        format!("\nsettings: {}", named.join(", "))
    }
}

/// After `simulate`'s data rate, the ADR that moves the run from it: `, tracking ADR from this
/// rate`, LoRaWAN's with its margin and history; nothing for a fixed rate. (A swarm's header
/// names its ADR beside its SF plan.)
fn adr_text(net: &loratrack::NetworkSettings) -> String {
    match net.adr {
        loratrack::AdrMode::Off => String::new(),
        loratrack::AdrMode::Tracking => ", tracking ADR from this rate".to_string(),
        loratrack::AdrMode::Lorawan => format!(
            ", LoRaWAN ADR from this rate (margin {} dB, {} uplink{})",
            net.adr_margin,
            net.adr_history,
            plural(net.adr_history)
        ),
    }
}

/// The plan in words: `US915 DR1, every 1 s, no duty cycle`, `EU868 DR5, 1 % duty cycle`,
/// `EU868, raw LoRa outside its data rates, 1 % duty cycle`.
fn plan_text(c: &loratrack::RunConfig) -> String {
    let a = &c.settings.access;
    let region = a.region.label();
    let rate = c
        .data_rate
        .map_or(format!("{region}, raw LoRa outside its data rates"), |dr| {
            format!("{region} DR{dr}")
        });
    format!("{rate}, {}", limit_text(a, c.settings.radio.duty_cycle))
}

/// What paces the uplinks under `a` with the `duty_cycle` setting, in words: `1 % duty cycle`,
/// `listen-before-talk, 100 s of airtime per hour`, `every 1 s, no duty cycle`, each followed by
/// `, TTN fair use` where that applies.
fn limit_text(a: &loratrack::AccessSettings, duty_cycle: f64) -> String {
    let limit = match a.region.duty_cycle() {
        Some(_) if a.access == loratrack::ChannelAccess::Lbt => {
            "listen-before-talk, 100 s of airtime per hour".to_string()
        }
        Some(_) => format!("{} duty cycle", exact_percent(duty_cycle)),
        None => format!(
            "every {} s, no duty cycle",
            a.interval.unwrap_or(opt::INTERVAL.default)
        ),
    };
    let fair = match a.fair_use {
        loratrack::FairUse::Off => String::new(),
        f => format!(", {} fair use", f.name().to_uppercase()),
    };
    format!("{limit}{fair}")
}

/// A setting's fraction as a percentage in the decimals that say it (0.0007 → `0.07 %`, not the
/// float product's `0.06999999999999999 %`), where a measured share is rounded ([`percent`]).
fn exact_percent(fraction: f64) -> String {
    let text = format!("{:.10}", 100.0 * fraction);
    format!("{} %", text.trim_end_matches('0').trim_end_matches('.'))
}

/// `v` with `decimals` decimals, right-aligned in a column `width` wide (0: no column) with as
/// many fewer decimals as keep it in it (a p95 of 1299.82 m prints 1299.8, so that the columns
/// after it stay under their heads); a dash where there is none (an empty sample's statistic).
fn num(v: f64, width: usize, decimals: usize) -> String {
    if !v.is_finite() {
        return format!("{:>width$}", "-");
    }
    let text = (0..=decimals)
        .rev()
        .map(|d| format!("{v:.d$}"))
        .find(|t| width == 0 || t.len() <= width)
        .unwrap_or_else(|| format!("{v:.0}"));
    format!("{text:>width$}")
}

pub(crate) fn results_table(results: &[ModelResult]) -> String {
    let mut out = String::from(
        "model     interval  received  tracked   mean    p50    p75    p95    max  cover95   NEES  mC/uplink  (3D error, m)\n",
    );
    for m in results {
        out += &format!(
            "{:<9} {:>7.2}s {:>5}/{:<5} {:>6}% {} {} {} {} {} {} {} {}\n",
            m.model.label(),
            // With ADR the mean over the packets, as the page shows; the rates are listed below.
            m.interval_shown(),
            m.delivery.packets_received,
            m.delivery.packets_sent,
            num(100.0 * m.whole_flight.tracked, 6, 1),
            num(m.error3d.mean, 6, 2),
            num(m.error3d.p50, 6, 2),
            num(m.error3d.p75, 6, 2),
            num(m.error3d.p95, 6, 2),
            num(m.error3d.max, 6, 1),
            num(m.coverage95, 7, 3),
            num(m.nees, 6, 2),
            // No uplink, no charge per uplink (the core's NaN, a dash).
            num(m.energy.charge_per_uplink, 10, 2),
        );
        if let Some(p) = &m.model_probability {
            let parts: Vec<String> = p.iter().map(|(k, v)| format!("{k} {v:.2}")).collect();
            out += &format!("          mean model probability: {}\n", parts.join(", "));
        }
        if m.data_rate_use.len() > 1 {
            out += &format!("          {}\n", rates_line(&m.data_rate_use));
        }
        if m.sent_slower {
            out += &format!(
                "          sent every {:.2} s on average; the interval column is what the plan allows\n",
                m.sent_every
            );
        }
        if m.lean_packets > 0 {
            out += &format!(
                "          lean payload: {} of {} packet{} left out a, omega or psi{}\n",
                m.lean_packets,
                m.delivery.packets_sent,
                plural(m.delivery.packets_sent),
                m.lean_frame.map_or(String::new(), |f| format!(
                    " (shortest {:.1} ms on air, {:.2} s interval)",
                    f.time_on_air * 1e3,
                    f.interval
                ))
            );
        }
    }
    let intervals: Vec<String> = results
        .iter()
        .filter_map(|m| {
            m.ci95
                .map(|c| format!("{} {:.2}-{:.2}", m.model.label(), c.p75[0], c.p75[1]))
        })
        .collect();
    if let Some(c) = results.iter().find_map(|m| m.ci95) {
        out += &format!(
            "p75 95 % interval (bootstrap over {} runs): {}\n",
            c.runs,
            intervals.join(", ")
        );
    }
    out += &versus_lowest_line(results);
    if results.iter().any(|m| m.whole_flight.partly_tracked) {
        out += "tracked: the share of the flight time after each flight's first packet; the errors cover only that time\n";
    }
    out += &caveat_lines(results);
    out.trim_end().to_string()
}

/// Each station's p75 against the lowest one's on the same runs, resampled together:
/// `p75 against CTRA+'s (paired bootstrap over 30 runs): DR 1.472x (1.388-1.580, clearly
/// higher), 3D-CTRA 1.056x (1.042-1.071, clearly higher)`; empty where there is nothing to pair.
fn versus_lowest_line(results: &[loratrack::ModelResult]) -> String {
    let versus: Vec<(&loratrack::ModelResult, loratrack::VersusLowest)> = results
        .iter()
        .filter_map(|m| m.p75_vs_lowest.map(|v| (m, v)))
        .collect();
    let Some((_, first)) = versus.first() else {
        return String::new();
    };
    let parts: Vec<String> = versus
        .iter()
        .map(|(m, v)| {
            let clear = if v.clearly_higher() {
                ", clearly higher"
            } else {
                ""
            };
            format!(
                "{} {:.3}x ({:.3}-{:.3}{clear})",
                m.model.label(),
                v.ratio,
                v.interval[0],
                v.interval[1]
            )
        })
        .collect();
    format!(
        "p75 against {}'s (paired bootstrap over {} runs): {}\n",
        first.lowest.label(),
        first.runs,
        parts.join(", ")
    )
}

/// Where ADR sent a station's packets, fastest rate first, received / sent and each rate's
/// duty-cycle interval: `ADR: DR6 0/4 every 3.08 s, DR3 78/112 every 20.58 s; the interval
/// column is their mean over the packets sent` (the page's interval cell too, its span below).
fn rates_line(rates: &[loratrack::DataRateUse]) -> String {
    let parts: Vec<String> = rates
        .iter()
        .rev()
        .map(|u| {
            format!(
                "{} {}/{} every {:.2} s",
                crate::doc_cells::rate_name(u),
                u.received,
                u.packets,
                u.interval
            )
        })
        .collect();
    format!(
        "ADR: {}; the interval column is their mean over the packets sent",
        parts.join(", ")
    )
}

/// The lines the page shows as notes under its results, for the stations whose `caveats` say so:
/// too few packets to compare, an error-triggered drone misled by its silence after losses,
/// packets that saturated a payload field, and stations whose packets the link delivered unlike
/// ([`loratrack::DeliverySpread`]).
fn caveat_lines(results: &[ModelResult]) -> String {
    let flagged = |f: fn(&ModelResult) -> bool, each: fn(&ModelResult) -> String| {
        let list: Vec<String> = results.iter().filter(|m| f(m)).map(each).collect();
        (!list.is_empty()).then(|| list.join(", "))
    };
    let mut out = String::new();
    if let Some(list) = flagged(
        |m| m.caveats.few_packets,
        |m| format!("{} {}", m.model.label(), m.delivery.packets_received),
    ) {
        out += &format!("too few packets to compare (under {FEW_PACKETS} received): {list}\n");
    }
    if let Some(list) = flagged(
        |m| m.caveats.silence_after_loss,
        |m| {
            format!(
                "{} {:.0} %",
                m.model.label(),
                100.0 * (1.0 - m.delivery.delivery_ratio)
            )
        },
    ) {
        out += &format!("lost: {list} of the packets; an error-triggered drone cannot tell a lost packet from a delivered one, so after a loss its silence misleads the station (docs/senders.md)\n");
    }
    if let Some(list) = flagged(
        |m| m.caveats.saturated_packets > 0,
        |m| {
            format!(
                "{} {} of {}",
                m.model.label(),
                m.caveats.saturated_packets,
                m.delivery.packets_received
            )
        },
    ) {
        let fields = results
            .iter()
            .fold(loratrack::SaturatedFields::default(), |f, m| {
                f.union(m.caveats.saturated)
            });
        out += &format!(
            "saturated: {list} received packets {}\n",
            beyond_range(fields, false)
        );
    }
    if let Some(d) = loratrack::DeliverySpread::of(results.iter().map(|m| (m.model, &m.delivery))) {
        out += &format!(
            "delivered: {} {:.0} % of its packets, {} {:.0} %; stations with frames of other lengths send at other moments, and the link's fades took other packets from each, so part of the difference in their errors is the link's, not the model's (docs/paper-reproduction.md, the real flight at every data rate)\n",
            d.highest.label(),
            100.0 * d.highest_ratio,
            d.lowest.label(),
            100.0 * d.lowest_ratio
        );
    }
    out
}

/// The network summary under a simulate table: each gateway, the copies removed, the energy.
fn network_lines(r: &SimReport) -> String {
    let d = &r.delivery;
    let share = if d.delivery_ratio.is_nan() {
        "none sent".to_string()
    } else {
        format!("{:.1} %", 100.0 * d.delivery_ratio)
    };
    let mut out = format!(
        "network: {} of {} packet{} delivered ({share}), {} duplicate{} removed",
        d.packets_received,
        d.packets_sent,
        plural(d.packets_sent),
        d.duplicates,
        plural(d.duplicates)
    );
    out += &gateway_lines(&d.gateways);
    for m in &r.results {
        out += &match m.energy.charge_per_uplink {
            charge if charge.is_finite() => format!(
                "\nenergy {:<9} {charge:.2} mC per uplink, {:.3} mAh per hour (SX1276 radio only)",
                m.model.label(),
                m.energy.charge_per_hour
            ),
            _ => format!("\nenergy {:<9} no uplink sent", m.model.label()),
        };
    }
    out
}

/// Each gateway's line: the downlinks it sent, those its duty cycle refused ("dropped") and, where
/// any, those the network server held back for a later uplink to keep a crowded gateway listening
/// (`GatewayReport::downlinks_held_back`); the page's notes give the same counts.
fn gateway_lines(gateways: &[loratrack::GatewayReport]) -> String {
    gateways
        .iter()
        .enumerate()
        .map(|(i, g)| {
            format!(
                "\n  gateway {} at ({:.0}, {:.0}) m, {:.0} m high: heard {}, only it {}, downlinks {} sent / {} dropped{}{}",
                i + 1,
                g.east,
                g.north,
                g.height,
                g.heard,
                g.only_heard,
                g.downlinks_sent,
                g.downlinks_dropped,
                match g.downlinks_held_back {
                    0 => String::new(),
                    n => format!(" / {n} held back"),
                },
                match g.missed_while_transmitting {
                    0 => String::new(),
                    n => format!(", {n} uplinks missed while sending"),
                }
            )
        })
        .collect()
}

fn swarm(a: SwarmArgs) -> Result<String, ApiError> {
    let params = a.scenario.scenario(a.flight.settings()?, a.swarm);
    let mut progress = Progress::on_stderr("swarm");
    let r = api::swarm_with_progress(&params, &mut |done, total| progress.update(done, total))?;
    drop(progress);
    if a.out.json {
        return Ok(json(&r));
    }
    Ok(swarm_text(&r))
}

/// `swarm`'s text: what flew and how ([`swarm_header`]), what the air carried
/// ([`swarm_traffic`]), how well the stations tracked ([`swarm_tracking`]), and the caveats and
/// gateways under them.
fn swarm_text(r: &SwarmReport) -> String {
    let d = &r.delivery;
    let mut out = swarm_header(r);
    out += &swarm_traffic(r);
    out += &swarm_tracking(r);
    out += &swarm_saturated_line(&r.saturation, d.packets_received);
    out += &gateway_lines(&d.gateways);
    out
}

/// What each drone flies: the synthetic set, one of its flights, the real flight, a CSV or a
/// plan flown, with its length (with a flight chosen every drone flies it whole; the duration is
/// for chained synthetic flights), and as which vehicle.
fn swarm_flown(r: &SwarmReport) -> String {
    let c = &r.config.settings;
    let f = &c.flight;
    let clean = loratrack::api::clean_message;
    let chosen = match (f.synthetic, &f.sample, &f.trajectory_name, &f.plan_name) {
        (Some(loratrack::SyntheticChoice::All), ..) => Some("the synthetic set".to_string()),
        (Some(loratrack::SyntheticChoice::One(i)), ..) => Some(format!("synthetic {i}")),
        (None, Some(sample), ..) => Some(sample.to_string()),
        (None, None, Some(name), _) => Some(clean(name)),
        (None, None, None, Some(plan)) => Some(format!("{} (flown)", clean(plan))),
        _ => None,
    };
    let flown = match chosen {
        Some(flight) => format!("each flying {flight} ({:.0} s)", r.flight_time),
        None => format!("x {:.0} s", c.swarm.duration),
    };
    flown + vehicle_text(r.config.plan_cornering, c.drone.vehicle)
}

/// The swarm's settings: its first line (drones, flight, distance, plan, channels, SFs, station,
/// the network's switches, seed) and the sending policy with the settings changed from their
/// defaults.
fn swarm_header(r: &SwarmReport) -> String {
    let c = &r.config.settings;
    format!(
        "{} drone{} {}, at {} m, {} ({}), {} channel{}, {}, {} station, capture {}, inter-SF {}, ADR {}, seed {}\n{}{}\n",
        c.swarm.drones,
        plural(c.swarm.drones),
        swarm_flown(r),
        c.channel.distance,
        c.access.region.label(),
        limit_text(&c.access, c.radio.duty_cycle),
        c.channels(),
        plural(usize::from(c.channels())),
        sf_plan_text(r),
        r.config.station.label(),
        if c.network.capture { "on" } else { "off" },
        if c.network.inter_sf { "on" } else { "off" },
        c.network.adr.name(),
        c.run.seed,
        policy_text(c, true),
        // The channel access line gives the swarm's timing.
        settings_line(c, &["jitter", "clockDrift"]),
    )
}

/// The air's lines: channel access, packets sent and at which SFs, collisions against the ALOHA
/// formula, the largest swarm a gateway serves, delivery, and the packets lost otherwise.
fn swarm_traffic(r: &SwarmReport) -> String {
    let d = &r.delivery;
    let lean = r.lean_packets > 0;
    let mut out = format!("channel access      {}\n", schedule_text(r));
    out += &format!("packets sent        {}{}", d.packets_sent, sf_shares(r));
    if lean {
        out += &format!("  ({} with lean payloads)", r.lean_packets);
    }
    out += &format!(
        "\ncollision rate      {}  (pure-ALOHA formula at the duty cycle achieved: {:.4})\n",
        num(r.collision_rate, 0, 4),
        r.collision_rate_theory
    );
    let l = &r.largest_swarm;
    out += &format!(
        "largest swarm       {} drone{} at <= 1 % collisions, {} at <= 10 % (ALOHA formula); {} slotted, with none{}\n",
        l.aloha1,
        plural(l.aloha1),
        l.aloha10,
        l.slotted,
        if lean {
            " (full frames; the lean ones leave room for more)"
        } else {
            ""
        },
    );
    out += &format!(
        "delivery ratio      {}  ({} distinct packets, {} duplicate{} removed)\n",
        num(d.delivery_ratio, 0, 4),
        d.packets_received,
        d.duplicates,
        plural(d.duplicates)
    );
    out += &format!("below sensitivity   {}\n", r.packets_below_sensitivity);
    out += &format!("no demodulator      {}", r.packets_no_demodulator);
    if r.packets_gateway_transmitting > 0 {
        out += &format!(
            "\ngateway sending     {}  (on air while the gateway sent a downlink: it is half-duplex)",
            r.packets_gateway_transmitting
        );
    }
    out + "\n"
}

/// The tracking's lines: the pooled errors and the median drone's p75, the share of the flight
/// time they cover, the radio's charge, and the drones that received nothing or too little to
/// compare (the page draws those hollow).
fn swarm_tracking(r: &SwarmReport) -> String {
    let silent = r.drones.iter().filter(|d| d.error3d.count == 0).count();
    let thin = r
        .drones
        .iter()
        .filter(|d| d.caveats.few_packets && d.error3d.count > 0)
        .count();
    let energy = match r.energy.charge_per_uplink {
        charge if charge.is_finite() => format!(
            "{charge:.2} mC per uplink (mean over the drones that sent), {:.3} mAh per hour (mean drone), SX1276 radio only",
            r.energy.charge_per_hour
        ),
        _ => "no uplink sent".to_string(),
    };
    format!(
        "3D error (pooled)   mean {}  p75 {}  p95 {} m; median drone p75 {} m\n\
         tracked             {}  (the share of the flight time after each flight's first packet, all the errors cover){}\n\
         energy              {energy}\n\
         drones that received nothing: {silent}; too few packets for their own p75 to compare (1 to {}): {thin}",
        num(r.error3d.mean, 0, 2),
        num(r.error3d.p75, 0, 2),
        num(r.error3d.p95, 0, 2),
        num(r.median_drone_p75, 0, 2),
        percent(r.whole_flight.tracked),
        tracked_by_sf(r),
        loratrack::FEW_PACKETS - 1,
    )
}

/// The drones whose received packets saturated a payload field (the core's `saturation`), as the
/// page's swarm note says it; nothing where none did.
fn swarm_saturated_line(s: &loratrack::SwarmSaturation, received: usize) -> String {
    if s.drones == 0 {
        return String::new();
    }
    format!(
        "\nsaturated: {} of the drones' {received} received packets, from {} drone{}, {}",
        s.packets,
        s.drones,
        plural(s.drones),
        beyond_range(s.fields, true)
    )
}

/// What received packets that saturated `fields` did to a station (`swarm`: to their drones'
/// stations), the words the results' and the swarm's `saturated:` lines end with.
fn beyond_range(fields: loratrack::SaturatedFields, swarm: bool) -> String {
    let (whose, its) = if swarm {
        ("their stations", "their")
    } else {
        ("the station", "its")
    };
    format!(
        "carried a value beyond the payload's range ({}), sent as the range's edge: {whose} started from a state other than the drone's estimate, so part of {its} error is the payload's, not the model's (the payload is sized for a quadcopter; docs/reference.md §5)",
        fields.words()
    )
}

/// The SFs the drones were dealt, as the page's swarm note says them: "SF7-SF12 in turn" (drone
/// i on the plan's SF i mod n), "all on SF9"; with ADR, where they started; and why where
/// `spread` dealt fewer than it had drones for (the core's `sf_limit`): "SF7-SF9 in turn (at
/// 125 kHz US915 carries the frame at no other SF)", "all starting on SF7 (at 250 kHz ADR can
/// start at no other SF)", "SF7-SF11 in turn (at 125 kHz a slower SF's frame outlasts the 1 s
/// interval set)".
fn sf_plan_text(r: &SwarmReport) -> String {
    let mut sfs: Vec<u8> = r.drones.iter().map(|d| d.sf).collect();
    sfs.sort_unstable();
    sfs.dedup();
    let settings = &r.config.settings;
    let adr = settings.network.adr != loratrack::AdrMode::Off;
    let all_on = if adr { "all starting on" } else { "all on" };
    let dealt = match sfs.as_slice() {
        [] => format!("{all_on} SF{}", settings.radio.sf),
        [sf] => format!("{all_on} SF{sf}"),
        [first, .., last] if usize::from(last - first) + 1 == sfs.len() => {
            format!("SF{first}-SF{last} in turn")
        }
        several => {
            let names: Vec<String> = several.iter().map(|sf| format!("SF{sf}")).collect();
            format!("{} in turn", names.join(", "))
        }
    };
    let start = if adr && sfs.len() > 1 {
        " at the start"
    } else {
        ""
    };
    let bw = settings.radio.bw;
    let why = match r.sf_limit {
        Some(loratrack::SfLimit::Adr) => format!("at {bw} kHz ADR can start at no other SF"),
        Some(loratrack::SfLimit::Region) => format!(
            "at {bw} kHz {} carries the frame at no other SF",
            settings.access.region.label()
        ),
        Some(loratrack::SfLimit::Interval) => format!(
            "at {bw} kHz a slower SF's frame outlasts the {} s interval set",
            settings
                .access
                .interval
                .unwrap_or(loratrack::options::INTERVAL.default)
        ),
        None => return format!("{dealt}{start}"),
    };
    format!("{dealt}{start} ({why})")
}

/// With ADR, where the swarm's packets went: "  (ADR sent them at SF7 61 %, SF8 39 %)"; empty
/// without (every drone stays at its SF).
fn sf_shares(r: &SwarmReport) -> String {
    if r.config.settings.network.adr == loratrack::AdrMode::Off {
        return String::new();
    }
    format!("  (ADR sent them at {})", share_words(r.packets_by_sf))
}

/// The packets `sent` at SF7..SF12 as shares: "SF7 61 %, SF8 39 %", an SF with none left out,
/// one with under half a per cent "<1 %". Halves round up, as the page's note rounds them
/// (`toFixed`), where Rust's formatting rounds them to even: 1 packet of 8 is 13 % in both.
fn share_words(sent: [usize; 6]) -> String {
    let total = sent.iter().sum::<usize>().max(1) as f64;
    let shares: Vec<String> = (7..)
        .zip(sent)
        .filter(|&(_, n)| n > 0)
        .map(|(sf, n)| match 100.0 * n as f64 / total {
            share if share < 0.5 => format!("SF{sf} <1 %"),
            share => format!("SF{sf} {} %", share.round()),
        })
        .collect();
    shares.join(", ")
}

/// A share as "78.2 %", or a dash.
fn percent(share: f64) -> String {
    if share.is_finite() {
        format!("{:.1} %", 100.0 * share)
    } else {
        "-".to_string()
    }
}

/// "; SF7 99.1 %, ..., SF12 23.0 %": the tracked share of each SF's drones, when the swarm
/// spreads them over more than one.
fn tracked_by_sf(r: &SwarmReport) -> String {
    let mut by_sf: std::collections::BTreeMap<u8, (usize, f64)> = Default::default();
    for d in &r.drones {
        let e = by_sf.entry(d.sf).or_default();
        (e.0, e.1) = (e.0 + 1, e.1 + d.whole_flight.tracked);
    }
    if by_sf.len() < 2 {
        return String::new();
    }
    let parts: Vec<String> = by_sf
        .iter()
        .map(|(sf, (n, sum))| format!("SF{sf} {}", percent(sum / *n as f64)))
        .collect();
    format!("; by SF (mean drone) {}", parts.join(", "))
}

/// The schedule line of `swarm`'s text: ALOHA with its clocks, or the slotted frame.
fn schedule_text(r: &SwarmReport) -> String {
    let a = &r.config.settings.access;
    let t = a.swarm_timing();
    if let (Some(deferred), Some(avoided)) = (r.lbt_deferrals, r.lbt_collisions_avoided) {
        return format!(
            "listen-before-talk: {deferred} deferrals (channel busy), {avoided} of them on the drone's own SF (collisions avoided)"
        );
    }
    match r.frame_length {
        Some(frame) => format!("slotted on GPS time, longest frame {frame:.2} s"),
        None => format!(
            "{}, random delay up to {} s, clocks within {} ppm",
            a.schedule.name(),
            t.jitter,
            t.clock_drift_ppm
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[test]
    fn a_number_too_wide_for_its_column_drops_decimals_before_it_pushes_the_next_one() {
        assert_eq!(num(12.345, 6, 2), " 12.35");
        assert_eq!(num(1299.82, 6, 2), "1299.8");
        assert_eq!(num(99999.4, 6, 2), " 99999");
        // Past its width with no decimals left it is printed whole, wider.
        assert_eq!(num(1234567.0, 6, 2), "1234567");
        assert_eq!(num(f64::NAN, 6, 2), "     -");
        // Outside a column (width 0), every decimal asked for.
        assert_eq!(num(0.0699, 0, 4), "0.0699");
    }

    #[test]
    fn a_budget_of_one_packet_is_named_in_the_singular() {
        let mut s = Scenario::default();
        s.sending.duty_cycle_mode = loratrack::DutyCycleMode::Budget;
        for (burst, words) in [(1, "budget of 1 packet"), (10, "budget of 10 packets")] {
            s.sending.burst = burst;
            let line = policy_text(&s, false);
            assert!(line.ends_with(words), "{line}");
        }
    }

    #[derive(Parser)]
    struct Bare {
        #[command(flatten)]
        swarm: SwarmSettings,
        #[command(flatten)]
        scenario: ScenarioArgs,
    }

    /// The CLI's defaults are the core's: an option left out means what a JS caller who leaves
    /// the key out gets (`Scenario::default`, from `loratrack::options` and each enum's
    /// `Default`).
    #[test]
    fn every_option_left_out_takes_the_cores_default() {
        let bare = Bare::try_parse_from(["loratrack"]).expect("no option is required");
        let cli = bare
            .scenario
            .scenario(FlightSettings::default(), bare.swarm);
        assert_eq!(cli, Scenario::default());
    }

    /// `swarm`'s options, which are every option a command line may hold: for reading one back.
    #[derive(Parser)]
    struct Whole {
        #[command(flatten)]
        swarm: SwarmArgs,
    }

    /// Each setting away from its default, written as `Scenario::cli_args` writes it, reads back
    /// through the CLI's own options into the same settings; every setting the wire knows is
    /// among them, so a setting the command line cannot carry fails here.
    #[test]
    fn every_setting_survives_its_command_line() {
        let dir = std::env::temp_dir().join(format!("loratrack-cli-args-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (flight_file, plan_file) = (dir.join("a flight.csv"), dir.join("plan.csv"));
        std::fs::write(&flight_file, "t,x,y,z\n0,0,0,10\n1,1,0,10\n").unwrap();
        std::fs::write(&plan_file, "0,0,10\n100,0,10\n").unwrap();
        let changes = serde_json::json!([
            {"synthetic": "all"}, {"synthetic": 7}, {"sample": "canberra"},
            {"model": "dr,imm", "prediction": "bounded", "headingNoise": "adaptive", "step": 0.2,
             "eta": 0.8, "planPace": "packet", "planTolerance": 25.5},
            {"sender": "error", "threshold": 3.5, "maxInterval": 30, "channelSense": "off",
             "dutyCycleMode": "budget", "payload": "lean", "burst": 4},
            {"sf": 9, "bw": 125, "cr": 2, "overhead": 0, "dutyCycle": 0.001, "txPower": -3.5},
            {"distance": 2500.25, "pathLossExponent": 3.1, "shadowing": 0, "shadowingModel": "field",
             "gatewayHeight": 30},
            {"gateways": [{"east": -500, "north": 0}, {"east": 10, "north": 20.5, "height": 30}],
             "channels": 1, "capture": false, "interSf": false, "adr": "tracking", "adrMargin": 15,
             "adrHistory": 10},
            {"sensorRate": 50, "q": 0.07, "vehicle": "fixed-wing"},
            {"region": "us915", "interval": 5, "fairUse": "ttn", "jitter": 0.5, "clockDrift": 10,
             "schedule": "slotted"},
            {"access": "lbt"},
            {"drones": 50, "duration": 120, "sfPlan": "fixed"},
            {"seed": 9007199254740991u64, "seeds": 3, "series": true},
        ]);
        let mut covered = std::collections::BTreeSet::new();
        let mut runs: Vec<Scenario> = changes
            .as_array()
            .unwrap()
            .iter()
            .map(|c| {
                covered.extend(c.as_object().unwrap().keys().cloned());
                Scenario::default().with(c).unwrap()
            })
            .collect();
        let mut csv = Scenario::default();
        csv.flight.trajectory = Some(std::fs::read_to_string(&flight_file).unwrap().into());
        csv.flight.trajectory_name = Some(flight_file.display().to_string());
        csv.flight.plan = Some(std::fs::read_to_string(&plan_file).unwrap());
        csv.flight.plan_name = Some(plan_file.display().to_string());
        runs.push(csv);
        let every = serde_json::to_value(Scenario::default()).unwrap();
        let missing: Vec<&String> = every
            .as_object()
            .unwrap()
            .keys()
            .filter(|k| !covered.contains(*k))
            .collect();
        assert!(missing.is_empty(), "settings no case changes: {missing:?}");
        for original in runs {
            let args = original.cli_args(loratrack::CliCommand::Swarm);
            assert_eq!(read_back(&args), original, "{args:?}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// The settings a command line's arguments give, as the CLI reads them.
    fn read_back(args: &[String]) -> Scenario {
        let whole = Whole::try_parse_from(
            std::iter::once("loratrack").chain(args.iter().map(String::as_str)),
        )
        .unwrap_or_else(|e| panic!("{args:?}: {e}"))
        .swarm;
        whole
            .scenario
            .scenario(whole.flight.settings().unwrap(), whole.swarm)
    }

    proptest::proptest! {
        /// Any value a numeric setting accepts, at full precision, reads back from its command
        /// line to the same bits.
        #[test]
        fn any_accepted_number_survives_its_command_line(
            i in 0..loratrack::options::OPTIONS.len(),
            u in 0.0f64..=1.0,
            pick in 0usize..8,
        ) {
            let o = loratrack::options::OPTIONS[i];
            let v = match o.values {
                [] if o.integer => (o.min + u * (o.max - o.min)).round(),
                [] => o.min + u * (o.max - o.min),
                values => values[pick % values.len()],
            };
            proptest::prop_assume!(o.accepts(v));
            // A whole number as JSON writes one: a whole-number setting reads no `1.0`.
            let value = if v.fract() == 0.0 { serde_json::json!(v as i64) } else { serde_json::json!(v) };
            let change = match o.key {
                // A limit on the list's length, not a setting.
                "gateways" => return Ok(()),
                "gateway" => serde_json::json!({ "gateways": [{ "east": v, "north": -v }] }),
                key => serde_json::json!({ key: value }),
            };
            let original = Scenario::default().with(&change).unwrap();
            proptest::prop_assert!(original.unknown.is_empty(), "{} is not a setting", o.key);
            let args = original.cli_args(loratrack::CliCommand::Swarm);
            proptest::prop_assert_eq!(read_back(&args), original, "{:?}", args);
        }
    }

    /// The header names every setting of the station's prediction and the drone's sending, so
    /// that two runs differing in one of them never print alike.
    #[test]
    fn runs_that_differ_in_prediction_or_sending_print_different_headers() {
        let base = Scenario::default();
        let mut variants = vec![base.clone()];
        let mut vary = |f: &dyn Fn(&mut Scenario)| {
            let mut s = variants.last().cloned().unwrap_or_default();
            f(&mut s);
            variants.push(s);
        };
        vary(&|s| s.station.prediction = loratrack::Prediction::Bounded);
        vary(&|s| s.station.heading_noise = loratrack::HeadingNoise::Adaptive);
        vary(&|s| s.sending.sender = loratrack::SenderKind::Error);
        vary(&|s| s.sending.threshold = 5.0);
        vary(&|s| s.sending.max_interval = 30.0);
        vary(&|s| s.sending.channel_sense = loratrack::ChannelSense::Off);
        vary(&|s| s.sending.duty_cycle_mode = loratrack::DutyCycleMode::Budget);
        vary(&|s| s.sending.burst = 4);
        vary(&|s| s.sending.payload = loratrack::PayloadChoice::Lean);
        let headers: Vec<String> = variants.iter().map(|s| policy_text(s, true)).collect();
        for (i, a) in headers.iter().enumerate() {
            for b in &headers[i + 1..] {
                assert_ne!(a, b, "{headers:#?}");
            }
        }
        // The defaults read as the paper's station and drone.
        let prediction = format!("{} prediction;", base.station.prediction.name());
        assert!(headers[0].contains(&prediction), "{}", headers[0]);
        assert!(headers[0].contains("; periodic sending,"), "{}", headers[0]);
    }

    /// Where the plan has no duty cycle the drone sends at the interval set, and the policy line
    /// says so instead of an off-time.
    #[test]
    fn the_policy_line_names_the_interval_where_the_plan_has_no_duty_cycle() {
        let mut s = Scenario::default();
        assert!(policy_text(&s, false).ends_with(", an off-time per packet"));
        s.access.region = loratrack::Region::Us915;
        assert!(policy_text(&s, false)
            .ends_with(", every 1 s (the interval set; US915 has no duty cycle)"));
        s.access.interval = Some(5.0);
        assert!(policy_text(&s, false)
            .ends_with(", every 5 s (the interval set; US915 has no duty cycle)"));
    }

    #[test]
    fn adr_shares_round_halves_up_as_the_page_does() {
        // 12.5 % and 87.5 %: formatted with {:.0}, Rust would say 12 % and 88 %.
        assert_eq!(share_words([1, 7, 0, 0, 0, 0]), "SF7 13 %, SF8 88 %");
        assert_eq!(share_words([0, 0, 999, 1, 0, 0]), "SF9 100 %, SF10 <1 %");
    }

    /// A plan's vehicle is on `simulate`'s first line, since it changes how the plan is flown;
    /// a run without a plan names a plane only where `--vehicle` sets one (it bounds the
    /// station at a plane's speed), and a multicopter, the default, not at all.
    #[test]
    fn the_first_line_says_which_vehicle_a_plan_is_flown_as() {
        use loratrack::{Cornering, VehicleChoice};
        assert_eq!(vehicle_text(None, VehicleChoice::Auto), "");
        assert_eq!(vehicle_text(None, VehicleChoice::Multicopter), "");
        assert_eq!(vehicle_text(None, VehicleChoice::FixedWing), ", a plane");
        let plane = vehicle_text(Some(Cornering::FixedWing), VehicleChoice::Auto);
        let copter = vehicle_text(Some(Cornering::Multicopter), VehicleChoice::Auto);
        assert!(plane.ends_with("plan as a plane") && copter.ends_with("plan as a multicopter"));
    }

    /// `simulate`'s first line names the ADR that moves the rate it states, with LoRaWAN's
    /// settings; a fixed rate's says nothing more.
    #[test]
    fn simulates_header_names_the_adr_that_moves_its_rate() {
        let mut net = Scenario::default().network;
        assert_eq!(adr_text(&net), "");
        net.adr = loratrack::AdrMode::Tracking;
        assert_eq!(adr_text(&net), ", tracking ADR from this rate");
        net.adr = loratrack::AdrMode::Lorawan;
        let lorawan = adr_text(&net);
        net.adr_margin = 15.0;
        assert_ne!(adr_text(&net), lorawan);
        net.adr_history = 10;
        assert_eq!(
            adr_text(&net),
            ", LoRaWAN ADR from this rate (margin 15 dB, 10 uplinks)"
        );
    }
}
