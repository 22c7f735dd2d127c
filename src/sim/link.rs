//! The link: the sender under the duty-cycle rule, the codec and the channel (SPEC §5–6).

use super::sender::Sender;
use super::{AdrSession, DroneTrack};
use crate::codec::{decode, encode};
use crate::lora::{
    Bandwidth, Channel, DataRate, DutyCycle, Shadowing, SpreadingFactor, RECEIVE_DELAY1_S,
};
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
    /// Spreading factor it was sent with.
    pub sf: SpreadingFactor,
    /// Bandwidth it was sent with.
    pub bw: Bandwidth,
    /// Its time on air, s.
    pub time_on_air: f64,
    /// The duty-cycle interval at that data rate, s (what the station expects until the next).
    pub interval: f64,
}

impl Transmission {
    /// Its EU868 data rate, if the SF and bandwidth form one.
    pub fn data_rate(&self) -> Option<DataRate> {
        DataRate::of(self.sf, self.bw)
    }
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
    /// Interval between packets under the per-packet duty-cycle rule, s (the window of the
    /// first packet's random offset).
    pub interval: f64,
    /// Horizontal distance from the flight's first point to the gateway, m.
    pub distance: f64,
    /// Direction from the flight's first point to the gateway, rad counter-clockwise from +x
    /// (`simulate`: 0; a swarm spreads its drones around the gateway).
    pub bearing: f64,
}

/// Runs the drone's transmissions over the flight: at each sensor step the duty-cycle `rule`
/// allows, the `sender` decides whether to send that step's estimate.
///
/// The first transmission may leave at a uniformly random offset within one interval (drawn from
/// `rng`'s first number, so every model starts at the same fraction of its own interval). A packet
/// leaves at a sensor step, carrying that step's estimate; after it, the next candidate is the
/// first sensor step the rule allows, so no schedule ever breaks the rule. Positions are encoded
/// relative to the flight's first point, which both ends agree on before take-off. Shadowing
/// evolves over the distance flown between transmissions.
///
/// With `adr`, each packet goes at the device's current data rate and power; a received one is
/// shown to the network, whose downlink (when it sends one) reaches the drone
/// [`RECEIVE_DELAY1_S`] after the uplink ends if the reciprocal channel carries it, and a new
/// data rate applies from the next packet.
pub fn schedule_transmissions(
    flight: &Trajectory,
    drone: &DroneTrack,
    link: &LinkSetup,
    sender: &mut dyn Sender,
    rule: &mut DutyCycle,
    rng: &mut Rng,
    mut adr: Option<&mut AdrSession>,
) -> Vec<Transmission> {
    let origin = flight.pos[0];
    let (sb, cb) = crate::math::sin_cos(link.bearing);
    let gateway = [
        origin[0] + link.distance * cb,
        origin[1] + link.distance * sb,
        link.channel.params().gateway_height,
    ];
    let params = link.channel.params();
    let mut shadowing = Shadowing::new(params.shadowing_sigma_db, params.decorrelation_distance);
    let step_at_or_after =
        |t: f64| ((t - drone.start) / drone.period - 1e-9).ceil().max(0.0) as usize;
    let mut k = step_at_or_after(flight.t[0] + rng.uniform() * link.interval);
    let mut out = Vec::new();
    let mut hint = 0;
    let mut last_pos: Option<[f64; 3]> = None;
    let n = drone.model.state_len();
    while k < drone.states.len() {
        let sent = drone.start + k as f64 * drone.period;
        let estimate = &drone.states[k][..n];
        if !sender.wants_to_send(sent, &[estimate[0], estimate[1], estimate[2]]) {
            k += 1;
            continue;
        }
        // The estimate has the model's length and the filter keeps it finite, so this succeeds;
        // were it ever not encodable, the drone would have nothing to send at this step.
        let decoded = encode(drone.model, estimate, origin)
            .and_then(|e| decode(drone.model, &e.bytes, origin));
        let Ok(decoded) = decoded else {
            k += 1;
            continue;
        };
        let mut state = [0.0; 9];
        state[..n].copy_from_slice(&decoded);
        let frame = adr.as_deref_mut().map(AdrSession::uplink);
        let (sf, bw, toa, interval, reduction) = match (&frame, adr.as_deref()) {
            (Some(f), Some(a)) => (
                f.dr.sf(),
                f.dr.bw(),
                a.time_on_air(f.dr),
                a.interval(f.dr),
                f.power_reduction_db,
            ),
            _ => (link.sf, link.bw, link.time_on_air, link.interval, 0.0),
        };
        rule.spend(sent);
        if frame.is_some() {
            sender.data_rate_changed(interval);
        }
        sender.sent(&state, sent);
        let p = flight.position_at(sent, &mut hint);
        let d = distance(&p, &gateway);
        let moved = last_pos.map_or(0.0, |q| distance(&p, &q));
        last_pos = Some(p);
        let s = shadowing.next(moved, rng);
        let rx = link.channel.mean_rx_power_dbm(d) + s - reduction;
        let received = rx >= Channel::sensitivity_dbm(sf, bw);
        out.push(Transmission {
            sent,
            arrival: sent + toa,
            received,
            state,
            distance: d,
            rx_power_dbm: rx,
            sf,
            bw,
            time_on_air: toa,
            interval,
        });
        if let (Some(f), Some(a)) = (frame, adr.as_deref_mut()) {
            let (answers, command) = if received {
                a.network_hears(&f, rx)
            } else {
                (false, None)
            };
            let heard = answers.then(|| {
                let q = flight.position_at(sent + toa + RECEIVE_DELAY1_S, &mut hint);
                let s_down = shadowing.next(distance(&q, &p), rng);
                last_pos = Some(q);
                AdrSession::downlink_heard(&link.channel, &f, distance(&q, &gateway), s_down)
            });
            a.finish(heard.unwrap_or(false).then_some(command));
            rule.set_time_on_air(a.time_on_air(a.dr()));
        }
        // The rule only relaxes until the next packet, so every later step is allowed too.
        k = step_at_or_after(rule.earliest(sent)).max(k + 1);
    }
    out
}
