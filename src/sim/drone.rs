//! The drone side: noisy sensors and the on-board UKF (SPEC §4, "Drone side").

use crate::filter::{measurement_noise, process_noise, SigmaParams, Ukf};
use crate::math::wrap_angle;
use crate::models::{with_model, ModelKind, MotionModel, ANGLES};
use crate::rng::Rng;
use crate::trajectory::Trajectory;
use nalgebra::SVector;

/// The drone's own estimates at every sensor step, padded to 9 components (unused ones 0).
#[derive(Clone, Debug, PartialEq)]
pub struct DroneTrack {
    /// The model the filter ran.
    pub model: ModelKind,
    /// Time of the first sensor step, s.
    pub start: f64,
    /// Sensor period, s.
    pub period: f64,
    /// Estimate after each step's update.
    pub states: Vec<[f64; 9]>,
    /// How often the filter repaired its covariance.
    pub recoveries: u64,
}

impl DroneTrack {
    /// The estimate at the last sensor step at or before `time`, and that step's time.
    pub fn latest(&self, time: f64) -> Option<(f64, &[f64; 9])> {
        if time < self.start {
            return None;
        }
        let k = (((time - self.start) / self.period + 1e-9).floor() as usize)
            .min(self.states.len() - 1);
        Some((self.start + k as f64 * self.period, &self.states[k]))
    }
}

/// Runs the drone's sensors and UKF over `flight`: at every sensor step the full true state is
/// measured with Gaussian noise of variances `r_diagonal` (paper Table I), and the filter runs
/// predict + update. The noise draws depend on `seed` and `stream` only — every model sees the
/// same noise on the components they share, so the comparison between models is paired.
pub fn run_drone(
    flight: &Trajectory,
    model: ModelKind,
    sensor_rate: f64,
    q: f64,
    r_diagonal: &[f64; 9],
    seed: u64,
    stream: u64,
) -> DroneTrack {
    with_model!(model, run(flight, sensor_rate, q, r_diagonal, seed, stream))
}

fn run<const N: usize, M: MotionModel<N>>(
    model: M,
    flight: &Trajectory,
    sensor_rate: f64,
    q: f64,
    r_diagonal: &[f64; 9],
    seed: u64,
    stream: u64,
) -> DroneTrack {
    let period = 1.0 / sensor_rate;
    let start = flight.t[0];
    let steps = (flight.duration() / period + 1e-9).floor() as usize + 1;
    let r = measurement_noise::<N>(r_diagonal);
    let sd: [f64; 9] = core::array::from_fn(|i| r_diagonal[i].sqrt());
    let mut rng = Rng::derive(seed, stream);
    let mut hint = 0;
    let mut measure = |k: usize| -> SVector<f64, N> {
        let truth = flight.state_at(start + k as f64 * period, &mut hint);
        // Nine draws every step whatever N is, so the noise on shared components is identical.
        let noise: [f64; 9] = core::array::from_fn(|i| sd[i] * rng.normal());
        let mut z = SVector::<f64, N>::from_fn(|i, _| truth[i] + noise[i]);
        for &i in ANGLES {
            z[i] = wrap_angle(z[i]);
        }
        z
    };
    let z0 = measure(0);
    let mut ukf = match Ukf::new(z0, r, process_noise(q), SigmaParams::default(), ANGLES) {
        Some(u) => u,
        None => unreachable!("the default sigma parameters are valid for every state size"),
    };
    let pad = |x: &SVector<f64, N>| -> [f64; 9] {
        core::array::from_fn(|i| if i < N { x[i] } else { 0.0 })
    };
    let mut states = Vec::with_capacity(steps);
    states.push(pad(&ukf.x));
    for k in 1..steps {
        let z = measure(k);
        ukf.predict(&model, period);
        ukf.update(&z, &r);
        states.push(pad(&ukf.x));
    }
    DroneTrack {
        model: M::KIND,
        start,
        period,
        states,
        recoveries: ukf.recoveries(),
    }
}
