//! An Interacting Multiple Model station over DR, CTRA+ and 3D-CTRA (Blom & Bar-Shalom 1988;
//! Bar-Shalom, Li & Kirubarajan 2001, §11.6).

use super::{
    received, start_from, ManoeuvreEvidence, Received, StationPredictor, StationSetup, Tracker,
    Upcoming,
};
use crate::math::exp;
use crate::models::{with_model, ModelKind, MotionModel};
use crate::parallel::{par_map, par_map_owned};
use crate::sim::packet::Transmission;
use nalgebra::{Matrix3, Vector3};

/// Probability that the drone keeps flying the manoeuvre one model describes from one packet to
/// the next; the rest is shared evenly among the other models. 0.9: manoeuvres of the synthetic
/// flights last 4–14 s, about two to five packet intervals at SF7, so a switch at one packet in
/// ten is the right order; lower values make the probabilities jumpy, higher ones slow to follow.
pub const IMM_STAY: f64 = 0.9;

/// An IMM member: a station predictor whose prediction can be scored against a packet.
pub trait ImmMember: Tracker + Send + Sync {
    /// See [`StationPredictor::log_likelihood`].
    fn log_likelihood(&self, z: &[f64; 9], sent: f64) -> f64;
    /// The log-likelihood of received packet `now` under a copy of this member as it stands
    /// when `now` arrives after `before`: reset to `before`, at `now`'s interval and with the
    /// station's trust in the silence after `now` ([`Tracker::trust_silence`]).
    fn forecast(&self, before: &Transmission, now: &Transmission, silence_trusted: bool) -> f64;
    /// A copy, to run ahead without moving this one ([`Tracker::look_ahead`]).
    fn boxed(&self) -> Box<dyn ImmMember>;
}

impl<const N: usize, M: MotionModel<N> + Copy + Send + Sync + 'static> ImmMember
    for StationPredictor<N, M>
{
    fn log_likelihood(&self, z: &[f64; 9], sent: f64) -> f64 {
        StationPredictor::log_likelihood(self, z, sent)
    }

    fn forecast(&self, before: &Transmission, now: &Transmission, silence_trusted: bool) -> f64 {
        let mut m = self.clone();
        m.reset(&before.state, before.sent);
        // start_from sets these before the reset whose probabilities the forecast scores.
        m.set_interval(now.interval);
        m.trust_silence(silence_trusted);
        m.log_likelihood(&now.state, now.sent)
    }

    fn boxed(&self) -> Box<dyn ImmMember> {
        Box::new(self.clone())
    }
}

fn member<const N: usize, M: MotionModel<N> + Copy + Send + Sync + 'static>(
    model: M,
    setup: StationSetup,
) -> Box<dyn ImmMember> {
    Box::new(StationPredictor::new(model, setup))
}

/// The IMM station. The drone sends the full 3D-CTRA state; every member is reset to (its part
/// of) each packet and predicts alone between packets, and the station reports the mixture.
///
/// Because every member restarts from the same received state, the IMM's interaction (mixing)
/// step is exact and trivial here; what remains is the model-probability cycle, once per packet:
///
/// ```text
/// c_j  = Σ_i π_ij μ_i                      (Markov prediction, π_ii = IMM_STAY)
/// μ_j ∝ c_j · Λ_j · M_j                    (Λ_j: the new packet forecast by model j from the last;
///                                           M_j: the packet's a, ω, ψ under model j)
/// x̂   = Σ_j μ_j x̂_j,  P = Σ_j μ_j (P_j + (x̂_j − x̂)(x̂_j − x̂)ᵀ)   (between packets, positions)
/// ```
///
/// Λ is evidence about the interval just flown; M ([`ManoeuvreEvidence`]) about the manoeuvre the
/// drone is flying as the packet leaves, which the coming interval continues. Without M the
/// probabilities learnt a manoeuvre one packet after it began and stayed near their prior (DR
/// kept a fifth to a half), and the IMM's p75 was 1.03–1.08× its best member's on the paper's
/// grid; with it 0.91–0.98× (docs/paper-reproduction.md). The first packet, with nothing to
/// forecast it from, is scored by M alone.
pub struct Imm {
    members: Vec<Box<dyn ImmMember>>,
    kinds: Vec<ModelKind>,
    probability: Vec<f64>,
    evidence: ManoeuvreEvidence,
    started: bool,
    /// The send time of the packet the members were last reset to.
    last_sent: f64,
    /// Each member's log-likelihood of the received packets, forecast from the packet before
    /// each ([`Tracker::prepare`]), in time order, and how many of them have been passed.
    forecasts: Vec<Forecast>,
    passed: usize,
    /// The members' estimates at the evaluation times of the next packets, computed ahead
    /// ([`Tracker::look_ahead`]).
    ahead: Option<Ahead>,
}

/// Evaluation times a batch of [`Tracker::look_ahead`] covers at least (if the packets last
/// that long): each member's share is then milliseconds of work, on a core of its own.
const AHEAD_TIMES: usize = 4096;

/// A member's position (m) and its covariance (m²) at one time.
type MemberEstimate = ([f64; 3], Matrix3<f64>);

/// Each member's position and its covariance at the evaluation times of a run of packets, and
/// where the station stands in it.
struct Ahead {
    /// Per packet: its send time (s) and evaluation times (s).
    packets: Vec<(f64, Vec<f64>)>,
    /// Per member, per packet, per time.
    at: Vec<Vec<Vec<MemberEstimate>>>,
    /// The packet the members were last reset to, and the time reached after it, if in `packets`.
    now: Option<(usize, Option<usize>)>,
}

/// The members' log-likelihoods of the packet sent at `to`, forecast from the one sent at `from`.
struct Forecast {
    from: f64,
    to: f64,
    log_l: Vec<f64>,
}

impl Imm {
    /// An IMM over `models` (each at most once; the paper's three for `--model imm`), starting
    /// from equal probabilities.
    pub fn new(models: &[ModelKind], setup: StationSetup) -> Self {
        let members = models
            .iter()
            .map(|&m| with_model!(m, member(setup)))
            .collect::<Vec<_>>();
        let n = members.len().max(1) as f64;
        Imm {
            members,
            kinds: models.to_vec(),
            probability: vec![1.0 / n; models.len()],
            evidence: ManoeuvreEvidence::new(&setup),
            started: false,
            last_sent: f64::NAN,
            forecasts: Vec::new(),
            passed: 0,
            ahead: None,
        }
    }

    /// Each member's position and its covariance now, in the members' order: from what
    /// [`Tracker::look_ahead`] computed where it covers the time reached, else the members'.
    fn member_estimates(&self) -> Vec<MemberEstimate> {
        if let Some(Ahead {
            at,
            now: Some((p, Some(k))),
            ..
        }) = &self.ahead
        {
            return at.iter().map(|m| m[*p][*k]).collect();
        }
        self.members
            .iter()
            .map(|m| (m.position(), m.position_covariance()))
            .collect()
    }

    /// The probability-weighted mean of the members' positions `members` (as
    /// [`Self::member_estimates`] gives them), m.
    fn mixed_position(&self, members: &[MemberEstimate]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for ((q, _), mu) in members.iter().zip(&self.probability) {
            for k in 0..3 {
                p[k] += mu * q[k];
            }
        }
        p
    }

    /// The current model probabilities, in the order of `new`'s models.
    pub fn probabilities(&self) -> &[f64] {
        &self.probability
    }

    /// The model probabilities after packet `z` sent at `sent` (the members not yet reset to it).
    fn update_probabilities(&mut self, z: &[f64; 9], sent: f64) {
        let n = self.members.len();
        let (predicted, forecast) = if self.started {
            (
                self.markov_prediction(),
                self.forecast_log_likelihoods(z, sent),
            )
        } else {
            (self.probability.clone(), vec![0.0; n])
        };
        let log_l: Vec<f64> = forecast
            .iter()
            .zip(&self.kinds)
            .map(|(f, &kind)| f + self.evidence.log_likelihood(kind, z))
            .collect();
        let best = log_l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !best.is_finite() {
            // No member could score the packet: keep the Markov prediction alone.
            self.probability = predicted;
            return;
        }
        let weights: Vec<f64> = (0..n)
            .map(|j| predicted[j] * exp(log_l[j] - best))
            .collect();
        let sum: f64 = weights.iter().sum();
        self.probability = weights.iter().map(|w| w / sum).collect();
    }

    /// c_j = Σ_i π_ij μ_i, with π: IMM_STAY on the diagonal, the rest shared evenly (one member
    /// always stays).
    fn markov_prediction(&self) -> Vec<f64> {
        let n = self.members.len();
        let (stay, off) = if n > 1 {
            (IMM_STAY, (1.0 - IMM_STAY) / (n - 1) as f64)
        } else {
            (1.0, 0.0)
        };
        let total: f64 = self.probability.iter().sum();
        (0..n)
            .map(|j| stay * self.probability[j] + off * (total - self.probability[j]))
            .collect()
    }

    /// Each member's log-likelihood of the packet, forecast from the one before.
    fn forecast_log_likelihoods(&mut self, z: &[f64; 9], sent: f64) -> Vec<f64> {
        match self.prepared(sent) {
            Some(log_l) => log_l,
            None => self
                .members
                .iter()
                .map(|m| m.log_likelihood(z, sent))
                .collect(),
        }
    }
}

impl Imm {
    /// The members' log-likelihoods of the packet sent at `sent` as [`Tracker::prepare`]
    /// forecast them, when it forecast this packet from the one the members were reset to (a
    /// packet that arrived in the same step as a newer one is never applied; the newer one is
    /// then forecast in order).
    fn prepared(&mut self, sent: f64) -> Option<Vec<f64>> {
        while self.forecasts.get(self.passed).is_some_and(|f| f.to < sent) {
            self.passed += 1;
        }
        let f = self.forecasts.get(self.passed)?;
        (f.to == sent && f.from == self.last_sent).then(|| f.log_l.clone())
    }
}

impl Tracker for Imm {
    /// Forecasts every received packet from the one before under each member, in parallel:
    /// a forecast depends only on the two packets (a member's forecast restarts from its last
    /// packet), and it is half of what an IMM station computes.
    fn prepare(&mut self, transmissions: &[Transmission]) {
        let packets = received(transmissions);
        let members = &self.members;
        self.forecasts = par_map(1..packets.len().max(1), |k| {
            let (before, now) = (packets[k - 1].packet, &packets[k]);
            let log_l = members
                .iter()
                .map(|m| m.forecast(before, now.packet, now.silence_trusted))
                .collect();
            Forecast {
                from: before.sent,
                to: now.packet.sent,
                log_l,
            }
        });
        self.passed = 0;
    }

    fn reset(&mut self, state: &[f64; 9], sent: f64) {
        self.update_probabilities(state, sent);
        self.started = true;
        self.last_sent = sent;
        for m in &mut self.members {
            m.reset(state, sent);
        }
        if let Some(a) = &mut self.ahead {
            a.now = a
                .packets
                .iter()
                .position(|(s, _)| *s == sent)
                .map(|p| (p, None));
        }
    }

    /// Runs copies of the members through the next packets' evaluation times (at least
    /// `AHEAD_TIMES` of them), each member on a core of its own, unless the last batch
    /// covers this packet: between packets each member predicts alone, and one after another
    /// they were the longest sequential work of a long flight. The members themselves only
    /// reset; `predict_to` then reads the batch.
    fn look_ahead(&mut self, upcoming: &Upcoming) {
        let mut batch = Vec::new();
        let mut times = 0;
        for (packet, silence_trusted, served) in upcoming.packets() {
            if batch.is_empty()
                && self
                    .ahead
                    .as_ref()
                    .is_some_and(|a| a.packets.iter().any(|(s, _)| *s == packet.sent))
            {
                return;
            }
            times += served.len();
            let received = Received {
                packet,
                silence_trusted,
            };
            batch.push((received, served));
            if times >= AHEAD_TIMES {
                break;
            }
        }
        // The largest state first: this thread runs it while the others are taken by an idle
        // core (3D-CTRA's predictions alone cost about as much as CTRA+'s and DR's together).
        let mut order: Vec<usize> = (0..self.members.len()).collect();
        order.sort_by_key(|&i| core::cmp::Reverse(self.kinds[i].state_len()));
        let copies: Vec<(usize, Box<dyn ImmMember>)> = order
            .iter()
            .map(|&i| (i, self.members[i].boxed()))
            .collect();
        let mut done = par_map_owned(copies, |(i, mut m)| {
            let at: Vec<Vec<MemberEstimate>> = batch
                .iter()
                .map(|(received, served)| {
                    start_from(m.as_mut(), received);
                    served
                        .iter()
                        .map(|&t| {
                            m.predict_to(t);
                            (m.position(), m.position_covariance())
                        })
                        .collect()
                })
                .collect();
            (i, at)
        });
        done.sort_by_key(|&(i, _)| i);
        let at = done.into_iter().map(|(_, at)| at).collect();
        self.ahead = Some(Ahead {
            packets: batch
                .into_iter()
                .map(|(r, served)| (r.packet.sent, served))
                .collect(),
            at,
            now: None,
        });
    }

    fn predict_to(&mut self, t: f64) {
        if let Some(Ahead {
            packets,
            now: Some((p, reached)),
            ..
        }) = &mut self.ahead
        {
            let from = reached.unwrap_or(0);
            if let Some(k) = packets[*p].1[from..].iter().position(|&s| s == t) {
                *reached = Some(from + k);
                return;
            }
        }
        // A time the batch does not hold (an IMM not scored by track_station, or a packet
        // outside the batch): the members predict, from the packet they were reset to.
        if let Some(a) = &mut self.ahead {
            a.now = None;
        }
        for m in &mut self.members {
            m.predict_to(t);
        }
    }

    fn set_interval(&mut self, interval: f64) {
        for m in &mut self.members {
            m.set_interval(interval);
        }
    }

    fn trust_silence(&mut self, trusted: bool) {
        for m in &mut self.members {
            m.trust_silence(trusted);
        }
    }

    /// The mixture's position is the members' positions weighted by probabilities that the
    /// packets' forecasts decide, so a member's covariance never reaches it.
    fn ignore_uncertainty(&mut self) {
        for m in &mut self.members {
            m.ignore_uncertainty();
        }
    }

    fn position(&self) -> [f64; 3] {
        self.mixed_position(&self.member_estimates())
    }

    fn position_covariance(&self) -> Matrix3<f64> {
        let members = self.member_estimates();
        let mean = Vector3::from(self.mixed_position(&members));
        members
            .iter()
            .zip(&self.probability)
            .map(|((q, c), mu)| {
                let d = Vector3::from(*q) - mean;
                (c + d * d.transpose()) * *mu
            })
            .sum()
    }

    fn model_probabilities(&self) -> Option<[f64; 3]> {
        let mut out = [0.0; 3];
        for (k, mu) in self.kinds.iter().zip(&self.probability) {
            out[k.index()] = *mu;
        }
        Some(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::station::tests::paper_setup as setup;
    use crate::sim::station::Prediction;

    /// Packets of a drone on a steady turn, 2 s apart.
    fn turn(k: usize) -> [f64; 9] {
        let t = 2.0 * k as f64;
        let (r, w) = (20.0, 0.3);
        let th = w * t;
        [
            r * crate::math::sin(th),
            r - r * crate::math::cos(th),
            50.0,
            crate::math::wrap_angle(th),
            0.0,
            r * w,
            0.0,
            w,
            0.0,
        ]
    }

    #[test]
    fn one_member_reduces_to_that_member() {
        let mut imm = Imm::new(&[ModelKind::CtraPlus], setup());
        let mut alone = StationPredictor::new(crate::models::CtraPlus, setup());
        for k in 0..5 {
            imm.reset(&turn(k), 2.0 * k as f64);
            alone.reset(&turn(k), 2.0 * k as f64);
            for j in 1..=20 {
                let t = 2.0 * k as f64 + 0.1 * j as f64;
                imm.predict_to(t);
                alone.predict_to(t);
                assert_eq!(imm.position(), alone.position());
                assert_eq!(imm.position_covariance(), alone.position_covariance());
            }
        }
        assert_eq!(imm.probabilities(), &[1.0]);
    }

    #[test]
    fn probabilities_stay_a_distribution_and_favour_the_turning_models_in_a_turn() {
        let mut imm = Imm::new(&ModelKind::ALL, setup());
        for k in 0..10 {
            imm.reset(&turn(k), 2.0 * k as f64);
            imm.predict_to(2.0 * k as f64 + 2.0);
            let p = imm.probabilities();
            assert!(p.iter().all(|x| (0.0..=1.0).contains(x)), "{p:?}");
            assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{p:?}");
        }
        let p = imm.probabilities();
        assert!(p[0] < 0.1, "DR should lose a steady turn: {p:?}");
    }

    /// Flight 2's state every 2 s at intervals that vary, received where `pattern` has a 1;
    /// frame 3 goes out 0.05 s before frame 4 and arrives in the same 0.1 s step, so only frame
    /// 4 is applied and the IMM forecasts it from frame 2, in order.
    fn packets(flight: &crate::trajectory::Trajectory, pattern: &str) -> Vec<Transmission> {
        let t0 = flight.t[0];
        let mut tx = crate::sim::station::tests::frames(pattern);
        for (k, t) in tx.iter_mut().enumerate() {
            t.sent = if k == 3 { t0 + 7.95 } else { t0 + t.sent };
            t.arrival = if k == 3 { t0 + 8.01 } else { t.sent + 0.02 };
            let i = flight.t.partition_point(|&s| s < t.sent);
            t.state = flight.state(i.min(flight.t.len() - 1));
            t.interval = 2.0 + 0.5 * (k % 3) as f64;
        }
        tx
    }

    /// An IMM at `setup` scored over `tx` with its members stepped in order at every
    /// evaluation time (no look-ahead), and the IMM after it.
    fn scored_in_order(
        flight: &crate::trajectory::Trajectory,
        tx: &[Transmission],
        scoring: crate::sim::station::Scoring,
        setup: StationSetup,
    ) -> (crate::sim::station::StationTrack, Imm) {
        use crate::sim::station::{score_station, start_from, Estimate};
        let mut imm = Imm::new(&ModelKind::ALL, setup);
        let track = score_station(flight, tx, scoring, None, &mut |t, packet, upcoming| {
            if upcoming.is_some() {
                start_from(&mut imm, packet);
            }
            imm.predict_to(t);
            Estimate::of(&imm)
        });
        (track, imm)
    }

    #[test]
    fn members_run_ahead_in_batches_score_as_members_stepped_in_order() {
        use crate::sim::station::{track_station, Scoring};
        let set: Vec<_> = (1..=12)
            .map(|i| crate::trajectory::synthetic_flight(i).unwrap())
            .collect();
        // 9000 evaluation times: three batches of look_ahead.
        let flight = crate::trajectory::chain_flights(&set, 0, 900.0, 10).unwrap();
        let t0 = flight.t[0];
        let pattern: String = (0..359)
            .map(|k| if k % 7 == 3 { '0' } else { '1' })
            .collect();
        let mut tx = crate::sim::station::tests::frames(&pattern);
        for (k, t) in tx.iter_mut().enumerate() {
            t.sent = t0 + 2.5 * k as f64;
            t.arrival = t.sent + 0.02;
            let i = flight.t.partition_point(|&s| s < t.sent);
            t.state = flight.state(i.min(flight.t.len() - 1));
        }
        let scoring = Scoring {
            step: 0.1,
            series: true,
            axes: true,
            calibrate: true,
            uncertainty: true,
        };
        let setup = StationSetup {
            prediction: Prediction::Bounded,
            ..setup()
        };
        let mut ahead = Imm::new(&ModelKind::ALL, setup);
        let batched = track_station(&flight, &mut ahead, &tx, scoring);
        assert!(batched.error3d.len() > 2 * AHEAD_TIMES);
        let (in_order, imm) = scored_in_order(&flight, &tx, scoring, setup);
        assert!(imm.ahead.is_none());
        assert_eq!(batched, in_order);
    }

    #[test]
    fn forecasts_made_ahead_in_parallel_score_as_those_made_in_order() {
        use crate::sim::station::{track_station, Scoring};
        let flight = crate::trajectory::synthetic_flight(2).unwrap();
        let tx = packets(&flight, "11111110110111111100111111111");
        // Bounded and error-triggered: the forecasts depend on each packet's interval and on
        // the station's trust in the drone's silence, which the losses move.
        let setup = StationSetup {
            prediction: Prediction::Bounded,
            error_triggered: true,
            ..setup()
        };
        let scoring = Scoring {
            step: 0.1,
            series: false,
            axes: true,
            calibrate: false,
            uncertainty: true,
        };
        let mut ahead = Imm::new(&ModelKind::ALL, setup);
        let prepared = track_station(&flight, &mut ahead, &tx, scoring);
        assert_eq!(
            ahead.forecasts.len(),
            tx.iter().filter(|t| t.received).count() - 1
        );
        let (in_order, imm) = scored_in_order(&flight, &tx, scoring, setup);
        assert_eq!(prepared, in_order);
        assert_eq!(ahead.probabilities(), imm.probabilities());
        assert!(
            imm.probabilities().iter().all(|&p| p != 1.0 / 3.0),
            "the packets moved them"
        );
    }
}
