use super::percentile;
use serde::Serialize;

/// Tukey boxplot statistics (m): quartiles, and whiskers at the most extreme data within
/// 1.5 IQR of the box — the convention of matplotlib's `boxplot`, which the paper's figures use.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "camelCase")]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Boxplot {
    /// Lower whisker.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub whisker_low: f64,
    /// First quartile.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub q1: f64,
    /// Median.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub median: f64,
    /// Third quartile.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub q3: f64,
    /// Upper whisker.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub whisker_high: f64,
    /// Samples beyond the whiskers.
    pub outliers: usize,
    /// Number of samples.
    pub count: usize,
}

impl Boxplot {
    /// Boxplot of ascending `sorted` data (NaN statistics when empty).
    pub fn of_sorted(sorted: &[f64]) -> Self {
        let (q1, median, q3) = (
            percentile(sorted, 25.0),
            percentile(sorted, 50.0),
            percentile(sorted, 75.0),
        );
        let iqr = q3 - q1;
        let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
        let whisker_low = sorted
            .iter()
            .copied()
            .find(|&v| v >= lo_fence)
            .unwrap_or(f64::NAN);
        let whisker_high = sorted
            .iter()
            .rev()
            .copied()
            .find(|&v| v <= hi_fence)
            .unwrap_or(f64::NAN);
        let outliers = sorted
            .iter()
            .filter(|&&v| v < lo_fence || v > hi_fence)
            .count();
        Boxplot {
            whisker_low,
            q1,
            median,
            q3,
            whisker_high,
            outliers,
            count: sorted.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn whiskers_stop_at_the_last_point_inside_the_fences() {
        let mut d: Vec<f64> = (1..=20).map(f64::from).collect();
        d.push(100.0);
        let b = Boxplot::of_sorted(&d);
        assert_eq!(b.median, 11.0);
        assert_eq!(b.q1, 6.0);
        assert_eq!(b.q3, 16.0);
        assert_eq!(b.whisker_high, 20.0);
        assert_eq!(b.whisker_low, 1.0);
        assert_eq!(b.outliers, 1);
    }
}
