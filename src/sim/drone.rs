//! The drone side: noisy sensors and the on-board UKF (reference §4, "Drone side").

use crate::filter::{
    measurement_noise, process_noise, SigmaParams, Ukf, PAPER_Q, PAPER_R_DIAGONAL,
};
use crate::math::wrap_angle;
use crate::models::{with_model, ModelKind, MotionModel, ANGLES};
use crate::rng::Rng;
use crate::sim::streams::DroneStreams;
use crate::trajectory::Trajectory;
use nalgebra::{SMatrix, SVector};

/// The drone's sensors and filter on one flight (reference §4, "Drone side"): how often it
/// measures, the noise it assumes and meets, and the random streams its sensor noise draws from.
///
/// ```
/// use loratrack::{run_drone, synthetic_flight, ModelKind, Sensing};
/// let flight = synthetic_flight(1).unwrap();
/// let track = run_drone(&flight, ModelKind::Dr, &Sensing::paper(1, 0));
/// assert_eq!(track.period, 0.1);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sensing {
    /// Sensor and filter rate, Hz.
    pub rate: f64,
    /// Process noise q of Q = q·I per second (the filter's; reference §4).
    pub q: f64,
    /// Measurement variances (paper Table I): the sensors' noise and the filter's R.
    pub r_diagonal: [f64; 9],
    /// The drone's random streams: the noise draws depend on them only.
    pub streams: DroneStreams,
}

impl Sensing {
    /// The paper's drone (Table I): 10 Hz, q = 0.1, the measurement variances of Table I
    /// ([`PAPER_Q`](crate::PAPER_Q), [`PAPER_R_DIAGONAL`](crate::PAPER_R_DIAGONAL)), drawing
    /// from stream `stream` of `seed`.
    pub fn paper(seed: u64, stream: u64) -> Self {
        Sensing {
            rate: crate::options::SENSOR_RATE.default,
            q: PAPER_Q,
            r_diagonal: PAPER_R_DIAGONAL,
            streams: DroneStreams { seed, stream },
        }
    }
}

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
/// measured with Gaussian noise of variances `sensing.r_diagonal` (paper Table I), and the filter
/// runs predict + update. The noise draws depend on the seed and stream only — every model sees
/// the same noise on the components they share, so the comparison between models is paired.
pub fn run_drone(flight: &Trajectory, model: ModelKind, sensing: &Sensing) -> DroneTrack {
    let mut tracks = run_drones(flight, &[model], sensing);
    tracks.remove(0)
}

/// [`run_drone`] for each of `models` on the same readings: the sensors are read once per step
/// and every model's filter takes that reading, which is what each would have drawn alone (the
/// same draws, in the same order), so each track equals its [`run_drone`] (and a
/// [`DroneFilter`]'s estimates). Reading the true state and drawing nine normals was a tenth of
/// a whole-set run with three models (perf).
pub fn run_drones(flight: &Trajectory, models: &[ModelKind], sensing: &Sensing) -> Vec<DroneTrack> {
    let mut sensors = Sensors::new(flight, sensing);
    let steps = sensors.steps();
    let mut filters: Vec<Box<dyn Onboard + Send>> = models
        .iter()
        .map(|&m| with_model!(m, onboard(sensing, sensors.period)))
        .collect();
    let mut states: Vec<Vec<[f64; 9]>> = models.iter().map(|_| Vec::with_capacity(steps)).collect();
    for k in 0..steps {
        let z = sensors.read(k);
        for (f, out) in filters.iter_mut().zip(&mut states) {
            out.push(f.step(&z));
        }
    }
    models
        .iter()
        .zip(filters)
        .zip(states)
        .map(|((&model, f), states)| DroneTrack {
            model,
            start: sensors.start,
            period: sensors.period,
            states,
            recoveries: f.recoveries(),
        })
        .collect()
}

/// The drone's filter stepped one sensor step at a time (what [`run_drone`] collects), so that
/// a swarm of hundreds of drones holds one filter per drone rather than every estimate.
pub struct DroneFilter<'a> {
    /// The model the filter runs.
    pub model: ModelKind,
    /// Time of the first sensor step, s.
    pub start: f64,
    /// Sensor period, s.
    pub period: f64,
    /// Sensor steps over the flight.
    pub steps: usize,
    k: usize,
    // Boxed, as the filter is: a live drone is a variant of `Estimates` beside a stored one.
    sensors: Box<Sensors<'a>>,
    onboard: Box<dyn Onboard + Send>,
}

/// The drone's sensors over a flight: at step `k` (time start + k · period) the full true state
/// with Gaussian noise of standard deviations √`r_diagonal`, angles wrapped.
struct Sensors<'a> {
    flight: &'a Trajectory,
    sd: [f64; 9],
    rng: Rng,
    hint: usize,
    start: f64,
    period: f64,
}

impl<'a> Sensors<'a> {
    fn new(flight: &'a Trajectory, sensing: &Sensing) -> Self {
        Sensors {
            flight,
            sd: core::array::from_fn(|i| sensing.r_diagonal[i].sqrt()),
            rng: sensing.streams.sensors(),
            hint: 0,
            start: flight.t[0],
            period: 1.0 / sensing.rate,
        }
    }

    /// Sensor steps over the flight.
    fn steps(&self) -> usize {
        (self.flight.duration() / self.period + 1e-9).floor() as usize + 1
    }

    /// The reading at step `k`; steps are read in order, each once.
    fn read(&mut self, k: usize) -> [f64; 9] {
        let truth = self
            .flight
            .state_at(self.start + k as f64 * self.period, &mut self.hint);
        // Nine draws every step whatever the model's N, so the noise on shared components is
        // identical.
        let noise: [f64; 9] = core::array::from_fn(|i| self.sd[i] * self.rng.normal());
        let mut z: [f64; 9] = core::array::from_fn(|i| truth[i] + noise[i]);
        for &i in ANGLES {
            z[i] = wrap_angle(z[i]);
        }
        z
    }
}

/// The on-board UKF of one model, fed one reading per sensor step.
trait Onboard {
    /// The estimate after this reading (the first reading starts the filter), padded to 9.
    fn step(&mut self, reading: &[f64; 9]) -> [f64; 9];
    fn recoveries(&self) -> u64;
}

struct OnboardUkf<const N: usize, M> {
    model: M,
    ukf: Option<Ukf<N>>,
    r: SMatrix<f64, N, N>,
    q: f64,
    /// Sensor period, s: each step predicts over it.
    period: f64,
}

fn onboard<const N: usize, M: MotionModel<N> + Send + 'static>(
    model: M,
    sensing: &Sensing,
    period: f64,
) -> Box<dyn Onboard + Send> {
    Box::new(OnboardUkf {
        model,
        ukf: None,
        r: measurement_noise::<N>(&sensing.r_diagonal),
        q: sensing.q,
        period,
    })
}

impl<const N: usize, M: MotionModel<N>> Onboard for OnboardUkf<N, M> {
    fn step(&mut self, reading: &[f64; 9]) -> [f64; 9] {
        let z = SVector::<f64, N>::from_fn(|i, _| reading[i]);
        let ukf = match &mut self.ukf {
            Some(u) => {
                u.predict(&self.model, self.period);
                u.update(&z, &self.r);
                u
            }
            None => self.ukf.insert(
                match Ukf::new(
                    z,
                    self.r,
                    process_noise(self.q),
                    SigmaParams::default(),
                    ANGLES,
                ) {
                    Some(u) => u,
                    None => {
                        unreachable!("the default sigma parameters are valid for every state size")
                    }
                },
            ),
        };
        core::array::from_fn(|i| if i < N { ukf.x[i] } else { 0.0 })
    }

    fn recoveries(&self) -> u64 {
        self.ukf.as_ref().map_or(0, Ukf::recoveries)
    }
}

impl<'a> DroneFilter<'a> {
    /// A filter about to take its first measurement (see [`run_drone`]).
    pub fn new(flight: &'a Trajectory, model: ModelKind, sensing: &Sensing) -> Self {
        let sensors = Box::new(Sensors::new(flight, sensing));
        DroneFilter {
            model,
            start: sensors.start,
            period: sensors.period,
            steps: sensors.steps(),
            k: 0,
            onboard: with_model!(model, onboard(sensing, sensors.period)),
            sensors,
        }
    }

    /// The estimate after the next sensor step's update (the first: the first measurement);
    /// `None` after the last step.
    pub fn next_estimate(&mut self) -> Option<[f64; 9]> {
        if self.k >= self.steps {
            return None;
        }
        let z = self.sensors.read(self.k);
        self.k += 1;
        Some(self.onboard.step(&z))
    }

    /// How often the filter repaired its covariance so far.
    pub fn recoveries(&self) -> u64 {
        self.onboard.recoveries()
    }
}

/// A drone's estimates as the event loop reads them: stored (a cached [`DroneTrack`]) or
/// computed as the loop asks (a [`DroneFilter`], keeping only what may still be read). The loop
/// reads steps in increasing order only.
pub enum Estimates<'a> {
    /// Every estimate, computed before.
    Stored(&'a DroneTrack),
    /// A live filter and the estimates from step `first` on.
    Live {
        /// The filter.
        filter: DroneFilter<'a>,
        /// Estimates of steps `first..`.
        window: std::collections::VecDeque<[f64; 9]>,
        /// The step of `window[0]`.
        first: usize,
    },
}

impl<'a> Estimates<'a> {
    /// Estimates computed as they are read.
    pub fn live(filter: DroneFilter<'a>) -> Self {
        Estimates::Live {
            filter,
            window: std::collections::VecDeque::new(),
            first: 0,
        }
    }

    /// The model the filter runs.
    pub fn model(&self) -> ModelKind {
        match self {
            Estimates::Stored(t) => t.model,
            Estimates::Live { filter, .. } => filter.model,
        }
    }

    /// Time of the first sensor step, s.
    pub fn start(&self) -> f64 {
        match self {
            Estimates::Stored(t) => t.start,
            Estimates::Live { filter, .. } => filter.start,
        }
    }

    /// Sensor period, s.
    pub fn period(&self) -> f64 {
        match self {
            Estimates::Stored(t) => t.period,
            Estimates::Live { filter, .. } => filter.period,
        }
    }

    /// Number of sensor steps.
    pub fn len(&self) -> usize {
        match self {
            Estimates::Stored(t) => t.states.len(),
            Estimates::Live { filter, .. } => filter.steps,
        }
    }

    /// Whether there is no step at all.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The estimate at step `k`; steps before the last one read are forgotten by a live filter.
    pub fn get(&mut self, k: usize) -> Option<[f64; 9]> {
        match self {
            Estimates::Stored(t) => t.states.get(k).copied(),
            Estimates::Live {
                filter,
                window,
                first,
            } => {
                while *first < k && !window.is_empty() {
                    window.pop_front();
                    *first += 1;
                }
                while *first + window.len() <= k {
                    let x = filter.next_estimate()?;
                    if *first + window.len() < k {
                        *first += 1;
                    } else {
                        window.push_back(x);
                    }
                }
                window.get(k - *first).copied()
            }
        }
    }

    /// Computes a live filter's estimates up to step `upto` (exclusive) ahead of the loop, so
    /// that many drones' filters can run in parallel between the loop's events.
    pub fn prefetch(&mut self, upto: usize) {
        if let Estimates::Live {
            filter,
            window,
            first,
        } = self
        {
            while *first + window.len() < upto {
                match filter.next_estimate() {
                    Some(x) => window.push_back(x),
                    None => break,
                }
            }
        }
    }

    /// How many estimates the filter has computed so far (all of them, when stored).
    #[cfg(test)]
    pub(crate) fn computed(&self) -> usize {
        match self {
            Estimates::Stored(t) => t.states.len(),
            Estimates::Live { window, first, .. } => first + window.len(),
        }
    }

    /// How often the filter repaired its covariance.
    pub fn recoveries(&self) -> u64 {
        match self {
            Estimates::Stored(t) => t.recoveries,
            Estimates::Live { filter, .. } => filter.recoveries(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trajectory::synthetic_flight;

    #[test]
    fn models_reading_shared_sensors_track_as_each_would_alone() {
        let flight = synthetic_flight(4).unwrap();
        let models = [ModelKind::Ctra3d, ModelKind::Dr, ModelKind::CtraPlus];
        let sensing = Sensing::paper(7, 3);
        let together = run_drones(&flight, &models, &sensing);
        assert_eq!(together.len(), 3);
        for (track, &model) in together.iter().zip(&models) {
            // Alone, and step by step as a swarm's live drone runs it.
            let alone = run_drone(&flight, model, &sensing);
            assert_eq!(track, &alone, "{model:?}");
            let mut live = DroneFilter::new(&flight, model, &sensing);
            let states: Vec<[f64; 9]> = core::iter::from_fn(|| live.next_estimate()).collect();
            assert_eq!(states, track.states, "{model:?} live");
            assert_eq!(live.recoveries(), track.recoveries);
            assert_eq!((live.start, live.period), (track.start, track.period));
        }
        // Another stream reads other noise: the tracks would not be equal by accident.
        let other = run_drone(
            &flight,
            ModelKind::Dr,
            &Sensing {
                streams: DroneStreams {
                    stream: 4,
                    ..sensing.streams
                },
                ..sensing
            },
        );
        assert_ne!(together[1].states, other.states);
    }
}
