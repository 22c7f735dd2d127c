//! The output of `swarm`, and the ALOHA collision rate it is checked against.

use super::params::SwarmParams;
use crate::math::pow;
use crate::metrics::Summary;
use serde::Serialize;

/// The collision probability of one packet among `n` periodic senders that share an SF and hop
/// at random over `channels` channels, each on air a fraction `duty_cycle` of the time: another
/// sender's packet overlaps it with probability 2·DC (a window of two packet lengths) and lands
/// on its channel with probability 1/C, so P = 1 − (1 − 2·DC/C)^(n−1) (pure ALOHA; SPEC §10).
///
/// ```
/// let p = loratrack::aloha_collision_rate(0.01, 3, 12);
/// assert!((p - (1.0 - (1.0f64 - 0.02 / 3.0).powi(11))).abs() < 1e-15);
/// ```
pub fn aloha_collision_rate(duty_cycle: f64, channels: u8, n: usize) -> f64 {
    if n <= 1 {
        return 0.0;
    }
    1.0 - pow(1.0 - 2.0 * duty_cycle / f64::from(channels), (n - 1) as f64)
}

/// One drone of the swarm.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct DroneReport {
    /// 0-based index.
    pub id: usize,
    /// Its spreading factor.
    pub sf: u8,
    /// Direction from its starting point to the gateway, degrees counter-clockwise from east.
    pub bearing_deg: f64,
    /// Packets it sent on each channel.
    pub channel_use: Vec<usize>,
    /// Packets sent.
    pub packets_sent: usize,
    /// Packets the gateway received.
    pub packets_received: usize,
    /// Packets lost to interference.
    pub packets_collided: usize,
    /// Its station's 3D error, m (`count` 0: nothing arrived, nothing counted).
    pub error3d: Summary,
}

/// The output of `swarm`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SwarmReport {
    /// The settings (the duty cycle is EU868's 1 %).
    pub config: SwarmEcho,
    /// Packets lost to interference / packets sent.
    pub collision_rate: f64,
    /// [`aloha_collision_rate`] per SF group, weighted by the packets each group sent: what the
    /// formula predicts for periodic senders without capture or inter-SF effects.
    pub collision_rate_theory: f64,
    /// Packets received / packets sent.
    pub delivery_ratio: f64,
    /// Packets sent by all drones.
    pub packets_sent: usize,
    /// Packets received.
    pub packets_received: usize,
    /// Packets lost to interference.
    pub packets_collided: usize,
    /// Packets below the gateway's sensitivity.
    pub packets_below_sensitivity: usize,
    /// Packets lost because all eight demodulation paths were busy.
    pub packets_no_demodulator: usize,
    /// Time on air of all packets, s.
    pub airtime: f64,
    /// 3D error of every drone's station, pooled, m.
    pub error3d: Summary,
    /// Median over the drones of their p75 error, m (drones that received nothing excluded).
    pub median_drone_p75: f64,
    /// Per drone.
    pub drones: Vec<DroneReport>,
}

/// The settings echoed in a report.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
pub struct SwarmEcho {
    /// Drones.
    pub drones: usize,
    /// Seconds per drone.
    pub duration: f64,
    /// Distance of each drone's start from the gateway, m.
    pub distance: f64,
    /// Channels.
    pub channels: u8,
    /// SF plan.
    pub sf_plan: super::SfPlan,
    /// SF of the fixed plan.
    pub sf: i64,
    /// Bandwidth, kHz.
    pub bandwidth_khz: f64,
    /// Station model.
    pub model: String,
    /// Prediction.
    pub prediction: crate::sim::Prediction,
    /// When the drones send (`sender`, `threshold`, `maxInterval`, `dutyCycleMode`, `burst`).
    #[serde(flatten)]
    pub sending: crate::sim::Sending,
    /// Duty cycle.
    pub duty_cycle: f64,
    /// Same-SF capture.
    pub capture: bool,
    /// Inter-SF interference.
    pub inter_sf: bool,
    /// Shadowing, dB.
    pub shadowing: f64,
    /// MAC overhead, bytes.
    pub overhead: usize,
    /// Seed.
    pub seed: u64,
}

impl SwarmEcho {
    /// The echo of validated parameters.
    pub fn of(p: &SwarmParams, duty_cycle: f64) -> Self {
        SwarmEcho {
            drones: p.drones,
            duration: p.duration,
            distance: p.distance,
            channels: p.channels,
            sf_plan: p.sf_plan,
            sf: p.sf,
            bandwidth_khz: p.bw,
            model: p.model.to_ascii_lowercase(),
            prediction: p.prediction,
            sending: p.sending(),
            duty_cycle,
            capture: p.capture,
            inter_sf: p.inter_sf,
            shadowing: p.shadowing,
            overhead: p.overhead,
            seed: p.seed,
        }
    }
}
