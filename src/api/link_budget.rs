//! `linkBudget`: why packets stop arriving. Received power against distance, the sensitivity
//! and range of each spreading factor, and the delivery ratio the shadowing leaves (reference §6).

use super::ApiError;
use crate::lora::{Bandwidth, Channel, ChannelParams, Region, SpreadingFactor};
use crate::math::{hypot, normal_cdf};
use serde::{Deserialize, Serialize};

/// Input of `linkBudget`: the channel options of `simulate`, and the distances to evaluate.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields, default)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct LinkBudgetParams {
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Transmit power, dBm.
    pub tx_power: f64,
    /// Path-loss exponent.
    pub path_loss_exponent: f64,
    /// Shadowing standard deviation, dB.
    pub shadowing: f64,
    /// Gateway antenna height, m.
    pub gateway_height: f64,
    /// Horizontal distances, m (at most 1000 of them, each 1..100000).
    pub distances: Vec<f64>,
    /// The regional plan: each SF's data rate at `bw`, or that the plan lacks it (§14).
    pub region: Region,
}

impl Default for LinkBudgetParams {
    fn default() -> Self {
        use crate::options as opt;
        LinkBudgetParams {
            bw: opt::BW.default,
            tx_power: opt::TX_POWER.default,
            path_loss_exponent: opt::PATH_LOSS_EXPONENT.default,
            shadowing: opt::SHADOWING.default,
            gateway_height: opt::GATEWAY_HEIGHT.default,
            distances: (1..=100).map(|k| 100.0 * f64::from(k)).collect(),
            region: Region::Eu868,
        }
    }
}

/// One spreading factor's side of the budget.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct SfBudget {
    /// Spreading factor.
    pub sf: u8,
    /// Gateway sensitivity at the bandwidth, dBm.
    pub sensitivity_dbm: f64,
    /// Horizontal distance at which the mean power meets the sensitivity, m.
    pub range_m: f64,
    /// Share of packets received at each distance: Φ((mean power − sensitivity) / σ).
    pub delivery: Vec<f64>,
    /// The plan's data rate at this SF and the bandwidth (`null`: none; then `inPlan` says
    /// whether the plan allows the SF as raw LoRa, as EU868 does).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub data_rate: Option<u8>,
    /// Whether the plan lets a drone send at this SF and bandwidth.
    pub in_plan: bool,
}

/// The output of `linkBudget`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct LinkBudgetReport {
    /// The distances, m.
    pub distances: Vec<f64>,
    /// Mean received power at each, dBm (before shadowing), for a drone on the ground
    /// (3D distance from the gateway's antenna).
    pub mean_rx_dbm: Vec<f64>,
    /// The transmit power the mean rests on, dBm.
    pub tx_power: f64,
    /// The path-loss exponent the mean rests on.
    pub path_loss_exponent: f64,
    /// The shadowing σ, dB: 90 % of packets arrive within ±1.645 σ of the mean.
    pub shadowing: f64,
    /// SF7..SF12.
    pub sfs: Vec<SfBudget>,
}

/// The link budget at each distance.
///
/// ```
/// use loratrack::api::{link_budget, LinkBudgetParams};
/// let r = link_budget(&LinkBudgetParams::default()).unwrap();
/// assert!(r.sfs[0].range_m < r.sfs[5].range_m); // SF12 reaches further than SF7
/// ```
pub fn link_budget(p: &LinkBudgetParams) -> Result<LinkBudgetReport, ApiError> {
    let bw = Bandwidth::from_khz(p.bw)?;
    let channel = Channel::new(ChannelParams {
        tx_power_dbm: p.tx_power,
        path_loss_exponent: p.path_loss_exponent,
        shadowing_sigma_db: p.shadowing,
        gateway_height: p.gateway_height,
        ..ChannelParams::default()
    })?;
    if p.distances.len() > 1000 || !p.distances.iter().all(|d| (1.0..=100_000.0).contains(d)) {
        return Err(ApiError::Invalid(
            "distances: at most 1000, each 1..100000 m".into(),
        ));
    }
    let h = p.gateway_height;
    let mean: Vec<f64> = p
        .distances
        .iter()
        .map(|&d| channel.mean_rx_power_dbm(hypot(d, h)))
        .collect();
    let sfs = (7..=12)
        .map(|n| {
            let sf = SpreadingFactor::new(n).map_err(ApiError::Lora)?;
            let sens = Channel::sensitivity_dbm(sf, bw);
            let range3d = channel.range_m(sf, bw);
            let rate = p
                .region
                .rate(sf.get(), bw)
                .filter(|r| r.max_payload.is_some());
            Ok(SfBudget {
                data_rate: rate.map(|r| r.dr),
                in_plan: rate.is_some() || p.region.allows_raw_lora(),
                sf: sf.get(),
                sensitivity_dbm: sens,
                range_m: (range3d * range3d - h * h).max(0.0).sqrt(),
                delivery: mean
                    .iter()
                    .map(|&m| delivery(m - sens, p.shadowing))
                    .collect(),
            })
        })
        .collect::<Result<_, ApiError>>()?;
    Ok(LinkBudgetReport {
        distances: p.distances.clone(),
        mean_rx_dbm: mean,
        tx_power: p.tx_power,
        path_loss_exponent: p.path_loss_exponent,
        shadowing: p.shadowing,
        sfs,
    })
}

/// Share of packets above the sensitivity with mean margin `margin` dB and shadowing `sigma`.
fn delivery(margin: f64, sigma: f64) -> f64 {
    if sigma == 0.0 {
        f64::from(u8::from(margin >= 0.0))
    } else {
        normal_cdf(margin / sigma)
    }
}
