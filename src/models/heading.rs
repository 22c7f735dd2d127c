//! The sines and cosines of a state's course and flight-path angle, shared between sigma points.

use super::{PHI, THETA};
use crate::math::sin_cos;
use nalgebra::SVector;

/// (sin θ, cos θ) and (sin φ, cos φ) of a state (reference §2): every paper model needs them, and
/// they are most of a propagation's trigonometry.
///
/// The sigma points of a prediction come in pairs x̄ ± d, so their headings follow from the
/// centre's by the addition formulas, sin(θ ± δ) = sin θ cos δ ± cos θ sin δ: one sincos of δ
/// serves both points of a pair, and none is needed where d leaves the angle alone (the columns of
/// the lower Cholesky factor past θ and φ). That halves the trigonometric calls of a 3D-CTRA
/// prediction; the values differ from direct calls by rounding only (below 1e-15, tested).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Heading {
    /// (sin θ, cos θ).
    pub theta: (f64, f64),
    /// (sin φ, cos φ).
    pub phi: (f64, f64),
}

impl Heading {
    /// The heading of `state`, whose components [`THETA`] and [`PHI`] are angles (the paper's
    /// models; `N` ≥ 5).
    pub fn of<const N: usize>(state: &SVector<f64, N>) -> Self {
        Heading {
            theta: sin_cos(state[THETA]),
            phi: sin_cos(state[PHI]),
        }
    }

    /// The headings of the states shifted by +`offset` and −`offset` from the one this is of.
    pub fn around<const N: usize>(&self, offset: &SVector<f64, N>) -> (Self, Self) {
        let (theta_plus, theta_minus) = rotate(self.theta, offset[THETA]);
        let (phi_plus, phi_minus) = rotate(self.phi, offset[PHI]);
        (
            Heading {
                theta: theta_plus,
                phi: phi_plus,
            },
            Heading {
                theta: theta_minus,
                phi: phi_minus,
            },
        )
    }
}

/// (sin, cos) of α + δ and of α − δ from those of α.
fn rotate((s, c): (f64, f64), delta: f64) -> ((f64, f64), (f64, f64)) {
    if delta == 0.0 {
        return ((s, c), (s, c));
    }
    let (sd, cd) = sin_cos(delta);
    (
        (s * cd + c * sd, c * cd - s * sd),
        (s * cd - c * sd, c * cd + s * sd),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shifted_headings_equal_direct_ones_to_rounding() {
        let centre = SVector::<f64, 6>::from([0.0, 0.0, 0.0, 3.0, -0.4, 5.0]);
        let offset = SVector::<f64, 6>::from([1.0, 2.0, 3.0, 0.5, 0.25, 1.0]);
        let (plus, minus) = Heading::of(&centre).around(&offset);
        for (shifted, direct) in [
            (plus, Heading::of(&(centre + offset))),
            (minus, Heading::of(&(centre - offset))),
        ] {
            for (a, b) in [
                (shifted.theta.0, direct.theta.0),
                (shifted.theta.1, direct.theta.1),
                (shifted.phi.0, direct.phi.0),
                (shifted.phi.1, direct.phi.1),
            ] {
                assert!((a - b).abs() < 1e-15, "{a} vs {b}");
            }
        }
    }

    #[test]
    fn an_offset_that_leaves_the_angles_alone_keeps_the_heading_exactly() {
        let centre = SVector::<f64, 6>::from([0.0, 0.0, 0.0, 2.0, 0.1, 5.0]);
        let mut offset = SVector::<f64, 6>::zeros();
        offset[5] = 0.3;
        let heading = Heading::of(&centre);
        assert_eq!(heading.around(&offset), (heading, heading));
    }
}
