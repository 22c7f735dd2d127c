//! The three motion models of the paper (reference §2–3): DR, CTRA+ and 3D-CTRA.
//!
//! All three share the convention of reference §2: local ENU metres, seconds, radians, and states that
//! begin `x y z theta phi v`. `theta` and `phi` describe the *velocity vector* (course and
//! flight-path angle), not the airframe.

mod arc_integral;
mod ctra3d;
mod ctra_plus;
mod dr;
mod heading;
mod kind;

pub use arc_integral::arc_integral;
use arc_integral::arc_integrals;
pub use ctra3d::Ctra3d;
pub use ctra_plus::CtraPlus;
pub use dr::Dr;
pub use heading::Heading;
pub use kind::{ModelError, ModelKind, MAX_DT, STATE_RANGES};

use nalgebra::{SMatrix, SVector};

/// Runs a function generic over `MotionModel<N>` with the model chosen at run time:
/// `with_model!(kind, run(args…))` becomes `run::<N, _>(Model, args…)` for the matching model,
/// so the one `match` from a runtime choice to a fixed-size filter lives here.
macro_rules! with_model {
    ($kind:expr, $run:ident($($arg:expr),* $(,)?)) => {
        match $kind {
            $crate::models::ModelKind::Dr => $run::<6, _>($crate::models::Dr, $($arg),*),
            $crate::models::ModelKind::CtraPlus => $run::<8, _>($crate::models::CtraPlus, $($arg),*),
            $crate::models::ModelKind::Ctra3d => $run::<9, _>($crate::models::Ctra3d, $($arg),*),
        }
    };
}
pub(crate) use with_model;

/// Index of x (east, m) in every state.
pub const X: usize = 0;
/// Index of y (north, m).
pub const Y: usize = 1;
/// Index of z (up, m).
pub const Z: usize = 2;
/// Index of theta (course, rad, counter-clockwise from +x).
pub const THETA: usize = 3;
/// Index of phi (flight-path angle, rad, above the horizontal).
pub const PHI: usize = 4;
/// Index of v (speed, m/s).
pub const V: usize = 5;
/// Index of a (tangential acceleration, m/s²), CTRA+ and 3D-CTRA.
pub const A: usize = 6;
/// Index of omega (turn rate dtheta/dt, rad/s), CTRA+ and 3D-CTRA.
pub const OMEGA: usize = 7;
/// Index of psi (tilt rate dphi/dt, rad/s), 3D-CTRA only.
pub const PSI: usize = 8;

/// The state components that are angles (theta, phi): the filter averages and differences them
/// on the circle.
pub const ANGLES: &[usize] = &[THETA, PHI];

/// A motion model with an `N`-dimensional state that can be propagated over any time step in
/// closed form (noise-free).
pub trait MotionModel<const N: usize> {
    /// Which of the paper's models this is.
    const KIND: ModelKind;

    /// Whether [`Self::propagate_with`] uses the [`Heading`] it is given: then the filter
    /// derives its sigma points' headings from the centre's instead of calling sin and cos for
    /// each point (see [`Heading`]). The paper's three models do; a model whose state has no θ
    /// and φ at [`THETA`] and [`PHI`] must not.
    const SHARES_HEADING: bool = false;

    /// The kinematic part of the model, when it has one: every component past [`Z`] advances
    /// linearly, component i by dt · component j for each listed (i, j) (θ by ω, φ by ψ, v by a;
    /// the angles wrapped into (−π, π]) and the rest stay constant; the rates j are themselves
    /// constant. Only x, y and z are nonlinear. The filter then takes the linear rows' mean and
    /// covariance in closed form, F P Fᵀ, and the sigma points only for the position rows
    /// ([`SigmaPoints::kinematic_moments`](crate::SigmaPoints::kinematic_moments)). `None` (the
    /// default) claims nothing; the paper's three models declare theirs, checked against
    /// [`Self::propagate`] by a test.
    const LINEAR_TAIL: Option<&'static [(usize, usize)]> = None;

    /// Whether [`Self::LINEAR_TAIL`] describes how `state` moves over `dt`. Always, for a model
    /// that declares one outright (the default); a model whose tail is linear only in part of the
    /// state space (a [bounded station](crate::sim::station::Bounded), whose speed and pitch stop at their
    /// limits) says where. The filter takes the closed form only where every sigma point holds it.
    fn tail_holds(&self, _state: &SVector<f64, N>, _dt: f64) -> bool {
        true
    }

    /// The state after `dt` seconds (`dt` may be any finite value; the station uses dt ≥ 0).
    fn propagate(&self, state: &SVector<f64, N>, dt: f64) -> SVector<f64, N>;

    /// [`Self::propagate`] with the sines and cosines of the state's θ and φ given (equal to
    /// `Heading::of(state)` up to rounding). Models that do not share headings ignore them.
    fn propagate_with(
        &self,
        state: &SVector<f64, N>,
        _heading: &Heading,
        dt: f64,
    ) -> SVector<f64, N> {
        self.propagate(state, dt)
    }

    /// [`Self::propagate_with`] for the two points of a sigma pair x̄ ± d, with their headings:
    /// the same results, which a model may compute together (3D-CTRA batches the pair's six arc
    /// integrals, CTRA+ its two).
    fn propagate_pair(
        &self,
        states: [&SVector<f64, N>; 2],
        headings: [&Heading; 2],
        dt: f64,
    ) -> [SVector<f64, N>; 2] {
        each_of_pair(self, states, headings, dt)
    }

    /// Applies the station's tilt-rate decay after one prediction step: psi ← eta·psi
    /// (paper §III-B, last paragraph). Models without psi leave the state unchanged.
    fn decay_tilt_rate(&self, _state: &mut SVector<f64, N>, _eta: f64) {}

    /// The same decay for a covariance of the state: P ← D P Dᵀ with D scaling psi by eta, so
    /// that the uncertainty of the tilt rate dies out with the tilt rate itself (a bounded
    /// station; the paper decays the state only). Models without psi leave it unchanged.
    fn decay_tilt_rate_covariance(&self, _p: &mut SMatrix<f64, N, N>, _eta: f64) {}
}

/// A sigma pair's two points through [`MotionModel::propagate_with`] one at a time: the default
/// [`MotionModel::propagate_pair`], and the way out of a batched one that cannot batch.
pub(crate) fn each_of_pair<const N: usize, M: MotionModel<N> + ?Sized>(
    model: &M,
    states: [&SVector<f64, N>; 2],
    headings: [&Heading; 2],
    dt: f64,
) -> [SVector<f64, N>; 2] {
    [
        model.propagate_with(states[0], headings[0], dt),
        model.propagate_with(states[1], headings[1], dt),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::wrap_angle;

    /// Checks a model's [`MotionModel::LINEAR_TAIL`] against its propagation on states with
    /// angles near ±π (so that the wrap is exercised), manoeuvres and steps of either sign.
    fn tail_claim_holds<const N: usize, M: MotionModel<N>>(model: M) {
        let rates = M::LINEAR_TAIL.expect("the paper's models declare their linear tail");
        for (n, dt) in [0.1, 2.5, -0.7].into_iter().enumerate() {
            let mut s = SVector::<f64, N>::from_fn(|i, _| {
                [12.0, -3.0, 50.0, 3.1, -1.5, 9.0, 0.8, 0.4, -0.3][i] * (1.0 + 0.1 * n as f64)
            });
            for &i in ANGLES {
                s[i] = wrap_angle(s[i]);
            }
            let out = model.propagate(&s, dt);
            for i in Z + 1..N {
                let expected = match rates.iter().find(|&&(row, _)| row == i) {
                    Some(&(_, rate)) => s[i] + dt * s[rate],
                    None => s[i],
                };
                let expected = if ANGLES.contains(&i) {
                    wrap_angle(expected)
                } else {
                    expected
                };
                assert!(
                    (out[i] - expected).abs() < 1e-12,
                    "{:?} component {i}, dt {dt}: {} vs {expected}",
                    M::KIND,
                    out[i]
                );
            }
        }
    }

    #[test]
    fn the_declared_linear_tails_match_the_propagation() {
        tail_claim_holds::<6, _>(Dr);
        tail_claim_holds::<8, _>(CtraPlus);
        tail_claim_holds::<9, _>(Ctra3d);
    }
}
