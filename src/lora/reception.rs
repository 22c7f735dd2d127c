//! Whether a receiver hears a LoRa packet: the one place reception is decided, for every gateway
//! and for the drone's downlink receiver alike (reference: `docs/reference.md` §5).
//!
//! A packet whose received power (mean path loss + shadowing, per drone–gateway link) is below
//! the sensitivity for its SF and bandwidth is never detected. An audible one needs a free
//! demodulation path when its preamble arrives (an SX1301 gateway has 8; a drone's SX1276 one),
//! and then survives if, for each SF, the summed power of every packet that overlaps it in time
//! on its channel — audible or not, demodulated or not: the energy is on the air either way —
//! leaves it the signal-to-interference ratio the [`InterferenceModel`] requires (same-SF capture,
//! inter-SF rejection). Any overlap counts, as in LoRaSim's basic model (Bor et al. 2016); ns-3
//! weighs interference by the overlap's duration instead, which loses fewer packets to short
//! overlaps.

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
}

impl Receiver {
    /// A receiver with `demodulators` paths judging interference by `model`.
    pub fn new(model: InterferenceModel, demodulators: usize) -> Self {
        Receiver {
            model,
            demodulators,
            on_air: Vec::new(),
        }
    }

    /// Packet `id` starts: an audible one takes a free demodulation path, if there is one.
    /// Calls come in order of start time (ties in a fixed order: the loop's drone order).
    pub fn start(&mut self, id: u64, uplink: Uplink) {
        let busy = self
            .on_air
            .iter()
            .filter(|p| p.locked && p.uplink.end > uplink.start)
            .count();
        self.on_air.push(OnAir {
            id,
            uplink,
            locked: uplink.audible && busy < self.demodulators,
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
        let outcome = decide(&u, me.locked, &per_sf.map(sum_dbm), self.model);
        self.on_air[pos].finished = true;
        // Forget what can no longer overlap a packet still on air.
        let oldest_open = self
            .on_air
            .iter()
            .filter(|p| !p.finished)
            .map(|p| p.uplink.start)
            .fold(f64::INFINITY, f64::min);
        self.on_air
            .retain(|p| !p.finished || p.uplink.end > oldest_open.min(u.end));
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
