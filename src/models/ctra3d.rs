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

    #[inline(always)]
    fn propagate_with(&self, s: &SVector<f64, 9>, heading: &Heading, dt: f64) -> SVector<f64, 9> {
        let arcs = Arcs::of(s, heading);
        let (cosines, sines) = arc_integrals(arcs.sa, arcs.ca, arcs.k, [s[V]; 3], [s[A]; 3], dt);
        finish(s, cosines, sines, dt)
    }

    #[inline(always)]
    fn propagate_pair(
        &self,
        states: [&SVector<f64, 9>; 2],
        headings: [&Heading; 2],
        dt: f64,
    ) -> [SVector<f64, 9>; 2] {
        let [p, m] = states;
        let (ap, am) = (Arcs::of(p, headings[0]), Arcs::of(m, headings[1]));
        let join = |x: [f64; 3], y: [f64; 3]| [x[0], x[1], x[2], y[0], y[1], y[2]];
        let (v, a) = (
            [p[V], p[V], p[V], m[V], m[V], m[V]],
            [p[A], p[A], p[A], m[A], m[A], m[A]],
        );
        let (c, s) = arc_integrals(
            join(ap.sa, am.sa),
            join(ap.ca, am.ca),
            join(ap.k, am.k),
            v,
            a,
            dt,
        );
        [
            finish(p, [c[0], c[1], c[2]], [s[0], s[1], s[2]], dt),
            finish(m, [c[3], c[4], c[5]], [s[3], s[4], s[5]], dt),
        ]
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

/// The three arc integrals of a 3D-CTRA step (eqs. `x_int`–`z_int`): along θ + φ at ω + ψ, along
/// θ − φ at ω − ψ, and the vertical one along φ at ψ; their directions' sines and cosines by the
/// addition formulas.
struct Arcs {
    sa: [f64; 3],
    ca: [f64; 3],
    k: [f64; 3],
}

impl Arcs {
    #[inline(always)]
    fn of(s: &SVector<f64, 9>, heading: &Heading) -> Self {
        let ((st, ct), (sp, cp)) = (heading.theta, heading.phi);
        Arcs {
            sa: [st * cp + ct * sp, st * cp - ct * sp, sp],
            ca: [ct * cp - st * sp, ct * cp + st * sp, cp],
            k: [s[OMEGA] + s[PSI], s[OMEGA] - s[PSI], s[PSI]],
        }
    }
}

/// The state after `dt` from the three integrals' cosine and sine parts (Werner's formula for x
/// and y, the vertical integral's sine part for z).
#[inline(always)]
fn finish(s: &SVector<f64, 9>, cosines: [f64; 3], sines: [f64; 3], dt: f64) -> SVector<f64, 9> {
    let mut out = *s;
    out[X] += 0.5 * (cosines[0] + cosines[1]);
    out[Y] += 0.5 * (sines[0] + sines[1]);
    out[Z] += sines[2];
    out[THETA] = wrap_angle(s[THETA] + s[OMEGA] * dt);
    out[PHI] = wrap_angle(s[PHI] + s[PSI] * dt);
    out[V] = s[V] + s[A] * dt;
    out
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
    fn a_pair_propagates_to_the_bits_of_two_single_points() {
        let centre = SVector::<f64, 9>::from([3.0, -1.0, 20.0, 2.9, 0.2, 7.0, 0.3, 0.05, -0.02]);
        // A short turn for both points (the batched series), then a long one for one of them.
        for d_omega in [0.01, 3.0] {
            let d = SVector::<f64, 9>::from([0.5, 0.2, -0.3, 0.4, 0.1, 0.6, 0.2, d_omega, 0.03]);
            let (p, m) = (centre + d, centre - d);
            let (hp, hm) = (Heading::of(&p), Heading::of(&m));
            let [a, b] = Ctra3d.propagate_pair([&p, &m], [&hp, &hm], 0.1);
            assert_eq!(a, Ctra3d.propagate_with(&p, &hp, 0.1));
            assert_eq!(b, Ctra3d.propagate_with(&m, &hm, 0.1));
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
