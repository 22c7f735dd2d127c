//! What a station's numbers rest on, where a reader could be misled by them: the flags that the
//! CLI's lines under its table and the page's notes under its results both read, so that both say
//! it for the same runs (README "The playground"; the untracked time is
//! [`WholeFlightError::partly_tracked`](crate::WholeFlightError::partly_tracked)).

use super::report::Delivery;
use super::sender::SenderKind;
use super::station::StationModel;
use serde::Serialize;

/// Fewer received packets than this, and a station's statistics are too thin to compare with
/// another's: a p75 over a handful of packets is mostly the luck of where they fell.
pub const FEW_PACKETS: usize = 10;

/// The share of an error-triggered drone's packets lost above which its silence misleads the
/// station: the drone cannot tell a lost packet from a delivered one, so after a loss it stays
/// silent while the station drifts (docs/senders.md: at 3 km the p95 up to 1.06× that of
/// periodic sending at the same airtime, on the real flight the p75 up to 3×).
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

/// Delivery ratios further apart than this, between the stations of one run, and part of the
/// difference in their errors is the link's, not the models'.
pub const DELIVERY_SPREAD: f64 = 0.05;

/// Two stations of one run whose packets the link delivered at rates more than
/// [`DELIVERY_SPREAD`] apart. Stations whose payloads differ in length send at other moments
/// (each waits its own time on air × 99), and the shadowing, correlated along the flight, fades
/// other packets for each: on the real Canberra flight at SF7 / 125 kHz and 3.3 km DR's frames
/// arrived 91 % of the time and CTRA+'s 84 % (16 seeds), and CTRA+'s p95 was 1.64× DR's, but
/// 1.04× that of DR sending frames as long as CTRA+'s, which lose the same packets
/// (docs/paper-reproduction.md, "The real flight at every data rate").
///
/// ```
/// use loratrack::{Delivery, DeliverySpread, ModelKind, StationModel};
/// let sent = |received| Delivery { packets_sent: 100, packets_received: received, delivery_ratio: received as f64 / 100.0, ..Delivery::default() };
/// let (dr, ctra) = (StationModel::Single(ModelKind::Dr), StationModel::Single(ModelKind::CtraPlus));
/// let spread = DeliverySpread::of([(dr, &sent(91)), (ctra, &sent(84))]).unwrap();
/// assert_eq!((spread.lowest, spread.highest), (ctra, dr));
/// assert!(DeliverySpread::of([(dr, &sent(91)), (ctra, &sent(88))]).is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct DeliverySpread {
    /// The station whose packets arrived least often.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub lowest: StationModel,
    /// Its delivery ratio, 0..1.
    pub lowest_ratio: f64,
    /// The station whose packets arrived most often.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "ModelName"))]
    pub highest: StationModel,
    /// Its delivery ratio, 0..1.
    pub highest_ratio: f64,
}

impl DeliverySpread {
    /// From each station's model and delivery: `None` unless the delivery ratios of the stations
    /// that sent anything lie more than [`DELIVERY_SPREAD`] apart.
    pub fn of<'a>(
        stations: impl IntoIterator<Item = (StationModel, &'a Delivery)>,
    ) -> Option<Self> {
        let sent: Vec<(StationModel, f64)> = stations
            .into_iter()
            .filter(|(_, d)| d.packets_sent > 0)
            .map(|(m, d)| (m, d.delivery_ratio))
            .collect();
        let lowest = sent.iter().min_by(|a, b| a.1.total_cmp(&b.1))?;
        let highest = sent.iter().max_by(|a, b| a.1.total_cmp(&b.1))?;
        (highest.1 - lowest.1 > DELIVERY_SPREAD).then_some(DeliverySpread {
            lowest: lowest.0,
            lowest_ratio: lowest.1,
            highest: highest.0,
            highest_ratio: highest.1,
        })
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
    fn stations_whose_delivery_differs_by_over_five_points_are_named_and_silent_ones_ignored() {
        use crate::models::ModelKind;
        let d = |sent, received| Delivery {
            packets_sent: sent,
            packets_received: received,
            delivery_ratio: if sent == 0 {
                0.0
            } else {
                received as f64 / sent as f64
            },
            ..Delivery::default()
        };
        let [dr, ctra, imm] = [
            StationModel::Single(ModelKind::Dr),
            StationModel::Single(ModelKind::CtraPlus),
            StationModel::Imm,
        ];
        let s = DeliverySpread::of([(dr, &d(100, 95)), (ctra, &d(100, 80)), (imm, &d(100, 90))]);
        let s = s.unwrap();
        assert_eq!((s.lowest, s.highest), (ctra, dr));
        assert!((s.lowest_ratio - 0.8).abs() < 1e-12 && (s.highest_ratio - 0.95).abs() < 1e-12);
        // Five points apart is within chance; a station that sent nothing says nothing.
        assert!(DeliverySpread::of([(dr, &d(100, 95)), (ctra, &d(100, 90))]).is_none());
        assert!(DeliverySpread::of([(dr, &d(100, 95)), (ctra, &d(0, 0))]).is_none());
        assert!(DeliverySpread::of([]).is_none());
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
