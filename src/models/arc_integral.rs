//! The one integral behind CTRA+ and 3D-CTRA, in a form that is exact at and near every
//! special case.

use crate::math::sin_cos;

/// ∫₀ᵗ (v0 + a τ) · (cos(α + kτ), sin(α + kτ)) dτ, returned as (cosine part, sine part), metres.
///
/// The paper's closed forms (eqs. `x_int`–`z_int`) evaluate this by parts and divide by k and k²,
/// which is singular at k = 0 and loses digits near it (`omega = ±psi`, `psi = 0`). Here the
/// integral is written with u = k t as
///
/// ```text
/// e^{iα} [ v0 t f(u) + a t² g(u) ],   f(u) = ∫₀¹ e^{ius} ds,   g(u) = ∫₀¹ s e^{ius} ds
/// f(u) = sinc u + i sin(u/2) sinc(u/2)
/// g(u) = sinc u − ½ sinc²(u/2) + i (sin u − u cos u)/u²
/// ```
///
/// Every term is a product of bounded, well-conditioned factors, except (sin u − u cos u)/u² which
/// cancels for small u and is summed as its Taylor series there. The result is therefore
/// continuous across k = 0 with no switch between formulas, and at k = 0 it reduces exactly to
/// `v0 t + a t²/2` along the direction α.
///
/// ```
/// use loratrack::arc_integral;
/// // 2D CTRA reference (reference §3): theta = 0, v = 1, a = 1, omega = 1, dt = 0.5.
/// let (x, y) = arc_integral(0.0, 1.0, 1.0, 1.0, 0.5);
/// assert!((x - 0.5967208697966773).abs() < 1e-15);
/// assert!((y - 0.16305169576864387).abs() < 1e-15);
/// ```
pub fn arc_integral(alpha: f64, k: f64, v0: f64, a: f64, t: f64) -> (f64, f64) {
    let (sa, ca) = sin_cos(alpha);
    arc_integral_from(sa, ca, k, v0, a, t)
}

/// Below this |u/2| the half angle's sinc and cosine are summed as their Taylor series (five terms
/// each; the first left out is below 3e-19 of the result) instead of calling sincos and dividing:
/// within one filter step (|ω dt| ≲ 0.1) that is nearly always, and a sincos and a division are
/// most of an arc integral's cost. The series are also exact at u = 0 and for subnormal u, where
/// sin(u/2)/(u/2) by division loses bits or becomes 0/0.
const HALF_ANGLE_SERIES_BELOW: f64 = 0.0625;

/// sinc x = Σ (−1)ⁿ x²ⁿ / (2n+1)!, coefficients of x²ⁿ.
const SINC_SERIES: [f64; 5] = taylor_coefficients(1);

/// cos x = Σ (−1)ⁿ x²ⁿ / (2n)!, coefficients of x²ⁿ.
const COS_SERIES: [f64; 5] = taylor_coefficients(0);

/// (−1)ⁿ / (2n + offset)! for n = 0..5.
const fn taylor_coefficients(offset: usize) -> [f64; 5] {
    let mut c = [0.0; 5];
    let mut n = 0;
    while n < 5 {
        let mut factorial = 1.0;
        let mut m = 2;
        while m <= 2 * n + offset {
            factorial *= m as f64;
            m += 1;
        }
        c[n] = if n % 2 == 0 { 1.0 } else { -1.0 } / factorial;
        n += 1;
    }
    c
}

/// (sin x / x, sin x, cos x) for the half angle x = u/2.
#[inline(always)]
fn half_angle(x: f64) -> (f64, f64, f64) {
    if x.abs() < HALF_ANGLE_SERIES_BELOW {
        half_angle_series(x)
    } else {
        let (s, c) = sin_cos(x);
        (s / x, s, c)
    }
}

/// [`half_angle`] below [`HALF_ANGLE_SERIES_BELOW`]: the series.
#[inline(always)]
fn half_angle_series(x: f64) -> (f64, f64, f64) {
    let x2 = x * x;
    let sinc = horner(&SINC_SERIES, x2);
    (sinc, x * sinc, horner(&COS_SERIES, x2))
}

/// [`arc_integral`] with sin α and cos α given: the models build them for θ ± φ from the sines
/// and cosines of θ and φ, which saves the trigonometric calls that dominate a UKF prediction.
#[inline(always)]
pub(crate) fn arc_integral_from(sa: f64, ca: f64, k: f64, v0: f64, a: f64, t: f64) -> (f64, f64) {
    let u = k * t;
    // The half angle serves everything: sin u / u = cos(u/2) · sinc(u/2), sin u = 2 sin(u/2)
    // cos(u/2), cos u = cos²(u/2) − sin²(u/2).
    let half = half_angle(0.5 * u);
    let odd = odd_moment(u, half.2, half.1);
    assemble((sa, ca), v0, a, t, half, odd)
}

/// The integral along (cos α, sin α) = (`ca`, `sa`) from the half angle's (sinc, sin, cos) and
/// the odd moment: e^{iα} [v0 t f(u) + a t² g(u)].
#[inline(always)]
fn assemble(
    (sa, ca): (f64, f64),
    v0: f64,
    a: f64,
    t: f64,
    (sinc_half, s_half, c_half): (f64, f64, f64),
    odd: f64,
) -> (f64, f64) {
    let sinc_u = c_half * sinc_half;
    let f = (sinc_u, s_half * sinc_half);
    let g = (sinc_u - 0.5 * sinc_half * sinc_half, odd);
    let re = v0 * t * f.0 + a * t * t * g.0;
    let im = v0 * t * f.1 + a * t * t * g.1;
    (ca * re - sa * im, sa * re + ca * im)
}

/// [`arc_integral_from`] for `L` integrals over one `t`, lane by lane: (cosine parts, sine parts).
///
/// Where every lane's turn is short (|k t| < [`SHORT_SERIES_BELOW`], nearly every filter step) the
/// lanes run through the series together with no branch, so the compiler interleaves (and, where
/// it can, vectorises) them; otherwise each lane takes [`arc_integral_from`]. Each lane performs
/// exactly [`arc_integral_from`]'s operations in its order: the same bits (tested).
#[inline(always)]
pub(crate) fn arc_integrals<const L: usize>(
    sa: [f64; L],
    ca: [f64; L],
    k: [f64; L],
    v0: [f64; L],
    a: [f64; L],
    t: f64,
) -> ([f64; L], [f64; L]) {
    let u: [f64; L] = core::array::from_fn(|l| k[l] * t);
    let short = u
        .iter()
        .all(|u| u.abs() < SHORT_SERIES_BELOW && (0.5 * u).abs() < HALF_ANGLE_SERIES_BELOW);
    if !short {
        let each: [(f64, f64); L] =
            core::array::from_fn(|l| arc_integral_from(sa[l], ca[l], k[l], v0[l], a[l], t));
        return (each.map(|e| e.0), each.map(|e| e.1));
    }
    let (mut x, mut y) = ([0.0; L], [0.0; L]);
    for l in 0..L {
        let half = half_angle_series(0.5 * u[l]);
        let odd = odd_moment_short(u[l]);
        (x[l], y[l]) = assemble((sa[l], ca[l]), v0[l], a[l], t, half, odd);
    }
    (x, y)
}

/// The series of (sin u − u cos u) / u² = Σ (−1)ⁿ u^{2n+1} / ((2n+1)! (2n+3)): its coefficients,
/// so that the hot path is ten multiply-adds instead of twenty divisions.
const ODD_MOMENT_SERIES: [f64; 10] = {
    let mut c = [0.0; 10];
    let mut factorial = 1.0; // (2n+1)!
    let mut n = 0;
    while n < 10 {
        let m = (2 * n + 1) as f64;
        if n > 0 {
            factorial *= (m - 1.0) * m;
        }
        let sign = if n % 2 == 0 { 1.0 } else { -1.0 };
        c[n] = sign / (factorial * (m + 2.0));
        n += 1;
    }
    c
};

/// Below this |u| five terms of the series reach 1e-17 relative (the sixth is c₅ u¹⁰ < 6e-18 of
/// the first), so the other five are left out: the turn over one filter step (|ω dt| ≲ 0.1) is
/// nearly always here, and the shorter chain of dependent multiply-adds is what a step waits on.
const SHORT_SERIES_BELOW: f64 = 0.125;

/// Σ cₙ xⁿ by Horner's rule from the highest coefficient. The coefficient count is a constant, so
/// the loop unrolls: with a count chosen at run time its bookkeeping cost as much as its arithmetic.
#[inline(always)]
fn horner<const TERMS: usize>(coefficients: &[f64; TERMS], x: f64) -> f64 {
    let mut acc = 0.0;
    for c in coefficients.iter().rev() {
        acc = acc * x + c;
    }
    acc
}

/// [`odd_moment`] below [`SHORT_SERIES_BELOW`]: five terms of the series.
#[inline(always)]
fn odd_moment_short(u: f64) -> f64 {
    u * horner(ODD_MOMENT_SERIES.first_chunk::<5>().unwrap(), u * u)
}

/// (sin u − u cos u) / u², the imaginary part of g(u).
fn odd_moment(u: f64, c_half: f64, s_half: f64) -> f64 {
    if u.abs() < 1.0 {
        if u.abs() < SHORT_SERIES_BELOW {
            odd_moment_short(u)
        } else {
            // Ten terms reach 1e-19 relative for |u| < 1; Horner in u².
            u * horner(&ODD_MOMENT_SERIES, u * u)
        }
    } else {
        let sin_u = 2.0 * s_half * c_half;
        let cos_u = c_half * c_half - s_half * s_half;
        (sin_u - u * cos_u) / (u * u)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_odd_moment_series_matches_the_closed_form_where_both_are_accurate() {
        for u in [0.5f64, 0.9, -0.7, 0.99] {
            let closed = (u.sin() - u * u.cos()) / (u * u);
            let (s, c) = (0.5 * u).sin_cos();
            let series = odd_moment(u, c, s);
            assert!(
                (series - closed).abs() < 1e-15,
                "u {u}: {series} vs {closed}"
            );
        }
        assert_eq!(ODD_MOMENT_SERIES[0], 1.0 / 3.0);
        assert_eq!(ODD_MOMENT_SERIES[1], -1.0 / 30.0);
    }

    #[test]
    fn the_short_series_agrees_with_the_long_one_to_rounding() {
        let long = |u: f64| {
            u * ODD_MOMENT_SERIES
                .iter()
                .rev()
                .fold(0.0, |acc, c| acc * u * u + c)
        };
        for u in [1e-9f64, 1e-3, 0.05, -0.1, 0.124_999] {
            let (s, c) = (0.5 * u).sin_cos();
            let short = odd_moment(u, c, s);
            assert!(
                (short - long(u)).abs() <= 2.0 * f64::EPSILON * long(u).abs(),
                "u {u}"
            );
        }
    }

    #[test]
    fn the_lanes_give_the_single_integrals_bits() {
        // Short turns in every lane (the branch-free path), then one long turn among them.
        for spread in [0.01, 0.3] {
            let k: [f64; 3] = [0.2 * spread, -spread, 0.0];
            let (sa, ca) = ([0.3f64.sin(), -0.8, 0.0], [0.3f64.cos(), 0.6, 1.0]);
            let (v0, a) = ([8.0, 12.5, -3.0], [0.4, -1.2, 0.0]);
            for t in [0.1, 0.25, 4.0] {
                let (x, y) = arc_integrals(sa, ca, k, v0, a, t);
                for l in 0..3 {
                    let one = arc_integral_from(sa[l], ca[l], k[l], v0[l], a[l], t);
                    assert_eq!((x[l], y[l]), one, "lane {l}, k {}, t {t}", k[l]);
                }
            }
        }
    }

    #[test]
    fn straight_line_when_k_is_zero() {
        let (x, y) = arc_integral(0.0, 0.0, 1.0, 1.0, 0.5);
        assert_eq!(x, 0.625);
        assert_eq!(y, 0.0);
    }

    #[test]
    fn continuous_across_the_series_switch() {
        let below = arc_integral(0.3, 0.999_999_999_9, 7.0, 2.0, 1.0);
        let above = arc_integral(0.3, 1.000_000_000_1, 7.0, 2.0, 1.0);
        assert!((below.0 - above.0).abs() < 1e-8);
        assert!((below.1 - above.1).abs() < 1e-8);
    }

    #[test]
    fn subnormal_rates_give_the_straight_line() {
        for k in [1.5e-323, 5e-324, -5e-324, 1e-310, f64::MIN_POSITIVE] {
            let (x, y) = arc_integral(0.0, k, 10.0, 0.0, 1.0);
            assert_eq!(x, 10.0, "k = {k:e}");
            assert!(y.abs() < 1e-300, "k = {k:e}: y = {y:e}");
        }
    }

    #[test]
    fn the_half_angle_series_agrees_with_sincos_to_rounding() {
        for x in [1e-300f64, 1e-8, 1e-3, -0.01, 0.03, -0.05, 0.062_499] {
            let (sinc, s, c) = half_angle(x);
            let (s_ref, c_ref) = sin_cos(x);
            assert!(
                (s - s_ref).abs() <= 2.0 * f64::EPSILON * s_ref.abs(),
                "sin {x}"
            );
            assert!((c - c_ref).abs() <= f64::EPSILON, "cos {x}");
            assert!((sinc - s_ref / x).abs() <= 2.0 * f64::EPSILON, "sinc {x}");
        }
    }

    #[test]
    fn continuous_across_the_half_angle_series_switch() {
        let below = arc_integral(0.3, 0.125 * (1.0 - 1e-15), 7.0, 2.0, 1.0);
        let above = arc_integral(0.3, 0.125 * (1.0 + 1e-15), 7.0, 2.0, 1.0);
        assert!((below.0 - above.0).abs() < 1e-13 && (below.1 - above.1).abs() < 1e-13);
    }

    #[test]
    fn matches_integration_by_parts_far_from_zero() {
        // Closed form by parts, well conditioned for k = 2.
        let (alpha, k, v0, a, t) = (0.4f64, 2.0f64, 3.0f64, 0.7f64, 1.3f64);
        let vt = v0 + a * t;
        let x = vt * (alpha + k * t).sin() / k - v0 * alpha.sin() / k
            + a * ((alpha + k * t).cos() - alpha.cos()) / (k * k);
        let y = -vt * (alpha + k * t).cos() / k
            + v0 * alpha.cos() / k
            + a * ((alpha + k * t).sin() - alpha.sin()) / (k * k);
        let got = arc_integral(alpha, k, v0, a, t);
        assert!((got.0 - x).abs() < 1e-12 && (got.1 - y).abs() < 1e-12);
    }
}
