//! The link: duty-cycled transmissions, the codec and the channel (SPEC §5–6).

use super::DroneTrack;
use crate::codec::{decode, encode};
use crate::lora::{Bandwidth, Channel, Shadowing, SpreadingFactor};
use crate::math::distance;
use crate::rng::Rng;
use crate::trajectory::Trajectory;

/// One transmission of the drone's state.
#[derive(Clone, Debug, PartialEq)]
pub struct Transmission {
    /// When the drone sent it (a sensor step), s.
    pub sent: f64,
    /// When it finished arriving (sent + time on air), s.
    pub arrival: f64,
    /// Whether the gateway received it.
    pub received: bool,
    /// The state the station decodes (quantised), padded to 9.
    pub state: [f64; 9],
    /// 3D distance to the gateway, m.
    pub distance: f64,
    /// Received power including shadowing, dBm.
    pub rx_power_dbm: f64,
}

/// Everything the link needs besides the flight and the drone's estimates.
#[derive(Clone, Debug)]
pub struct LinkSetup {
    /// Spreading factor.
    pub sf: SpreadingFactor,
    /// Bandwidth.
    pub bw: Bandwidth,
    /// Link budget.
    pub channel: Channel,
    /// Time on air of one packet, s.
    pub time_on_air: f64,
    /// Minimum interval between packets under the duty cycle, s.
    pub interval: f64,
    /// Horizontal distance from the flight's first point to the gateway (along +x), m.
    pub distance: f64,
}

/// Sends the drone's estimate as often as the duty cycle allows.
///
/// The first transmission is at a uniformly random offset within one interval (drawn from
/// `rng`'s first number, so every model starts at the same fraction of its own interval). A
/// transmission leaves at the first sensor step at or after its scheduled time, carrying that
/// step's estimate, and the next one is scheduled one full interval later — so the spacing is
/// never below the duty-cycle minimum. Positions are encoded relative to the flight's first
/// point, which both ends agree on before take-off. Shadowing evolves over the distance flown
/// between transmissions.
pub fn schedule_transmissions(
    flight: &Trajectory,
    drone: &DroneTrack,
    link: &LinkSetup,
    rng: &mut Rng,
) -> Vec<Transmission> {
    let origin = flight.pos[0];
    let gateway = [
        origin[0] + link.distance,
        origin[1],
        link.channel.params().gateway_height,
    ];
    let params = link.channel.params();
    let mut shadowing = Shadowing::new(params.shadowing_sigma_db, params.decorrelation_distance);
    let end = flight.t[flight.t.len() - 1];
    let mut scheduled = flight.t[0] + rng.uniform() * link.interval;
    let mut out = Vec::new();
    let mut hint = 0;
    let mut last_pos: Option<[f64; 3]> = None;
    let n = drone.model.state_len();
    while scheduled <= end {
        let k = ((scheduled - drone.start) / drone.period - 1e-9)
            .ceil()
            .max(0.0) as usize;
        if k >= drone.states.len() {
            break;
        }
        let sent = drone.start + k as f64 * drone.period;
        let estimate = &drone.states[k][..n];
        // The estimate has the model's length and the filter keeps it finite, so this succeeds;
        // were it ever not encodable, the drone would have nothing to send at this slot.
        let decoded = encode(drone.model, estimate, origin)
            .and_then(|e| decode(drone.model, &e.bytes, origin));
        let Ok(decoded) = decoded else {
            scheduled = sent + link.interval;
            continue;
        };
        let mut state = [0.0; 9];
        state[..n].copy_from_slice(&decoded);
        let p = flight.position_at(sent, &mut hint);
        let d = distance(&p, &gateway);
        let moved = last_pos.map_or(0.0, |q| distance(&p, &q));
        last_pos = Some(p);
        let s = shadowing.next(moved, rng);
        let rx = link.channel.mean_rx_power_dbm(d) + s;
        out.push(Transmission {
            sent,
            arrival: sent + link.time_on_air,
            received: link.channel.received(link.sf, link.bw, d, s),
            state,
            distance: d,
            rx_power_dbm: rx,
        });
        scheduled = sent + link.interval;
    }
    out
}
