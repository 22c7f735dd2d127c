//! One function per command: parse options into the API's parameter struct, run, format.

use clap::{Args, Subcommand};
use loratrack::api::{self, ApiError};
use loratrack::LdroMode;
use serde::Serialize;

#[derive(Subcommand)]
pub enum Command {
    /// Time on air and 1 % duty-cycle interval of one LoRa packet (Semtech SX1276 formula).
    Airtime(AirtimeArgs),
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
