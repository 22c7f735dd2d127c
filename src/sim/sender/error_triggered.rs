//! Error-triggered sending: the drone runs the station's own predictor on what it sent and sends
//! when that belief has drifted from its own estimate (the paper's future work, §V).

use super::Sender;
use crate::math::distance;
use crate::sim::station::Tracker;

/// The drone mirrors the station: a [`Tracker`] of the station's kind (same model, same
/// prediction setting), reset to each packet's decoded — quantised — state. It wants to send
/// when the mirror's position is more than `threshold` m from its own estimate, or when
/// `max_interval` s have passed since its last packet (a heartbeat, so that a lost packet, which
/// an unconfirmed uplink cannot reveal, is repaired). The mirror assumes every packet arrived.
/// Before its first packet the drone always wants to send: the station knows nothing yet.
pub struct ErrorTriggered {
    mirror: Box<dyn Tracker>,
    threshold: f64,
    max_interval: f64,
    last: Option<f64>,
}

impl ErrorTriggered {
    /// A sender mirroring `mirror` (a fresh station), with `threshold` in m and `max_interval`
    /// in s.
    pub fn new(mirror: Box<dyn Tracker>, threshold: f64, max_interval: f64) -> Self {
        ErrorTriggered {
            mirror,
            threshold,
            max_interval,
            last: None,
        }
    }
}

impl Sender for ErrorTriggered {
    fn wants_to_send(&mut self, t: f64, own: &[f64; 3]) -> bool {
        let Some(last) = self.last else {
            return true;
        };
        if t - last >= self.max_interval - 1e-9 {
            return true;
        }
        self.mirror.predict_to(t);
        distance(&self.mirror.position(), own) > self.threshold
    }

    fn data_rate_changed(&mut self, interval: f64) {
        self.mirror.set_interval(interval);
    }

    fn sent(&mut self, state: &[f64; 9], t: f64) {
        self.mirror.reset(state, t);
        self.last = Some(t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};
    use crate::models::ModelKind;
    use crate::sim::station::{new_tracker, Bounds, Prediction, StationModel, StationSetup};

    /// A sender mirroring a DR station with process noise `q` per second.
    fn sender(threshold: f64, q: f64) -> ErrorTriggered {
        let setup = StationSetup {
            prediction: Prediction::Paper,
            bounds: Bounds::default(),
            step: 0.1,
            eta: 0.9,
            q,
            r_diagonal: PAPER_R_DIAGONAL,
            interval: 2.0,
            drone_covariance: None,
        };
        let mirror = new_tracker(StationModel::Single(ModelKind::Dr), setup);
        ErrorTriggered::new(mirror, threshold, 10.0)
    }

    /// With little process noise the DR station predicts a straight line exactly. (With the
    /// paper's q = 0.1 per second the UKF's heading spread makes its mean lag about 1 m behind a
    /// 5 m/s line after 2 s, so even a straight flight trips a 1 m threshold.)
    #[test]
    fn a_straight_line_needs_only_heartbeats() {
        let mut s = sender(1.0, 1e-4);
        let state = |t: f64| [5.0 * t, 0.0, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0];
        let mut sends = Vec::new();
        for k in 0..600 {
            let t = 0.1 * k as f64;
            let st = state(t);
            if s.wants_to_send(t, &[st[0], st[1], st[2]]) {
                s.sent(&st, t);
                sends.push(t);
            }
        }
        assert_eq!(sends.len(), 6, "{sends:?}");
        for w in sends.windows(2) {
            assert!((w[1] - w[0] - 10.0).abs() < 0.11, "{sends:?}");
        }
    }

    #[test]
    fn a_drift_beyond_the_threshold_triggers_a_packet() {
        let mut s = sender(2.0, PAPER_Q);
        s.sent(&[0.0, 0.0, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0], 0.0);
        assert!(!s.wants_to_send(1.0, &[5.0, 1.5, 30.0]));
        assert!(s.wants_to_send(1.1, &[5.5, 2.5, 30.0]));
    }
}
