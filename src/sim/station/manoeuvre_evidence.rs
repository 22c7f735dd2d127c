//! What a packet's own manoeuvre fields say about which IMM member fits the drone now
//! (reference §4, `imm`).
//!
//! The IMM's forecast likelihood scores each member by how well it predicted this packet from
//! the last one: evidence about the interval just flown, one packet late at the start of every
//! manoeuvre. But the 12-byte packet also carries the drone filter's acceleration, turn rate and
//! tilt rate *now*. A member without a field (DR has none of them, CTRA+ no tilt rate) says the
//! drone is not doing it, so the field is the drone filter's estimation noise around zero; a
//! member with it says the field is drawn from the manoeuvres the drone flies. This is the usual
//! mode-conditioned measurement likelihood of an IMM (Bar-Shalom, Li & Kirubarajan 2001, §11.6)
//! applied to the fields on which the modes differ.

use super::StationSetup;
use crate::codec::quantization_variance;
use crate::math::ln;
use crate::models::{ModelKind, A, OMEGA, PSI};

/// The spread (root mean square) of acceleration, m/s², turn rate, rad/s, and tilt rate, rad/s,
/// that a member modelling them expects in a packet: the synthetic set's, sampled every 0.1 s
/// (`tests/integration/station.rs` measures it: 0.92, 0.27, 0.12; the jerkier Canberra flight
/// shows 1.8, 0.73 and 0.37). A wider spread only makes a small field count a little more for
/// the member without it; the IMM's p75 on the paper's grid moves by at most 0.01 between the
/// two flights' spreads.
pub const MANOEUVRE_SPREAD: [f64; 3] = [0.92, 0.27, 0.12];

/// The manoeuvre fields a, ω, ψ of the 9-component state, in [`MANOEUVRE_SPREAD`]'s order.
const FIELDS: [usize; 3] = [A, OMEGA, PSI];

/// How uncertain a packet's manoeuvre fields are when the drone is not manoeuvring; a member
/// that models a field adds [`MANOEUVRE_SPREAD`]² to its variance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ManoeuvreEvidence {
    /// The drone filter's estimation variance of each field + the payload's quantisation.
    noise: [f64; 3],
}

impl ManoeuvreEvidence {
    /// From the station's noise settings: the drone's settled 3D-CTRA covariance when the
    /// station knows it ([`StationSetup::drone_covariance`], bounded prediction), else one sensor
    /// fix's R (the paper's station, which resets to R as well).
    pub fn new(setup: &StationSetup) -> Self {
        let quant = quantization_variance(ModelKind::Ctra3d);
        let drone = setup.drone_covariance.map(|c| c.of::<9>(ModelKind::Ctra3d));
        let estimate = |i: usize| drone.map_or(setup.r_diagonal[i], |p| p[(i, i)]);
        ManoeuvreEvidence {
            noise: FIELDS.map(|i| estimate(i) + quant[i]),
        }
    }

    /// The log-likelihood (up to a constant shared by all members) of packet state `z`'s
    /// manoeuvre fields under a member of kind `kind`.
    pub fn log_likelihood(&self, kind: ModelKind, z: &[f64; 9]) -> f64 {
        FIELDS
            .iter()
            .zip(self.noise.iter().zip(MANOEUVRE_SPREAD))
            .map(|(&i, (&noise, spread))| {
                let var = if i < kind.state_len() {
                    noise + spread * spread
                } else {
                    noise
                };
                -0.5 * (z[i] * z[i] / var + ln(var))
            })
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::filter::{PAPER_Q, PAPER_R_DIAGONAL};
    use crate::sim::station::tests::paper_setup;
    use crate::sim::station::{DroneCovariances, Prediction};

    fn evidence() -> ManoeuvreEvidence {
        ManoeuvreEvidence::new(&StationSetup {
            prediction: Prediction::Bounded,
            drone_covariance: Some(DroneCovariances::new(0.1, PAPER_Q, &PAPER_R_DIAGONAL)),
            ..paper_setup()
        })
    }

    fn state(a: f64, omega: f64, psi: f64) -> [f64; 9] {
        [0.0, 0.0, 50.0, 0.3, 0.0, 5.0, a, omega, psi]
    }

    #[test]
    fn a_packet_without_manoeuvre_favours_dead_reckoning() {
        let e = evidence();
        let z = state(0.0, 0.0, 0.0);
        let dr = e.log_likelihood(ModelKind::Dr, &z);
        assert!(dr > e.log_likelihood(ModelKind::CtraPlus, &z));
        assert!(
            e.log_likelihood(ModelKind::CtraPlus, &z) > e.log_likelihood(ModelKind::Ctra3d, &z)
        );
    }

    #[test]
    fn a_turn_favours_the_turning_models_and_a_climbing_turn_3d_ctra() {
        let e = evidence();
        let turn = state(0.5, 0.3, 0.0);
        assert!(
            e.log_likelihood(ModelKind::CtraPlus, &turn) > e.log_likelihood(ModelKind::Dr, &turn)
        );
        let climbing = state(0.5, 0.3, 0.2);
        assert!(
            e.log_likelihood(ModelKind::Ctra3d, &climbing)
                > e.log_likelihood(ModelKind::CtraPlus, &climbing)
        );
    }
}
