//! One motion model's station predictor: replace on receipt, then predict (reference §4).

use super::{
    Bounded, Bounds, DroneCovariances, HeadingNoise, HedgeChoice, Prediction, Tracker,
    HEDGE_FORECAST_STEP, HEDGE_LEVELS,
};
use crate::codec::quantization_variance;
use crate::filter::{measurement_noise, process_noise, Ukf};
use crate::math::ln;
use crate::models::{MotionModel, ANGLES, PHI, THETA, X, Y, Z};
use nalgebra::{Cholesky, Matrix3, SMatrix, SVector};

/// Everything a station predictor needs besides its model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StationSetup {
    /// Paper or bounded prediction.
    pub prediction: Prediction,
    /// The limits of bounded prediction.
    pub bounds: Bounds,
    /// Prediction step T, s.
    pub step: f64,
    /// Tilt-rate decay per step (paper: 0.9).
    pub eta: f64,
    /// Process-noise intensity q per second.
    pub q: f64,
    /// Measurement variances of the 9-component state (paper Table I).
    pub r_diagonal: [f64; 9],
    /// The nominal interval between packets under the duty cycle, s (bounded: the grace time).
    pub interval: f64,
    /// Whether the drone sends on error (`--sender error`): it is then silent while the
    /// station's forecast holds, so once the drone could have sent again (one `interval` after
    /// a packet) a bounded prediction follows its model without the unscented mean's hedge,
    /// while the link delivers well enough for a silence to be news
    /// ([`Tracker::trust_silence`]); `false` for a periodic drone.
    pub error_triggered: bool,
    /// The drone filters' settled covariances, when the station resets to them after a packet
    /// (bounded prediction); `None` resets to R + quantisation (the paper's station, reference
    /// §4).
    pub drone_covariance: Option<DroneCovariances>,
}

impl StationSetup {
    /// The part of it a station's estimates read, the rest set to defaults: each packet brings
    /// its own interval ([`Tracker::set_interval`]), and the paper's prediction reads neither the
    /// bounds nor whether the drone sends on error. Setups with equal parts estimate alike from
    /// the same packet (a swarm's stations share their errors by it: `ForecastMemo`).
    pub fn estimate_inputs(&self) -> StationSetup {
        let read = StationSetup {
            interval: 0.0,
            ..*self
        };
        match self.prediction {
            Prediction::Paper => StationSetup {
                bounds: Bounds::default(),
                error_triggered: false,
                ..read
            },
            Prediction::Bounded => read,
        }
    }
}

/// The station's UKF for one model: on each packet its state is replaced by the decoded state
/// with covariance R + quantisation variance (step²/12 per field) — or, with
/// [`StationSetup::drone_covariance`], the drone filter's settled covariance + quantisation —
/// dated at the packet's send time; between packets it only predicts, multiplying psi by eta
/// after every step.
///
/// With [`Prediction::Bounded`] it keeps speed and pitch within limits and lets an overdue
/// manoeuvre decay ([`Bounds`]); and once a packet is overdue (with an error-triggered drone,
/// once it could have sent again: [`StationSetup::error_triggered`]) its estimate follows the
/// model from its own last value, while the unscented transform carries only the covariance. Over a
/// long gap the covariance grows until the sigma points span every heading, and their weighted
/// mean (whose centre weight λ/(n+λ) is negative for κ = 3 − n) then drifts *backwards*, away
/// from where the drone flew: the paper's station flies its estimate back over its own track.
#[derive(Clone, Debug)]
pub struct StationPredictor<const N: usize, M> {
    model: M,
    setup: StationSetup,
    ukf: Ukf<N>,
    p0: SMatrix<f64, N, N>,
    /// One sensor fix's covariance R + quantisation: what the IMM likelihood scores against.
    fix: SMatrix<f64, N, N>,
    /// The time the filter state refers to, s.
    clock: f64,
    /// The send time of the packet the filter was last reset to, s.
    reset_at: f64,
    /// That packet's state.
    received: SVector<f64, N>,
    /// Whether the link lets it read an error-triggered drone's silence as news
    /// ([`Tracker::trust_silence`]).
    silence_trusted: bool,
    /// Whether anyone reads the covariance ([`Tracker::ignore_uncertainty`]).
    uncertainty_read: bool,
    /// With [`HeadingNoise::Adaptive`]: the flight's choice of noise on θ and φ, and whether a
    /// packet has come yet (the first has nothing to be forecast from).
    hedge: Option<(HedgeChoice, bool)>,
}

/// The station's process noise per second: the drone's q·I for the paper's station; for a
/// bounded station the same without the position terms. Between packets the station's position
/// moves only by its velocity (a kinematic model; Bar-Shalom et al. 2001, §6.2), so its
/// uncertainty should grow through velocity, heading and manoeuvre, not by white noise on the
/// position itself, which only the drone's 10 Hz filter needs. With it the 95 % region at
/// 1 km was too wide (coverage95 0.98).
fn station_process_noise<const N: usize>(setup: &StationSetup) -> SMatrix<f64, N, N> {
    let mut q = process_noise::<N>(setup.q);
    if setup.prediction == Prediction::Bounded {
        for i in [X, Y, Z] {
            q[(i, i)] = 0.0;
        }
    }
    q
}

impl<const N: usize, M: MotionModel<N> + Copy> StationPredictor<N, M> {
    /// A predictor that has received nothing yet.
    pub fn new(model: M, setup: StationSetup) -> Self {
        let quant = SMatrix::from_diagonal(&SVector::<f64, N>::from_iterator(
            quantization_variance(M::KIND),
        ));
        let fix = measurement_noise::<N>(&setup.r_diagonal) + quant;
        let p0 = match &setup.drone_covariance {
            Some(c) => c.of::<N>(M::KIND) + quant,
            None => fix,
        };
        let x = SVector::zeros();
        let ukf = match Ukf::new(
            x,
            p0,
            station_process_noise(&setup),
            setup.prediction.sigma_params(),
            ANGLES,
        ) {
            Some(u) => u,
            None => unreachable!("either prediction's sigma parameters suit every state size"),
        };
        StationPredictor {
            model,
            setup,
            ukf,
            p0,
            fix,
            clock: 0.0,
            reset_at: 0.0,
            received: x,
            silence_trusted: true,
            uncertainty_read: true,
            hedge: (setup.prediction == Prediction::Bounded
                && setup.bounds.heading_noise == HeadingNoise::Adaptive)
                .then(|| (HedgeChoice::default(), false)),
        }
    }

    /// [`HeadingNoise::Adaptive`], as a packet at `state` sent at `sent` arrives: scores each
    /// level's forecast of it from the packet before, then sets the noise on θ and φ for the
    /// prediction from this packet on.
    fn choose_hedge(&mut self, state: &[f64; 9], sent: f64) {
        let Some((mut choice, primed)) = self.hedge else {
            return;
        };
        if primed {
            choice.score(HEDGE_LEVELS.map(|factor| self.forecast_miss(factor, state, sent)));
        }
        self.hedge = Some((choice, true));
        self.ukf.q = self.hedged_noise(choice.factor());
    }

    /// The station's process noise with `factor` × q on θ and φ.
    fn hedged_noise(&self, factor: f64) -> SMatrix<f64, N, N> {
        let mut q = station_process_noise::<N>(&self.setup);
        for i in [THETA, PHI] {
            q[(i, i)] *= factor;
        }
        q
    }

    /// This predictor run again from the last packet to `t` s, in steps of `step` s: the
    /// forecast it made of the moment `t`, whatever grid times the station served since.
    fn replay(mut self, t: f64, step: f64) -> Self {
        self.ukf.reset(self.received, self.p0);
        self.clock = self.reset_at;
        while self.clock < t {
            let next = (self.clock + step).min(t);
            self.step_to(next);
        }
        self
    }

    /// How far, squared (m²), the forecast from the last packet with `factor` × q on θ and φ
    /// puts the drone at `sent` from the position `state` reports.
    fn forecast_miss(&self, factor: f64, state: &[f64; 9], sent: f64) -> f64 {
        let mut forecast = self.clone();
        forecast.hedge = None;
        forecast.uncertainty_read = true;
        forecast.ukf.q = self.hedged_noise(factor);
        let forecast = forecast.replay(sent, HEDGE_FORECAST_STEP);
        (0..3)
            .map(|k| {
                let d = forecast.ukf.x[k] - state[k];
                d * d
            })
            .sum()
    }

    /// Whether the drone's silence at `age` s after its packet means that the forecast holds: it
    /// sends on error, the link delivers well enough, and its duty cycle would have let it send
    /// again. Within the off-time after a packet it could not have spoken however far the
    /// forecast drifted, so there its silence says nothing and the station hedges as for a
    /// periodic drone. Trusted from the packet on, the silence cost where the drift passes any
    /// threshold within one interval (up to 1.37× periodic's p75 with the same packets on the
    /// synthetic set, 2.0× on the real flight, where it cost from 5.7 s intervals on;
    /// docs/beyond-the-paper.md, "When to send"). Under the budget rule the drone may have had
    /// credit to send sooner; the station does not track that credit and waits the nominal
    /// interval either way, since trusting the silence sooner is what cost the real flight.
    fn silence_is_news(&self, age: f64) -> bool {
        self.setup.error_triggered && self.silence_trusted && age > self.setup.interval
    }

    /// The state estimate.
    pub fn state(&self) -> &SVector<f64, N> {
        &self.ukf.x
    }

    /// One prediction step to `t`, with the decays that follow every step.
    fn step_to(&mut self, t: f64) {
        let dt = t - self.clock;
        match self.setup.prediction {
            Prediction::Paper => self.ukf.predict(&self.model, dt),
            Prediction::Bounded => {
                let bounded = Bounded {
                    model: self.model,
                    bounds: self.setup.bounds,
                };
                let grace = self.setup.bounds.grace_intervals * self.setup.interval;
                let (before, after) = (self.clock - self.reset_at, t - self.reset_at);
                // With an error-triggered drone the estimate follows the model once the drone
                // could have sent: the unscented mean hedges against turns the station cannot see
                // (its heading spread shortens a straight line), but from then on that drone
                // reports every drift past its threshold itself, so the hedge would only cost.
                let follows_model = after > grace || self.silence_is_news(after);
                let own = follows_model.then(|| bounded.propagate(&self.ukf.x, dt));
                // Until the next packet the estimate then no longer depends on the covariance
                // (a packet replaces both), so where nobody reads the covariance the unscented
                // transform, 19 propagations and a factorisation, is skipped.
                if self.uncertainty_read || !follows_model {
                    self.ukf.predict(&bounded, dt);
                }
                if let Some(own) = own {
                    self.ukf.x = own;
                }
                let b = self.setup.bounds;
                b.decay_manoeuvre(&mut self.ukf.x, &mut self.ukf.p, before, after, grace);
            }
        }
        self.model.decay_tilt_rate(&mut self.ukf.x, self.setup.eta);
        if self.setup.prediction == Prediction::Bounded {
            // The decay is part of the motion, so the covariance follows it; left alone, the
            // tilt rate's variance grew with q for ever and its sigma points pulled the mean.
            self.model
                .decay_tilt_rate_covariance(&mut self.ukf.p, self.setup.eta);
        }
        self.clock = t;
    }

    /// The log-likelihood (up to a constant) of a received state `z` sent at `sent`, under the
    /// prediction this model made from the previous packet, over the components every model
    /// shares (x y z theta phi v). The prediction is rerun from the previous packet in steps of
    /// T, so it does not depend on where the station's evaluation grid fell.
    ///
    /// The residual is scored against the uncertainty of two sensor fixes, 2·(R + quantisation),
    /// not against the textbook predicted covariance + P0: the predicted covariances are
    /// dominated by the same process noise (q·I per second on every component, heading included)
    /// and barely differ between models, so with them a straight-line prediction of a steady
    /// turn scores as well as an exact one, and the probabilities cannot tell the models apart.
    /// (Scoring against the bounded station's settled P0 instead left IMM's p75 within 1 % of
    /// this and raised DR's mean probability from 0.27 to 0.41 at SF7/1 km, so R stays.)
    pub fn log_likelihood(&self, z: &[f64; 9], sent: f64) -> f64 {
        let mut forecast = self.clone();
        // Only its state is scored, against two sensor fixes' uncertainty.
        forecast.uncertainty_read = false;
        let x = forecast.replay(sent, self.setup.step).ukf.x;
        let s: SMatrix<f64, 6, 6> = self.fix.fixed_view::<6, 6>(0, 0) * 2.0;
        let mut r = SVector::<f64, 6>::from_fn(|i, _| z[i] - x[i]);
        for i in [THETA, PHI] {
            r[i] = crate::math::wrap_angle(r[i]);
        }
        let Some(c) = Cholesky::new(0.5 * (s + s.transpose())) else {
            return f64::NEG_INFINITY;
        };
        let log_det: f64 = c.l().diagonal().iter().map(|d| 2.0 * ln(*d)).sum();
        -0.5 * (r.dot(&c.solve(&r)) + log_det)
    }
}

impl<const N: usize, M: MotionModel<N> + Copy> Tracker for StationPredictor<N, M> {
    fn reset(&mut self, state: &[f64; 9], sent: f64) {
        self.choose_hedge(state, sent);
        self.received = SVector::from_fn(|i, _| state[i]);
        self.ukf.reset(self.received, self.p0);
        self.clock = sent;
        self.reset_at = sent;
    }

    fn predict_to(&mut self, t: f64) {
        if t > self.clock {
            self.step_to(t);
        }
    }

    fn set_interval(&mut self, interval: f64) {
        self.setup.interval = interval;
    }

    fn trust_silence(&mut self, trusted: bool) {
        self.silence_trusted = trusted;
    }

    fn ignore_uncertainty(&mut self) {
        self.uncertainty_read = false;
    }

    fn forgets_the_past(&self) -> bool {
        // A reset replaces the state and covariance and restarts the clocks; only an adaptive
        // heading noise's scores carry over.
        self.hedge.is_none()
    }

    fn position(&self) -> [f64; 3] {
        [self.ukf.x[0], self.ukf.x[1], self.ukf.x[2]]
    }

    fn position_covariance(&self) -> Matrix3<f64> {
        let p = self.ukf.p.fixed_view::<3, 3>(0, 0).into_owned();
        match self.setup.prediction {
            Prediction::Paper => p,
            Prediction::Bounded => {
                let age = (self.clock - self.reset_at).max(0.0);
                p + Matrix3::identity() * self.setup.bounds.model_error_variance(M::KIND, age)
            }
        }
    }
}
