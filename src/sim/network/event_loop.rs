//! The one event loop: every drone's uplinks on one time axis, every gateway deciding each of
//! them, the network server answering. Two events per uplink: it starts (the drone spends its
//! duty cycle, each gateway sees it arrive and may lock a demodulation path), and it ends (each
//! gateway decides it; the server keeps the first copy, runs ADR and answers in a receive window;
//! the drone plans its next uplink once any downlink it heard has arrived).

use super::gateway::Gateway;
use super::server::{AdrUplink, Network};
use crate::lora::{
    audible, downlink_time_on_air, empty_window_s, lbt, Bandwidth, DataRate, LinkAdrReq, Outcome,
    Uplink, UplinkActivity, Window, ACK_DOWNLINK_BYTES, ADR_DOWNLINK_BYTES,
};
use crate::math::distance;
use crate::models::V;
use crate::parallel::par_each;
use crate::sim::flier::Flier;
use crate::sim::link::Reception;
use crate::sim::radio::Frame;
use core::cmp::Ordering;
use std::collections::BinaryHeap;

/// An event: at `time`, drone `drone`'s uplink starts (`start`) or ends.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Event {
    time: f64,
    start: bool,
    drone: usize,
}

impl Eq for Event {}

impl Ord for Event {
    /// The heap is a max-heap: the earliest event is the greatest. At one instant, ends come
    /// before starts (a demodulation path frees as its packet ends, and a packet starting as
    /// another ends does not overlap it), and lower drone numbers first.
    fn cmp(&self, other: &Self) -> Ordering {
        other
            .time
            .total_cmp(&self.time)
            .then(self.start.cmp(&other.start).reverse())
            .then(other.drone.cmp(&self.drone))
    }
}

impl PartialOrd for Event {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// The packet a drone has on air: its sensor step and start time (s), frame, the power each
/// gateway receives, its channel, and where the drone was when it started (network frame, m).
struct OnAir {
    k: (usize, f64),
    frame: Frame,
    receptions: Vec<Reception>,
    channel: u8,
    at: [f64; 3],
}

impl OnAir {
    /// The power, dBm, at which a drone at `at` (network frame, m) receives this packet: the shared
    /// path-loss model, drone to drone, without shadowing (listening before talk, and channel
    /// activity detection).
    fn rx_dbm_at(&self, net: &Network, at: [f64; 3]) -> f64 {
        // Two drones at one spot are 1 m apart: the path loss's reference distance.
        let d = distance(&self.at, &at).max(1.0);
        net.channel.mean_rx_power_dbm(d) - self.frame.power_reduction_db
    }
}

fn packet_id(drone: usize, index: usize) -> u64 {
    ((drone as u64) << 32) | index as u64
}

/// Seconds of flight whose drone estimates are computed ahead, all drones in parallel, before
/// the loop reaches them (a swarm's filters are most of its work).
const LOOKAHEAD_S: f64 = 30.0;

/// Drones whose estimates are computed ahead between two progress reports: where they run in
/// turn (WebAssembly), 32 drones' 30 s at 100 Hz take 0.2–0.4 s, so a swarm told to stop
/// (`run_episode`) stops within about that long, not the 1.3–2 s all 200 of the panel's largest
/// swarm take (docs/performance.md, twenty-third session).
const AHEAD_GROUP: usize = 32;

/// Runs one episode: every flier's uplinks until its flight ends, through every gateway of
/// `net` (at most 32: `heard_by` is a bit set; settings allow 16), filling each flier's `tx`.
/// The network's radios, ADR state and gateway counts carry over to the next episode; the
/// gateways' receivers and duty cycles start afresh (each flight has its own time axis).
///
/// With several fliers, `progress(share)` is called as the loop's clock passes each stretch of
/// the drones' estimates computed ahead: the share (0..=1) of the episode's time span behind it.
/// Where it returns `false` the episode stops there, its fliers' `tx` half filled, and
/// `run_episode` returns `false` (a swarm then ends [stopped](crate::sim::SimError::Stopped));
/// otherwise it returns `true` once every flight has ended. A lone flier is never asked.
#[must_use = "a stopped episode's transmissions are not its whole flights'"]
pub fn run_episode(
    net: &mut Network,
    fliers: &mut [Flier<'_>],
    progress: &mut dyn FnMut(f64) -> bool,
) -> bool {
    let mut episode = Episode::new(net, fliers.len());
    let span = time_span(fliers);
    for (d, f) in fliers.iter_mut().enumerate() {
        episode.plan(f, d, f64::NEG_INFINITY);
    }
    while let Some(e) = episode.queue.pop() {
        let share = ((e.time - span.0) / (span.1 - span.0)).clamp(0.0, 1.0);
        if !episode.look_ahead(fliers, e.time, &mut || progress(share)) {
            return false;
        }
        let f = &mut fliers[e.drone];
        if e.start {
            episode.start(net, f, e);
        } else {
            episode.end(net, f, e);
        }
    }
    true
}

/// The first and last sample times of the fliers' flights, s (a span of at least 1 s).
fn time_span(fliers: &[Flier<'_>]) -> (f64, f64) {
    let first = fliers
        .iter()
        .filter_map(|f| f.flight.t.first())
        .fold(f64::INFINITY, |a, &b| a.min(b));
    let last = fliers
        .iter()
        .filter_map(|f| f.flight.t.last())
        .fold(f64::NEG_INFINITY, |a, &b| a.max(b));
    if first.is_finite() && last.is_finite() {
        (first, last.max(first + 1.0))
    } else {
        (0.0, 1.0)
    }
}

/// One episode under way: the gateways' receivers and downlink duty cycles, the events to come,
/// each drone's planned uplink (its sensor step and start time) and the packet it has on air.
struct Episode {
    gateways: Vec<Gateway>,
    queue: BinaryHeap<Event>,
    next: Vec<Option<(usize, f64)>>,
    on_air: Vec<Option<OnAir>>,
    /// The time up to which every drone's estimates have been computed ahead, s.
    computed_to: f64,
}

impl Episode {
    fn new(net: &Network, drones: usize) -> Self {
        Episode {
            gateways: net
                .sites
                .iter()
                .map(|_| Gateway::new(net.interference))
                .collect(),
            queue: BinaryHeap::new(),
            next: vec![None; drones],
            on_air: (0..drones).map(|_| None).collect(),
            computed_to: f64::NEG_INFINITY,
        }
    }

    /// Once the loop's clock reaches the estimates computed ahead (with several fliers): every
    /// drone's estimates for the next LOOKAHEAD_S, in parallel, a group of AHEAD_GROUP drones at
    /// a time, asking `go_on()` after each group. `false` where it said stop.
    fn look_ahead(
        &mut self,
        fliers: &mut [Flier<'_>],
        time: f64,
        go_on: &mut dyn FnMut() -> bool,
    ) -> bool {
        if time < self.computed_to || fliers.len() < 2 {
            return true;
        }
        self.computed_to = time + LOOKAHEAD_S;
        let mut ahead: Vec<_> = fliers
            .iter_mut()
            .map(|f| f.estimates_until(self.computed_to))
            .collect();
        ahead.chunks_mut(AHEAD_GROUP).all(|group| {
            par_each(group, |(est, upto)| est.prefetch(*upto));
            go_on()
        })
    }

    /// Drone `e.drone`'s planned uplink starts: it takes a channel (or, listening before talk,
    /// backs off), goes on air and reaches each gateway. Without ADR its next uplink is planned
    /// now; with ADR once its receive windows have told it what the network answered.
    fn start(&mut self, net: &mut Network, f: &mut Flier<'_>, e: Event) {
        let Some(k) = self.next[e.drone].take() else {
            return;
        };
        let frame = net.radios[f.drone].uplink();
        let frame = f.with_payload(k.0, frame, &net.radios[f.drone]);
        let at = f.network_position(e.time);
        let Some(ch) = channel_for(net, &self.on_air, f, at, frame.sf.get()) else {
            let wait = f.backoff(lbt::max_backoff(frame.time_on_air));
            self.plan(f, e.drone, e.time + wait);
            return;
        };
        if f.listens() {
            f.channel_sensed(detects_another(net, &self.on_air, at, ch, &frame));
        }
        let Some(receptions) = f.transmit(k, ch, &frame, &net.channel) else {
            self.plan(f, e.drone, e.time);
            return;
        };
        let Some(t) = f.tx.last() else { return };
        let (sent, arrival, channel, sf, bw) = (t.sent, t.arrival, t.channel, t.sf, t.bw);
        let id = packet_id(e.drone, f.tx.len() - 1);
        for (g, r) in self.gateways.iter_mut().zip(&receptions) {
            g.start(
                id,
                Uplink {
                    start: sent,
                    end: arrival,
                    channel,
                    sf: sf.get(),
                    rx_dbm: r.rx_dbm,
                    audible: audible(r.rx_dbm, sf, bw),
                },
            );
        }
        self.queue.push(Event {
            time: arrival,
            start: false,
            drone: e.drone,
        });
        if !net.radios[f.drone].adaptive() {
            // No downlink can change anything: the next uplink is planned at once, at the
            // radio's own frame (this one may have been lean).
            f.after_packet(k, net.radios[f.drone].current().time_on_air);
            self.plan(f, e.drone, arrival + off_time(net));
        }
        self.on_air[e.drone] = Some(OnAir {
            k,
            frame,
            receptions,
            channel: ch,
            at,
        });
    }

    /// Drone `e.drone`'s uplink ends: each gateway decides it, the network server keeps the
    /// first copy and answers, and the packet's outcome is recorded.
    fn end(&mut self, net: &mut Network, f: &mut Flier<'_>, e: Event) {
        let Some(air) = self.on_air[e.drone].take() else {
            return;
        };
        let index = f.tx.len() - 1;
        let id = packet_id(e.drone, index);
        let mut heard_by = 0u32;
        let mut outcome = Outcome::BelowSensitivity;
        for (g, gw) in self.gateways.iter_mut().enumerate() {
            let o = gw.finish(id);
            if o == Outcome::Received {
                heard_by |= 1 << g;
            }
            if o == Outcome::GatewayTransmitting {
                net.gateways[g].missed_while_transmitting += 1;
            }
            outcome = outcome.max(o);
        }
        net.count_copies(heard_by);
        let ended = Ended {
            air,
            heard_by,
            time: e.time,
        };
        let next_from = self.finish_exchange(net, f, &ended);
        let t = &mut f.tx[index];
        t.received = heard_by != 0;
        t.heard_by = heard_by;
        t.outcome = outcome;
        if net.radios[f.drone].adaptive() {
            let toa = net.radios[f.drone].current().time_on_air;
            f.after_packet(ended.air.k, toa);
            self.plan(f, e.drone, next_from + off_time(net));
        }
    }

    /// Plans drone `d`'s next uplink at or after `not_before` s, if its flight has one.
    fn plan(&mut self, f: &mut Flier<'_>, d: usize, not_before: f64) {
        if let Some((k, time)) = f.next_uplink(not_before) {
            self.next[d] = Some((k, time));
            self.queue.push(Event {
                time,
                start: true,
                drone: d,
            });
        }
    }
}

/// The least silence after an uplink ends before the next may start, s: listen-before-talk's
/// 100 ms (which a budget of airtime could otherwise skip), nothing under a duty cycle.
fn off_time(net: &Network) -> f64 {
    if net.listen_before_talk {
        lbt::MIN_OFF_TIME_S
    } else {
        0.0
    }
}

/// The channel `f`'s uplink from `at` (network frame, m) takes: its first pick, or with
/// listen-before-talk a free one (a busy first channel counted as a deferral, and as a collision
/// avoided when it carried the drone's own SF `sf`); `None` when every channel is busy.
fn channel_for(
    net: &Network,
    on_air: &[Option<OnAir>],
    f: &mut Flier<'_>,
    at: [f64; 3],
    sf: u8,
) -> Option<u8> {
    let (first, channels) = f.pick_channel();
    if !net.listen_before_talk {
        return Some(first);
    }
    let heard = listen(net, on_air, at, (first, channels), sf);
    if let Heard::Moved(_, same) | Heard::Busy(same) = heard {
        f.lbt_deferrals += 1;
        f.lbt_avoided += usize::from(same);
    }
    match heard {
        Heard::Free(c) | Heard::Moved(c, _) => Some(c),
        Heard::Busy(_) => None,
    }
}

/// Whether a drone at `at` (network frame, m) starting `frame` on channel `ch` detects another
/// packet of its spreading factor on air there (channel activity detection: a preamble above
/// the SF's sensitivity, [`OnAir::rx_dbm_at`]).
fn detects_another(
    net: &Network,
    on_air: &[Option<OnAir>],
    at: [f64; 3],
    ch: u8,
    frame: &Frame,
) -> bool {
    on_air
        .iter()
        .flatten()
        .filter(|a| a.channel == ch && a.frame.sf == frame.sf)
        .any(|a| audible(a.rx_dbm_at(net, at), frame.sf, frame.bw))
}

/// What a drone listening before talk heard. The flag says whether the busy first channel
/// carried a packet on the drone's own SF (a collision avoided).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Heard {
    /// Its first channel was free.
    Free(u8),
    /// Its first channel was busy, this one free: it moves there.
    Moved(u8, bool),
    /// Every channel was busy: it backs off.
    Busy(bool),
}

/// Listen-before-talk at `at` (network frame, m) on the `(first, channels)` a drone of spreading
/// factor `sf` may use: a channel is busy when any packet on air on it reaches the listener
/// above the threshold (the shared path-loss model, drone to drone, without shadowing). Every
/// packet on air now was on air during the listen time before (packets last longer than it).
fn listen(
    net: &Network,
    on_air: &[Option<OnAir>],
    at: [f64; 3],
    (first, channels): (u8, u8),
    sf: u8,
) -> Heard {
    let heard_on = |c: u8| -> Option<bool> {
        let mut heard = None;
        for a in on_air.iter().flatten().filter(|a| a.channel == c) {
            if lbt::busy(a.rx_dbm_at(net, at)) {
                heard = Some(heard.unwrap_or(false) || a.frame.sf.get() == sf);
            }
        }
        heard
    };
    let Some(same) = heard_on(first) else {
        return Heard::Free(first);
    };
    for c in (1..channels).map(|i| (first + i) % channels) {
        if heard_on(c).is_none() {
            return Heard::Moved(c, same);
        }
    }
    Heard::Busy(same)
}

/// An uplink as it ends: what was on air, the gateways that received it (bit `g` for gateway
/// `g`), and the time it ended, s.
struct Ended {
    air: OnAir,
    heard_by: u32,
    time: f64,
}

/// A downlink the network sent: its window, its time on air (s), whether the drone heard it.
type Downlink = (Window, f64, bool);

impl Episode {
    /// After an uplink ends at `end`: ADR's answer (if any), the drone's radio told what came, and
    /// the uplink's charge recorded. Returns the earliest time the drone's next uplink may start,
    /// s: once a downlink it heard has fully arrived (a command cannot apply before it is heard),
    /// otherwise at the uplink's end (nothing was learnt; the drone's empty receive windows cost
    /// energy but do not hold back the next uplink, as before ADR existed).
    fn finish_exchange(&mut self, net: &mut Network, f: &mut Flier<'_>, ended: &Ended) -> f64 {
        let (air, end) = (&ended.air, ended.time);
        let (downlink, command) = self.answer(net, f, ended);
        let heard = matches!(downlink, Some((_, _, true)));
        net.radios[f.drone].exchange_done(heard.then_some(command));
        // Class A receive windows, when the drone speaks LoRaWAN.
        let opens = net.lorawan || air.frame.adr.is_some();
        let activity = UplinkActivity {
            tx_power_dbm: net.channel.params().tx_power_dbm - air.frame.power_reduction_db,
            time_on_air: air.frame.time_on_air,
            windows: if opens {
                listening(&air.frame, downlink)
            } else {
                [(0.0, air.frame.bw), (0.0, DataRate::DR0.bw())]
            },
        };
        if let Some(t) = f.tx.last_mut() {
            t.charge_mc = activity.charge_mc();
            t.active_s = activity.active_s();
        }
        match downlink {
            Some((w, toa, true)) => end + w.delay_s() + toa,
            _ => end,
        }
    }

    /// The network server's answer to a received uplink with ADR: through the gateway that heard
    /// it best, in RX1, or in RX2 when that gateway's RX1 duty cycle forbids it, or dropped (and
    /// counted) when both do. The downlink sent, if any, and the ADR command.
    fn answer(
        &mut self,
        net: &mut Network,
        f: &mut Flier<'_>,
        ended: &Ended,
    ) -> (Option<Downlink>, Option<LinkAdrReq>) {
        let (Some(g), Some(frame)) = (ended.loudest(), ended.air.frame.adr) else {
            return (None, None);
        };
        // The payload the server decodes: this uplink's, the last the drone put on air.
        let speed = f.tx.last().map_or(0.0, |t| t.state[V]);
        let uplink = AdrUplink {
            frame: &frame,
            rssi_dbm: ended.air.receptions[g].rx_dbm,
            speed_mps: speed,
            time: ended.time,
            channels: f.aloha_channels(),
        };
        let (answers, command) = net.adr_hears(f.drone, &uplink);
        if !answers {
            return (None, command);
        }
        let bytes = if command.is_some() {
            ADR_DOWNLINK_BYTES
        } else {
            ACK_DOWNLINK_BYTES
        };
        let sent = self.downlink(net, f, g, (frame.dr, ended.time), bytes);
        (sent, command)
    }

    /// A downlink of `bytes` through gateway `g` after an uplink at data rate `dr` that ended at
    /// `end` (s): in RX1, else in RX2, where the server keeps the window free and the gateway's
    /// duty cycle allows; else none, counted as held back (the server kept a window the duty
    /// cycle may have allowed) or dropped.
    fn downlink(
        &mut self,
        net: &mut Network,
        f: &mut Flier<'_>,
        g: usize,
        (dr, end): (DataRate, f64),
        bytes: usize,
    ) -> Option<Downlink> {
        let mut held_back = false;
        for w in [Window::Rx1, Window::Rx2] {
            let dr = w.data_rate(dr);
            let Ok(toa) = downlink_time_on_air(dr, bytes) else {
                break;
            };
            if !net.may_answer_in(f.drone, w, toa) {
                held_back = true;
                continue;
            }
            let at = end + w.delay_s();
            if self.gateways[g].try_downlink(w, at, toa) {
                net.gateways[g].downlinks_sent += 1;
                let pos = f.position_at(at);
                let r = f.links[g].downlink(&net.channel, pos);
                return Some((w, toa, audible(r.rx_dbm, dr.sf(), dr.bw())));
            }
        }
        let unsent = &mut net.gateways[g];
        if held_back {
            unsent.downlinks_held_back += 1;
        } else {
            unsent.downlinks_dropped += 1;
        }
        None
    }
}

impl Ended {
    /// The gateway that heard the uplink loudest, if any heard it (a reception per gateway).
    fn loudest(&self) -> Option<usize> {
        let receptions = &self.air.receptions;
        (0..receptions.len())
            .filter(|g| self.heard_by & (1 << g) != 0)
            .max_by(|&a, &b| receptions[a].rx_dbm.total_cmp(&receptions[b].rx_dbm))
    }
}

/// Seconds each class A receive window listens, and at which bandwidth: RX1 at the uplink's
/// rate, RX2 at SF12/125 kHz unless RX1 brought the downlink; an empty window lasts its
/// preamble timeout, one with a downlink the downlink's time on air.
fn listening(frame: &Frame, downlink: Option<Downlink>) -> [(f64, Bandwidth); 2] {
    let dr0 = DataRate::DR0;
    let empty_rx1 = empty_window_s(frame.sf, frame.bw);
    match downlink {
        Some((Window::Rx1, toa, true)) => [(toa, frame.bw), (0.0, dr0.bw())],
        Some((Window::Rx2, toa, true)) => [(empty_rx1, frame.bw), (toa, dr0.bw())],
        _ => [
            (empty_rx1, frame.bw),
            (empty_window_s(dr0.sf(), dr0.bw()), dr0.bw()),
        ],
    }
}
