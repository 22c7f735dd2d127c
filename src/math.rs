//! Transcendental functions and angle helpers used by the whole core.
//!
//! Every `sin`, `cos`, `exp`, `ln`, … in loratrack goes through this module, which calls the
//! pure-Rust [`libm`] crate. Platform maths libraries (glibc natively, the compiler's builtins in
//! WebAssembly) may differ in the last bit; a seeded simulation that runs thousands of filter steps
//! would then give different numbers natively, in Node and in the browser. One implementation on
//! every target keeps them identical.

use core::f64::consts::{PI, TAU};

/// sin(x), x in radians.
#[inline]
pub fn sin(x: f64) -> f64 {
    libm::sin(x)
}

/// cos(x), x in radians.
#[inline]
pub fn cos(x: f64) -> f64 {
    libm::cos(x)
}

/// (sin x, cos x) in one call.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// tan(x), x in radians.
#[inline]
pub fn tan(x: f64) -> f64 {
    libm::tan(x)
}

/// arccos(x), in [0, pi]; NaN outside [-1, 1].
#[inline]
pub fn acos(x: f64) -> f64 {
    libm::acos(x)
}

/// Four-quadrant arctangent of y/x, in (-pi, pi].
#[inline]
pub fn atan2(y: f64, x: f64) -> f64 {
    libm::atan2(y, x)
}

/// e^x.
#[inline]
pub fn exp(x: f64) -> f64 {
    libm::exp(x)
}

/// Natural logarithm.
#[inline]
pub fn ln(x: f64) -> f64 {
    libm::log(x)
}

/// Base-10 logarithm.
#[inline]
pub fn log10(x: f64) -> f64 {
    libm::log10(x)
}

/// x^y.
#[inline]
pub fn pow(x: f64, y: f64) -> f64 {
    libm::pow(x, y)
}

/// The standard normal distribution function Φ(z).
pub fn normal_cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z / core::f64::consts::SQRT_2)
}

/// x^n by repeated multiplication (exact in the same way on every target).
pub fn powi(x: f64, n: i32) -> f64 {
    (0..n).fold(1.0, |acc, _| acc * x)
}

/// sqrt(x*x + y*y) without intermediate overflow.
#[inline]
pub fn hypot(x: f64, y: f64) -> f64 {
    libm::hypot(x, y)
}

/// Euclidean distance between two points (m).
#[inline]
pub fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Wraps an angle to (-pi, pi] (radians).
///
/// ```
/// use loratrack::wrap_angle;
/// assert!((wrap_angle(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
/// ```
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    if a > -PI && a <= PI {
        return a;
    }
    let r = a - TAU * libm::floor((a + PI) / TAU);
    // floor() lands exactly on -pi for odd multiples of pi; the interval is open there.
    if r <= -PI {
        r + TAU
    } else {
        r
    }
}

/// sin(u)/u, exact at u = 0 (no cancellation exists for any other u).
#[inline]
pub fn sinc(u: f64) -> f64 {
    if u == 0.0 {
        1.0
    } else {
        sin(u) / u
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_angle_maps_into_half_open_interval() {
        for k in -5..=5 {
            let a = 0.3 + TAU * k as f64;
            assert!((wrap_angle(a) - 0.3).abs() < 1e-12);
        }
        assert_eq!(wrap_angle(-PI), PI);
        assert_eq!(wrap_angle(PI), PI);
        assert!(wrap_angle(-3.0 * PI) > 0.0);
    }

    #[test]
    fn sinc_is_one_at_zero_and_continuous() {
        assert_eq!(sinc(0.0), 1.0);
        assert!((sinc(1e-9) - 1.0).abs() < 1e-15);
        assert!((sinc(PI)).abs() < 1e-15);
    }
}
