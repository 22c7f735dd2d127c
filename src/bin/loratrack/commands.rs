//! One function per command: parse options into the API's parameter struct, run, format.

use clap::{Args, Subcommand};
use loratrack::api::{self, ApiError};
use loratrack::{LdroMode, ModelKind};
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
}

/// Motion model names accepted by --model.
const MODEL_HELP: &str =
    "Motion model: dr (x y z theta phi v), ctra-plus (+ a omega) or 3d-ctra (+ a omega psi)";

#[derive(Args)]
pub struct PredictArgs {
    #[arg(long, help = MODEL_HELP)]
    model: ModelKind,
    /// State, comma-separated, SPEC §2 order and units (m, rad, m/s, m/s^2, rad/s), e.g. 0,0,0,0,0,1,1,1.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    state: Vec<f64>,
    /// Time to propagate over, seconds (>= 0).
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
    #[arg(long, help = MODEL_HELP)]
    model: ModelKind,
    /// State, comma-separated, SPEC §2 order and units.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true
    )]
    state: Vec<f64>,
    /// Origin x,y,z in metres (ENU) that both ends agree on; positions are sent relative to it.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    origin: Option<Vec<f64>>,
    #[command(flatten)]
    out: Output,
}

#[derive(Args)]
pub struct DecodeArgs {
    #[arg(long, help = MODEL_HELP)]
    model: ModelKind,
    /// Payload as hex digits (9, 11 or 12 bytes for dr, ctra-plus, 3d-ctra).
    #[arg(long)]
    hex: String,
    /// Origin x,y,z in metres (ENU) that both ends agree on.
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    origin: Option<Vec<f64>>,
    #[command(flatten)]
    out: Output,
}

fn origin(o: Option<Vec<f64>>) -> Result<Option<[f64; 3]>, ApiError> {
    o.map(|v| {
        <[f64; 3]>::try_from(v.as_slice()).map_err(|_| {
            ApiError::Invalid(format!("--origin needs 3 numbers x,y,z, got {}", v.len()))
        })
    })
    .transpose()
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
    /// Duty-cycle limit as a fraction (EU868 868.0–868.6 MHz: 0.01).
    #[arg(long, default_value_t = 0.01)]
    duty_cycle: f64,
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

/// Runs a command; `Ok` is what to print, `Err` the error message.
pub fn run(cmd: Command) -> Result<String, String> {
    match cmd {
        Command::Airtime(a) => airtime(a),
        Command::Predict(a) => predict(a),
        Command::Encode(a) => encode(a),
        Command::Decode(a) => decode(a),
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
        "time on air      {:.3} ms\nsymbol time      {:.3} ms\npayload symbols  {}\nPHY payload      {} B\nLDRO             {}\nmin interval     {:.3} s (duty cycle {})",
        r.time_on_air * 1e3,
        r.symbol_time * 1e3,
        r.payload_symbols,
        r.phy_payload_bytes,
        if r.low_data_rate_optimize { "on" } else { "off" },
        r.min_interval,
        a.duty_cycle
    ))
}

fn predict(a: PredictArgs) -> Result<String, ApiError> {
    let r = api::predict(&api::PredictParams {
        model: a.model,
        state: a.state,
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
        model: a.model,
        state: a.state,
        origin: origin(a.origin)?,
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
        origin: origin(a.origin)?,
    })?;
    Ok(if a.out.json {
        json(&r)
    } else {
        format!("{} {}", r.model, numbers(&r.state))
    })
}
