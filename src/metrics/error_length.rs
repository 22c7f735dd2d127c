//! How long a 3D Gaussian error gets: the radius that the length of an error e ~ N(0, P) stays
//! under 95 % of the time. The error chart's band draws it, so that a station whose covariance is
//! honest sees its error above the band 5 % of the time, whatever the covariance's shape (the
//! 95 % ellipsoid's longest semi-axis, drawn before, holds 95 % for a round covariance and up to
//! 99.5 % for a long one). docs/reference.md §12.
//!
//! With P's eigenvalues λ₁ ≥ λ₂ ≥ λ₃, |e|² = λ₁ (z₁² + a z₂² + b z₃²), z standard normal, a = λ₂/λ₁
//! and b = λ₃/λ₁: the quantile is √(λ₁ c(a, b)), c the 95 % quantile of that weighted sum of
//! χ²₁ (Imhof 1961). c is read off a table over (a, b) by cubic interpolation, within 1e-4 of the
//! direct solution in the length (tested).

/// Grid points per axis of the table of c(a, b), a and b in [0, 1] (steps of 1/12).
const GRID: usize = 13;

/// c(a, b) at a = i/12 ≥ b = j/12, row i's entries j = 0..=i one after another (c(a, b) =
/// c(b, a): the weights' order does not matter). From the product Gauss–Legendre rule of the
/// tests (`quantile_95`): the mean over the directions u of the error of χ²₃'s distribution
/// function at c / (u₁² + a u₂² + b u₃²), solved for 0.95 by Newton's method; a test computes
/// it again and prints it anew where it differs. Worked out once, not at a run's start: the 91
/// quantiles take ~30 ms natively (that test), which each of the page's workers would pay.
#[rustfmt::skip]
const QUANTILES: [f64; GRID * (GRID + 1) / 2] = [
    3.8414588207095,
    3.9295389699171, 4.0176222536840,
    4.0290489025575, 4.1171480150675, 4.2167516768636,
    4.1447207289617, 4.2328590479407, 4.3326140323483, 4.4486232998124,
    4.2825521518459, 4.3707150458108, 4.4705079994518, 4.5862547815376, 4.7228075622546,
    4.4445947853953, 4.5327201298866, 4.6322878207790, 4.7471979092898, 4.8817997660375, 5.0377817957513,
    4.6282830067413, 4.7163059146899, 4.8154144090913, 4.9290717106113, 5.0611819309193, 5.2135388195972, 5.3850139423383,
    4.8294284713517, 4.9173049061717, 5.0158146873560, 5.1280199692009, 5.2574383660060, 5.4059698617560, 5.5729444431631, 5.7561317029961,
    5.0441867372636, 5.1318936887291, 5.2297445683162, 5.3404509750406, 5.4671932330057, 5.6119530643109, 5.7744764912715, 5.9529472352741, 6.1450481523503,
    5.2696032280509, 5.3571321649792, 5.4543133090024, 5.5635575235480, 5.6877478050229, 5.8289140271585, 5.9871664248759, 6.1610792504048, 6.3486004447781, 6.5476878418806,
    5.5035507070225, 5.5909016711486, 5.6874288615641, 5.7952862654522, 5.9170925669211, 6.0548917220422, 6.2091039593519, 6.3786676440587, 6.5617938041464, 6.7565831267584, 6.9613346973219,
    5.7445262981554, 5.8317039748992, 5.9276057921301, 6.0341657922442, 6.1537663513038, 6.2884349788067, 6.4388487510269, 6.6042816244593, 6.7832049473305, 6.9738700107333, 7.1746414055684, 7.3841261616891,
    5.9914645471115, 6.0784759240977, 6.1737860949186, 6.2791397370730, 6.3967072033287, 6.5284741556832, 6.6753243089086, 6.8368369474404, 7.0117392095763, 7.1984409998360, 7.3953822837909, 7.6011914945749, 7.8147279032512,
];

/// The length that an error of a 3D Gaussian with eigenvalues `eigenvalues` (m², any order)
/// stays under with probability 0.95 (m). Negative eigenvalues, which rounding leaves in a
/// covariance that should be positive semi-definite, count as 0; NaN in, NaN out.
///
/// For a round covariance σ²I it is σ √χ²₃(0.95) = 2.795 σ; for one axis alone 1.960 σ.
///
/// ```
/// use loratrack::length_95;
/// assert!((length_95([4.0, 4.0, 4.0]) - 5.591).abs() < 1e-3); // 2 m × 2.795
/// assert!((length_95([0.0, 4.0, 0.0]) - 3.920).abs() < 1e-3); // 2 m × 1.960
/// ```
pub fn length_95(eigenvalues: [f64; 3]) -> f64 {
    if eigenvalues.iter().any(|v| v.is_nan()) {
        return f64::NAN;
    }
    let mut l = eigenvalues.map(|v| v.max(0.0));
    l.sort_by(|x, y| y.total_cmp(x));
    if l[0] == 0.0 {
        return 0.0;
    }
    (l[0] * quantile_at(l[1] / l[0], l[2] / l[0])).sqrt()
}

/// c(a, b) for a, b in [0, 1], by cubic interpolation along each axis through the four nearest
/// grid points (bilinear interpolation was off by 2e-3; c bends most near a = b = 0.3).
fn quantile_at(a: f64, b: f64) -> f64 {
    let (i, wa) = cubic(a);
    let (j, wb) = cubic(b);
    let mut c = 0.0;
    for (di, wa) in wa.iter().enumerate() {
        for (dj, wb) in wb.iter().enumerate() {
            c += wa * wb * grid(i + di, j + dj);
        }
    }
    c
}

/// c at the grid point (i/12, j/12).
fn grid(i: usize, j: usize) -> f64 {
    let (i, j) = (i.max(j), i.min(j));
    QUANTILES[i * (i + 1) / 2 + j]
}

/// The first of the four grid points nearest `x` in [0, 1] and their Lagrange weights.
fn cubic(x: f64) -> (usize, [f64; 4]) {
    let s = x.clamp(0.0, 1.0) * (GRID - 1) as f64;
    let first = (s.floor() as usize).saturating_sub(1).min(GRID - 4);
    let u = s - first as f64;
    // The cubic through the points at 0, 1, 2 and 3 of u.
    let w = [
        -(u - 1.0) * (u - 2.0) * (u - 3.0) / 6.0,
        u * (u - 2.0) * (u - 3.0) / 2.0,
        -u * (u - 1.0) * (u - 3.0) / 2.0,
        u * (u - 1.0) * (u - 2.0) / 6.0,
    ];
    (first, w)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Gauss–Legendre nodes per axis of the integral over the directions of the error: enough
    /// for 1e-9 where it is hardest, a = b = 0 (χ²₁).
    const NODES: usize = 32;

    /// χ²'s 95 % quantiles with 1, 2 and 3 degrees of freedom: 1.959964² (the normal's 97.5 %),
    /// −2 ln 0.05, and the constant of the 95 % ellipsoid.
    const CHI2_95: [f64; 3] = [
        3.841_458_820_694_124,
        5.991_464_547_107_979,
        crate::metrics::CHI2_3DOF_95,
    ];

    /// The 95 % quantile of z₁² + a z₂² + b z₃² (a, b in [0, 1]), by Newton's method on its
    /// distribution function [`share_within`], from χ²₁'s quantile (a = b = 0) toward χ²₃'s
    /// (a = b = 1).
    fn quantile_95(a: f64, b: f64) -> f64 {
        let rule = gauss_legendre();
        let mut q = CHI2_95[0] + 2.0 * (a + b);
        for _ in 0..50 {
            let (share, density) = share_within(&rule, q, a, b);
            let step = (share - 0.95) / density;
            q -= step;
            if step.abs() <= 1e-13 * q {
                break;
            }
        }
        q
    }

    /// P(z₁² + a z₂² + b z₃² ≤ q) and its derivative in q. The sum is r² g(u), r² ~ χ²₃ and u
    /// a direction drawn uniformly, g(u) = u₁² + a u₂² + b u₃²; so the share is the mean over
    /// the directions of χ²₃'s distribution function at q / g(u). By Archimedes' hat-box
    /// theorem u₃ = t is uniform on [−1, 1], and with the azimuth φ the mean over one octant (g
    /// is even in each coordinate) is a product Gauss–Legendre rule in t ∈ [0, 1] and φ ∈
    /// [0, π/2].
    fn share_within(rule: &[(f64, f64)], q: f64, a: f64, b: f64) -> (f64, f64) {
        let (mut share, mut density) = (0.0, 0.0);
        for &(t, wt) in rule {
            for &(s, wp) in rule {
                // cos² φ at φ = s π/2.
                let cos2 = 0.5 * (1.0 + (s * std::f64::consts::PI).cos());
                let g = (1.0 - t * t) * (cos2 + a * (1.0 - cos2)) + b * t * t;
                let (cdf, pdf) = chi2_3(q / g);
                share += wt * wp * cdf;
                density += wt * wp * pdf / g;
            }
        }
        (share, density)
    }

    /// χ²₃'s distribution function and density at x ≥ 0: erf(√(x/2)) − √(2x/π) e^(−x/2) and
    /// √(x/2π) e^(−x/2).
    fn chi2_3(x: f64) -> (f64, f64) {
        let root = (x / (2.0 * std::f64::consts::PI)).sqrt();
        let tail = (-0.5 * x).exp();
        (libm::erf((0.5 * x).sqrt()) - 2.0 * root * tail, root * tail)
    }

    /// The [`NODES`]-point Gauss–Legendre rule on [0, 1]: nodes and weights (summing to 1),
    /// each node a root of the Legendre polynomial found by Newton's method from Tricomi's
    /// estimate. No node lies on an end, so g above is never 0.
    fn gauss_legendre() -> Vec<(f64, f64)> {
        let n = NODES as f64;
        (0..NODES)
            .map(|i| {
                let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5)).cos();
                let mut derivative = 1.0;
                for _ in 0..100 {
                    // P_n(x) by the three-term recurrence, and P_n'(x) from it.
                    let (mut p, mut previous) = (x, 1.0);
                    for k in 2..=NODES {
                        let k = k as f64;
                        (p, previous) = (((2.0 * k - 1.0) * x * p - (k - 1.0) * previous) / k, p);
                    }
                    derivative = n * (x * p - previous) / (x * x - 1.0);
                    let step = p / derivative;
                    x -= step;
                    if step.abs() < 1e-15 {
                        break;
                    }
                }
                (
                    0.5 * (x + 1.0),
                    1.0 / ((1.0 - x * x) * derivative * derivative),
                )
            })
            .collect()
    }

    #[test]
    fn the_quadrature_gives_chi_square_quantiles_where_the_weights_are_equal() {
        for ((a, b), expected) in [
            ((0.0, 0.0), CHI2_95[0]),
            ((1.0, 0.0), CHI2_95[1]),
            ((1.0, 1.0), CHI2_95[2]),
        ] {
            let q = quantile_95(a, b);
            assert!(
                (q - expected).abs() < 1e-9 * expected,
                "({a}, {b}): {q} against {expected}"
            );
        }
        let weights: f64 = gauss_legendre().iter().map(|(_, w)| w).sum();
        assert!((weights - 1.0).abs() < 1e-14);
    }

    #[test]
    fn the_table_holds_the_quadratures_quantiles() {
        let step = 1.0 / (GRID - 1) as f64;
        let computed: Vec<f64> = (0..GRID)
            .flat_map(|i| (0..=i).map(move |j| quantile_95(i as f64 * step, j as f64 * step)))
            .collect();
        let same = computed
            .iter()
            .zip(QUANTILES)
            .all(|(c, t)| (c - t).abs() < 1e-11 * c);
        let rows: Vec<String> = (0..GRID)
            .map(|i| {
                let row = &computed[i * (i + 1) / 2..(i + 1) * (i + 2) / 2];
                format!(
                    "    {},",
                    row.iter()
                        .map(|c| format!("{c:.13}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })
            .collect();
        assert!(
            same,
            "QUANTILES differ from the quadrature's:\n{}",
            rows.join("\n")
        );
    }

    #[test]
    fn the_lengths_from_the_table_are_within_1e_4_of_the_direct_solutions() {
        let mut rng = Rng::new(3);
        let mut worst = 0.0_f64;
        for _ in 0..300 {
            let (a, b) = (rng.uniform(), rng.uniform());
            let direct = quantile_95(a, b).sqrt();
            worst = worst.max((quantile_at(a, b).sqrt() - direct).abs() / direct);
        }
        assert!(worst < 1e-4, "worst relative difference {worst:e}");
    }

    #[test]
    fn the_length_is_a_round_errors_and_one_axis_errors_known_quantile() {
        let round = length_95([4.0, 4.0, 4.0]);
        assert!((round - 2.0 * CHI2_95[2].sqrt()).abs() < 1e-9);
        let line = length_95([0.0, 9.0, 0.0]);
        assert!((line - 3.0 * CHI2_95[0].sqrt()).abs() < 1e-9);
        assert_eq!(length_95([0.0, -1e-18, 0.0]), 0.0);
        assert!(length_95([1.0, f64::NAN, 1.0]).is_nan());
    }

    #[test]
    fn gaussian_errors_stay_under_the_length_95_percent_of_the_time() {
        let mut rng = Rng::new(17);
        for l in [
            [1.0, 1.0, 1.0],
            [100.0, 1.0, 0.01],
            [25.0, 16.0, 0.0],
            [9.0, 4.0, 1.0],
            [1.0, 0.0, 0.0],
        ] {
            let bound = length_95(l);
            let n = 100_000;
            let under = (0..n)
                .filter(|_| {
                    let squared: f64 = l.iter().map(|v| v * rng.normal().powi(2)).sum();
                    squared.sqrt() <= bound
                })
                .count();
            let share = under as f64 / n as f64;
            // Three standard errors of a share of 0.95 in 100 000 draws: 0.002.
            assert!((share - 0.95).abs() < 0.002, "{l:?}: {share}");
        }
    }
}
