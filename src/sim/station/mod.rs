//! The station side: predictors that consume received packets and estimate the drone's position
//! every T (reference §4, "Station side"), and the loop that scores them against the truth.
//!
//! * [`StationPredictor`]: one motion model, reset on each packet (the paper's station), with the
//!   paper's or a bounded prediction ([`Prediction`]).
//! * [`Imm`]: an Interacting Multiple Model mixture of the three.
//! * [`MissionStation`]: flies the drone's plan between packets, a bounded 3D-CTRA off it.
//!
//! All implement [`Tracker`], which is also what an error-triggered drone mirrors. A station
//! that forgets the past at each packet errs alike from it in every run that delivers it, so
//! runs of a family may share those errors ([`ForecastMemo`], [`track_station_recalling`]).

mod calibration;
mod chains;
mod drone_covariance;
mod forecast_memo;
mod heading_noise;
mod imm;
mod manoeuvre_evidence;
mod mission;
mod prediction;
mod predictor;
mod station_model;
mod workload;

pub use calibration::{Calibration, CALIBRATION_GAIN};
pub(crate) use chains::{FlightChains, MAX_GRIDS};
pub use drone_covariance::{DroneCovariances, NOMINAL_SPEED};
pub use forecast_memo::{ForecastMemo, SpanKey};
pub use heading_noise::{
    HeadingNoise, HedgeChoice, HEDGE_FORECAST_STEP, HEDGE_LEVELS, HEDGE_MEMORY, HEDGE_MIN_SCORED,
    HEDGE_MISS_CAP,
};
pub use imm::{Imm, ImmMember, IMM_STAY};
pub use manoeuvre_evidence::{ManoeuvreEvidence, MANOEUVRE_SPREAD};
pub use mission::{
    MissionPlan, MissionStation, PlanPace, HOLD_RADIUS, HOLD_SPEED, OFFSET_TIME, PACE_SIGMA,
    PACE_TIME,
};
pub use prediction::{Bounded, Bounds, Prediction, PLANE_V_MAX};
pub use predictor::{StationPredictor, StationSetup};
pub use station_model::StationModel;
pub(crate) use workload::drone_run_work;
pub use workload::{split_stations, station_work};

use super::packet::Transmission;
use crate::metrics::{bound_95, Consistency};
use crate::models::{with_model, ModelKind, MotionModel};
use crate::trajectory::Trajectory;
use nalgebra::Matrix3;

/// A station estimator: what it believes about the drone's position, from received packets.
pub trait Tracker {
    /// Replaces the estimate with a decoded packet's state (9 components, the unused ones 0),
    /// which describes the drone at `sent` (s).
    fn reset(&mut self, state: &[f64; 9], sent: f64);
    /// Predicts forward to time `t` (s) in one step; a `t` not after the estimate's time is a
    /// no-op.
    fn predict_to(&mut self, t: f64);
    /// The estimated position x, y, z (m, ENU).
    fn position(&self) -> [f64; 3];
    /// The covariance of that position (m²).
    fn position_covariance(&self) -> Matrix3<f64>;
    /// The packets now come every `interval` s (ADR changed the data rate): what a bounded
    /// prediction counts as overdue follows.
    fn set_interval(&mut self, _interval: f64) {}
    /// For a multiple-model tracker, the probability of DR, CTRA+ and 3D-CTRA.
    fn model_probabilities(&self) -> Option<[f64; 3]> {
        None
    }
    /// Whether the link has been delivering well enough for an error-triggered drone's silence
    /// to mean that the forecast holds ([`StationSetup::error_triggered`]; [`silence_trusted`]).
    fn trust_silence(&mut self, _trusted: bool) {}
    /// Nobody will read the position covariance, only the estimate (a swarm keeps only each
    /// drone's errors): a station may then stop propagating its covariance wherever its estimate
    /// no longer depends on it. The estimates stay the same bit for bit;
    /// [`Tracker::position_covariance`] is then meaningless.
    fn ignore_uncertainty(&mut self) {}
    /// Sees the flight's transmissions before the flight is scored ([`track_station`]), so that
    /// work which does not depend on the scoring's order is done ahead, on every core: an IMM
    /// forecasts each received packet from the one before under each member. The numbers are
    /// those of the work done in order.
    fn prepare(&mut self, _transmissions: &[Transmission]) {}
    /// Just before a packet is applied during scoring ([`track_station`]): the packets still to
    /// come and the evaluation times each will serve, this one first, so that work on them may
    /// be done ahead, on every core (an IMM runs its members through them side by side). The
    /// numbers are those of the work done in order.
    fn look_ahead(&mut self, _upcoming: &Upcoming) {}
    /// Whether its estimates after a packet depend on that packet and the settings alone, not on
    /// the packets before: runs that deliver the same packet then err alike from it, and may
    /// share those errors ([`ForecastMemo`]). A single-model station with a fixed heading noise
    /// does; an IMM (its probabilities) and an adaptive heading noise (its scores) carry the past.
    fn forgets_the_past(&self) -> bool {
        false
    }
}

/// The received packets a station has still to apply during scoring, from the one being
/// applied now, each with the evaluation times it serves (until the next one applies or the
/// flight ends; [`Tracker::look_ahead`]).
pub struct Upcoming<'a> {
    spans: &'a [Span],
    received: &'a [Received<'a>],
    t0: f64,
    step: f64,
}

impl Upcoming<'_> {
    /// Each packet, whether the station trusts the silence after it, and its evaluation times,
    /// s, in order.
    pub fn packets(&self) -> impl Iterator<Item = (&Transmission, bool, Vec<f64>)> + '_ {
        self.spans.iter().map(|s| {
            let r = &self.received[s.packet];
            let times = (s.first..s.first + s.count)
                .map(|j| self.t0 + j as f64 * self.step)
                .collect();
            (r.packet, r.silence_trusted, times)
        })
    }
}

/// One received packet's turn in the scoring: from evaluation time `first` (its index on the
/// grid), `count` times.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    packet: usize,
    first: usize,
    count: usize,
}

/// The turns of the received packets from grid index `j` on: at each time t0 + jT up to `end`
/// (s), the newest packet that has fully arrived applies (a packet overtaken within one step
/// never does).
fn spans(received: &[Received], t0: f64, step: f64, end: f64, mut j: usize) -> Vec<Span> {
    let mut out: Vec<Span> = Vec::new();
    let mut next = 0;
    loop {
        let t = t0 + j as f64 * step;
        if t > end + 1e-9 {
            break;
        }
        while next < received.len() && received[next].packet.arrival <= t + 1e-9 {
            next += 1;
        }
        // j starts at the first arrival, so at least one packet has arrived.
        let packet = next - 1;
        match out.last_mut() {
            Some(s) if s.packet == packet => s.count += 1,
            _ => out.push(Span {
                packet,
                first: j,
                count: 1,
            }),
        }
        j += 1;
    }
    out
}

/// How many of a drone's latest frames (by frame counter, up to a received one) the station
/// counts when it decides whether to trust its silence, and how many of them may be lost.
pub const SILENCE_WINDOW: usize = 10;
/// See [`SILENCE_WINDOW`]: one frame in ten.
pub const SILENCE_LOSSES: usize = 1;

/// For each received transmission (in order), whether the station trusts the sender's silence
/// after it: at most [`SILENCE_LOSSES`] of the latest [`SILENCE_WINDOW`] frames up to it were
/// lost. A network server sees the losses as gaps in the frame counter. Where frames collide or
/// fade, silence is as likely a loss as a forecast that holds, and the station keeps hedging.
pub fn silence_trusted(transmissions: &[Transmission]) -> Vec<bool> {
    let mut out = Vec::new();
    for (i, t) in transmissions.iter().enumerate() {
        if t.received {
            let window = &transmissions[(i + 1).saturating_sub(SILENCE_WINDOW)..=i];
            out.push(window.iter().filter(|w| !w.received).count() <= SILENCE_LOSSES);
        }
    }
    out
}

fn single<const N: usize, M: MotionModel<N> + Copy + 'static>(
    model: M,
    setup: StationSetup,
) -> Box<dyn Tracker> {
    Box::new(StationPredictor::new(model, setup))
}

/// A fresh station of the given kind, having received nothing yet; `plan` is the drone's
/// mission, which only a [`StationModel::Mission`] station reads (without one it is its bounded
/// fallback throughout).
pub fn new_tracker(
    model: StationModel,
    setup: StationSetup,
    plan: Option<&MissionPlan>,
) -> Box<dyn Tracker> {
    match model {
        StationModel::Single(m) => with_model!(m, single(setup)),
        StationModel::Imm => Box::new(Imm::new(&ModelKind::ALL, setup)),
        StationModel::Mission => Box::new(MissionStation::new(plan.cloned(), setup)),
    }
}

/// The station's estimate and its error at every T from the first arrival on.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StationTrack {
    /// Evaluation times, s (only when asked for, [`Scoring::series`]: the errors are what the
    /// statistics need, and a 10⁶-row flight's four stations would hold ~50 MB more).
    pub times: Vec<f64>,
    /// Estimated position at each time, m (only with [`Scoring::series`]).
    pub estimate: Vec<[f64; 3]>,
    /// |estimate − truth| along east, north and up, m (only with [`Scoring::axes`]).
    pub error_axes: [Vec<f64>; 3],
    /// 3D distance between estimate and truth, m.
    pub error3d: Vec<f64>,
    /// How the truth fell against the station's claimed position uncertainty (95 % coverage,
    /// the share under its 95 % bound, NEES).
    pub consistency: Consistency,
    /// The station's own 95 % bound on its error at each step, m ([`bound_95`]; only with
    /// [`Scoring::series`]).
    pub bound95: Vec<f64>,
    /// Sum over the evaluation times of the model probabilities (multiple-model trackers).
    pub probability_sum: Option<[f64; 3]>,
    /// Evaluation times (every T from the flight's start) before the first packet arrived, or
    /// all of them when none did: the station had no estimate there ([`WholeFlightError`]).
    ///
    /// [`WholeFlightError`]: crate::metrics::WholeFlightError
    pub untracked: usize,
}

/// What a station believes at one evaluation time.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Estimate {
    /// Position, m.
    pub position: [f64; 3],
    /// Its covariance, m².
    pub covariance: Matrix3<f64>,
    /// For a multiple-model tracker, the probability of DR, CTRA+ and 3D-CTRA.
    pub probabilities: Option<[f64; 3]>,
}

impl Estimate {
    /// The tracker's estimate now.
    pub fn of(tracker: &dyn Tracker) -> Self {
        Estimate {
            position: tracker.position(),
            covariance: tracker.position_covariance(),
            probabilities: tracker.model_probabilities(),
        }
    }
}

/// How a station is scored over a flight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Scoring {
    /// The evaluation step T, s.
    pub step: f64,
    /// Whether to keep what a plot of the flight shows at every step: the time, the estimate
    /// and the station's own 95 % bound on its error.
    pub series: bool,
    /// Whether to keep the error along each axis ([`StationTrack::error_axes`]).
    pub axes: bool,
    /// Whether the station calibrates its covariance against its forecasts of the packets
    /// ([`Calibration`]; a bounded station: the paper's is scored as published).
    pub calibrate: bool,
    /// Whether the station's uncertainty is scored: coverage95 and NEES
    /// ([`StationTrack::consistency`]); `series` (its bound) and `calibrate` need it. Without it
    /// ([`Scoring::errors_only`]) the consistency stays empty and [`track_station`] tells the
    /// tracker that nobody reads its covariance ([`Tracker::ignore_uncertainty`]).
    pub uncertainty: bool,
}

impl Scoring {
    /// Only the 3D errors, every `step` s: no series, no axes, no calibration, no uncertainty (a
    /// swarm keeps each drone's errors alone).
    pub fn errors_only(step: f64) -> Self {
        Scoring {
            step,
            series: false,
            axes: false,
            calibrate: false,
            uncertainty: false,
        }
    }

    /// Whether it keeps the 3D errors alone ([`Scoring::errors_only`]).
    fn errors_alone(&self) -> bool {
        !(self.series || self.axes || self.calibrate || self.uncertainty)
    }
}

/// Runs a station over the flight.
///
/// At every grid time t0 + jT from the first arrival on, the newest packet that has fully arrived
/// is applied (the tracker reset to it, dated at its send time: the station knows the time on
/// air), the tracker predicts to t, and its estimate is compared with the truth. Before the first
/// arrival nothing is counted: the station has no estimate at all then.
pub fn track_station(
    flight: &Trajectory,
    tracker: &mut dyn Tracker,
    transmissions: &[Transmission],
    scoring: Scoring,
) -> StationTrack {
    track_station_recalling(flight, tracker, transmissions, scoring, None)
}

/// [`track_station`], with a memo of the errors other runs of this station over this flight
/// made from the packets they received: for a tracker that forgets the past at each packet
/// ([`Tracker::forgets_the_past`]) scored for its errors only ([`Scoring::errors_only`]), each
/// packet's errors are recalled from `memo` where it holds them and kept there otherwise. The
/// track is the same, bit for bit; any other tracker or scoring runs as without a memo.
pub fn track_station_recalling(
    flight: &Trajectory,
    tracker: &mut dyn Tracker,
    transmissions: &[Transmission],
    scoring: Scoring,
    memo: Option<&dyn ForecastMemo>,
) -> StationTrack {
    if !scoring.uncertainty {
        tracker.ignore_uncertainty();
    }
    tracker.prepare(transmissions);
    let memo = memo.filter(|_| tracker.forgets_the_past() && scoring.errors_alone());
    score_station(
        flight,
        transmissions,
        scoring,
        memo,
        &mut |t, packet, upcoming| {
            if let Some(upcoming) = upcoming {
                tracker.look_ahead(upcoming);
                start_from(tracker, packet);
            }
            tracker.predict_to(t);
            Estimate::of(tracker)
        },
    )
}

/// A transmission as the station received it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Received<'a> {
    /// The transmission.
    pub packet: &'a Transmission,
    /// Whether the station trusts the sender's silence after it ([`silence_trusted`]).
    pub silence_trusted: bool,
}

/// The received transmissions in order, each with whether the station trusts the silence
/// after it.
pub(crate) fn received(transmissions: &[Transmission]) -> Vec<Received<'_>> {
    transmissions
        .iter()
        .filter(|t| t.received)
        .zip(silence_trusted(transmissions))
        .map(|(packet, silence_trusted)| Received {
            packet,
            silence_trusted,
        })
        .collect()
}

/// Resets `tracker` to a received packet, at the interval the packet came with.
pub(crate) fn start_from(tracker: &mut dyn Tracker, r: &Received) {
    tracker.set_interval(r.packet.interval);
    tracker.trust_silence(r.silence_trusted);
    tracker.reset(&r.packet.state, r.packet.sent);
}

/// The evaluation loop of [`track_station`], with the station's estimate at each grid time `t`
/// from `estimate(t, newest packet, upcoming)`; `upcoming` is `Some` where the packet is newly
/// applied, and holds it and the packets after it with the times each serves. A packet's errors
/// found in `memo` are recalled instead (the station then skips that packet: each packet's first
/// estimate starts from it), and those computed are kept there.
pub(crate) fn score_station(
    flight: &Trajectory,
    transmissions: &[Transmission],
    scoring: Scoring,
    memo: Option<&dyn ForecastMemo>,
    estimate: &mut dyn FnMut(f64, &Received, Option<&Upcoming>) -> Estimate,
) -> StationTrack {
    let step = scoring.step;
    let received = received(transmissions);
    let t0 = flight.t[0];
    let end = flight.t[flight.t.len() - 1];
    // The evaluation times t0 + j·T up to the flight's end, as the loop below steps them.
    let grid = ((end - t0 + 1e-9) / step).floor() as usize + 1;
    let Some(first) = received.first() else {
        return StationTrack {
            untracked: grid,
            ..StationTrack::default()
        };
    };
    let j = ((first.packet.arrival - t0) / step - 1e-9).ceil().max(0.0) as usize;
    let spans = spans(&received, t0, step, end, j);
    let mut scorer = Scorer::new(flight, grid, j.min(grid), scoring);
    for (s, span) in spans.iter().enumerate() {
        let packet = &received[span.packet];
        let memo = memo.map(|m| (m, SpanKey::of(packet, span.first)));
        if let Some(errors) = memo.as_ref().and_then(|(m, key)| m.recall(key, span.count)) {
            scorer.out.error3d.extend_from_slice(&errors[..span.count]);
            continue;
        }
        let from = scorer.out.error3d.len();
        for j in span.first..span.first + span.count {
            let t = t0 + j as f64 * step;
            let fresh = j == span.first;
            let upcoming = fresh.then(|| Upcoming {
                spans: &spans[s..],
                received: &received,
                t0,
                step,
            });
            let e = estimate(t, packet, upcoming.as_ref());
            scorer.add(t, fresh.then_some(packet), e);
        }
        if let Some((m, key)) = memo {
            m.keep(key, &scorer.out.error3d[from..]);
        }
    }
    scorer.out
}

/// Scores a station's estimates against the flight's truth, one evaluation time after another.
struct Scorer<'f> {
    out: StationTrack,
    calibration: Option<Calibration>,
    flight: &'f Trajectory,
    /// Where the last truth lookup found its time in the flight.
    hint: usize,
    series: bool,
    axes: bool,
    uncertainty: bool,
}

impl<'f> Scorer<'f> {
    /// For up to `grid` evaluation times of `flight`, the first `untracked` of which had no
    /// estimate.
    fn new(flight: &'f Trajectory, grid: usize, untracked: usize, scoring: Scoring) -> Self {
        let (series, axes, uncertainty) = (scoring.series, scoring.axes, scoring.uncertainty);
        Scorer {
            out: StationTrack {
                times: Vec::with_capacity(if series { grid } else { 0 }),
                estimate: Vec::with_capacity(if series { grid } else { 0 }),
                error_axes: core::array::from_fn(|_| {
                    Vec::with_capacity(if axes { grid } else { 0 })
                }),
                error3d: Vec::with_capacity(grid),
                untracked,
                ..StationTrack::default()
            },
            calibration: scoring
                .calibrate
                .then(|| Calibration::new(CALIBRATION_GAIN)),
            flight,
            hint: 0,
            series,
            axes,
            uncertainty,
        }
    }

    /// Adds the estimate `e` at time `t` (s): its error against the flight's truth, its
    /// covariance calibrated (once per packet, as `applied` brings it) and scored, and what a
    /// plot shows when the scoring keeps series.
    fn add(&mut self, t: f64, applied: Option<&Received>, mut e: Estimate) {
        let out = &mut self.out;
        if let Some(c) = &mut self.calibration {
            if let Some(packet) = applied {
                c.packet(packet.packet);
            }
            e.covariance = c.estimate(t, e.position, e.covariance);
        }
        let truth = self.flight.position_at(t, &mut self.hint);
        let est = e.position;
        let d: [f64; 3] = core::array::from_fn(|k| est[k] - truth[k]);
        if self.axes {
            for (axis, d) in out.error_axes.iter_mut().zip(d) {
                axis.push(d.abs());
            }
        }
        out.error3d
            .push((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt());
        if self.uncertainty {
            out.consistency.add(&d, &e.covariance);
        }
        if self.series {
            out.times.push(t);
            out.estimate.push(est);
            out.bound95.push(bound_95(&e.covariance));
        }
        if let Some(p) = e.probabilities {
            let sum = out.probability_sum.get_or_insert([0.0; 3]);
            for k in 0..3 {
                sum[k] += p[k];
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::lora::{Bandwidth, Outcome, SpreadingFactor};

    /// The paper's station at T = 0.1 s, η 0.9, Table I noise and a 2 s interval, under a
    /// periodic drone.
    pub(crate) fn paper_setup() -> StationSetup {
        StationSetup {
            prediction: Prediction::Paper,
            bounds: Bounds::default(),
            step: 0.1,
            eta: 0.9,
            q: crate::filter::PAPER_Q,
            r_diagonal: crate::filter::PAPER_R_DIAGONAL,
            interval: 2.0,
            error_triggered: false,
            drone_covariance: None,
        }
    }

    /// Frames sent every 2 s, received where `pattern` has a 1.
    pub(crate) fn frames(pattern: &str) -> Vec<Transmission> {
        pattern
            .chars()
            .enumerate()
            .map(|(i, c)| Transmission {
                sent: 2.0 * i as f64,
                arrival: 2.0 * i as f64 + 0.02,
                received: c == '1',
                outcome: Outcome::BelowSensitivity,
                heard_by: 0,
                state: [0.0; 9],
                saturated: Default::default(),
                distance: 1000.0,
                rx_power_dbm: -100.0,
                sf: SpreadingFactor::new(7).unwrap(),
                bw: Bandwidth::from_khz(250.0).unwrap(),
                channel: 0,
                time_on_air: 0.02,
                interval: 2.0,
                payload: None,
                charge_mc: 0.0,
                active_s: 0.0,
            })
            .collect()
    }

    /// Every station model, bounded, under a periodic and under an error-triggered drone (whose
    /// station follows its model once the drone could have sent again).
    fn bounded_stations() -> Vec<(StationModel, StationSetup)> {
        let models = StationModel::PAPER.into_iter().chain([StationModel::Imm]);
        models
            .flat_map(|model| {
                [false, true].map(|error_triggered| {
                    let setup = StationSetup {
                        prediction: Prediction::Bounded,
                        error_triggered,
                        ..paper_setup()
                    };
                    (model, setup)
                })
            })
            .collect()
    }

    #[test]
    fn over_a_long_gap_the_paper_sigma_points_fly_the_mean_backwards_and_the_bounded_ones_do_not() {
        // Straight and level at 8 m/s, a packet every 30 s: after 30 s (not yet overdue) the
        // drone is 240 m on. The heading's variance grows by q = 0.1 rad² a second, so the sigma
        // points fan out over every direction and their mean falls short of the line. With the
        // paper's negative centre weight the mean lands behind the start, where no point flies;
        // with the bounded station's non-negative weights it stays between start and line.
        let advance = |prediction, model| {
            let setup = StationSetup {
                prediction,
                interval: 30.0,
                ..paper_setup()
            };
            let mut station = new_tracker(model, setup, None);
            station.reset(&[0.0, 0.0, 50.0, 0.0, 0.0, 8.0, 0.0, 0.0, 0.0], 0.0);
            for j in 1..=300 {
                station.predict_to(j as f64 * 0.1);
            }
            station.position()[0]
        };
        for model in StationModel::PAPER {
            let paper = advance(Prediction::Paper, model);
            let bounded = advance(Prediction::Bounded, model);
            assert!(paper < 0.0, "{model:?}: the paper's mean at x = {paper} m");
            assert!(
                bounded > 0.0 && bounded < 240.0,
                "{model:?}: the bounded mean at x = {bounded} m"
            );
        }
    }

    #[test]
    fn a_station_told_its_uncertainty_is_not_read_estimates_the_same_and_skips_the_covariance() {
        // A turning, climbing, accelerating drone whose packets are lost in runs, so that every
        // station goes overdue.
        let mut sent = frames("1100011101000000001101");
        for (i, t) in sent.iter_mut().enumerate() {
            let k = i as f64;
            t.state = [
                16.0 * k,
                3.0 * k,
                40.0 + k,
                0.3 + 0.1 * k,
                0.05,
                8.0,
                0.5,
                0.2,
                0.02,
            ];
        }
        let received: Vec<&Transmission> = sent.iter().filter(|t| t.received).collect();
        let end = sent.last().map_or(0.0, |t| t.sent) + 10.0;
        for (model, setup) in bounded_stations() {
            let mut read = new_tracker(model, setup, None);
            let mut ignored = new_tracker(model, setup, None);
            ignored.ignore_uncertainty();
            let (mut next, mut covariance_differs) = (0, false);
            for j in 0..=(end / 0.1) as usize {
                let t = j as f64 * 0.1;
                while next < received.len() && received[next].arrival <= t {
                    let r = Received {
                        packet: received[next],
                        silence_trusted: true,
                    };
                    start_from(read.as_mut(), &r);
                    start_from(ignored.as_mut(), &r);
                    next += 1;
                }
                if next == 0 {
                    continue;
                }
                read.predict_to(t);
                ignored.predict_to(t);
                assert_eq!(read.position(), ignored.position(), "{model:?} at {t} s");
                covariance_differs |= read.position_covariance() != ignored.position_covariance();
            }
            assert!(
                covariance_differs,
                "{model:?}: the covariance was still propagated"
            );
        }
    }

    #[test]
    fn scored_for_its_errors_only_a_station_has_the_same_errors_and_no_consistency() {
        let flight = crate::trajectory::synthetic_flight(2).unwrap();
        let t0 = flight.t[0];
        let mut tx = frames("110111000011111100000001111011");
        for t in &mut tx {
            t.sent += t0;
            t.arrival += t0;
            let i = flight.t.partition_point(|&s| s < t.sent);
            t.state = flight.state(i.min(flight.t.len() - 1));
        }
        let full = Scoring {
            uncertainty: true,
            axes: true,
            ..Scoring::errors_only(0.1)
        };
        for (model, setup) in bounded_stations() {
            let track = |scoring| {
                track_station(
                    &flight,
                    new_tracker(model, setup, None).as_mut(),
                    &tx,
                    scoring,
                )
            };
            let (scored, errors_only) = (track(full), track(Scoring::errors_only(0.1)));
            assert_eq!(scored.error3d, errors_only.error3d, "{model:?}");
            assert!(
                errors_only.error_axes.iter().all(Vec::is_empty),
                "{model:?}"
            );
            assert_eq!(errors_only.consistency, Consistency::default(), "{model:?}");
            assert!(scored.consistency.coverage95() > 0.0, "{model:?}");
        }
    }

    /// A memo that keeps every packet's errors and counts the evaluation times it gives back.
    #[derive(Default)]
    struct CountingMemo {
        kept: std::cell::RefCell<std::collections::HashMap<SpanKey, Vec<f64>>>,
        recalled: std::cell::Cell<usize>,
    }

    impl ForecastMemo for CountingMemo {
        fn recall(&self, key: &SpanKey, count: usize) -> Option<std::sync::Arc<[f64]>> {
            let kept = self.kept.borrow();
            let errors = kept.get(key).filter(|e| e.len() >= count)?;
            self.recalled.set(self.recalled.get() + count);
            Some(errors.as_slice().into())
        }

        fn keep(&self, key: SpanKey, errors: &[f64]) {
            let mut kept = self.kept.borrow_mut();
            let entry = kept.entry(key).or_default();
            if errors.len() > entry.len() {
                *entry = errors.to_vec();
            }
        }
    }

    #[test]
    fn a_station_that_forgets_the_past_recalls_the_errors_it_would_compute() {
        let flight = crate::trajectory::synthetic_flight(2).unwrap();
        let t0 = flight.t[0];
        // Two runs of the same frames, delivered differently: most packets arrive in both, some
        // in one only, so some of the second run's turns are the first's and some are longer.
        let delivered = |pattern: &str| {
            let mut tx = frames(pattern);
            for t in &mut tx {
                t.sent += t0;
                t.arrival += t0;
                let i = flight.t.partition_point(|&s| s < t.sent);
                t.state = flight.state(i.min(flight.t.len() - 1));
            }
            tx
        };
        let runs = [
            delivered("110111011111111100111101111011"),
            delivered("110110011111101100111111111011"),
        ];
        let adaptive = StationSetup {
            prediction: Prediction::Bounded,
            bounds: Bounds {
                heading_noise: HeadingNoise::Adaptive,
                ..Bounds::default()
            },
            ..paper_setup()
        };
        let stations = bounded_stations()
            .into_iter()
            .chain([(StationModel::Single(ModelKind::Ctra3d), paper_setup())])
            .chain([(StationModel::Single(ModelKind::Ctra3d), adaptive)]);
        for (model, setup) in stations {
            let memo = CountingMemo::default();
            for tx in &runs {
                let track = |memo: Option<&dyn ForecastMemo>| {
                    let mut tracker = new_tracker(model, setup, None);
                    let scoring = Scoring::errors_only(0.1);
                    track_station_recalling(&flight, tracker.as_mut(), tx, scoring, memo)
                };
                assert_eq!(track(Some(&memo)), track(None), "{model:?} {setup:?}");
            }
            let forgets = new_tracker(model, setup, None).forgets_the_past();
            assert_eq!(forgets, model != StationModel::Imm && setup != adaptive);
            // Only a station that forgets the past recalls, and the second run met packets
            // the first had delivered and served as long.
            assert_eq!(memo.recalled.get() > 0, forgets, "{model:?} {setup:?}");
        }
    }

    #[test]
    fn what_estimate_inputs_leaves_out_moves_no_estimate() {
        let flight = crate::trajectory::synthetic_flight(2).unwrap();
        let mut tx = frames("1101110111111111001111");
        for t in &mut tx {
            t.sent += flight.t[0];
            t.arrival += flight.t[0];
            t.state = flight.state(flight.t.partition_point(|&s| s < t.sent));
        }
        let other = |setup: StationSetup| StationSetup {
            interval: 7.5,
            error_triggered: setup.prediction == Prediction::Paper,
            bounds: match setup.prediction {
                Prediction::Paper => Bounds {
                    v_max: 3.0,
                    tau_a: 0.5,
                    ..Bounds::default()
                },
                Prediction::Bounded => setup.bounds,
            },
            ..setup
        };
        let bounded = StationSetup {
            prediction: Prediction::Bounded,
            ..paper_setup()
        };
        for setup in [paper_setup(), bounded] {
            let changed = other(setup);
            assert_ne!(changed, setup);
            assert_eq!(changed.estimate_inputs(), setup.estimate_inputs());
            let track = |setup| {
                let mut tracker = new_tracker(StationModel::Single(ModelKind::Ctra3d), setup, None);
                track_station(&flight, tracker.as_mut(), &tx, Scoring::errors_only(0.1))
            };
            assert_eq!(track(changed), track(setup), "{setup:?}");
        }
        // What a bounded station reads stays in.
        let error_triggered = StationSetup {
            error_triggered: true,
            ..bounded
        };
        assert_ne!(error_triggered.estimate_inputs(), bounded.estimate_inputs());
    }

    #[test]
    fn silence_is_trusted_while_at_most_one_frame_in_ten_is_lost() {
        // One flag per received frame.
        assert_eq!(silence_trusted(&frames("1111")), vec![true; 4]);
        assert_eq!(silence_trusted(&frames("1011")), vec![true; 3]);
        assert_eq!(silence_trusted(&frames("10011")), vec![true, false, false]);
        // The trust returns once one of the two losses has left the last ten frames.
        let t = silence_trusted(&frames("1001111111111"));
        let mut expected = vec![true];
        expected.extend([false; 8]);
        expected.extend([true; 2]);
        assert_eq!(t, expected);
    }
}
