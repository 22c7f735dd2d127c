//! Filter consistency: does the true position lie inside the station's 95 % ellipsoid, and how
//! large is the error against the uncertainty the station claims? (Bar-Shalom, Li & Kirubarajan
//! 2001, §5.4: the normalised estimation error squared, NEES.)

use nalgebra::{Cholesky, Matrix3, Vector3};

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
    let e = Vector3::from(*e);
    match Cholesky::new(*p) {
        Some(c) => e.dot(&c.solve(&e)),
        None if e == Vector3::zeros() => 0.0,
        None => f64::INFINITY,
    }
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
/// truth lay inside the 95 % ellipsoid, and the mean [`nees`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Consistency {
    samples: usize,
    inside: usize,
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
        if n.is_finite() {
            self.nees_sum += n;
            self.finite += 1;
        }
    }

    /// Pools another run's counts.
    pub fn merge(&mut self, other: &Consistency) {
        self.samples += other.samples;
        self.inside += other.inside;
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

    /// The mean NEES over the samples whose covariance was positive definite (3 when honest;
    /// above 3 the station claims too little uncertainty, below too much), or NaN with none.
    pub fn mean_nees(&self) -> f64 {
        if self.finite == 0 {
            return f64::NAN;
        }
        self.nees_sum / self.finite as f64
    }
}

/// The longest semi-axis of the 95 % ellipsoid of `p` (m): √(χ²₃(0.95) · λmax). The 3D error
/// stays below it whenever the position is inside the ellipsoid, so the page draws it as the
/// station's own bound on its error.
pub fn bound_95(p: &Matrix3<f64>) -> f64 {
    let sym = 0.5 * (p + p.transpose());
    let lambda = sym.symmetric_eigenvalues().max().max(0.0);
    (CHI2_3DOF_95 * lambda).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

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
        assert!((c.mean_nees() - 3.0).abs() < 0.03, "NEES {}", c.mean_nees());
    }

    #[test]
    fn bound_is_the_longest_semi_axis() {
        let p = Matrix3::from_diagonal(&Vector3::new(1.0, 9.0, 4.0));
        assert!((bound_95(&p) - (CHI2_3DOF_95 * 9.0).sqrt()).abs() < 1e-12);
    }

    #[test]
    fn a_singular_covariance_covers_only_a_perfect_estimate() {
        let p = Matrix3::zeros();
        assert!(inside_95(&[0.0; 3], &p));
        assert!(!inside_95(&[1e-9, 0.0, 0.0], &p));
        let empty = Consistency::default();
        assert!(empty.coverage95().is_nan() && empty.mean_nees().is_nan());
    }

    #[test]
    fn a_singular_covariance_counts_outside_and_out_of_the_mean() {
        let mut c = Consistency::default();
        c.add(&[1.0, 0.0, 0.0], &Matrix3::zeros());
        c.add(&[1.0, 0.0, 0.0], &Matrix3::identity());
        assert_eq!(c.coverage95(), 0.5);
        assert_eq!(c.mean_nees(), 1.0);
        let mut pooled = Consistency::default();
        pooled.merge(&c);
        pooled.merge(&c);
        assert_eq!((pooled.coverage95(), pooled.mean_nees()), (0.5, 1.0));
    }
}
