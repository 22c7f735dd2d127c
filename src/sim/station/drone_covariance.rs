//! What a packet's state is worth: the covariance of the drone filter that produced it, which a
//! bounded station resets to (reference §4, "Honest uncertainty").

use crate::filter::steady_state_covariance;
use crate::models::{with_model, ModelKind, MotionModel};
use nalgebra::SMatrix;

/// The speed the drone's settled covariance is computed at, m/s: a multicopter's cruise. The
/// covariance grows a little with speed (heading uncertainty moves the position across the
/// track): at 0, 5 and 10 m/s the cross-track variance is 0.086, 0.094 and 0.11 m² with the
/// paper's noise.
pub const NOMINAL_SPEED: f64 = 5.0;

/// The settled covariance of the drone's UKF for each model ([`steady_state_covariance`]),
/// computed once from the shared noise settings: DR's 6 × 6 and CTRA+'s 8 × 8 in the top-left
/// corner of a 9 × 9 matrix, indexed like [`ModelKind::ALL`].
///
/// A packet carries the drone's *filtered* state, so the station's uncertainty right after it is
/// this covariance (plus the payload's quantisation), not one sensor fix's R: with R the
/// station's 95 % region covered the truth 99.9 % of the time at 1 km (coverage95 0.999, NEES
/// 0.47 against the honest 3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DroneCovariances([SMatrix<f64, 9, 9>; 3]);

impl DroneCovariances {
    /// For a drone filtering every `period` s with process noise `q` per second and measurement
    /// variances `r_diagonal`.
    pub fn new(period: f64, q: f64, r_diagonal: &[f64; 9]) -> Self {
        DroneCovariances(
            ModelKind::ALL.map(|kind| with_model!(kind, padded(period, q, r_diagonal))),
        )
    }

    /// The `N × N` covariance of `kind`'s state.
    pub fn of<const N: usize>(&self, kind: ModelKind) -> SMatrix<f64, N, N> {
        self.0[kind.index()].fixed_view::<N, N>(0, 0).into_owned()
    }
}

fn padded<const N: usize, M: MotionModel<N>>(
    model: M,
    period: f64,
    q: f64,
    r_diagonal: &[f64; 9],
) -> SMatrix<f64, 9, 9> {
    let p = steady_state_covariance(&model, period, q, r_diagonal, NOMINAL_SPEED);
    let mut out = SMatrix::<f64, 9, 9>::zeros();
    out.fixed_view_mut::<N, N>(0, 0).copy_from(&p);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};

    #[test]
    fn each_model_gets_its_own_block_far_below_one_fix() {
        let c = DroneCovariances::new(0.1, PAPER_Q, &PAPER_R_DIAGONAL);
        let dr = c.of::<6>(ModelKind::Dr);
        let d3 = c.of::<9>(ModelKind::Ctra3d);
        for i in 0..3 {
            assert!(
                dr[(i, i)] < 0.3 * PAPER_R_DIAGONAL[i],
                "{i}: {}",
                dr[(i, i)]
            );
            assert!(d3[(i, i)] > 0.0);
        }
        // 3D-CTRA's tilt rate is filtered; DR has none.
        assert!(d3[(8, 8)] > 0.0 && d3[(8, 8)] < PAPER_R_DIAGONAL[8]);
    }

    #[test]
    fn a_slower_sensor_leaves_the_drone_less_sure() {
        let fast =
            DroneCovariances::new(0.01, PAPER_Q, &PAPER_R_DIAGONAL).of::<9>(ModelKind::Ctra3d);
        let slow =
            DroneCovariances::new(1.0, PAPER_Q, &PAPER_R_DIAGONAL).of::<9>(ModelKind::Ctra3d);
        assert!(slow[(0, 0)] > fast[(0, 0)]);
    }
}
