//! A LoRa gateway receiving many devices at once: sensitivity, interference between overlapping
//! packets, and the SX1301's eight demodulation paths.

use super::interference::{sum_dbm, survives, InterferenceModel};

/// Demodulation paths of an SX1301 gateway: at most this many packets are received at once.
pub const SX1301_DEMODULATORS: usize = 8;

/// One uplink as the gateway sees it.
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
    /// Received power including shadowing, dBm.
    pub rx_dbm: f64,
    /// Whether that power reaches the gateway's sensitivity for the packet's SF and bandwidth.
    pub audible: bool,
}

/// What became of an uplink at the gateway.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// Demodulated.
    Received,
    /// Below the sensitivity: never detected.
    BelowSensitivity,
    /// All demodulation paths were busy when its preamble arrived.
    NoDemodulator,
    /// Lost to interference from overlapping packets on its channel.
    Collided,
}

/// The gateway's reception rules.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Gateway {
    /// Capture and inter-SF rules.
    pub interference: InterferenceModel,
    /// Demodulation paths.
    pub demodulators: usize,
}

impl Gateway {
    /// The outcome of every uplink (in the order given).
    ///
    /// A packet below the sensitivity is never detected (and occupies no path). An audible one
    /// takes a free demodulation path when it starts, or is lost if all are busy (counted apart,
    /// as the SX1301 limit, not interference). It then survives if, for each SF, the summed power
    /// of every packet that overlaps it in time on its channel — audible or not, demodulated or
    /// not: the energy is on the air either way — leaves it the signal-to-interference ratio the
    /// [`InterferenceModel`] requires. Any overlap counts, as in LoRaSim's basic model (Bor et al.
    /// 2016); ns-3 weighs interference by the overlap's duration instead, which loses fewer packets
    /// to short overlaps.
    pub fn resolve(&self, uplinks: &[Uplink]) -> Vec<Outcome> {
        let mut order: Vec<usize> = (0..uplinks.len()).collect();
        order.sort_by(|&a, &b| uplinks[a].start.total_cmp(&uplinks[b].start));
        let mut outcome = vec![Outcome::BelowSensitivity; uplinks.len()];
        let mut busy_until: Vec<f64> = Vec::new();
        for (pos, &i) in order.iter().enumerate() {
            let u = &uplinks[i];
            if !u.audible {
                continue;
            }
            busy_until.retain(|&end| end > u.start);
            if busy_until.len() >= self.demodulators {
                outcome[i] = Outcome::NoDemodulator;
                continue;
            }
            busy_until.push(u.end);
            let interference = self.interference_at(uplinks, &order, pos);
            outcome[i] = if survives(u.sf, u.rx_dbm, &interference, self.interference) {
                Outcome::Received
            } else {
                Outcome::Collided
            };
        }
        outcome
    }

    /// Summed power per SF of the packets overlapping `order[pos]` on its channel, dBm.
    fn interference_at(&self, uplinks: &[Uplink], order: &[usize], pos: usize) -> [f64; 6] {
        let u = &uplinks[order[pos]];
        // Sorted by start: earlier packets overlap if they end after u starts; later ones if they
        // start before u ends. Packets last at most a few seconds, so both scans stay short.
        let before = order[..pos].iter().rev().map(|&j| &uplinks[j]);
        let after = order[pos + 1..]
            .iter()
            .map(|&j| &uplinks[j])
            .take_while(|v| v.start < u.end);
        let mut per_sf: [Vec<f64>; 6] = Default::default();
        for v in before.filter(|v| v.end > u.start).chain(after) {
            if v.channel == u.channel {
                per_sf[usize::from(v.sf - 7)].push(v.rx_dbm);
            }
        }
        per_sf.map(sum_dbm)
    }
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

    fn gateway(capture: bool, inter_sf: bool) -> Gateway {
        Gateway {
            interference: InterferenceModel { capture, inter_sf },
            demodulators: SX1301_DEMODULATORS,
        }
    }

    #[test]
    fn overlapping_same_sf_packets_collide_unless_one_captures() {
        let g = gateway(true, true);
        let r = g.resolve(&[up(0.0, 7, -100.0), up(0.05, 7, -103.0), up(0.5, 7, -100.0)]);
        assert_eq!(r, [Outcome::Collided, Outcome::Collided, Outcome::Received]);
        let r = g.resolve(&[up(0.0, 7, -90.0), up(0.05, 7, -103.0)]);
        assert_eq!(r, [Outcome::Received, Outcome::Collided]);
        let r = gateway(false, false).resolve(&[
            up(0.0, 7, -90.0),
            up(0.05, 7, -103.0),
            up(0.06, 8, -80.0),
        ]);
        assert_eq!(r, [Outcome::Collided, Outcome::Collided, Outcome::Received]);
    }

    #[test]
    fn other_channels_do_not_interfere() {
        let mut b = up(0.05, 7, -100.0);
        b.channel = 1;
        assert_eq!(
            gateway(false, true).resolve(&[up(0.0, 7, -100.0), b]),
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
        let r = gateway(false, false).resolve(&ups);
        let no_path = r.iter().filter(|o| **o == Outcome::NoDemodulator).count();
        assert_eq!(no_path, 1, "{r:?}");
        assert_eq!(r[8], Outcome::NoDemodulator);
    }

    #[test]
    fn inaudible_packets_are_not_detected_but_still_interfere() {
        let mut weak = up(0.05, 7, -100.0);
        weak.audible = false;
        let r = gateway(true, true).resolve(&[up(0.0, 7, -102.0), weak]);
        assert_eq!(r, [Outcome::Collided, Outcome::BelowSensitivity]);
    }
}
