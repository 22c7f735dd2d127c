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
    let data = l.as_mut_slice();
    for j in 0..N {
        // Column j below the diagonal, and the finished columns before it, as separate slices:
        // each update is a loop over contiguous memory that the compiler vectorises.
        let (done, rest) = data.split_at_mut(j * N);
        let column = &mut rest[j..N];
        column.copy_from_slice(&p.as_slice()[j * N + j..(j + 1) * N]);
        for k in 0..j {
            let earlier = &done[k * N + j..(k + 1) * N];
            let factor = -earlier[0];
            for (x, e) in column.iter_mut().zip(earlier) {
                *x += factor * e;
            }
        }
        let pivot = column[0];
        if pivot.is_nan() || pivot <= 0.0 {
            return None;
        }
        let root = pivot.sqrt();
        column[0] = root;
        for x in &mut column[1..] {
            *x /= root;
        }
    }
    Some(l)
}

/// X with L X = `b`, for the lower-triangular `l` of [`cholesky_lower`] (a positive diagonal), by
/// forward substitution: row by row, each entry's sum taken over the rows before it in order.
///
/// X is built transposed, so that a row of X is contiguous and each step updates all its
/// entries in one loop (vectorised; every entry's own sum keeps its order).
pub(crate) fn forward_substitute<const N: usize, const C: usize>(
    l: &SMatrix<f64, N, N>,
    b: &SMatrix<f64, N, C>,
) -> SMatrix<f64, N, C> {
    let mut xt = b.transpose();
    let data = xt.as_mut_slice();
    for i in 0..N {
        let inverse = 1.0 / l[(i, i)];
        let (done, rest) = data.split_at_mut(i * C);
        let row = &mut rest[..C];
        for k in 0..i {
            let lik = l[(i, k)];
            for (x, d) in row.iter_mut().zip(&done[k * C..(k + 1) * C]) {
                *x -= lik * d;
            }
        }
        for x in row.iter_mut() {
            *x *= inverse;
        }
    }
    xt.transpose()
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
