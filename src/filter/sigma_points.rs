//! Scaled sigma points (van der Merwe, "Sigma-Point Kalman Filters", 2004, §3.2).

use crate::math::wrap_angle;
use crate::models::{Heading, MotionModel, ANGLES, PHI, Z};
use nalgebra::{SMatrix, SVector};
use serde::{Deserialize, Serialize};

/// The rows a [linear tail](MotionModel::LINEAR_TAIL) leaves nonlinear: x, y and z.
const POSITION_ROWS: usize = Z + 1;

/// How far (rad) an angle's sigma points may lie from the centre for
/// [`SigmaPoints::kinematic_moments`]: below π with a margin, so that no residual wraps, even
/// after the rounding of the mean.
pub const UNWRAPPED_SPREAD: f64 = 3.0;

/// F `m` for a [linear tail](MotionModel::LINEAR_TAIL) `rates` over `dt`: row i gains dt · row j.
fn advance_rows<const N: usize>(m: &mut SMatrix<f64, N, N>, rates: &[(usize, usize)], dt: f64) {
    for &(i, j) in rates {
        for c in 0..N {
            m[(i, c)] += dt * m[(j, c)];
        }
    }
}

/// Scaling parameters of the sigma points: lambda = alpha² (n + kappa) − n.
///
/// Defaults: alpha = 1, beta = 2, kappa = 3 − n, so that n + lambda = 3 and the points sit at
/// ±√3 standard deviations, which matches the fourth moment of a Gaussian (Julier & Uhlmann 1997).
/// A small alpha (1e-3, common in textbooks) puts the points very close to the mean and makes
/// the centre weight huge and negative; this filter survives that too (see [`crate::Ukf`]), but
/// for models with strongly nonlinear angles the wider spread estimates the mean better.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "camelCase")]
pub struct SigmaParams {
    /// Spread of the points around the mean (0 < alpha ≤ 1).
    pub alpha: f64,
    /// Prior knowledge of the distribution (2 is optimal for a Gaussian).
    pub beta: f64,
    /// Secondary scaling; `None` means 3 − n.
    pub kappa: Option<f64>,
}

impl Default for SigmaParams {
    fn default() -> Self {
        SigmaParams {
            alpha: 1.0,
            beta: 2.0,
            kappa: None,
        }
    }
}

/// The weights of the 2n + 1 sigma points. All points but the centre share one weight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmaWeights {
    /// Mean weight of the centre point.
    pub mean0: f64,
    /// Covariance weight of the centre point.
    pub cov0: f64,
    /// Weight (mean and covariance) of each of the other 2n points.
    pub other: f64,
    /// √(n + lambda), the spread in standard deviations.
    pub gamma: f64,
}

impl SigmaWeights {
    /// Weights for an `n`-dimensional state. Returns `None` when n + lambda ≤ 0 (no real sigma
    /// points exist for such parameters).
    pub fn new(n: usize, p: SigmaParams) -> Option<Self> {
        let nf = n as f64;
        let kappa = p.kappa.unwrap_or(3.0 - nf);
        let lambda = p.alpha * p.alpha * (nf + kappa) - nf;
        let spread = nf + lambda;
        if !(spread > 0.0 && spread.is_finite() && p.beta.is_finite()) {
            return None;
        }
        let mean0 = lambda / spread;
        Some(SigmaWeights {
            mean0,
            cov0: mean0 + 1.0 - p.alpha * p.alpha + p.beta,
            other: 0.5 / spread,
            gamma: spread.sqrt(),
        })
    }
}

/// 2n + 1 sigma points kept on the stack: the centre and the two mirrored sets of n columns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SigmaPoints<const N: usize> {
    /// The centre point (the mean).
    pub center: SVector<f64, N>,
    /// center + gamma · column i of the Cholesky factor.
    pub plus: SMatrix<f64, N, N>,
    /// center − gamma · column i of the Cholesky factor.
    pub minus: SMatrix<f64, N, N>,
}

impl<const N: usize> SigmaPoints<N> {
    /// Points around `mean` from a lower-triangular square root `l` of the covariance.
    pub fn new(mean: &SVector<f64, N>, l: &SMatrix<f64, N, N>, gamma: f64) -> Self {
        Self::new_mapped(mean, l, gamma, |s| *s)
    }

    /// The points around `mean` (as [`SigmaPoints::new`]) with `f` applied to each as it is made:
    /// the same numbers as `new(..).map(f)` without building and copying the unmapped set.
    pub fn new_mapped(
        mean: &SVector<f64, N>,
        l: &SMatrix<f64, N, N>,
        gamma: f64,
        mut f: impl FnMut(&SVector<f64, N>) -> SVector<f64, N>,
    ) -> Self {
        let mut plus = SMatrix::<f64, N, N>::zeros();
        let mut minus = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            let offset = l.column(i) * gamma;
            plus.set_column(i, &f(&(mean + offset)));
            minus.set_column(i, &f(&(mean - offset)));
        }
        SigmaPoints {
            center: f(mean),
            plus,
            minus,
        }
    }

    /// The points around `mean` (as [`SigmaPoints::new`]) propagated through `model` over `dt`
    /// seconds. A model that [shares headings](MotionModel::SHARES_HEADING) gets each point's
    /// sines and cosines of θ and φ from the centre's ([`Heading::around`]) instead of computing
    /// them: the same points, and the same images up to rounding, for half the trigonometry.
    pub fn propagated<M: MotionModel<N>>(
        model: &M,
        mean: &SVector<f64, N>,
        l: &SMatrix<f64, N, N>,
        gamma: f64,
        dt: f64,
    ) -> Self {
        if !M::SHARES_HEADING {
            return Self::new_mapped(mean, l, gamma, |s| model.propagate(s, dt));
        }
        let centre = Heading::of(mean);
        let mut plus = SMatrix::<f64, N, N>::zeros();
        let mut minus = SMatrix::<f64, N, N>::zeros();
        for i in 0..N {
            let offset = l.column(i) * gamma;
            let (up, down) = centre.around(&offset);
            let [p, m] =
                model.propagate_pair([&(mean + offset), &(mean - offset)], [&up, &down], dt);
            plus.set_column(i, &p);
            minus.set_column(i, &m);
        }
        SigmaPoints {
            center: model.propagate_with(mean, &centre, dt),
            plus,
            minus,
        }
    }

    /// Whether `model`'s [linear tail](MotionModel::LINEAR_TAIL) holds over `dt` at the centre
    /// and at every point around it (placed as [`Self::new`] places them): where it does,
    /// [`Self::kinematic_moments`] may replace the general sums. Free for a model that declares
    /// its tail outright; a bounded station's points are checked one by one.
    pub fn tail_holds<M: MotionModel<N>>(
        model: &M,
        mean: &SVector<f64, N>,
        l: &SMatrix<f64, N, N>,
        gamma: f64,
        dt: f64,
    ) -> bool {
        model.tail_holds(mean, dt)
            && (0..N).all(|i| {
                let offset = l.column(i) * gamma;
                model.tail_holds(&(mean + offset), dt) && model.tail_holds(&(mean - offset), dt)
            })
    }

    /// Applies `f` (a motion model, a measurement of the full state) to every point.
    pub fn map(&self, mut f: impl FnMut(&SVector<f64, N>) -> SVector<f64, N>) -> Self {
        let mut out = *self;
        out.center = f(&self.center);
        for i in 0..N {
            out.plus
                .set_column(i, &f(&self.plus.column(i).into_owned()));
            out.minus
                .set_column(i, &f(&self.minus.column(i).into_owned()));
        }
        out
    }

    /// Weighted mean of the points. Components listed in `angles` are averaged on the circle:
    /// as the centre plus the weighted mean of wrapped residuals from it, which stays correct
    /// with the negative centre weight of the scaled transform (a plain atan2 of weighted sines
    /// and cosines does not).
    pub fn mean(&self, w: &SigmaWeights, angles: &[usize]) -> SVector<f64, N> {
        let mut sum = self.center * w.mean0;
        for i in 0..N {
            sum += (self.plus.column(i) + self.minus.column(i)) * w.other;
        }
        for &k in angles {
            let c = self.center[k];
            let mut r = 0.0;
            for i in 0..N {
                r += wrap_angle(self.plus[(k, i)] - c) + wrap_angle(self.minus[(k, i)] - c);
            }
            sum[k] = wrap_angle(c + r * w.other);
        }
        sum
    }

    /// The mean and covariance of points propagated (by [`Self::propagated`]) through a model
    /// with a [linear tail](MotionModel::LINEAR_TAIL) `rates`, from the covariance `p` the
    /// points were drawn with (`l` its Cholesky factor, `dt` the step): equal to
    /// [`Self::mean`] and [`Self::covariance`] up to rounding, for a third of the work.
    ///
    /// Only x, y and z need the points. A point's offset from the centre in the linear rows is
    /// exactly γ F Lₖ (F the tail's linear map), so those rows' weighted mean is the centre's,
    /// their covariance is 2wγ² F L Lᵀ Fᵀ = F P Fᵀ, and their cross-covariance with the
    /// position is w Σₖ (χₖ⁺ − χₖ⁻)ₚ (γ F Lₖ)ᵀ. The position rows' mean and covariance are
    /// summed as [`Self::mean`] and [`Self::covariance`] sum them, bit for bit.
    ///
    /// `None` when an angle's points reach [`UNWRAPPED_SPREAD`] from the centre (wrapping would
    /// then change the residuals: use the general sums), or when `angles` are not θ and φ.
    pub fn kinematic_moments(
        &self,
        p: &SMatrix<f64, N, N>,
        l: &SMatrix<f64, N, N>,
        rates: &[(usize, usize)],
        dt: f64,
        w: &SigmaWeights,
        angles: &[usize],
    ) -> Option<(SVector<f64, N>, SMatrix<f64, N, N>)> {
        if angles != ANGLES || N <= PHI {
            return None;
        }
        // e = γ F L: column k is point k's offset in the linear rows (its position rows unused).
        let mut e = l * w.gamma;
        advance_rows(&mut e, rates, dt);
        let unwrapped = |a: &usize| (0..N).all(|k| e[(*a, k)].abs() < UNWRAPPED_SPREAD);
        if !angles.iter().all(unwrapped) {
            return None;
        }
        let mut mean = self.center;
        for &a in angles {
            mean[a] = wrap_angle(mean[a]);
        }
        for r in 0..POSITION_ROWS {
            let mut sum = self.center[r] * w.mean0;
            for k in 0..N {
                sum += (self.plus[(r, k)] + self.minus[(r, k)]) * w.other;
            }
            mean[r] = sum;
        }
        // F P Fᵀ, one rate at a time: its row, then its column.
        let mut cov = *p;
        for &(i, j) in rates {
            for c in 0..N {
                cov[(i, c)] += dt * cov[(j, c)];
            }
            for r in 0..N {
                cov[(r, i)] += dt * cov[(r, j)];
            }
        }
        let residual = |points: &SMatrix<f64, N, N>, k: usize| -> [f64; POSITION_ROWS] {
            core::array::from_fn(|r| points[(r, k)] - mean[r])
        };
        let d0: [f64; POSITION_ROWS] = core::array::from_fn(|r| self.center[r] - mean[r]);
        let mut pp = [[0.0; POSITION_ROWS]; POSITION_ROWS];
        let mut mm = [[0.0; POSITION_ROWS]; POSITION_ROWS];
        let mut cross = [[0.0; N]; POSITION_ROWS];
        for k in 0..N {
            let a = residual(&self.plus, k);
            let b = residual(&self.minus, k);
            for j in 0..POSITION_ROWS {
                for i in j..POSITION_ROWS {
                    pp[j][i] += a[i] * a[j];
                    mm[j][i] += b[i] * b[j];
                }
                let spread = a[j] - b[j];
                for t in POSITION_ROWS..N {
                    cross[j][t] += spread * e[(t, k)];
                }
            }
        }
        for j in 0..POSITION_ROWS {
            for i in j..POSITION_ROWS {
                let v = d0[i] * d0[j] * w.cov0 + (pp[j][i] + mm[j][i]) * w.other;
                cov[(i, j)] = v;
                cov[(j, i)] = v;
            }
            for t in POSITION_ROWS..N {
                let v = cross[j][t] * w.other;
                cov[(t, j)] = v;
                cov[(j, t)] = v;
            }
        }
        Some((mean, cov))
    }

    /// Residual of one point from `mean`, with angles wrapped to (−pi, pi].
    #[inline(always)]
    pub fn residual(
        point: &SVector<f64, N>,
        mean: &SVector<f64, N>,
        angles: &[usize],
    ) -> SVector<f64, N> {
        let mut d = point - mean;
        for &k in angles {
            d[k] = wrap_angle(d[k]);
        }
        d
    }

    /// Weighted covariance Σ w (χ − x̄)(χ − x̄)ᵀ of these points.
    pub fn covariance(
        &self,
        mean: &SVector<f64, N>,
        angles: &[usize],
        w: &SigmaWeights,
    ) -> SMatrix<f64, N, N> {
        let d0 = Self::residual(&self.center, mean, angles);
        // The result is symmetric: each product commutes, so the upper triangle repeats the
        // lower bit for bit. Sum the lower one in the same order as the matrix form
        // d0 d0ᵀ c0 + (Dp Dpᵀ + Dm Dmᵀ) w (over k, point by point) and mirror it: half the
        // multiplications. Each pair's residuals are made as they are needed, not stored.
        let mut p = SMatrix::<f64, N, N>::zeros();
        let mut m = SMatrix::<f64, N, N>::zeros();
        for k in 0..N {
            let a = Self::residual(&self.plus.column(k).into_owned(), mean, angles);
            let b = Self::residual(&self.minus.column(k).into_owned(), mean, angles);
            for j in 0..N {
                let (aj, bj) = (a[j], b[j]);
                for i in j..N {
                    p[(i, j)] += a[i] * aj;
                    m[(i, j)] += b[i] * bj;
                }
            }
        }
        let mut cov = SMatrix::<f64, N, N>::zeros();
        for j in 0..N {
            for i in j..N {
                let v = d0[i] * d0[j] * w.cov0 + (p[(i, j)] + m[(i, j)]) * w.other;
                cov[(i, j)] = v;
                cov[(j, i)] = v;
            }
        }
        cov
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for n in [2usize, 6, 8, 9] {
            for alpha in [1e-3, 0.1, 0.5, 1.0] {
                let w = SigmaWeights::new(
                    n,
                    SigmaParams {
                        alpha,
                        beta: 2.0,
                        kappa: Some(0.0),
                    },
                )
                .unwrap();
                let sum = w.mean0 + 2.0 * n as f64 * w.other;
                assert!((sum - 1.0).abs() < 1e-9, "n={n} alpha={alpha}: {sum}");
            }
        }
    }

    #[test]
    fn rejects_parameters_without_real_points() {
        assert!(SigmaWeights::new(
            9,
            SigmaParams {
                alpha: 1.0,
                beta: 2.0,
                kappa: Some(-9.0)
            }
        )
        .is_none());
    }

    /// The moments [`SigmaPoints::kinematic_moments`] finds, against the general sums, for a
    /// model and a covariance with correlations everywhere.
    fn closed_form_against_sums<const N: usize, M: MotionModel<N>>(model: M, scale: f64) {
        let x =
            SVector::<f64, N>::from_fn(|i, _| [5.0, -2.0, 40.0, 3.0, 0.2, 8.0, 0.5, 0.3, -0.1][i]);
        let a = SMatrix::<f64, N, N>::from_fn(|i, j| ((i * 7 + j * 3) % 11) as f64 / 11.0 - 0.4);
        let p = (a * a.transpose() + SMatrix::identity()) * scale;
        let l = crate::cholesky_lower(&p).unwrap();
        let w = SigmaWeights::new(N, SigmaParams::default()).unwrap();
        let points = SigmaPoints::propagated(&model, &x, &l, w.gamma, 0.4);
        let rates = M::LINEAR_TAIL.unwrap();
        let (mean, cov) = points
            .kinematic_moments(&p, &l, rates, 0.4, &w, ANGLES)
            .expect("the points stay within the unwrapped spread");
        let sum_mean = points.mean(&w, ANGLES);
        let sum_cov = points.covariance(&sum_mean, ANGLES, &w);
        for i in 0..N {
            assert!((mean[i] - sum_mean[i]).abs() < 1e-12, "mean {i}");
            for j in 0..N {
                let tolerance = 1e-13 * (1.0 + sum_cov[(i, j)].abs());
                assert!(
                    (cov[(i, j)] - sum_cov[(i, j)]).abs() < tolerance,
                    "cov ({i}, {j}): {} vs {}",
                    cov[(i, j)],
                    sum_cov[(i, j)]
                );
            }
        }
        // The position rows are summed in the same order as the general sums: the same bits.
        for i in 0..3 {
            assert_eq!(mean[i], sum_mean[i]);
            for j in 0..3 {
                assert_eq!(cov[(i, j)], sum_cov[(i, j)]);
            }
        }
    }

    #[test]
    fn closed_form_moments_equal_the_sums_to_rounding() {
        closed_form_against_sums::<6, _>(crate::Dr, 0.01);
        closed_form_against_sums::<8, _>(crate::CtraPlus, 0.01);
        closed_form_against_sums::<9, _>(crate::Ctra3d, 0.01);
        closed_form_against_sums::<9, _>(crate::Ctra3d, 0.2);
    }

    #[test]
    fn closed_form_moments_step_aside_when_an_angle_could_wrap() {
        let x = SVector::<f64, 9>::from([0.0, 0.0, 0.0, 3.0, 0.0, 5.0, 0.0, 0.0, 0.0]);
        let p = SMatrix::<f64, 9, 9>::identity() * 4.0;
        let l = crate::cholesky_lower(&p).unwrap();
        let w = SigmaWeights::new(9, SigmaParams::default()).unwrap();
        let points = SigmaPoints::propagated(&crate::Ctra3d, &x, &l, w.gamma, 0.1);
        let rates = crate::Ctra3d::LINEAR_TAIL.unwrap();
        // γ·2 rad = 3.46 rad: the points of θ reach past UNWRAPPED_SPREAD.
        assert!(points
            .kinematic_moments(&p, &l, rates, 0.1, &w, ANGLES)
            .is_none());
        // Without θ and φ as the angles the closed form makes no claim.
        let small = SMatrix::<f64, 9, 9>::identity() * 1e-4;
        let l = crate::cholesky_lower(&small).unwrap();
        let points = SigmaPoints::propagated(&crate::Ctra3d, &x, &l, w.gamma, 0.1);
        assert!(points
            .kinematic_moments(&small, &l, rates, 0.1, &w, &[])
            .is_none());
    }

    #[test]
    fn circular_mean_straddles_pi() {
        let w = SigmaWeights::new(1, SigmaParams::default()).unwrap();
        let pts = SigmaPoints::<1> {
            center: SVector::from([3.1]),
            plus: SMatrix::from([[-3.1]]),
            minus: SMatrix::from([[3.0]]),
        };
        let m = pts.mean(&w, &[0]);
        // Points at 3.1, -3.1 (= 3.183) and 3.0: the mean is near pi, not near 0.
        assert!(m[0].abs() > 3.0, "{}", m[0]);
    }
}
