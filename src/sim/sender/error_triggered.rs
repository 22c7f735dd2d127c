//! Error-triggered sending: the drone runs the station's own predictor on what it sent and sends
//! when that belief has drifted from its own estimate (the paper's future work, §V; reference
//! §4, "Station under an error-triggered drone").

use super::{ChannelLoad, ChannelSense, Sender};
use crate::math::distance;
use crate::sim::station::{new_tracker, MissionPlan, StationModel, StationSetup, Tracker};

/// The drone mirrors the station: a [`Tracker`] of the station's kind (same model, same
/// prediction setting, told that the drone sends on error), reset to each packet's decoded —
/// quantised — state and stepped every T from it, as the station steps between packets. It
/// wants to send when the mirror's position is more than `threshold` m from its own estimate, or
/// when `max_interval` s have passed since its last packet (a heartbeat, so that a lost packet,
/// which an unconfirmed uplink cannot reveal, is repaired). The mirror assumes every packet
/// arrived (and so that the station trusts the silence after it). Before its first packet the
/// drone always wants to send: the station knows nothing yet.
///
/// What makes this pay at equal airtime is a station whose forecast holds while nothing
/// happens: a bounded station (`--prediction bounded`) under an error-triggered drone does not
/// lag behind a straight line ([`StationSetup::error_triggered`]), so the drone sends in turns,
/// climbs and stops and stays quiet in between (docs/senders.md).
pub struct ErrorTriggered {
    mirror: Box<dyn Tracker>,
    /// The station's step T, s, and the time the mirror has been stepped to.
    step: f64,
    clock: f64,
    threshold: f64,
    max_interval: f64,
    last: Option<f64>,
    /// What it has heard of its channel, when it listens ([`ChannelSense::Cad`]).
    load: Option<ChannelLoad>,
}

impl ErrorTriggered {
    /// A sender mirroring a station of `model` with `setup`, with `threshold` in m and
    /// `max_interval` in s, listening to its channel as `sense` says.
    pub fn new(
        model: StationModel,
        setup: StationSetup,
        plan: Option<&MissionPlan>,
        (threshold, max_interval): (f64, f64),
        sense: ChannelSense,
    ) -> Self {
        // The drone compares the mirror's position alone with its own estimate.
        let mut mirror = new_tracker(model, setup, plan);
        mirror.ignore_uncertainty();
        ErrorTriggered {
            mirror,
            step: setup.step,
            clock: 0.0,
            threshold,
            max_interval,
            last: None,
            load: (sense == ChannelSense::Cad).then(ChannelLoad::default),
        }
    }

    /// The mirror's position at `t` s, stepped there every T from the last packet.
    fn mirror_at(&mut self, t: f64) -> [f64; 3] {
        while self.clock + self.step < t - 1e-9 {
            self.clock += self.step;
            self.mirror.predict_to(self.clock);
        }
        self.clock = self.clock.max(t);
        self.mirror.predict_to(t);
        self.mirror.position()
    }
}

impl Sender for ErrorTriggered {
    fn wants_to_send(&mut self, t: f64, own: &[f64; 9]) -> bool {
        let Some(last) = self.last else {
            return true;
        };
        if t - last >= self.max_interval - 1e-9 {
            return true;
        }
        let threshold = match &self.load {
            Some(load) => load.threshold(self.threshold),
            None => self.threshold,
        };
        distance(&self.mirror_at(t), &[own[0], own[1], own[2]]) > threshold
    }

    fn listens(&self) -> bool {
        self.load.is_some()
    }

    fn channel_sensed(&mut self, busy: bool) {
        if let Some(load) = &mut self.load {
            load.sensed(busy);
        }
    }

    fn data_rate_changed(&mut self, interval: f64) {
        self.mirror.set_interval(interval);
    }

    fn sent(&mut self, state: &[f64; 9], t: f64) {
        self.mirror.reset(state, t);
        self.clock = t;
        self.last = Some(t);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};
    use crate::models::ModelKind;
    use crate::sim::station::{Bounds, Prediction};

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
            error_triggered: true,
            drone_covariance: None,
        };
        ErrorTriggered::new(
            StationModel::Single(ModelKind::Dr),
            setup,
            None,
            (threshold, 10.0),
            ChannelSense::Off,
        )
    }

    #[test]
    fn a_listening_drone_that_hears_a_busy_channel_waits_for_a_larger_drift() {
        let setup = StationSetup {
            prediction: Prediction::Paper,
            bounds: Bounds::default(),
            step: 0.1,
            eta: 0.9,
            q: 1e-4,
            r_diagonal: PAPER_R_DIAGONAL,
            interval: 2.0,
            error_triggered: true,
            drone_covariance: None,
        };
        let still = [0.0, 0.0, 30.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        let moved = [3.0, 0.0, 30.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
        for (sense, busy, wants) in [
            (ChannelSense::Off, true, true),
            (ChannelSense::Cad, false, true),
            (ChannelSense::Cad, true, false),
        ] {
            let mut s = ErrorTriggered::new(
                StationModel::Single(ModelKind::Dr),
                setup,
                None,
                (2.0, 60.0),
                sense,
            );
            s.sent(&still, 0.0);
            for _ in 0..30 {
                s.channel_sensed(busy);
            }
            // 3 m off: past 2 m, short of 2 m / (1 - b)² once most starts were busy.
            assert_eq!(
                s.wants_to_send(1.0, &moved),
                wants,
                "{sense:?}, busy {busy}"
            );
        }
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
            if s.wants_to_send(t, &st) {
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
        assert!(!s.wants_to_send(1.0, &[5.0, 1.5, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0]));
        assert!(s.wants_to_send(1.1, &[5.5, 2.5, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0]));
    }

    /// The mirror steps every T as the station does, however far apart the drone asks: asked
    /// once after 2 s it must stand where a station stepped 20 times stands.
    #[test]
    fn the_mirror_steps_as_the_station_does() {
        let packet = [0.0, 0.0, 30.0, 0.0, 0.0, 5.0, 0.0, 0.0, 0.0];
        let mut s = sender(2.0, PAPER_Q);
        s.sent(&packet, 0.0);
        let jumped = s.mirror_at(2.0);
        let mut station = sender(2.0, PAPER_Q).mirror;
        station.reset(&packet, 0.0);
        for k in 1..=20 {
            station.predict_to(0.1 * k as f64);
        }
        let stepped = station.position();
        assert!(distance(&jumped, &stepped) < 1e-9, "{jumped:?} {stepped:?}");
        let mut once = sender(2.0, PAPER_Q).mirror;
        once.reset(&packet, 0.0);
        once.predict_to(2.0);
        assert!(
            distance(&once.position(), &stepped) > 1e-3,
            "one 2-s step differs"
        );
    }
}
