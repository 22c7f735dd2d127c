//! Dead reckoning (DR): uniform rectilinear motion, the paper's baseline.

use super::{Heading, ModelKind, MotionModel, V, X, Y, Z};
use nalgebra::SVector;

/// Dead reckoning: the drone keeps its velocity vector.
///
/// State (6): `[x, y, z, theta, phi, v]` — metres, radians, m/s (reference §2).
///
/// ```text
/// x(t) = x0 + v t cos(theta) cos(phi)
/// y(t) = y0 + v t sin(theta) cos(phi)
/// z(t) = z0 + v t sin(phi)
/// ```
///
/// This is the ODE of reference §3 with a = omega = psi = 0, i.e. constant velocity in 3D.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Dr;

impl MotionModel<6> for Dr {
    const KIND: ModelKind = ModelKind::Dr;

    const SHARES_HEADING: bool = true;

    const LINEAR_TAIL: Option<&'static [(usize, usize)]> = Some(&[]);

    fn propagate(&self, s: &SVector<f64, 6>, dt: f64) -> SVector<f64, 6> {
        self.propagate_with(s, &Heading::of(s), dt)
    }

    fn propagate_with(&self, s: &SVector<f64, 6>, heading: &Heading, dt: f64) -> SVector<f64, 6> {
        let ((st, ct), (sp, cp)) = (heading.theta, heading.phi);
        let d = s[V] * dt;
        let mut out = *s;
        out[X] += d * ct * cp;
        out[Y] += d * st * cp;
        out[Z] += d * sp;
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduces_to_constant_velocity() {
        let s = SVector::<f64, 6>::from([1.0, 2.0, 3.0, 0.6, 0.2, 5.0]);
        let (vx, vy, vz) = (
            5.0 * 0.6f64.cos() * 0.2f64.cos(),
            5.0 * 0.6f64.sin() * 0.2f64.cos(),
            5.0 * 0.2f64.sin(),
        );
        let out = Dr.propagate(&s, 2.5);
        assert!((out[X] - (1.0 + 2.5 * vx)).abs() < 1e-12);
        assert!((out[Y] - (2.0 + 2.5 * vy)).abs() < 1e-12);
        assert!((out[Z] - (3.0 + 2.5 * vz)).abs() < 1e-12);
        assert_eq!(out.fixed_rows::<3>(3), s.fixed_rows::<3>(3));
    }
}
