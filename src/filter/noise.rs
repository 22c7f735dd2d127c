//! The paper's noise settings (Table I; reference §4).

use nalgebra::{SMatrix, SVector};

/// Process-noise scale q of Q = q·I (paper Table I: 0.1).
///
/// The paper gives no time base for Q. loratrack reads q as an intensity per second: a prediction
/// over dt adds q·dt·I (at the paper's 0.1 s steps, 0.01 per step). Read per step instead, Q adds
/// 0.1 rad² of heading variance every 0.1 s; after the 2–4 s between packets the station's
/// sigma points then span headings and turn rates in every direction, and the UKF's predicted
/// mean shrinks toward the last fix — it undershoots the drone, and the richer models, whose extra
/// states accumulate the same noise, fall behind DR, the opposite of the paper's finding. With
/// q per second the filter is also independent of its step length, as a physical model should be.
pub const PAPER_Q: f64 = 0.1;

/// Measurement variances of the full 3D-CTRA state `x y z theta phi v a omega psi`
/// (paper Table I): m², m², m², rad², rad², (m/s)², (m/s²)², (rad/s)², (rad/s)².
pub const PAPER_R_DIAGONAL: [f64; 9] = [
    0.8274, 0.8274, 3.7481, 0.0085, 0.0085, 0.25, 0.1521, 0.0003, 0.0003,
];

/// Q = q·I for an `N`-dimensional state (an intensity per second; see [`PAPER_Q`]).
pub fn process_noise<const N: usize>(q: f64) -> SMatrix<f64, N, N> {
    SMatrix::<f64, N, N>::identity() * q
}

/// The diagonal R for the first `N` components of the 3D-CTRA state, from the given 9 variances.
/// The state orders of DR (6) and CTRA+ (8) are prefixes of 3D-CTRA's.
pub fn measurement_noise<const N: usize>(diagonal: &[f64; 9]) -> SMatrix<f64, N, N> {
    SMatrix::<f64, N, N>::from_diagonal(&SVector::<f64, N>::from_fn(|i, _| diagonal[i]))
}
