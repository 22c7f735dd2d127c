//! CTRA+: 2D CTRA on a plane tilted by a constant pitch (paper §III-A).

use super::{arc_integrals, Heading, ModelKind, MotionModel, A, OMEGA, THETA, V, X, Y, Z};
use crate::math::wrap_angle;
use nalgebra::SVector;

/// CTRA+: constant turn rate omega, constant tangential acceleration a, constant pitch phi.
///
/// State (8): `[x, y, z, theta, phi, v, a, omega]` — m, rad, m/s, m/s², rad/s (paper eq.
/// `plus_state`).
///
/// ```text
/// theta(t) = theta0 + omega t                                  (paper eq. theta)
/// v(t)     = v0 + a t,   phi(t) = phi0                         (eq. phi_plus)
/// [x, y](t) = [x0, y0] + cos(phi) · CTRA2D(theta0, omega, v0, a, t)
/// z(t)     = z0 + sin(phi) (v0 t + a t²/2)
/// ```
///
/// Erratum (reference §3): the paper says the horizontal part equals 2D CTRA multiplied by sin(phi);
/// it is cos(phi). The 2D CTRA integral is [`arc_integral`](crate::arc_integral), exact at omega = 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CtraPlus;

impl MotionModel<8> for CtraPlus {
    const KIND: ModelKind = ModelKind::CtraPlus;

    const SHARES_HEADING: bool = true;

    const LINEAR_TAIL: Option<&'static [(usize, usize)]> = Some(&[(THETA, OMEGA), (V, A)]);

    fn propagate(&self, s: &SVector<f64, 8>, dt: f64) -> SVector<f64, 8> {
        self.propagate_with(s, &Heading::of(s), dt)
    }

    #[inline(always)]
    fn propagate_with(&self, s: &SVector<f64, 8>, heading: &Heading, dt: f64) -> SVector<f64, 8> {
        let (st, ct) = heading.theta;
        let ([dx], [dy]) = arc_integrals([st], [ct], [s[OMEGA]], [s[V]], [s[A]], dt);
        finish(s, heading, (dx, dy), dt)
    }

    #[inline(always)]
    fn propagate_pair(
        &self,
        states: [&SVector<f64, 8>; 2],
        headings: [&Heading; 2],
        dt: f64,
    ) -> [SVector<f64, 8>; 2] {
        let ([p, m], [hp, hm]) = (states, headings);
        let (dx, dy) = arc_integrals(
            [hp.theta.0, hm.theta.0],
            [hp.theta.1, hm.theta.1],
            [p[OMEGA], m[OMEGA]],
            [p[V], m[V]],
            [p[A], m[A]],
            dt,
        );
        [
            finish(p, hp, (dx[0], dy[0]), dt),
            finish(m, hm, (dx[1], dy[1]), dt),
        ]
    }
}

/// The state after `dt` from the turn's arc integral (`dx`, `dy`): the horizontal part tilted by
/// the pitch, the climb along it.
#[inline(always)]
fn finish(
    s: &SVector<f64, 8>,
    heading: &Heading,
    (dx, dy): (f64, f64),
    dt: f64,
) -> SVector<f64, 8> {
    let (sp, cp) = heading.phi;
    let along = s[V] * dt + 0.5 * s[A] * dt * dt;
    let mut out = *s;
    out[X] += cp * dx;
    out[Y] += cp * dy;
    out[Z] += sp * along;
    out[THETA] = wrap_angle(s[THETA] + s[OMEGA] * dt);
    out[V] = s[V] + s[A] * dt;
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_the_2d_ctra_reference_values() {
        let s = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        let out = CtraPlus.propagate(&s, 0.5);
        assert!((out[X] - 0.5967208697966773).abs() < 1e-12);
        assert!((out[Y] - 0.16305169576864387).abs() < 1e-12);
        assert_eq!(out[V], 1.5);
        assert_eq!(out[THETA], 0.5);
        let mut straight = s;
        straight[OMEGA] = 0.0;
        assert!((CtraPlus.propagate(&straight, 0.5)[X] - 0.625).abs() < 1e-15);
    }

    #[test]
    fn a_pair_propagates_to_the_bits_of_two_single_points() {
        let centre = SVector::<f64, 8>::from([3.0, -1.0, 20.0, 2.9, 0.2, 7.0, 0.3, 0.05]);
        // A short turn for both points (the batched series), then a long one for one of them.
        for d_omega in [0.01, 3.0] {
            let d = SVector::<f64, 8>::from([0.5, 0.2, -0.3, 0.4, 0.1, 0.6, 0.2, d_omega]);
            let (p, m) = (centre + d, centre - d);
            let (hp, hm) = (Heading::of(&p), Heading::of(&m));
            let [a, b] = CtraPlus.propagate_pair([&p, &m], [&hp, &hm], 0.1);
            assert_eq!(a, CtraPlus.propagate_with(&p, &hp, 0.1));
            assert_eq!(b, CtraPlus.propagate_with(&m, &hm, 0.1));
        }
    }

    #[test]
    fn climbs_along_its_pitch() {
        let s = SVector::<f64, 8>::from([0.0, 0.0, 0.0, 0.0, 0.3, 2.0, 0.0, 0.0]);
        let out = CtraPlus.propagate(&s, 3.0);
        assert!((out[Z] - 6.0 * 0.3f64.sin()).abs() < 1e-12);
        assert!((out[X] - 6.0 * 0.3f64.cos()).abs() < 1e-12);
    }
}
