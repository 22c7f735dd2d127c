//! Stations of one run whose packets the link delivered unlike: where the difference in their
//! errors is partly the link's, not the models' (README "The playground"; the CLI's lines under
//! its table and the page's notes both read it, beside [`Caveats`](super::Caveats)).

use super::report::Delivery;
use super::station::StationModel;
use serde::Serialize;

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
}
