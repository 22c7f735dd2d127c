//! The Unscented Kalman Filter, generic over the state size, on the stack.

use super::{cholesky_lower, forward_substitute, SigmaParams, SigmaPoints, SigmaWeights};
use crate::math::wrap_angle;
use crate::models::MotionModel;
use nalgebra::{Cholesky, SMatrix, SVector};

/// An Unscented Kalman Filter over an `N`-dimensional state (van der Merwe 2004; reference §4).
///
/// * Scaled sigma points ([`SigmaParams`]), angle-aware means and wrapped residuals for the
///   components listed as angles (theta, phi for the motion models).
/// * Prediction through any [`MotionModel`]; the update takes a measurement of the full state
///   (the drone's sensors measure every component, reference §4), so h is the identity.
/// * The covariance is symmetrised after every step and factorised after every update and before
///   every prediction; when its Cholesky factorisation fails (rounding has made it indefinite)
///   jitter is added on the diagonal until it succeeds, and the event is counted in
///   [`Ukf::recoveries`]. The filter never yields NaN from a finite input.
///
/// ```
/// use loratrack::{Ukf, Dr, SigmaParams, process_noise};
/// use nalgebra::{SMatrix, SVector};
/// let x = SVector::<f64, 6>::from([0.0, 0.0, 10.0, 0.0, 0.0, 5.0]);
/// let p0 = SMatrix::identity() * 1e-6;
/// let mut ukf = Ukf::new(x, p0, process_noise(0.1), SigmaParams::default(), &[3, 4]).unwrap();
/// ukf.predict(&Dr, 1.0);
/// // 5 m east; with an uncertain heading the mean falls short by E[1 - cos theta] ≈ var/2.
/// assert!((ukf.x[0] - 5.0).abs() < 1e-5);
/// ```
#[derive(Clone, Debug)]
pub struct Ukf<const N: usize> {
    /// State estimate.
    pub x: SVector<f64, N>,
    /// State covariance (symmetric positive definite).
    pub p: SMatrix<f64, N, N>,
    /// Process-noise intensity per second: a prediction over `dt` adds `q · dt` (the first-order
    /// discretisation of continuous white noise), so the filter behaves the same whatever its
    /// step length. See `filter::noise` for why this reading of the paper's Q = qI.
    pub q: SMatrix<f64, N, N>,
    weights: SigmaWeights,
    angles: &'static [usize],
    recoveries: u64,
    /// The Cholesky factor found when the last step checked P, with the P it belongs to: the next
    /// step needs exactly that factor, and P is public, so the copy guards against edits.
    factor: Option<(SMatrix<f64, N, N>, SMatrix<f64, N, N>)>,
}

impl<const N: usize> Ukf<N> {
    /// A filter at `x` with covariance `p`. Returns `None` when the sigma parameters admit no
    /// real sigma points (n + lambda ≤ 0).
    pub fn new(
        x: SVector<f64, N>,
        p: SMatrix<f64, N, N>,
        q: SMatrix<f64, N, N>,
        sigma: SigmaParams,
        angles: &'static [usize],
    ) -> Option<Self> {
        let weights = SigmaWeights::new(N, sigma)?;
        Some(Ukf {
            x,
            p,
            q,
            weights,
            angles,
            recoveries: 0,
            factor: None,
        })
    }

    /// How many times the covariance had to be repaired (jitter added) to stay positive definite.
    pub fn recoveries(&self) -> u64 {
        self.recoveries
    }

    /// Replaces the state and covariance (the station does this on every received packet).
    pub fn reset(&mut self, x: SVector<f64, N>, p: SMatrix<f64, N, N>) {
        self.x = x;
        self.p = p;
    }

    /// Prediction step: propagates the sigma points through `model` over `dt` seconds,
    /// recombines them and adds Q·dt.
    pub fn predict<M: MotionModel<N>>(&mut self, model: &M, dt: f64) {
        let (l, exact) = self.factor_covariance();
        let gamma = self.weights.gamma;
        let points = SigmaPoints::propagated(model, &self.x, &l, gamma, dt);
        let closed_form = match M::LINEAR_TAIL {
            Some(rates) if exact && SigmaPoints::tail_holds(model, &self.x, &l, gamma, dt) => {
                points.kinematic_moments(&self.p, &l, rates, dt, &self.weights, self.angles)
            }
            _ => None,
        };
        let (mean, cov) = closed_form.unwrap_or_else(|| {
            let mean = points.mean(&self.weights, self.angles);
            (mean, points.covariance(&mean, self.angles, &self.weights))
        });
        self.x = mean;
        self.p = cov + self.q * dt.abs();
        self.defer_check();
    }

    /// Update step with a measurement `z` of the full state and its noise covariance `r`.
    ///
    /// h is the identity, and the unscented transform of a linear map is exact: the sigma points'
    /// mean is x and their covariance P, so the update is the Kalman filter's, and it is computed
    /// as such (no sigma points). Only where an angle's spread reaches ±pi, so that wrapping the
    /// points changes their mean and covariance, are the sigma points used.
    pub fn update(&mut self, z: &SVector<f64, N>, r: &SMatrix<f64, N, N>) {
        if self.angles_stay_within_pi() {
            self.linear_update(z, r);
        } else {
            self.unscented_update(z, r);
        }
    }

    /// Whether every sigma point lies within pi of the mean in every angle: |γ L_ki| ≤ γ √P_kk
    /// (a row of the Cholesky factor has the norm √P_kk), so no point wraps.
    fn angles_stay_within_pi(&self) -> bool {
        let gamma = self.weights.gamma;
        self.angles
            .iter()
            .all(|&k| gamma * self.p[(k, k)].sqrt() < core::f64::consts::PI)
    }

    /// The Kalman update for h = I: S = P + R, K = P S⁻¹, x += K (z − x), P −= K P.
    ///
    /// With S = L Lᵀ, W = L⁻¹ P and y = L⁻¹ (z − x), the gain is never formed: K (z − x) = Wᵀ y
    /// and K P = P S⁻¹ P = Wᵀ W, which is symmetric by construction. Two forward substitutions
    /// replace the solve for K (forward and back) and the product K P.
    fn linear_update(&mut self, z: &SVector<f64, N>, r: &SMatrix<f64, N, N>) {
        let mut x_mean = self.x;
        for &i in self.angles {
            x_mean[i] = wrap_angle(x_mean[i]);
        }
        let mut s = self.p + r;
        let factor = if symmetrise(&mut s) {
            cholesky_lower(&s)
        } else {
            None
        };
        let Some(l) = factor else {
            self.recoveries += 1;
            return;
        };
        let innovation = SigmaPoints::<N>::residual(z, &x_mean, self.angles);
        let w = forward_substitute(&l, &self.p);
        let y = forward_substitute(&l, &innovation);
        self.x = x_mean + w.tr_mul(&y);
        for &i in self.angles {
            self.x[i] = wrap_angle(self.x[i]);
        }
        // P − Wᵀ W, the lower triangle computed and mirrored.
        for j in 0..N {
            for i in j..N {
                let v = self.p[(i, j)] - w.column(i).dot(&w.column(j));
                self.p[(i, j)] = v;
                self.p[(j, i)] = v;
            }
        }
        self.stabilise(true);
    }

    /// The update through sigma points, for spreads wide enough that angles wrap.
    fn unscented_update(&mut self, z: &SVector<f64, N>, r: &SMatrix<f64, N, N>) {
        let points = self.sigma_points();
        let x_mean = points.mean(&self.weights, self.angles);
        // h is the identity: the measurement sigma points are the state sigma points.
        let pzz = points.covariance(&x_mean, self.angles, &self.weights) + r;
        let pxz = pzz - r;
        let Some(chol) = Cholesky::new(0.5 * (pzz + pzz.transpose())) else {
            // The innovation covariance is at least R, which is PD for any valid R; a failure means
            // R itself was not PD. Skip the update rather than corrupt the state.
            self.recoveries += 1;
            return;
        };
        let innovation = SigmaPoints::<N>::residual(z, &x_mean, self.angles);
        // K = Pxz Pzz⁻¹, computed as (Pzz⁻¹ Pxzᵀ)ᵀ through the factorisation.
        let k = chol.solve(&pxz.transpose()).transpose();
        self.x = x_mean + k * innovation;
        for &i in self.angles {
            self.x[i] = wrap_angle(self.x[i]);
        }
        self.p -= k * pzz * k.transpose();
        self.stabilise(false);
    }

    fn sigma_points(&mut self) -> SigmaPoints<N> {
        let l = self.sqrt_covariance();
        SigmaPoints::new(&self.x, &l, self.weights.gamma)
    }

    /// Lower Cholesky factor of P, repairing P first if needed.
    fn sqrt_covariance(&mut self) -> SMatrix<f64, N, N> {
        self.factor_covariance().0
    }

    /// Lower Cholesky factor of P, repairing P first if needed, and whether it is one (`false`:
    /// the repair failed and the factor is the square root of P's diagonal only).
    fn factor_covariance(&mut self) -> (SMatrix<f64, N, N>, bool) {
        if let Some((p, l)) = &self.factor {
            // As slices: nalgebra's `==` walks both matrices through zipped iterators, which
            // cost a drone's step ~5 % (perf); the slices compare in one tight loop.
            if p.as_slice() == self.p.as_slice() {
                return (*l, true);
            }
        }
        if let Some(l) = cholesky_lower(&self.p) {
            return (l, true);
        }
        self.repair();
        match cholesky_lower(&self.p) {
            Some(l) => (l, true),
            None => (
                SMatrix::from_diagonal(&self.p.diagonal().map(|d| d.abs().sqrt())),
                false,
            ),
        }
    }

    /// After a prediction: keeps P symmetric and finite, and leaves the factorisation that proves it
    /// positive definite to the next step that needs the factor ([`Self::sqrt_covariance`] repairs P
    /// there when it fails). A weighted sum of outer products plus Q·dt is positive definite unless
    /// rounding broke it, and a drone's update (Kalman form) needs no factor of P: its predict and
    /// update factorise twice instead of three times.
    fn defer_check(&mut self) {
        self.factor = None;
        if !symmetrise(&mut self.p) {
            self.repair();
        }
    }

    /// Keeps P symmetric, finite and positive definite after an update, and keeps its factor for
    /// the prediction that follows. `symmetric`: the update made P symmetric by construction (the
    /// Kalman form mirrors its lower triangle), so only finiteness is checked rather than each
    /// pair averaged with itself.
    fn stabilise(&mut self, symmetric: bool) {
        if !symmetric {
            self.defer_check();
        } else {
            self.factor = None;
            if !self.p.as_slice().iter().all(|v| v.is_finite()) {
                self.repair();
            }
        }
        match cholesky_lower(&self.p) {
            Some(l) => self.factor = Some((self.p, l)),
            None => self.repair(),
        }
    }

    /// Adds growing diagonal jitter until P factorises; falls back to Q if P is not finite.
    fn repair(&mut self) {
        self.recoveries += 1;
        if !self.p.iter().all(|v| v.is_finite()) {
            self.p = self.q;
        }
        self.p = 0.5 * (self.p + self.p.transpose());
        let scale = (self.p.trace().abs() / N as f64).max(1e-12);
        let mut jitter = scale * 1e-12;
        for _ in 0..30 {
            let candidate = self.p + SMatrix::<f64, N, N>::identity() * jitter;
            if cholesky_lower(&candidate).is_some() {
                self.p = candidate;
                return;
            }
            jitter *= 10.0;
        }
        self.p = SMatrix::from_diagonal(&self.p.diagonal().map(|d| d.abs().max(scale)));
    }
}

/// Makes `p` exactly symmetric, each pair of entries across the diagonal replaced by their mean
/// (the numbers of ½(P + Pᵀ) in half the operations), and tells whether every entry is finite.
fn symmetrise<const N: usize>(p: &mut SMatrix<f64, N, N>) -> bool {
    let mut finite = true;
    for j in 0..N {
        finite &= p[(j, j)].is_finite();
        for i in j + 1..N {
            let v = 0.5 * (p[(i, j)] + p[(j, i)]);
            p[(i, j)] = v;
            p[(j, i)] = v;
            finite &= v.is_finite();
        }
    }
    finite
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::ModelKind;

    /// Constant velocity in one dimension: [position, velocity]. Linear, so the UKF must equal
    /// the Kalman filter.
    struct ConstantVelocity;
    impl MotionModel<2> for ConstantVelocity {
        const KIND: ModelKind = ModelKind::Dr;
        fn propagate(&self, s: &SVector<f64, 2>, dt: f64) -> SVector<f64, 2> {
            SVector::from([s[0] + s[1] * dt, s[1]])
        }
    }

    #[test]
    fn matches_a_linear_kalman_filter_on_a_linear_model() {
        let f = SMatrix::<f64, 2, 2>::new(1.0, 0.5, 0.0, 1.0);
        let q = SMatrix::<f64, 2, 2>::new(0.01, 0.0, 0.0, 0.02);
        let r = SMatrix::<f64, 2, 2>::new(0.5, 0.0, 0.0, 0.3);
        let x0 = SVector::from([0.0, 1.0]);
        let p0 = SMatrix::<f64, 2, 2>::new(2.0, 0.3, 0.3, 1.0);
        for params in [
            SigmaParams::default(),
            SigmaParams {
                alpha: 1e-3,
                beta: 2.0,
                kappa: Some(0.0),
            },
        ] {
            let mut ukf = Ukf::new(x0, p0, q, params, &[]).unwrap();
            let (mut x, mut p) = (x0, p0);
            for k in 0..50 {
                let z = SVector::from([
                    0.5 * k as f64 + (k as f64 * 0.7).sin(),
                    1.0 + 0.1 * (k as f64).cos(),
                ]);
                ukf.predict(&ConstantVelocity, 0.5);
                x = f * x;
                p = f * p * f.transpose() + q * 0.5;
                ukf.update(&z, &r);
                let s = p + r;
                let k_gain = p * s.try_inverse().unwrap();
                x += k_gain * (z - x);
                p = (SMatrix::identity() - k_gain) * p;
                assert!((ukf.x - x).norm() < 1e-6, "step {k}: {} vs {}", ukf.x, x);
                assert!((ukf.p - p).norm() < 1e-6, "step {k}");
            }
        }
    }

    #[test]
    fn unscented_transform_recovers_mean_and_covariance_of_a_linear_map() {
        let x = SVector::<f64, 2>::from([1.0, -2.0]);
        let p = SMatrix::<f64, 2, 2>::new(2.0, 0.5, 0.5, 1.0);
        let a = SMatrix::<f64, 2, 2>::new(1.5, -0.3, 0.2, 0.8);
        let w = SigmaWeights::new(2, SigmaParams::default()).unwrap();
        let l = Cholesky::new(p).unwrap().l();
        let pts = SigmaPoints::new(&x, &l, w.gamma).map(|s| a * s);
        let m = pts.mean(&w, &[]);
        let c = pts.covariance(&m, &[], &w);
        assert!((m - a * x).norm() < 1e-12);
        assert!((c - a * p * a.transpose()).norm() < 1e-12);
    }

    #[test]
    fn the_kalman_update_equals_the_unscented_one_while_no_angle_wraps() {
        use crate::models::{Ctra3d, ANGLES};
        let x = SVector::<f64, 9>::from([10.0, -5.0, 40.0, 3.1, 0.1, 8.0, 0.3, 0.2, 0.05]);
        let p =
            SMatrix::<f64, 9, 9>::from_fn(|i, j| if i == j { 0.2 + 0.01 * i as f64 } else { 0.01 });
        let r = SMatrix::<f64, 9, 9>::from_diagonal_element(0.3);
        let z = x.map(|v| v + 0.1);
        let mut ukf = Ukf::new(x, p, p * 0.1, SigmaParams::default(), ANGLES).unwrap();
        ukf.predict(&Ctra3d, 0.5);
        assert!(ukf.angles_stay_within_pi());
        let (mut linear, mut unscented) = (ukf.clone(), ukf);
        linear.linear_update(&z, &r);
        unscented.unscented_update(&z, &r);
        assert!(
            (linear.x - unscented.x).norm() < 1e-12,
            "{} vs {}",
            linear.x,
            unscented.x
        );
        assert!((linear.p - unscented.p).norm() < 1e-12);
    }

    #[test]
    fn a_spread_past_pi_in_an_angle_takes_the_unscented_update() {
        let mut ukf = Ukf::<2>::new(
            SVector::from([0.0, 1.0]),
            SMatrix::<f64, 2, 2>::from_diagonal(&SVector::from([4.0, 1.0])),
            SMatrix::identity() * 1e-3,
            SigmaParams::default(),
            &[0],
        )
        .unwrap();
        assert!(!ukf.angles_stay_within_pi());
        let mut linear = ukf.clone();
        let z = SVector::from([3.0, 1.0]);
        let r = SMatrix::<f64, 2, 2>::identity() * 0.1;
        ukf.update(&z, &r);
        linear.linear_update(&z, &r);
        // Points at ±√3·2 rad wrap: the wrapped covariance is smaller, so the gain differs.
        assert!((ukf.x[0] - linear.x[0]).abs() > 1e-3);
    }

    #[test]
    fn recovers_from_an_indefinite_covariance_without_nan() {
        let mut ukf = Ukf::<2>::new(
            SVector::from([0.0, 1.0]),
            SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0), // indefinite
            SMatrix::identity() * 1e-3,
            SigmaParams::default(),
            &[],
        )
        .unwrap();
        ukf.predict(&ConstantVelocity, 0.1);
        assert!(ukf.recoveries() > 0);
        assert!(ukf.x.iter().all(|v| v.is_finite()));
        assert!(Cholesky::new(ukf.p).is_some());
    }
}
