//! 3D-CTRA: constant turn rate, constant tilt rate and constant acceleration (paper §III-B).

use super::{
    arc_integrals, Heading, ModelKind, MotionModel, A, OMEGA, PHI, PSI, THETA, V, X, Y, Z,
};
use crate::math::wrap_angle;
use nalgebra::{SMatrix, SVector};

/// 3D-CTRA: the drone turns at a constant rate omega in the horizontal plane and tilts its
/// velocity at a constant rate psi, while accelerating at a constant a: a curved helix.
///
/// State (9): `[x, y, z, theta, phi, v, a, omega, psi]` — m, rad, m/s, m/s², rad/s, rad/s
/// (paper eq. `3d_state`).
///
/// With the Werner formula cos θ cos φ = ½[cos(θ+φ) + cos(θ−φ)] (paper §III-B):
///
/// ```text
/// theta(t) = theta0 + omega t,  phi(t) = phi0 + psi t,  v(t) = v0 + a t   (eqs. theta, phi_3d)
/// [x, y](t) = [x0, y0] + ½ I(theta0+phi0, omega+psi) + ½ I(theta0−phi0, omega−psi)   (eqs. x_int, y_int)
/// z(t)     = z0 + Im I(phi0, psi)                                                    (eq. z_int)
/// I(α, k)  = ∫₀ᵗ (v0 + aτ) e^{i(α + kτ)} dτ  = [`arc_integral`](crate::arc_integral)
/// ```
///
/// The paper's printed forms divide by (omega ± psi) and psi and need separate special cases for
/// psi = 0 and omega = ±psi; [`arc_integral`](crate::arc_integral) is exact at and near all of them, so this one
/// expression covers every case continuously (reference §3). `phi` is kept in (−pi, pi]: a pitch past
/// ±pi/2 is a loop, which the ODE describes without any special handling.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Ctra3d;

impl MotionModel<9> for Ctra3d {
    const KIND: ModelKind = ModelKind::Ctra3d;

    const SHARES_HEADING: bool = true;

    const LINEAR_TAIL: Option<&'static [(usize, usize)]> =
        Some(&[(THETA, OMEGA), (PHI, PSI), (V, A)]);

    fn propagate(&self, s: &SVector<f64, 9>, dt: f64) -> SVector<f64, 9> {
        self.propagate_with(s, &Heading::of(s), dt)
    }

    fn propagate_with(&self, s: &SVector<f64, 9>, heading: &Heading, dt: f64) -> SVector<f64, 9> {
        let (theta, phi, v, a) = (s[THETA], s[PHI], s[V], s[A]);
        let (omega, psi) = (s[OMEGA], s[PSI]);
        let ((st, ct), (sp, cp)) = (heading.theta, heading.phi);
        // sin and cos of theta ± phi by the addition formulas; the three integrals in one batch.
        let (cosines, sines) = arc_integrals(
            [st * cp + ct * sp, st * cp - ct * sp, sp],
            [ct * cp - st * sp, ct * cp + st * sp, cp],
            [omega + psi, omega - psi, psi],
            [v; 3],
            [a; 3],
            dt,
        );
        let mut out = *s;
        out[X] += 0.5 * (cosines[0] + cosines[1]);
        out[Y] += 0.5 * (sines[0] + sines[1]);
        out[Z] += sines[2];
        out[THETA] = wrap_angle(theta + omega * dt);
        out[PHI] = wrap_angle(phi + psi * dt);
        out[V] = v + a * dt;
        out
    }

    fn decay_tilt_rate(&self, state: &mut SVector<f64, 9>, eta: f64) {
        state[PSI] *= eta;
    }

    fn decay_tilt_rate_covariance(&self, p: &mut SMatrix<f64, 9, 9>, eta: f64) {
        for k in 0..9 {
            p[(PSI, k)] *= eta;
            p[(k, PSI)] *= eta;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::CtraPlus;

    #[test]
    fn the_tilt_rate_covariance_decays_like_the_tilt_rate() {
        let mut p = SMatrix::<f64, 9, 9>::from_element(1.0);
        Ctra3d.decay_tilt_rate_covariance(&mut p, 0.9);
        assert!((p[(PSI, PSI)] - 0.81).abs() < 1e-15);
        assert!((p[(0, PSI)] - 0.9).abs() < 1e-15 && (p[(PSI, 0)] - 0.9).abs() < 1e-15);
        assert_eq!(p[(0, 1)], 1.0);
    }

    #[test]
    fn equals_ctra_plus_when_psi_is_zero() {
        let s8 = SVector::<f64, 8>::from([1.0, -2.0, 30.0, 0.7, 0.25, 8.0, -0.5, 0.4]);
        let mut s9 = SVector::<f64, 9>::zeros();
        s9.fixed_rows_mut::<8>(0).copy_from(&s8);
        let a = CtraPlus.propagate(&s8, 4.0);
        let b = Ctra3d.propagate(&s9, 4.0);
        for i in 0..8 {
            assert!(
                (a[i] - b[i]).abs() < 1e-12,
                "component {i}: {} vs {}",
                a[i],
                b[i]
            );
        }
    }

    #[test]
    fn decay_multiplies_psi_by_eta() {
        let mut s = SVector::<f64, 9>::zeros();
        s[PSI] = 0.5;
        Ctra3d.decay_tilt_rate(&mut s, 0.9);
        assert!((s[PSI] - 0.45).abs() < 1e-15);
    }
}
