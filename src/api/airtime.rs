//! `airtime` / `timeOnAir`: time on air and duty-cycle interval of one packet (reference §6, §8).

use super::ApiError;
use crate::lora::{
    self, ChannelAccess, FairUse, LdroMode, LoraParams, Region, LORAWAN_OVERHEAD_BYTES,
};
use crate::sim::AccessSettings;
use serde::{Deserialize, Serialize};

/// Input of `airtime`. Field names are the CLI's long options in camelCase.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct AirtimeParams {
    /// Spreading factor, 7..12.
    pub sf: i64,
    /// Bandwidth, kHz: 125, 250 or 500.
    pub bw: f64,
    /// Application payload, bytes.
    pub payload: usize,
    /// MAC overhead added to the payload, bytes (LoRaWAN: 13; raw LoRa as in the paper: 0).
    #[serde(default = "default_overhead")]
    pub overhead: usize,
    /// Coding rate index 1..4 (4/5..4/8).
    #[serde(default = "default_cr")]
    pub cr: i64,
    /// Preamble symbols.
    #[serde(default = "default_preamble")]
    pub preamble: i64,
    /// Implicit header mode.
    #[serde(default)]
    pub implicit_header: bool,
    /// Payload CRC off.
    #[serde(default)]
    pub no_crc: bool,
    /// Low data rate optimisation.
    #[serde(default)]
    pub ldro: LdroMode,
    /// Duty-cycle limit as a fraction (EU868 g1 sub-band: 0.01), in plans with a duty cycle.
    #[serde(default = "default_duty_cycle")]
    pub duty_cycle: f64,
    /// The regional plan (reference §14).
    #[serde(default)]
    pub region: Region,
    /// Where the plan has no duty cycle: seconds between uplinks (default 1).
    #[serde(default)]
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(optional))]
    pub interval: Option<f64>,
    /// Duty cycle or listen-before-talk.
    #[serde(default)]
    pub access: ChannelAccess,
    /// A network's fair-use policy.
    #[serde(default)]
    pub fair_use: FairUse,
}

fn default_overhead() -> usize {
    LORAWAN_OVERHEAD_BYTES
}
fn default_cr() -> i64 {
    1
}
fn default_preamble() -> i64 {
    8
}
fn default_duty_cycle() -> f64 {
    0.01
}

impl AirtimeParams {
    /// Validated radio settings.
    pub fn lora_params(&self) -> Result<LoraParams, ApiError> {
        let mut p = LoraParams::from_settings(self.sf, self.bw, self.cr)?;
        p.preamble = u16::try_from(self.preamble)
            .ok()
            .filter(|n| *n >= 6)
            .ok_or(lora::LoraError::Preamble(self.preamble))?;
        p.implicit_header = self.implicit_header;
        p.crc = !self.no_crc;
        p.ldro = self.ldro;
        Ok(p)
    }

    /// The plan's settings these parameters give: region, interval, access and fair use (the
    /// duty cycle is the `dutyCycle` beside them).
    pub fn access(&self) -> AccessSettings {
        AccessSettings {
            region: self.region,
            interval: self.interval,
            access: self.access,
            fair_use: self.fair_use,
            ..AccessSettings::default()
        }
    }
}

/// Output of `airtime` (reference §9).
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct AirtimeReport {
    /// Time on air, s.
    pub time_on_air: f64,
    /// Symbol duration, s.
    pub symbol_time: f64,
    /// Payload symbols.
    pub payload_symbols: u32,
    /// PHY payload bytes (payload + overhead).
    pub phy_payload_bytes: usize,
    /// Whether low data rate optimisation is on.
    pub low_data_rate_optimize: bool,
    /// Minimum interval between packets under the plan's rule (duty cycle, listen-before-talk's
    /// 100 s per hour, or the interval where the plan has none; within fair use), s.
    pub min_interval: f64,
    /// The plan's data rate at this SF and bandwidth (`null`: raw LoRa outside the data rates,
    /// which EU868 allows).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub data_rate: Option<u8>,
    /// Why the plan refuses this packet (no such data rate, payload limit, dwell time); `null`
    /// when it carries it.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "string | null"))]
    pub refused: Option<String>,
    /// Packets per day within The Things Network's fair-use policy (30 s of airtime a day), for
    /// information: loratrack does not enforce it.
    pub ttn_packets_per_day: u32,
}

/// Time on air and minimum duty-cycle interval of one packet.
pub fn airtime(p: &AirtimeParams) -> Result<AirtimeReport, ApiError> {
    let radio = p.lora_params()?;
    let phy = p
        .payload
        .checked_add(p.overhead)
        .ok_or(lora::LoraError::PayloadTooLarge(usize::MAX))?;
    let t = lora::time_on_air(&radio, phy)?;
    let access = p.access();
    crate::options::DUTY_CYCLE
        .check(p.duty_cycle)
        .map_err(lora::LoraError::OutOfRange)?;
    access.validate(p.duty_cycle)?;
    let check = p
        .region
        .check(radio.sf.get(), radio.bw, p.payload, t.time_on_air);
    // An interval shorter than the time on air is the packet's own refusal, not the call's.
    let (duty_cycle, short) = match access.duty_cycle_for(p.duty_cycle, t.time_on_air) {
        Ok(dc) => (dc, None),
        Err(e) => (1.0, Some(e.to_string())),
    };
    Ok(AirtimeReport {
        time_on_air: t.time_on_air,
        symbol_time: t.symbol_time,
        payload_symbols: t.payload_symbols,
        phy_payload_bytes: t.phy_payload_bytes,
        low_data_rate_optimize: t.low_data_rate_optimize,
        min_interval: lora::min_interval(t.time_on_air, duty_cycle)?,
        data_rate: check.as_ref().ok().and_then(|r| r.map(|r| r.dr)),
        refused: check.err().map(|e| e.to_string()).or(short),
        ttn_packets_per_day: (lora::TTN_FAIR_USE_SECONDS_PER_DAY / t.time_on_air).floor() as u32,
    })
}
