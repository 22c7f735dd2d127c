//! One drone during one episode of the event loop: its flight, its filter's estimates, its
//! sender under the duty-cycle rule, and its links to every gateway.

use super::clock::{Clock, Timing};
use super::drone::Estimates;
use super::link::{Link, Reception};
use super::packet::Transmission;
use super::radio::{DroneRadio, Frame};
use super::schedule::Slot;
use super::sender::{LeanPayload, Sender};
use super::streams::DroneStreams;
use crate::codec::{decode, encode};
use crate::lora::{Channel, DutyCycle, Outcome};
use crate::models::ModelKind;
use crate::rng::Rng;
use crate::trajectory::Trajectory;

/// What a drone flies with in an episode: its flight (in its own frame), its filter's estimates,
/// when it wants to send, and the duty-cycle rule that bounds that.
pub struct Aboard<'a> {
    /// Its flight, in its own frame.
    pub flight: &'a Trajectory,
    /// Its filter's estimate at every sensor step.
    pub estimates: Estimates<'a>,
    /// When it wants to send.
    pub sender: Box<dyn Sender>,
    /// The duty-cycle rule, from time 0 ([`Sending::rule`](super::sender::Sending::rule)); the
    /// flier starts it when its drone first may send.
    pub rule: DutyCycle,
    /// Which payload each packet takes: `None`, the model's own (the paper).
    pub payload: Option<LeanPayload>,
}

/// How a drone meets the network in an episode.
#[derive(Clone, Copy)]
pub struct Air<'g> {
    /// Every gateway's position in the drone's flight frame, m, in the network's order.
    pub gateways: &'g [[f64; 3]],
    /// The link budget all links share.
    pub channel: &'g Channel,
    /// The drone's random streams.
    pub streams: DroneStreams,
    /// The uplink channels it picks among.
    pub channels: u8,
    /// Its data rate's duty-cycle interval, s: its first packet's offset is drawn within it.
    pub interval: f64,
    /// Its clock's drift and delays.
    pub timing: Timing,
}

/// One drone in an episode.
pub struct Flier<'a> {
    /// Which drone (index into the network's radios).
    pub drone: usize,
    /// Its flight, in its own frame.
    pub flight: &'a Trajectory,
    /// Its filter's estimate at every sensor step.
    pub estimates: Estimates<'a>,
    sender: Box<dyn Sender>,
    rule: DutyCycle,
    payload: Option<LeanPayload>,
    /// One link per gateway, in the network's gateway order.
    pub links: Vec<Link>,
    hop: Rng,
    channels: u8,
    /// A schedule's channel for every packet, instead of a random one.
    fixed_channel: Option<u8>,
    /// The next sensor step that may carry a packet.
    k: usize,
    /// With a clock that is not exact: the earliest time the next uplink may start, s (it then
    /// carries the newest estimate, and starts between sensor steps).
    from: f64,
    clock: Clock,
    hint: usize,
    /// Where its flight frame's origin lies in the network's frame (the swarm's centre is the
    /// network's origin): its position there is its own minus this, m.
    origin: [f64; 3],
    /// Listen-before-talk: times it found its channel busy, and of those, how many on its own
    /// spreading factor (a collision avoided).
    pub lbt_deferrals: usize,
    /// See `lbt_deferrals`.
    pub lbt_avoided: usize,
    /// Its transmissions so far.
    pub tx: Vec<Transmission>,
}

impl<'a> Flier<'a> {
    /// Drone number `drone` flying with `aboard`, about to start, meeting the network through
    /// `air`. It draws from the random streams of `air.streams` (`sim/streams.rs`): the link stream
    /// first draws the first packet's offset (uniform within one `air.interval`, so every model
    /// starts at the same fraction of its own interval) and then carries the first gateway's
    /// shadowing; the gateway streams give the others'; the channel stream draws each packet's
    /// channel among `air.channels`; the clock stream the clock's drift and delays.
    pub fn new(drone: usize, aboard: Aboard<'a>, air: &Air<'_>) -> Self {
        let Aboard {
            flight,
            estimates,
            sender,
            rule,
            payload,
        } = aboard;
        let streams = air.streams;
        let mut link_rng = streams.link();
        let from = flight.t[0] + link_rng.uniform() * air.interval;
        let mut first = Some(link_rng);
        let links = air
            .gateways
            .iter()
            .enumerate()
            .map(|(g, &at)| {
                let rng = first.take().unwrap_or_else(|| streams.gateway(g));
                Link::new(air.channel, at, rng, streams.downlink(g))
            })
            .collect();
        let clock = if air.timing.is_exact() {
            Clock::exact()
        } else {
            Clock::new(
                air.timing.clock_drift_ppm,
                air.timing.jitter,
                streams.clock(),
            )
        };
        let mut f = Flier {
            drone,
            flight,
            estimates,
            sender,
            // The drone starts sending at `from`: its duty-cycle credit starts there too.
            rule: rule.starting_at(from),
            payload,
            links,
            hop: streams.channel(),
            channels: air.channels,
            fixed_channel: None,
            k: 0,
            from,
            clock,
            hint: 0,
            origin: [0.0; 3],
            lbt_deferrals: 0,
            lbt_avoided: 0,
            tx: Vec::new(),
        };
        f.k = f.step_at_or_after(f.from);
        f
    }

    fn step_at_or_after(&self, t: f64) -> usize {
        ((t - self.estimates.start()) / self.estimates.period() - 1e-9)
            .ceil()
            .max(0.0) as usize
    }

    /// The drone keeps `slot` of a schedule: it sends only at the slot's times, on its channel.
    pub fn with_slot(mut self, slot: &Slot) -> Self {
        self.clock = Clock::slotted(slot.offset, slot.frame);
        self.fixed_channel = Some(slot.channel);
        self.from = self.flight.t[0];
        self.rule = self.rule.starting_at(self.from);
        self
    }

    /// Places the network's origin at `origin` in this flight's frame (a swarm's centre).
    pub fn with_origin(mut self, origin: [f64; 3]) -> Self {
        self.origin = origin;
        self
    }

    /// Its position at `t` s in the network's frame, m.
    pub fn network_position(&mut self, t: f64) -> [f64; 3] {
        let p = self.position_at(t);
        [
            p[0] - self.origin[0],
            p[1] - self.origin[1],
            p[2] - self.origin[2],
        ]
    }

    /// The channels it hops over at random (ALOHA), or `None` when it keeps a slot of a
    /// schedule (its own time and channel, which no other drone's frame meets).
    pub fn aloha_channels(&self) -> Option<u8> {
        self.fixed_channel.is_none().then_some(self.channels)
    }

    /// The channel its next packet would take (its schedule's, or a random one), and how many
    /// channels it may use (1 with a schedule).
    pub fn pick_channel(&mut self) -> (u8, u8) {
        let ch = self.fixed_channel.unwrap_or_else(|| {
            let c = f64::from(self.channels);
            ((self.hop.uniform() * c) as u8).min(self.channels - 1)
        });
        (
            ch,
            if self.fixed_channel.is_some() {
                1
            } else {
                self.channels
            },
        )
    }

    /// A random backoff of up to `max` s (listen-before-talk found every channel busy).
    pub fn backoff(&mut self, max: f64) -> f64 {
        self.hop.uniform() * max
    }

    /// The newest sensor step at or before `t` s.
    fn step_at_or_before(&self, t: f64) -> usize {
        ((t - self.estimates.start()) / self.estimates.period() + 1e-9)
            .floor()
            .max(0.0) as usize
    }

    fn time_of(&self, k: usize) -> f64 {
        self.estimates.start() + k as f64 * self.estimates.period()
    }

    /// Whether its sender listens to its channel ([`Sender::listens`]).
    pub fn listens(&self) -> bool {
        self.sender.listens()
    }

    /// Tells the sender whether its channel was `busy` as an uplink started
    /// ([`Sender::channel_sensed`]).
    pub fn channel_sensed(&mut self, busy: bool) {
        self.sender.channel_sensed(busy);
    }

    /// The next uplink at or after `not_before` s that the sender wants: the sensor step whose
    /// estimate it carries and its start time, s; `None` when the flight ends first. Every time
    /// considered is one the duty-cycle rule allows. With an exact clock uplinks start on
    /// sensor steps; otherwise the first candidate is the planned start itself, carrying the
    /// newest estimate, and later ones the sensor steps after it.
    pub fn next_uplink(&mut self, not_before: f64) -> Option<(usize, f64)> {
        if !self.clock.is_exact() {
            let mut t = self.clock.slot_at_or_after(self.from.max(not_before));
            loop {
                let k = self.step_at_or_before(t);
                let e = self.sender_view(k)?;
                if self.sender.wants_to_send(t, &e) {
                    return Some((k, t));
                }
                match self.clock.slot_after(t) {
                    // A scheduled drone that does not need its slot waits for its next one.
                    Some(next) => t = next,
                    None => {
                        self.k = self.k.max(k + 1);
                        break;
                    }
                }
            }
        }
        self.k = self.k.max(self.step_at_or_after(not_before));
        while self.k < self.estimates.len() {
            let t = self.time_of(self.k);
            let Some(e) = self.sender_view(self.k) else {
                break;
            };
            if self.sender.wants_to_send(t, &e) {
                return Some((self.k, t));
            }
            self.k += 1;
        }
        None
    }

    /// What the sender is shown of step `k` (`None` past the flight's end): the estimate, or
    /// zeros for a sender that does not read it, whose filter then runs only as far as the
    /// packets it sends (in a swarm, ahead on every core: a periodic drone at SF12 plans its next
    /// uplink two and a half minutes ahead, which the event loop once filtered on one core).
    fn sender_view(&mut self, k: usize) -> Option<[f64; 9]> {
        if self.sender.reads_estimate() {
            self.estimates.get(k)
        } else {
            (k < self.estimates.len()).then_some([0.0; 9])
        }
    }

    /// `frame` with the payload step `k`'s packet takes ([`LeanPayload`]): unchanged for a
    /// drone that sends its model's own.
    pub fn with_payload(&mut self, k: usize, frame: Frame, radio: &DroneRadio) -> Frame {
        let Some(lean) = self.payload else {
            return frame;
        };
        let Some(estimate) = self.estimates.get(k) else {
            return frame;
        };
        let own = self.estimates.model();
        // Each smaller payload's frame (DR's, CTRA+'s) is built once, to be weighed and, if
        // chosen, sent; the drone's own is `frame`.
        let slot = |kind: ModelKind| usize::from(kind == ModelKind::CtraPlus);
        let mut smaller: [Option<Frame>; 2] = [None; 2];
        let kind = lean.choose(&estimate, |kind| {
            if kind == own {
                return frame.time_on_air;
            }
            match radio.with_payload(&frame, own, kind) {
                Ok(f) => {
                    smaller[slot(kind)] = Some(f);
                    f.time_on_air
                }
                Err(_) => f64::INFINITY,
            }
        });
        if kind == own {
            frame
        } else {
            smaller[slot(kind)].unwrap_or(frame)
        }
    }

    /// Puts the estimate of step `k` on air at `sent` s with `frame` on channel `ch`: spends the
    /// duty cycle, tells the sender, draws each gateway's received power. `None` when the
    /// estimate cannot be encoded (the filter keeps it finite, so this does not happen; the
    /// drone would then have nothing to send at this step).
    pub fn transmit(
        &mut self,
        (k, sent): (usize, f64),
        ch: u8,
        frame: &Frame,
        channel: &Channel,
    ) -> Option<Vec<Reception>> {
        // A lean payload is the shorter model's: the fields it leaves out decode as 0.
        let model = frame.payload.unwrap_or(self.estimates.model());
        let n = model.state_len();
        let origin = self.flight.pos[0];
        let estimate = self.estimates.get(k)?;
        let decoded = encode(model, &estimate[..n], origin)
            .and_then(|e| Ok((decode(model, &e.bytes, origin)?, e.saturated)));
        let Ok((decoded, saturated)) = decoded else {
            self.k = k + 1;
            self.from = self.time_of(k + 1);
            return None;
        };
        let mut state = [0.0; 9];
        state[..n].copy_from_slice(&decoded);
        match frame.payload {
            // The off-time follows the packet sent.
            Some(_) => self.rule.spend_airtime(sent, frame.time_on_air),
            None => self.rule.spend(sent),
        }
        if frame.adr.is_some() {
            self.sender.data_rate_changed(frame.interval);
        }
        self.sender.sent(&state, sent);
        let pos = self.flight.position_at(sent, &mut self.hint);
        let receptions: Vec<Reception> = self
            .links
            .iter_mut()
            .map(|l| l.uplink(channel, pos, frame.power_reduction_db))
            .collect();
        self.tx.push(Transmission {
            sent,
            arrival: sent + frame.time_on_air,
            received: false,
            outcome: Outcome::BelowSensitivity,
            heard_by: 0,
            state,
            saturated,
            distance: receptions
                .iter()
                .map(|r| r.distance)
                .fold(f64::INFINITY, f64::min),
            rx_power_dbm: receptions
                .iter()
                .map(|r| r.rx_dbm)
                .fold(f64::NEG_INFINITY, f64::max),
            sf: frame.sf,
            bw: frame.bw,
            channel: ch,
            time_on_air: frame.time_on_air,
            interval: frame.interval,
            payload: frame.payload,
            charge_mc: 0.0,
            active_s: 0.0,
        });
        Some(receptions)
    }

    /// Its estimates and the step index just past time `t` s (to compute them ahead).
    pub fn estimates_until(&mut self, t: f64) -> (&mut Estimates<'a>, usize) {
        let upto = self.step_at_or_after(t);
        (&mut self.estimates, upto)
    }

    /// The drone's position at `t` s.
    pub fn position_at(&mut self, t: f64) -> [f64; 3] {
        self.flight.position_at(t, &mut self.hint)
    }

    /// After the packet of step `k` that left at `sent` s: later packets take `time_on_air` s
    /// (ADR may have moved the rate), and the next candidate is the first time the rule allows
    /// after it, as the drone's clock keeps it. The rule only relaxes until the next packet, so
    /// every later time is allowed too.
    pub fn after_packet(&mut self, (k, sent): (usize, f64), time_on_air: f64) {
        self.rule.set_time_on_air(time_on_air);
        let earliest = self.rule.earliest(sent);
        if self.clock.is_exact() {
            self.k = self.step_at_or_after(earliest).max(k + 1);
        } else {
            self.from = self.clock.next_start(sent, earliest);
            self.k = self.step_at_or_before(self.from).max(k);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lora::{ChannelParams, DutyCycleMode};
    use crate::models::ModelKind;
    use crate::sim::clock::Timing;
    use crate::sim::drone::{DroneFilter, Sensing};
    use crate::sim::sender::{ChannelSense, ErrorTriggered, Periodic};
    use crate::sim::station::tests::paper_setup;
    use crate::sim::station::StationModel;
    use crate::trajectory::synthetic_flight;

    /// A 3D-CTRA drone with a live filter, one packet a second allowed.
    fn flier(flight: &Trajectory, sender: Box<dyn Sender>) -> Flier<'_> {
        let filter = DroneFilter::new(flight, ModelKind::Ctra3d, &Sensing::paper(1, 0));
        let rule = DutyCycle::new(DutyCycleMode::PerPacket, 0.01, 0.01, 1, flight.t[0]).unwrap();
        let channel = Channel::new(ChannelParams::default()).unwrap();
        let aboard = Aboard {
            flight,
            estimates: Estimates::live(filter),
            sender,
            rule,
            payload: None,
        };
        let air = Air {
            gateways: &[[1000.0, 0.0, 0.0]],
            channel: &channel,
            streams: DroneStreams { seed: 1, stream: 0 },
            channels: 1,
            interval: 1.0,
            timing: Timing::EXACT,
        };
        Flier::new(0, aboard, &air)
    }

    #[test]
    fn a_periodic_sender_plans_an_uplink_without_running_the_filter_up_to_it() {
        let flight = synthetic_flight(1).unwrap();
        let later = flight.t[0] + 60.0;
        let mut periodic = flier(&flight, Box::new(Periodic));
        let (k, t) = periodic.next_uplink(later).unwrap();
        assert!(k >= 600 && t >= later - 1e-9, "{k} {t}");
        assert_eq!(periodic.estimates.computed(), 0);
        // The packet reads its estimate when it goes out.
        assert!(periodic.estimates.get(k).is_some());
        assert_eq!(periodic.estimates.computed(), k + 1);
        // An error-triggered sender looks at every step it considers.
        let sender = ErrorTriggered::new(
            StationModel::Single(ModelKind::Ctra3d),
            paper_setup(),
            None,
            (1.0, 30.0),
            ChannelSense::Off,
        );
        let mut triggered = flier(&flight, Box::new(sender));
        let (k, _) = triggered.next_uplink(later).unwrap();
        assert_eq!(triggered.estimates.computed(), k + 1);
        // Past the flight's end neither plans an uplink.
        let end = flight.t[flight.t.len() - 1] + 1.0;
        assert_eq!(flier(&flight, Box::new(Periodic)).next_uplink(end), None);
    }
}
