//! Filter consistency: does the true position lie inside the station's 95 % ellipsoid?
//! (Bar-Shalom, Li & Kirubarajan 2001, §5.4: the normalised estimation error squared, NEES.)

use nalgebra::{Cholesky, Matrix3, Vector3};

/// The 95 % quantile of the chi-square distribution with 3 degrees of freedom: a 3D Gaussian
/// error e with covariance P satisfies eᵀ P⁻¹ e ≤ this with probability 0.95.
pub const CHI2_3DOF_95: f64 = 7.814_727_903_251_178;

/// Whether the position error `e` (m) lies inside the 95 % ellipsoid of the position covariance
/// `p` (m²). A covariance that is not positive definite claims no uncertainty at all, so only a
/// zero error counts as inside it.
///
/// ```
/// use loratrack::inside_95;
/// use nalgebra::Matrix3;
/// let p = Matrix3::identity(); // 1 m standard deviation on each axis
/// assert!(inside_95(&[1.5, 1.5, 1.5], &p)); // NEES 6.75
/// assert!(!inside_95(&[2.0, 2.0, 0.0], &p)); // NEES 8
/// ```
pub fn inside_95(e: &[f64; 3], p: &Matrix3<f64>) -> bool {
    let e = Vector3::from(*e);
    match Cholesky::new(*p) {
        Some(c) => e.dot(&c.solve(&e)) <= CHI2_3DOF_95,
        None => e == Vector3::zeros(),
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

/// The fraction of `inside` that is true, or NaN (JSON `null`) for an empty run.
pub fn coverage(inside: &[bool]) -> f64 {
    if inside.is_empty() {
        return f64::NAN;
    }
    inside.iter().filter(|b| **b).count() as f64 / inside.len() as f64
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
        let inside: Vec<bool> = (0..200_000)
            .map(|_| {
                let z = Vector3::new(rng.normal(), rng.normal(), rng.normal());
                let e = l * z;
                inside_95(&[e[0], e[1], e[2]], &p)
            })
            .collect();
        let c = coverage(&inside);
        assert!((c - 0.95).abs() < 0.003, "coverage {c}");
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
        assert!(coverage(&[]).is_nan());
    }
}
