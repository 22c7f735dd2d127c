//! The station side: replace on receipt, then predict every T (SPEC §4, "Station side").

use super::Transmission;
use crate::codec::quantization_variance;
use crate::filter::{measurement_noise, process_noise, SigmaParams, Ukf};
use crate::models::{with_model, ModelKind, MotionModel, ANGLES};
use crate::trajectory::Trajectory;
use nalgebra::{SMatrix, SVector};

/// The station's estimate and its error at every T from the first arrival on.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StationTrack {
    /// Evaluation times, s.
    pub times: Vec<f64>,
    /// Estimated position at each time, m.
    pub estimate: Vec<[f64; 3]>,
    /// |estimate − truth| per axis, m.
    pub error_axes: Vec<[f64; 3]>,
    /// 3D distance between estimate and truth, m.
    pub error3d: Vec<f64>,
}

/// Runs the station's predictor over the flight.
///
/// On each received packet the filter state is replaced by the decoded state, with covariance
/// R + quantisation variance (step²/12 per field), dated at the packet's send time (the station
/// knows the time on air). It then predicts to the first grid time t0 + jT after the arrival,
/// and on by T, multiplying psi by eta after every step. Before the first arrival nothing is
/// counted: the station has no estimate at all then.
pub fn track_station(
    flight: &Trajectory,
    model: ModelKind,
    transmissions: &[Transmission],
    step: f64,
    eta: f64,
    q: f64,
    r_diagonal: &[f64; 9],
) -> StationTrack {
    with_model!(model, run(flight, transmissions, step, eta, q, r_diagonal))
}

fn run<const N: usize, M: MotionModel<N>>(
    model: M,
    flight: &Trajectory,
    transmissions: &[Transmission],
    step: f64,
    eta: f64,
    q: f64,
    r_diagonal: &[f64; 9],
) -> StationTrack {
    let quant = quantization_variance(M::KIND);
    let p0: SMatrix<f64, N, N> = measurement_noise::<N>(r_diagonal)
        + SMatrix::from_diagonal(&SVector::<f64, N>::from_fn(|i, _| quant[i]));
    let Some(mut ukf) = Ukf::new(
        SVector::<f64, N>::zeros(),
        p0,
        process_noise(q),
        SigmaParams::default(),
        ANGLES,
    ) else {
        return StationTrack::default();
    };
    let received: Vec<&Transmission> = transmissions.iter().filter(|t| t.received).collect();
    let Some(first) = received.first() else {
        return StationTrack::default();
    };
    let t0 = flight.t[0];
    let end = flight.t[flight.t.len() - 1];
    let mut j = ((first.arrival - t0) / step - 1e-9).ceil().max(0.0) as usize;
    let mut next = 0;
    let mut applied = usize::MAX; // index of the packet the filter was last reset to
    let mut clock = 0.0; // time the filter state refers to
    let mut hint = 0;
    let capacity = ((end - t0) / step) as usize + 1;
    let mut out = StationTrack {
        times: Vec::with_capacity(capacity),
        estimate: Vec::with_capacity(capacity),
        error_axes: Vec::with_capacity(capacity),
        error3d: Vec::with_capacity(capacity),
    };
    loop {
        let t = t0 + j as f64 * step;
        if t > end + 1e-9 {
            break;
        }
        // Apply the newest packet that has fully arrived by t.
        while next < received.len() && received[next].arrival <= t + 1e-9 {
            next += 1;
        }
        // j starts at the first arrival, so at least one packet has arrived.
        if next - 1 != applied {
            applied = next - 1;
            let pkt = received[applied];
            ukf.reset(SVector::<f64, N>::from_fn(|i, _| pkt.state[i]), p0);
            clock = pkt.sent;
        }
        let dt = t - clock;
        if dt > 0.0 {
            ukf.predict(&model, dt);
            model.decay_tilt_rate(&mut ukf.x, eta);
            clock = t;
        }
        let truth = flight.position_at(t, &mut hint);
        let est = [ukf.x[0], ukf.x[1], ukf.x[2]];
        let e: [f64; 3] = core::array::from_fn(|k| (est[k] - truth[k]).abs());
        out.times.push(t);
        out.estimate.push(est);
        out.error_axes.push(e);
        out.error3d
            .push((e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt());
        j += 1;
    }
    out
}
