//! Filter consistency: does the true position lie inside the station's 95 % ellipsoid, and how
//! large is the error against the uncertainty the station claims? (Bar-Shalom, Li & Kirubarajan
//! 2001, §5.4: the normalised estimation error squared, NEES.)

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
    (CHI2_3DOF_95 * largest_eigenvalue(p).max(0.0)).sqrt()
}

/// The largest eigenvalue of the symmetric part of `p`, in closed form (Smith, "Eigenvalues of a
/// 3×3 real symmetric matrix", CACM 4(4), 1961): with q the mean of the diagonal and B =
/// (P − qI)/s scaled to unit spread, the eigenvalues are q + 2s cos(acos(det B / 2)/3 + 2πk/3),
/// the largest at k = 0. An iterative solver (nalgebra's) took its many square roots from libm,
/// in software in WebAssembly: most of a warm run's time once the page asks for the series.
/// Agrees with it to 1e-12 relative (tested; 2e-15 at worst over 2000 covariances). NaN for a
/// matrix that is not finite.
fn largest_eigenvalue(p: &Matrix3<f64>) -> f64 {
    if !p.iter().all(|v| v.is_finite()) {
        return f64::NAN;
    }
    // Scaled to its largest entry, so that no square or cube below can overflow.
    let scale = p.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    if scale == 0.0 {
        return 0.0;
    }
    let at = |i: usize, j: usize| 0.5 * (p[(i, j)] + p[(j, i)]) / scale;
    let (d, e, f) = (at(0, 1), at(0, 2), at(1, 2));
    let off = d * d + e * e + f * f;
    if off == 0.0 {
        return p[(0, 0)].max(p[(1, 1)]).max(p[(2, 2)]);
    }
    let (a, b, c) = (at(0, 0), at(1, 1), at(2, 2));
    let q = (a + b + c) / 3.0;
    let (a, b, c) = (a - q, b - q, c - q);
    let s = ((a * a + b * b + c * c + 2.0 * off) / 6.0).sqrt();
    let det = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e);
    let r = (det / (2.0 * s * s * s)).clamp(-1.0, 1.0);
    (q + 2.0 * s * libm::cos(libm::acos(r) / 3.0)) * scale
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
    fn the_closed_form_largest_eigenvalue_agrees_with_an_iterative_solver() {
        let mut worst = 0.0_f64;
        for p in covariances() {
            let sym = 0.5 * (p + p.transpose());
            let iterative = sym.symmetric_eigenvalues().max();
            let closed = largest_eigenvalue(&p);
            worst = worst.max((closed - iterative).abs() / iterative.abs());
        }
        assert!(worst < 1e-12, "worst relative difference {worst:e}");
        assert!(largest_eigenvalue(&Matrix3::from_element(f64::NAN)).is_nan());
        assert_eq!(bound_95(&Matrix3::zeros()), 0.0);
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
