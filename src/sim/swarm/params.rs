//! The input of `swarm` and its validation.

use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};
use crate::lora::{
    Channel, ChannelParams, DutyCycleMode, InterferenceModel, LoraParams, LORAWAN_OVERHEAD_BYTES,
};
use crate::sim::sender::{SenderKind, Sending};
use crate::sim::station::{Prediction, StationModel};
use crate::sim::{SimError, DEFAULT_BURST, DEFAULT_MAX_INTERVAL_S, DEFAULT_THRESHOLD_M, MAX_SEED};
use serde::{Deserialize, Serialize};

/// The most drones a swarm may have.
pub const MAX_DRONES: usize = 500;
/// The longest swarm run, s.
pub const MAX_SWARM_DURATION: f64 = 3600.0;

/// How spreading factors are shared out (`--sf-plan`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SfPlan {
    /// SF7..SF12 in turn (drone i gets SF 7 + i mod 6), so each SF carries a sixth of the swarm —
    /// the paper's suggestion for serving up to 72 drones.
    #[default]
    Spread,
    /// Every drone at `sf`.
    Fixed,
}

/// The input of `swarm`: N drones around one gateway (CLI long options in camelCase).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(rename_all = "camelCase", deny_unknown_fields, default)]
pub struct SwarmParams {
    /// Number of drones, 1..=500.
    pub drones: usize,
    /// Seconds of flight per drone (synthetic flights chained back to back), 10..=3600.
    pub duration: f64,
    /// Horizontal distance of every drone's starting point from the gateway, m.
    pub distance: f64,
    /// 1 (one channel) or 3 (EU868's 868.1/868.3/868.5 MHz, a random one per packet).
    pub channels: u8,
    /// How SFs are shared out.
    pub sf_plan: SfPlan,
    /// The SF of the `fixed` plan, 7..12.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bw: f64,
    /// Station model (one; `imm` too).
    pub model: String,
    /// Station prediction.
    pub prediction: Prediction,
    /// Sending policy.
    pub sender: SenderKind,
    /// Error-triggered threshold, m.
    pub threshold: f64,
    /// Error-triggered heartbeat, s; a drone whose duty-cycle interval is longer uses that.
    pub max_interval: f64,
    /// Duty-cycle rule.
    pub duty_cycle_mode: DutyCycleMode,
    /// Budget capacity, packets.
    pub burst: u32,
    /// Same-SF capture at 6 dB (off: every overlap is fatal).
    pub capture: bool,
    /// Inter-SF interference (off: SFs are orthogonal).
    pub inter_sf: bool,
    /// Shadowing standard deviation, dB.
    pub shadowing: f64,
    /// MAC overhead, bytes.
    pub overhead: usize,
    /// Seed of every random draw.
    pub seed: u64,
}

impl Default for SwarmParams {
    fn default() -> Self {
        SwarmParams {
            drones: 12,
            duration: 600.0,
            distance: 1000.0,
            channels: 3,
            sf_plan: SfPlan::Spread,
            sf: 7,
            bw: 125.0,
            model: "3d-ctra".into(),
            prediction: Prediction::Paper,
            sender: SenderKind::Periodic,
            threshold: DEFAULT_THRESHOLD_M,
            max_interval: DEFAULT_MAX_INTERVAL_S,
            duty_cycle_mode: DutyCycleMode::PerPacket,
            burst: DEFAULT_BURST,
            capture: true,
            inter_sf: true,
            shadowing: ChannelParams::default().shadowing_sigma_db,
            overhead: LORAWAN_OVERHEAD_BYTES,
            seed: 1,
        }
    }
}

/// Validated swarm settings.
#[derive(Clone, Debug, PartialEq)]
pub struct SwarmConfig {
    /// The settings as given.
    pub params: SwarmParams,
    /// The station model.
    pub model: StationModel,
    /// The link budget.
    pub channel: Channel,
    /// Interference rules.
    pub interference: InterferenceModel,
}

impl SwarmParams {
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
    pub fn validate(&self) -> Result<SwarmConfig, SimError> {
        let range = |name: &'static str, v: f64, ok: bool, allowed: &'static str| {
            if ok && v.is_finite() {
                Ok(())
            } else {
                Err(SimError::Parameter(name, v, allowed))
            }
        };
        range(
            "drones",
            self.drones as f64,
            (1..=MAX_DRONES).contains(&self.drones),
            "1..500",
        )?;
        range(
            "duration",
            self.duration,
            (10.0..=MAX_SWARM_DURATION).contains(&self.duration),
            "10..3600 s",
        )?;
        range(
            "distance",
            self.distance,
            (0.0..=100_000.0).contains(&self.distance),
            "0..100000 m",
        )?;
        range(
            "channels",
            f64::from(self.channels),
            matches!(self.channels, 1 | 3),
            "1 or 3",
        )?;
        self.sending().validate()?;
        range(
            "overhead",
            self.overhead as f64,
            self.overhead <= 255,
            "0..255 bytes",
        )?;
        if self.seed > MAX_SEED {
            return Err(SimError::Seed(self.seed));
        }
        // The SF and bandwidth must form a valid radio even when the plan overrides the SF.
        LoraParams::from_settings(self.sf, self.bw, 1)?;
        let model = self.model.parse::<StationModel>().map_err(|_| {
            SimError::Source(format!(
                "unknown model '{}' (expected dr, ctra-plus, 3d-ctra or imm)",
                self.model
            ))
        })?;
        let channel = Channel::new(ChannelParams {
            shadowing_sigma_db: self.shadowing,
            ..ChannelParams::default()
        })?;
        Ok(SwarmConfig {
            params: self.clone(),
            model,
            channel,
            interference: InterferenceModel {
                capture: self.capture,
                inter_sf: self.inter_sf,
            },
        })
    }
}

impl SwarmConfig {
    /// The SF of drone `i`.
    pub fn sf_of(&self, i: usize) -> i64 {
        match self.params.sf_plan {
            SfPlan::Spread => 7 + (i % 6) as i64,
            SfPlan::Fixed => self.params.sf,
        }
    }

    /// The noise settings every drone and station uses (paper Table I).
    pub fn noise(&self) -> (f64, [f64; 9]) {
        (PAPER_Q, PAPER_R_DIAGONAL)
    }
}
