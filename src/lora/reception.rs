//! Whether a receiver hears a LoRa packet: the one place reception is decided, for every gateway
//! and for the drone's downlink receiver alike (reference: `docs/reference.md` §6.3).
//!
//! A packet whose received power (mean path loss + shadowing, per drone–gateway link) is below
//! the sensitivity for its SF and bandwidth is never detected. An audible one needs a free
//! demodulation path when its preamble arrives (an SX1301 gateway has 8; a drone's SX1276 one),
//! and then survives if, for each SF, the summed power of every packet that overlaps it in time
//! on its channel — audible or not, demodulated or not: the energy is on the air either way —
//! leaves it the signal-to-interference ratio the [`InterferenceModel`] requires (same-SF capture,
//! inter-SF rejection). Any overlap counts, as in LoRaSim's basic model (Bor et al. 2016); ns-3
//! weighs interference by the overlap's duration instead, which loses fewer packets to short
//! overlaps. A gateway is half-duplex: while it transmits a downlink ([`Receiver::transmit`]) it
//! hears nothing, and a packet on air at any moment of it is lost, as in ns-3's
//! `SimpleGatewayLoraPhy` (a transmission frees every demodulation path; a packet arriving
//! during it finds none).

use super::interference::{sum_dbm, survives, InterferenceModel};
use super::{Bandwidth, Channel, SpreadingFactor};

/// Demodulation paths of an SX1301 gateway: at most this many packets are received at once.
pub const SX1301_DEMODULATORS: usize = 8;

/// One packet as one receiver sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uplink {
    /// Start of the transmission, s.
    pub start: f64,
    /// End (start + time on air), s.
    pub end: f64,
    /// Channel index (0..C).
    pub channel: u8,
    /// Spreading factor 7..12.
    pub sf: u8,
    /// Received power at this receiver, including shadowing, dBm.
    pub rx_dbm: f64,
    /// Whether that power reaches the receiver's sensitivity ([`audible`]).
    pub audible: bool,
}

/// What became of a packet at one receiver.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Outcome {
    /// Below the sensitivity: never detected.
    BelowSensitivity,
    /// Audible, but on air while the gateway transmitted a downlink (half-duplex).
    GatewayTransmitting,
    /// All demodulation paths were busy when its preamble arrived.
    NoDemodulator,
    /// Lost to interference from overlapping packets on its channel.
    Collided,
    /// Demodulated.
    Received,
}

/// Whether `rx_dbm` reaches the sensitivity for `sf` and `bw` (SX1301 table, as ns-3's
/// `lorawan` module uses it; the drone's receiver is given the same table).
pub fn audible(rx_dbm: f64, sf: SpreadingFactor, bw: Bandwidth) -> bool {
    rx_dbm >= Channel::sensitivity_dbm(sf, bw)
}

/// The reception decision: a packet `u` that did (`locked`) or did not find a demodulation path,
/// against `interference_dbm[k]`, the summed power at SF 7 + k of the packets overlapping it on
/// its channel (`-inf` for none).
pub fn decide(
    u: &Uplink,
    locked: bool,
    interference_dbm: &[f64; 6],
    model: InterferenceModel,
) -> Outcome {
    if !u.audible {
        Outcome::BelowSensitivity
    } else if !locked {
        Outcome::NoDemodulator
    } else if survives(u.sf, u.rx_dbm, interference_dbm, model) {
        Outcome::Received
    } else {
        Outcome::Collided
    }
}

#[derive(Clone, Copy, Debug)]
struct OnAir {
    id: u64,
    uplink: Uplink,
    locked: bool,
    finished: bool,
}

/// One receiver over time: the packets on air around it and its demodulation paths. Packets are
/// started in time order ([`Receiver::start`]) and each is decided when it ends
/// ([`Receiver::finish`]), when every packet that overlaps it has started.
#[derive(Clone, Debug)]
pub struct Receiver {
    model: InterferenceModel,
    demodulators: usize,
    on_air: Vec<OnAir>,
    /// The receiver's own transmissions (start, end), s: a gateway's downlinks.
    sending: Vec<(f64, f64)>,
}

impl Receiver {
    /// A receiver with `demodulators` paths judging interference by `model`.
    pub fn new(model: InterferenceModel, demodulators: usize) -> Self {
        Receiver {
            model,
            demodulators,
            on_air: Vec::new(),
            sending: Vec::new(),
        }
    }

    /// The receiver transmits from `start` to `end`, s (a gateway's downlink, decided at the end of
    /// the uplink it answers, so before any packet it can overlap has ended): every packet on air
    /// at any moment of it is lost ([`Outcome::GatewayTransmitting`]) and frees its demodulation
    /// path when the transmission begins.
    pub fn transmit(&mut self, start: f64, end: f64) {
        self.sending.push((start, end));
    }

    /// Whether the receiver transmits at some moment between `from` and `to`, s.
    fn sends_within(&self, from: f64, to: f64) -> bool {
        self.sending.iter().any(|&(s, e)| s <= to && e > from)
    }

    /// Packet `id` starts: an audible one takes a free demodulation path, if there is one and
    /// the receiver is not transmitting. Calls come in order of start time (ties in a fixed
    /// order: the loop's drone order).
    pub fn start(&mut self, id: u64, uplink: Uplink) {
        let at = uplink.start;
        // A path stays busy until its packet ends or a transmission since its start freed it.
        let busy = self
            .on_air
            .iter()
            .filter(|p| p.locked && p.uplink.end > at && !self.sends_within(p.uplink.start, at))
            .count();
        self.on_air.push(OnAir {
            id,
            uplink,
            locked: uplink.audible && busy < self.demodulators && !self.sends_within(at, at),
            finished: false,
        });
    }

    /// Packet `id` has ended: its outcome. Call at its end time, after every packet that
    /// started before then.
    pub fn finish(&mut self, id: u64) -> Outcome {
        let Some(pos) = self.on_air.iter().position(|p| p.id == id) else {
            return Outcome::BelowSensitivity;
        };
        let me = self.on_air[pos];
        let u = me.uplink;
        // Earlier starts (newest first), then later ones: the order the powers are summed in.
        let before = self.on_air[..pos]
            .iter()
            .rev()
            .filter(|v| v.uplink.end > u.start);
        let after = self.on_air[pos + 1..]
            .iter()
            .filter(|v| v.uplink.start < u.end);
        let mut per_sf: [Vec<f64>; 6] = Default::default();
        for v in before.chain(after) {
            if v.uplink.channel == u.channel {
                per_sf[usize::from(v.uplink.sf - 7)].push(v.uplink.rx_dbm);
            }
        }
        let outcome = if u.audible && self.sends_within(u.start, u.end) {
            Outcome::GatewayTransmitting
        } else {
            decide(&u, me.locked, &per_sf.map(sum_dbm), self.model)
        };
        self.on_air[pos].finished = true;
        // Forget what can no longer overlap a packet still on air.
        let oldest_open = self
            .on_air
            .iter()
            .filter(|p| !p.finished)
            .map(|p| p.uplink.start)
            .fold(f64::INFINITY, f64::min);
        let horizon = oldest_open.min(u.end);
        self.on_air
            .retain(|p| !p.finished || p.uplink.end > horizon);
        self.sending.retain(|&(_, end)| end > horizon);
        outcome
    }
}

/// The outcome of every packet in `uplinks` (any order) at one receiver, as the event loop
/// decides them: started in order of start time (ties in the order given), decided at their
/// ends (an end before a start at the same instant).
pub fn resolve(receiver: &mut Receiver, uplinks: &[Uplink]) -> Vec<Outcome> {
    let mut events: Vec<(f64, bool, usize)> = Vec::with_capacity(2 * uplinks.len());
    for (i, u) in uplinks.iter().enumerate() {
        events.push((u.start, true, i));
        events.push((u.end, false, i));
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
    let mut out = vec![Outcome::BelowSensitivity; uplinks.len()];
    for (_, is_start, i) in events {
        if is_start {
            receiver.start(i as u64, uplinks[i]);
        } else {
            out[i] = receiver.finish(i as u64);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn up(start: f64, sf: u8, rx: f64) -> Uplink {
        Uplink {
            start,
            end: start + 0.1,
            channel: 0,
            sf,
            rx_dbm: rx,
            audible: true,
        }
    }

    fn gateway(capture: bool, inter_sf: bool) -> Receiver {
        Receiver::new(InterferenceModel { capture, inter_sf }, SX1301_DEMODULATORS)
    }

    #[test]
    fn overlapping_same_sf_packets_collide_unless_one_captures() {
        let r = resolve(
            &mut gateway(true, true),
            &[up(0.0, 7, -100.0), up(0.05, 7, -103.0), up(0.5, 7, -100.0)],
        );
        assert_eq!(r, [Outcome::Collided, Outcome::Collided, Outcome::Received]);
        let r = resolve(
            &mut gateway(true, true),
            &[up(0.0, 7, -90.0), up(0.05, 7, -103.0)],
        );
        assert_eq!(r, [Outcome::Received, Outcome::Collided]);
        let r = resolve(
            &mut gateway(false, false),
            &[up(0.0, 7, -90.0), up(0.05, 7, -103.0), up(0.06, 8, -80.0)],
        );
        assert_eq!(r, [Outcome::Collided, Outcome::Collided, Outcome::Received]);
    }

    #[test]
    fn other_channels_do_not_interfere() {
        let mut b = up(0.05, 7, -100.0);
        b.channel = 1;
        assert_eq!(
            resolve(&mut gateway(false, true), &[up(0.0, 7, -100.0), b]),
            [Outcome::Received; 2]
        );
    }

    #[test]
    fn a_gateway_hears_nothing_on_air_while_it_transmits() {
        let mut gw = gateway(true, true);
        // A downlink from 1.0 to 1.5 s, decided before any of these packets ends.
        gw.transmit(1.0, 1.5);
        // Each on a channel of its own, so that none meets another.
        let ups: Vec<Uplink> = [0.85, 0.95, 1.2, 1.45, 1.5]
            .iter()
            .zip(0u8..)
            .map(|(&t, channel)| Uplink {
                channel,
                ..up(t, 7, -100.0)
            })
            .collect();
        // Ends before it; on air as it begins; within it; on air as it ends; after it.
        let r = resolve(&mut gw, &ups);
        use Outcome::{GatewayTransmitting as Tx, Received};
        assert_eq!(r, [Received, Tx, Tx, Tx, Received]);
        let mut faint = up(1.2, 7, -150.0);
        faint.audible = false;
        let mut gw = gateway(true, true);
        gw.transmit(1.0, 1.5);
        assert_eq!(
            resolve(&mut gw, &[faint]),
            [Outcome::BelowSensitivity],
            "a packet it could not hear is below its sensitivity, transmitting or not"
        );
    }

    #[test]
    fn a_transmission_frees_every_demodulation_path() {
        // Eight long packets hold every path; a transmission at 0.5 s frees them, so a packet
        // after it finds one.
        let long = |k: u8| Uplink {
            end: 2.0,
            channel: k % 3,
            ..up(0.01 * f64::from(k), 7 + k % 6, -100.0)
        };
        let mut ups: Vec<Uplink> = (0..8).map(long).collect();
        ups.push(Uplink {
            channel: 5,
            ..up(0.7, 7, -100.0)
        });
        let mut gw = gateway(false, false);
        gw.transmit(0.5, 0.6);
        let r = resolve(&mut gw, &ups);
        assert!(
            r[..8].iter().all(|o| *o == Outcome::GatewayTransmitting),
            "{r:?}"
        );
        assert_eq!(r[8], Outcome::Received);
        // Without the transmission the ninth finds none.
        let r = resolve(&mut gateway(false, false), &ups);
        assert_eq!(r[8], Outcome::NoDemodulator);
    }

    #[test]
    fn a_ninth_simultaneous_packet_finds_no_demodulator() {
        let ups: Vec<Uplink> = (0..9u8)
            .map(|k| Uplink {
                channel: k % 3,
                sf: 7 + k % 6,
                ..up(0.01 * f64::from(k), 7, -100.0)
            })
            .collect();
        let r = resolve(&mut gateway(false, false), &ups);
        let no_path = r.iter().filter(|o| **o == Outcome::NoDemodulator).count();
        assert_eq!(no_path, 1, "{r:?}");
        assert_eq!(r[8], Outcome::NoDemodulator);
    }

    #[test]
    fn a_path_frees_when_its_packet_ends() {
        let ups: Vec<Uplink> = (0..9u8)
            .map(|k| Uplink {
                // Every packet on its own channel and SF: none interferes with another.
                channel: k % 3,
                sf: 7 + k / 3,
                // The ninth starts exactly when the first ends.
                ..up(if k == 8 { 0.1 } else { 0.001 * f64::from(k) }, 7, -100.0)
            })
            .collect();
        let r = resolve(&mut gateway(false, false), &ups);
        assert!(r.iter().all(|o| *o == Outcome::Received), "{r:?}");
    }

    #[test]
    fn inaudible_packets_are_not_detected_but_still_interfere() {
        let mut weak = up(0.05, 7, -100.0);
        weak.audible = false;
        let r = resolve(&mut gateway(true, true), &[up(0.0, 7, -102.0), weak]);
        assert_eq!(r, [Outcome::Collided, Outcome::BelowSensitivity]);
    }

    #[test]
    fn a_receiver_forgets_only_what_can_no_longer_overlap() {
        let mut g = gateway(false, false);
        // A long packet on air while many short ones come and go: the last short one must
        // still see the long one.
        let long = Uplink {
            end: 10.0,
            ..up(0.0, 7, -100.0)
        };
        g.start(0, long);
        for k in 1..50u64 {
            let u = Uplink {
                channel: 1,
                ..up(k as f64 * 0.15, 7, -100.0)
            };
            g.start(k, u);
            assert_eq!(g.finish(k), Outcome::Received);
        }
        g.start(99, up(9.0, 7, -100.0));
        assert_eq!(g.finish(99), Outcome::Collided);
        assert_eq!(g.finish(0), Outcome::Collided);
    }
}
