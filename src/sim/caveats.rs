//! What a station's numbers rest on, where a reader could be misled by them: the flags that the
//! CLI's lines under its table and the page's notes under its results both read, so that both say
//! it for the same runs (README "The playground"; the untracked time is
//! [`WholeFlightError::partly_tracked`](crate::WholeFlightError::partly_tracked)).

use super::packet::Transmission;
use super::sender::SenderKind;
use crate::codec::SaturatedFields;
use crate::models::V;
use serde::Serialize;

/// Fewer received packets than this, and a station's statistics are too thin to compare with
/// another's: a p75 over a handful of packets is mostly the luck of where they fell.
pub const FEW_PACKETS: usize = 10;

/// The share of an error-triggered drone's packets lost above which its silence misleads the
/// station: the drone cannot tell a lost packet from a delivered one, so after a loss it stays
/// silent while the station drifts (docs/senders.md: at 3 km the p95 up to 1.23× that of
/// periodic sending at the same airtime, on the real flight 2.1×).
pub const SILENCE_LOSS: f64 = 0.05;

/// The caveats on one station's result.
///
/// ```
/// use loratrack::{Caveats, Saturation, SenderKind};
/// // 14 of 21 packets received.
/// let c = Caveats::of(14, 21, SenderKind::Error, Saturation::default());
/// assert!(c.silence_after_loss && !c.few_packets);
/// assert!(!Caveats::of(14, 21, SenderKind::Periodic, Saturation::default()).silence_after_loss);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Caveats {
    /// Fewer than [`FEW_PACKETS`] packets received.
    pub few_packets: bool,
    /// Error-triggered sending, more than [`SILENCE_LOSS`] of its packets lost.
    pub silence_after_loss: bool,
    /// Received packets that carried a value beyond its payload field's range, sent as the
    /// range's edge ([`SaturatedFields`]; the payload is sized for a quadcopter, reference §5):
    /// the station started from a state other than the drone's estimate.
    pub saturated_packets: usize,
    /// The fields those packets saturated, in state order (empty when none did).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "string[]"))]
    pub saturated: SaturatedFields,
}

impl Caveats {
    /// The caveats on a station whose run's drone sent `sent` packets by `sender`, of which
    /// `received` arrived, `saturation` of them with a saturated field.
    pub fn of(received: usize, sent: usize, sender: SenderKind, saturation: Saturation) -> Self {
        // In packets, not as 1 − received / sent, whose rounding puts 5 lost of 100 above 5 %.
        let lost = sent.saturating_sub(received) as f64;
        Caveats {
            few_packets: received < FEW_PACKETS,
            silence_after_loss: sender == SenderKind::Error && lost > SILENCE_LOSS * sent as f64,
            saturated_packets: saturation.packets,
            saturated: saturation.fields,
        }
    }
}

/// Received packets that saturated a payload field, counted packet by packet: a [`Caveats`]'
/// `saturated_packets` and `saturated`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Saturation {
    /// Received packets with a saturated field.
    pub packets: usize,
    /// The fields they saturated.
    pub fields: SaturatedFields,
}

impl Saturation {
    /// Counts `t` if it was received and saturated a field. A speed below zero, sent as 0, is not
    /// counted: it is a hovering drone's filter noise (at most 0.7 m/s below zero on the
    /// synthetic set, in about 5 % of its packets), and a hover is what 0 says.
    pub fn count(&mut self, t: &Transmission) {
        let mut fields = t.saturated;
        if t.state[V] == 0.0 {
            fields.remove(V);
        }
        if t.received && !fields.is_empty() {
            self.packets += 1;
            self.fields = self.fields.union(fields);
        }
    }

    /// `tx`'s received packets that saturated a field.
    pub fn of<'a>(tx: impl IntoIterator<Item = &'a Transmission>) -> Self {
        let mut s = Saturation::default();
        tx.into_iter().for_each(|t| s.count(t));
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A packet, `received` or lost, that saturated `fields` (indices in `FIELDS`) and decodes to
    /// speed `v`.
    fn saturating(fields: &[usize], v: f64, received: bool) -> Transmission {
        let mut t = crate::sim::station::tests::frames(if received { "1" } else { "0" }).remove(0);
        fields.iter().for_each(|&i| t.saturated.insert(i));
        t.state[V] = v;
        t
    }

    #[test]
    fn received_packets_that_saturated_a_field_are_counted_with_their_fields() {
        let tx = [
            saturating(&[V], 25.5, true),
            saturating(&[7], 12.0, true),
            saturating(&[], 12.0, true),
            saturating(&[0, V], 25.5, false),
        ];
        let s = Saturation::of(&tx);
        assert_eq!(s.packets, 2);
        assert_eq!(s.fields.names().collect::<Vec<_>>(), ["v", "omega"]);
        let c = Caveats::of(3, 4, SenderKind::Periodic, s);
        assert_eq!((c.saturated_packets, c.saturated), (2, s.fields));
    }

    #[test]
    fn a_hovering_drones_speed_below_zero_sent_as_zero_is_not_counted() {
        assert_eq!(Saturation::of(&[saturating(&[V], 0.0, true)]).packets, 0);
        let with_turn = Saturation::of(&[saturating(&[V, 7], 0.0, true)]);
        assert_eq!(with_turn.fields.names().collect::<Vec<_>>(), ["omega"]);
    }

    #[test]
    fn under_ten_received_packets_are_too_few_to_compare() {
        assert!(Caveats::of(9, 9, SenderKind::Periodic, Saturation::default()).few_packets);
        assert!(!Caveats::of(10, 30, SenderKind::Periodic, Saturation::default()).few_packets);
        assert!(Caveats::of(0, 0, SenderKind::Periodic, Saturation::default()).few_packets);
    }

    #[test]
    fn only_an_error_triggered_drone_that_lost_over_5_percent_is_misled_by_its_silence() {
        let error =
            |r, s| Caveats::of(r, s, SenderKind::Error, Saturation::default()).silence_after_loss;
        assert!(error(94, 100));
        assert!(!error(95, 100));
        assert!(!error(0, 0));
        assert!(
            !Caveats::of(50, 100, SenderKind::Periodic, Saturation::default()).silence_after_loss
        );
    }
}
