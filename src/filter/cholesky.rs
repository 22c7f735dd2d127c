//! The Cholesky factor of a small fixed-size covariance: the filter's most frequent factorisation
//! (before every prediction and after every update, reference §4).

use nalgebra::SMatrix;

/// The lower-triangular L with L Lᵀ = `p`, for a symmetric positive definite `p` (only its lower
/// triangle is read), or `None` when a pivot is not positive: `p` is not positive definite, or
/// not finite.
///
/// The operations and their order are those of nalgebra's `Cholesky::new` (column by column, each
/// column first updated by the ones before it, then divided by the square root of its pivot), so
/// the factor is the same bit for bit; the size is fixed at compile time, with no views or
/// strides and no second copy for the lower triangle.
///
/// ```
/// use loratrack::cholesky_lower;
/// use nalgebra::Matrix2;
/// let l = cholesky_lower(&Matrix2::new(4.0, 2.0, 2.0, 5.0)).unwrap();
/// assert_eq!(l, Matrix2::new(2.0, 0.0, 1.0, 2.0));
/// assert!(cholesky_lower(&Matrix2::new(1.0, 2.0, 2.0, 1.0)).is_none());
/// ```
pub fn cholesky_lower<const N: usize>(p: &SMatrix<f64, N, N>) -> Option<SMatrix<f64, N, N>> {
    let mut l = SMatrix::<f64, N, N>::zeros();
    for j in 0..N {
        for i in j..N {
            l[(i, j)] = p[(i, j)];
        }
        for k in 0..j {
            let factor = -l[(j, k)];
            for i in j..N {
                l[(i, j)] += factor * l[(i, k)];
            }
        }
        let pivot = l[(j, j)];
        if pivot.is_nan() || pivot <= 0.0 {
            return None;
        }
        let root = pivot.sqrt();
        l[(j, j)] = root;
        for i in j + 1..N {
            l[(i, j)] /= root;
        }
    }
    Some(l)
}

/// X with L X = `b`, for the lower-triangular `l` of [`cholesky_lower`] (a positive diagonal), by
/// forward substitution: row by row, each row's sum taken over the rows before it.
pub(crate) fn forward_substitute<const N: usize, const C: usize>(
    l: &SMatrix<f64, N, N>,
    b: &SMatrix<f64, N, C>,
) -> SMatrix<f64, N, C> {
    let mut x = *b;
    for i in 0..N {
        let inverse = 1.0 / l[(i, i)];
        for c in 0..C {
            let mut sum = x[(i, c)];
            for k in 0..i {
                sum -= l[(i, k)] * x[(k, c)];
            }
            x[(i, c)] = sum * inverse;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Cholesky;

    #[test]
    fn equals_nalgebras_factor_bit_for_bit() {
        let p = SMatrix::<f64, 9, 9>::from_fn(|i, j| {
            let (a, b) = (i as f64, j as f64);
            if i == j {
                1.0 + 0.37 * a
            } else {
                0.1 / (1.0 + (a - b).abs()) + 0.013 * a * b
            }
        });
        let mine = cholesky_lower(&p).unwrap();
        assert_eq!(mine, Cholesky::new(p).unwrap().l());
    }

    #[test]
    fn forward_substitution_solves_the_lower_system() {
        let l = SMatrix::<f64, 3, 3>::new(2.0, 0.0, 0.0, 1.0, 3.0, 0.0, -1.0, 0.5, 4.0);
        let x = SMatrix::<f64, 3, 2>::new(1.0, -2.0, 0.5, 3.0, 2.0, 0.25);
        let solved = forward_substitute(&l, &(l * x));
        assert!((solved - x).norm() < 1e-14, "{solved}");
    }

    #[test]
    fn refuses_what_is_not_positive_definite() {
        let mut p = SMatrix::<f64, 3, 3>::identity();
        p[(2, 2)] = 0.0;
        assert!(cholesky_lower(&p).is_none());
        p[(2, 2)] = f64::NAN;
        assert!(cholesky_lower(&p).is_none());
        p[(2, 2)] = 1.0;
        p[(2, 0)] = 2.0;
        assert!(cholesky_lower(&p).is_none());
    }
}
