//! Filter consistency: does the true position lie inside the station's 95 % ellipsoid, and how
//! large is the error against the uncertainty the station claims? (Bar-Shalom, Li & Kirubarajan
//! 2001, §5.4: the normalised estimation error squared, NEES.)

use super::error_length::length_95;
use crate::filter::cholesky_lower;
use nalgebra::Matrix3;

/// The 95 % quantile of the chi-square distribution with 3 degrees of freedom: a 3D Gaussian
/// error e with covariance P satisfies eᵀ P⁻¹ e ≤ this with probability 0.95.
pub const CHI2_3DOF_95: f64 = 7.814_727_903_251_178;

/// The normalised estimation error squared eᵀ P⁻¹ e of the position error `e` (m) against the
/// position covariance `p` (m²); χ²-distributed with 3 degrees of freedom (mean 3) when the
/// covariance is honest. A covariance that is not positive definite claims no uncertainty at
/// all: any error but zero is infinitely surprising.
///
/// ```
/// use loratrack::nees;
/// use nalgebra::Matrix3;
/// let p = Matrix3::identity() * 4.0; // 2 m standard deviation on each axis
/// assert!((nees(&[2.0, 2.0, 2.0], &p) - 3.0).abs() < 1e-12);
/// ```
pub fn nees(e: &[f64; 3], p: &Matrix3<f64>) -> f64 {
    let Some(l) = cholesky_lower(p) else {
        return if *e == [0.0; 3] { 0.0 } else { f64::INFINITY };
    };
    // P x = e through the factor, L y = e then Lᵀ x = y, in the order of operations of
    // nalgebra's `Cholesky::solve` (the same bits; tested). Written out because nalgebra takes
    // its square roots from libm, which in WebAssembly computes them in software: with the
    // bound below, most of a warm run's time once the page asks for the series.
    let mut x = *e;
    for i in 0..3 {
        let c = x[i] / l[(i, i)];
        x[i] = c;
        for k in i + 1..3 {
            x[k] -= c * l[(k, i)];
        }
    }
    for i in (0..3).rev() {
        let mut dot = 0.0;
        for k in i + 1..3 {
            dot += l[(k, i)] * x[k];
        }
        x[i] = (x[i] - dot) / l[(i, i)];
    }
    e[0] * x[0] + e[1] * x[1] + e[2] * x[2]
}

/// Whether the position error `e` (m) lies inside the 95 % ellipsoid of the position covariance
/// `p` (m²): [`nees`] at most [`CHI2_3DOF_95`].
///
/// ```
/// use loratrack::inside_95;
/// use nalgebra::Matrix3;
/// let p = Matrix3::identity(); // 1 m standard deviation on each axis
/// assert!(inside_95(&[1.5, 1.5, 1.5], &p)); // NEES 6.75
/// assert!(!inside_95(&[2.0, 2.0, 0.0], &p)); // NEES 8
/// ```
pub fn inside_95(e: &[f64; 3], p: &Matrix3<f64>) -> bool {
    nees(e, p) <= CHI2_3DOF_95
}

/// Running consistency of a station's claimed uncertainty over evaluation times: how often the
/// truth lay inside the 95 % ellipsoid, how often the error stayed under [`bound_95`], and the
/// mean [`nees`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Consistency {
    samples: usize,
    inside: usize,
    under: usize,
    /// NEES summed over the samples where it is finite.
    nees_sum: f64,
    finite: usize,
}

impl Consistency {
    /// Counts one evaluation: position error `e` (m) against covariance `p` (m²).
    pub fn add(&mut self, e: &[f64; 3], p: &Matrix3<f64>) {
        let n = nees(e, p);
        self.samples += 1;
        self.inside += usize::from(n <= CHI2_3DOF_95);
        self.under += usize::from(within_bound_95(e, p));
        if n.is_finite() {
            self.nees_sum += n;
            self.finite += 1;
        }
    }

    /// Pools another run's counts.
    pub fn merge(&mut self, other: &Consistency) {
        self.samples += other.samples;
        self.inside += other.inside;
        self.under += other.under;
        self.nees_sum += other.nees_sum;
        self.finite += other.finite;
    }

    /// The fraction of samples inside the 95 % ellipsoid (0.95 when honest), or NaN (JSON
    /// `null`) with none.
    pub fn coverage95(&self) -> f64 {
        if self.samples == 0 {
            return f64::NAN;
        }
        self.inside as f64 / self.samples as f64
    }

    /// The fraction of samples whose error was at most [`bound_95`] long (0.95 when honest, the
    /// error Gaussian), or NaN (JSON `null`) with none: how often the error chart's band held.
    pub fn under_bound95(&self) -> f64 {
        if self.samples == 0 {
            return f64::NAN;
        }
        self.under as f64 / self.samples as f64
    }

    /// The mean NEES over the samples whose covariance was positive definite (3 when honest;
    /// above 3 the station claims too little uncertainty, below too much), or NaN with none.
    pub fn mean_nees(&self) -> f64 {
        if self.finite == 0 {
            return f64::NAN;
        }
        self.nees_sum / self.finite as f64
    }
}

/// The station's own 95 % bound on its error, m: the length that a Gaussian error with the
/// position covariance `p` (m²) stays under 95 % of the time ([`length_95`] of its eigenvalues),
/// so that an honest station's error exceeds it 5 % of the time. It lies between 1.96 and 2.80
/// times the largest standard deviation (one axis and a round covariance), inside the 95 %
/// ellipsoid's longest semi-axis, √(χ²₃(0.95) λmax) = 2.80 σmax, which an error stays under at
/// least as often as the truth lies inside the ellipsoid. docs/reference.md §12.
///
/// ```
/// use loratrack::bound_95;
/// use nalgebra::Matrix3;
/// let round = Matrix3::identity() * 4.0; // 2 m on each axis
/// assert!((bound_95(&round) - 5.591).abs() < 1e-3); // 2 m × √χ²₃(0.95)
/// let line = Matrix3::from_diagonal(&nalgebra::Vector3::new(4.0, 0.0, 0.0));
/// assert!((bound_95(&line) - 3.920).abs() < 1e-3); // 2 m × 1.960
/// ```
pub fn bound_95(p: &Matrix3<f64>) -> f64 {
    length_95(eigenvalues(p))
}

/// Whether the error `e` (m) is at most [`bound_95`] of `p` (m²) long. The bound's square is at
/// least [`BOUND_OVER_TRACE`] times P's trace, so an error shorter than that, most of them, is
/// counted without the eigenvalues: scoring every step with the bound had cost a fifth of a
/// warm run.
fn within_bound_95(e: &[f64; 3], p: &Matrix3<f64>) -> bool {
    let squared = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    squared <= BOUND_OVER_TRACE * (p[(0, 0)] + p[(1, 1)] + p[(2, 2)])
        || squared.sqrt() <= bound_95(p)
}

/// A floor under [`bound_95`]² / trace P: c(a, b) / (1 + a + b) in [`length_95`]'s terms, least
/// for a round covariance, χ²₃(0.95) / 3 = 2.605 (one axis: 3.841); tested.
const BOUND_OVER_TRACE: f64 = 2.6;

/// The eigenvalues of the symmetric part of `p`, in closed form (Smith, "Eigenvalues of a 3×3
/// real symmetric matrix", CACM 4(4), 1961): with q the mean of the diagonal and B = (P − qI)/s
/// scaled to unit spread, the eigenvalues are q + 2s cos(acos(det B / 2)/3 + 2πk/3), k = 0, 1, 2.
/// An iterative solver (nalgebra's) took its many square roots from libm, in software in
/// WebAssembly: most of a warm run's time once the page asks for the series. Agrees with it to
/// 1e-12 in the largest and 1e-8 of the largest in the others, which a double eigenvalue splits
/// by the square root of a rounding error (tested). NaN for a matrix that is not finite.
fn eigenvalues(p: &Matrix3<f64>) -> [f64; 3] {
    if !p.iter().all(|v| v.is_finite()) {
        return [f64::NAN; 3];
    }
    // Scaled to its largest entry, so that no square or cube below can overflow.
    let scale = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if scale == 0.0 {
        return [0.0; 3];
    }
    let at = |i: usize, j: usize| 0.5 * (p[(i, j)] + p[(j, i)]) / scale;
    let (d, e, f) = (at(0, 1), at(0, 2), at(1, 2));
    let off = d * d + e * e + f * f;
    if off == 0.0 {
        return [p[(0, 0)], p[(1, 1)], p[(2, 2)]];
    }
    let (a, b, c) = (at(0, 0), at(1, 1), at(2, 2));
    let q = (a + b + c) / 3.0;
    let (a, b, c) = (a - q, b - q, c - q);
    let s = ((a * a + b * b + c * c + 2.0 * off) / 6.0).sqrt();
    let det = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e);
    let r = (det / (2.0 * s * s * s)).clamp(-1.0, 1.0);
    let angle = libm::acos(r) / 3.0;
    let third = 2.0 * std::f64::consts::FRAC_PI_3;
    [0.0, 1.0, 2.0].map(|k| (q + 2.0 * s * libm::cos(angle + k * third)) * scale)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;
    use nalgebra::{Cholesky, Vector3};

    /// Covariances of every shape the stations produce and more: random, nearly isotropic,
    /// of rank one and two, and with eigenvalues twelve decades apart.
    fn covariances() -> Vec<Matrix3<f64>> {
        let mut rng = Rng::new(11);
        let mut out = Vec::new();
        for k in 0..2000 {
            let m = Matrix3::from_fn(|_, _| rng.normal());
            let scale = 10f64.powi(k % 13 - 6);
            out.push(match k % 5 {
                0 => m * m.transpose() * scale,
                1 => Matrix3::identity() * scale + m * m.transpose() * 1e-9 * scale,
                2 => {
                    let v = m.column(0);
                    v * v.transpose() * scale
                }
                3 => {
                    let (u, v) = (m.column(0), m.column(1));
                    (u * u.transpose() + v * v.transpose()) * scale
                }
                _ => {
                    let q = m.qr().q();
                    let d = Vector3::new(1e-6, 1.0, 1e6).map(|x| x * scale);
                    q * Matrix3::from_diagonal(&d) * q.transpose()
                }
            });
        }
        out
    }

    #[test]
    fn the_closed_form_eigenvalues_agree_with_an_iterative_solver() {
        let (mut worst, mut worst_largest) = (0.0_f64, 0.0_f64);
        for p in covariances() {
            let sym = 0.5 * (p + p.transpose());
            let mut iterative: Vec<f64> = sym.symmetric_eigenvalues().iter().copied().collect();
            let mut closed = eigenvalues(&p).to_vec();
            iterative.sort_by(f64::total_cmp);
            closed.sort_by(f64::total_cmp);
            let largest = iterative[2].abs();
            worst_largest = worst_largest.max((closed[2] - iterative[2]).abs() / largest);
            for (c, i) in closed.iter().zip(&iterative) {
                worst = worst.max((c - i).abs() / largest);
            }
        }
        assert!(
            worst_largest < 1e-12,
            "largest: worst difference {worst_largest:e}"
        );
        assert!(worst < 1e-8, "worst difference {worst:e} of the largest");
        assert!(eigenvalues(&Matrix3::from_element(f64::NAN))[0].is_nan());
        assert_eq!(bound_95(&Matrix3::zeros()), 0.0);
    }

    #[test]
    fn the_bounds_square_is_at_least_its_floor_times_the_trace() {
        for p in covariances() {
            let trace = p.trace();
            assert!(
                bound_95(&p).powi(2) >= BOUND_OVER_TRACE * trace * (1.0 - 1e-12),
                "{p}"
            );
        }
        // Every shape, on a fine grid of the eigenvalues' ratios.
        for i in 0..=100 {
            for j in 0..=i {
                let l = [1.0, i as f64 / 100.0, j as f64 / 100.0];
                assert!(
                    length_95(l).powi(2) >= BOUND_OVER_TRACE * (l[0] + l[1] + l[2]),
                    "{l:?}"
                );
            }
        }
    }

    #[test]
    fn nees_equals_nalgebras_cholesky_solve_bit_for_bit() {
        let mut rng = Rng::new(5);
        for p in covariances()
            .into_iter()
            .filter(|p| Cholesky::new(*p).is_some())
        {
            let e = Vector3::new(rng.normal(), rng.normal(), rng.normal()) * p[(1, 1)].sqrt();
            let expected = e.dot(&Cholesky::new(p).unwrap().solve(&e));
            assert_eq!(nees(&[e[0], e[1], e[2]], &p).to_bits(), expected.to_bits());
        }
    }

    #[test]
    fn an_error_counts_under_the_bound_exactly_when_it_is_no_longer() {
        let mut rng = Rng::new(9);
        for p in covariances() {
            let bound = bound_95(&p);
            for scale in [0.5, 0.9, 1.0, 1.1, 2.0] {
                let z = Vector3::new(rng.normal(), rng.normal(), rng.normal()).normalize();
                let e = z * bound * scale;
                let e = [e[0], e[1], e[2]];
                let length = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
                assert_eq!(within_bound_95(&e, &p), length <= bound, "{p} {scale}");
            }
        }
    }

    #[test]
    fn gaussian_errors_fall_inside_95_percent_of_the_time() {
        let p = Matrix3::new(4.0, 1.0, 0.0, 1.0, 2.0, 0.5, 0.0, 0.5, 1.0);
        let l = Cholesky::new(p).unwrap().l();
        let mut rng = Rng::new(7);
        let mut c = Consistency::default();
        for _ in 0..200_000 {
            let z = Vector3::new(rng.normal(), rng.normal(), rng.normal());
            let e = l * z;
            c.add(&[e[0], e[1], e[2]], &p);
        }
        assert!(
            (c.coverage95() - 0.95).abs() < 0.003,
            "coverage {}",
            c.coverage95()
        );
        assert!(
            (c.under_bound95() - 0.95).abs() < 0.003,
            "under the bound {}",
            c.under_bound95()
        );
        assert!((c.mean_nees() - 3.0).abs() < 0.03, "NEES {}", c.mean_nees());
    }

    #[test]
    fn the_bound_lies_between_one_axis_and_the_ellipsoids_longest_semi_axis() {
        for p in covariances() {
            let largest = eigenvalues(&p).into_iter().fold(0.0, f64::max);
            let (bound, semi_axis) = (bound_95(&p), (CHI2_3DOF_95 * largest).sqrt());
            assert!(
                bound <= semi_axis * (1.0 + 1e-9),
                "{bound} over {semi_axis}"
            );
            assert!(
                bound >= 1.959_96 * largest.sqrt(),
                "{bound} under one axis's"
            );
        }
    }

    #[test]
    fn a_singular_covariance_covers_only_a_perfect_estimate() {
        let p = Matrix3::zeros();
        assert!(inside_95(&[0.0; 3], &p));
        assert!(!inside_95(&[1e-9, 0.0, 0.0], &p));
        let empty = Consistency::default();
        assert!(
            empty.coverage95().is_nan()
                && empty.under_bound95().is_nan()
                && empty.mean_nees().is_nan()
        );
    }

    #[test]
    fn a_singular_covariance_counts_outside_and_out_of_the_mean() {
        let mut c = Consistency::default();
        c.add(&[1.0, 0.0, 0.0], &Matrix3::zeros());
        c.add(&[1.0, 0.0, 0.0], &Matrix3::identity());
        assert_eq!(c.coverage95(), 0.5);
        assert_eq!(c.under_bound95(), 0.5);
        assert_eq!(c.mean_nees(), 1.0);
        let mut pooled = Consistency::default();
        pooled.merge(&c);
        pooled.merge(&c);
        assert_eq!((pooled.coverage95(), pooled.mean_nees()), (0.5, 1.0));
    }
}
