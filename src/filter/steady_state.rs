//! The drone filter's steady-state covariance: what its estimate is worth once the filter has
//! settled, computed from the shared noise settings alone (reference §4, "Honest uncertainty").

use super::{measurement_noise, process_noise, SigmaParams, Ukf};
use crate::models::{MotionModel, ANGLES, V};
use nalgebra::{SMatrix, SVector};

/// Sensor steps the recursion may take; it stops earlier once converged.
const MAX_STEPS: usize = 2_000;
/// Converged when no variance moves by more than this fraction in a step.
const TOLERANCE: f64 = 1e-7;

/// The covariance the drone's UKF settles at, m², rad², …, when it measures the whole state with
/// variances `r_diagonal` every `period` s under process noise `q` per second (paper Table I;
/// [`process_noise`]), flying straight and level at `speed` m/s.
///
/// The filter's covariance recursion does not depend on the measurements themselves (the
/// update is linear, h = I), only on the state through the model's nonlinearity: it is run from
/// P = R with zero innovation until it stops moving (the discrete Riccati equation's fixed
/// point).
///
/// ```
/// use loratrack::{steady_state_covariance, Ctra3d, PAPER_Q, PAPER_R_DIAGONAL};
/// let p = steady_state_covariance::<9, _>(&Ctra3d, 0.1, PAPER_Q, &PAPER_R_DIAGONAL, 5.0);
/// // Filtering at 10 Hz makes the position far surer than one fix (R = 0.83 m²).
/// assert!(p[(0, 0)] < 0.2 * PAPER_R_DIAGONAL[0]);
/// ```
pub fn steady_state_covariance<const N: usize, M: MotionModel<N>>(
    model: &M,
    period: f64,
    q: f64,
    r_diagonal: &[f64; 9],
    speed: f64,
) -> SMatrix<f64, N, N> {
    let r = measurement_noise::<N>(r_diagonal);
    let mut x = SVector::<f64, N>::zeros();
    x[V] = speed;
    let Some(mut ukf) = Ukf::new(x, r, process_noise(q), SigmaParams::default(), ANGLES) else {
        return r;
    };
    for _ in 0..MAX_STEPS {
        let before = ukf.p.diagonal();
        ukf.predict(model, period);
        let z = ukf.x;
        ukf.update(&z, &r);
        let after = ukf.p.diagonal();
        let moved = (0..N).any(|i| (after[i] - before[i]).abs() > TOLERANCE * before[i].abs());
        if !moved {
            break;
        }
    }
    ukf.p
}
