//! What a station's numbers rest on, where a reader could be misled by them: the flags that the
//! CLI's lines under its table and the page's notes under its results both read, so that both say
//! it for the same runs (README "The playground"; the untracked time is
//! [`WholeFlightError::partly_tracked`](crate::WholeFlightError::partly_tracked)).

use super::sender::SenderKind;
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
/// use loratrack::{Caveats, SenderKind};
/// // 14 of 21 packets received.
/// let c = Caveats::of(14, 21, SenderKind::Error);
/// assert!(c.silence_after_loss && !c.few_packets);
/// assert!(!Caveats::of(14, 21, SenderKind::Periodic).silence_after_loss);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Caveats {
    /// Fewer than [`FEW_PACKETS`] packets received.
    pub few_packets: bool,
    /// Error-triggered sending, more than [`SILENCE_LOSS`] of its packets lost.
    pub silence_after_loss: bool,
}

impl Caveats {
    /// The caveats on a station whose run's drone sent `sent` packets by `sender`, of which
    /// `received` arrived.
    pub fn of(received: usize, sent: usize, sender: SenderKind) -> Self {
        // In packets, not as 1 − received / sent, whose rounding puts 5 lost of 100 above 5 %.
        let lost = sent.saturating_sub(received) as f64;
        Caveats {
            few_packets: received < FEW_PACKETS,
            silence_after_loss: sender == SenderKind::Error && lost > SILENCE_LOSS * sent as f64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn under_ten_received_packets_are_too_few_to_compare() {
        assert!(Caveats::of(9, 9, SenderKind::Periodic).few_packets);
        assert!(!Caveats::of(10, 30, SenderKind::Periodic).few_packets);
        assert!(Caveats::of(0, 0, SenderKind::Periodic).few_packets);
    }

    #[test]
    fn only_an_error_triggered_drone_that_lost_over_5_percent_is_misled_by_its_silence() {
        let error = |r, s| Caveats::of(r, s, SenderKind::Error).silence_after_loss;
        assert!(error(94, 100));
        assert!(!error(95, 100));
        assert!(!error(0, 0));
        assert!(!Caveats::of(50, 100, SenderKind::Periodic).silence_after_loss);
    }
}
