use super::{percentile, sort_total};
use serde::Serialize;

/// Summary of absolute errors (m): the shape of `error3d`, `errorX`, … in reference §9. With no
/// samples every statistic is NaN (JSON `null`) and `count` is 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[cfg_attr(all(test, not(target_arch = "wasm32")), derive(ts_rs::TS))]
pub struct Summary {
    /// Arithmetic mean.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub mean: f64,
    /// Median.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub p50: f64,
    /// 75th percentile (the paper's headline statistic).
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub p75: f64,
    /// 95th percentile.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub p95: f64,
    /// Largest error.
    #[cfg_attr(all(test, not(target_arch = "wasm32")), ts(type = "number | null"))]
    pub max: f64,
    /// Number of samples.
    pub count: usize,
}

impl Summary {
    /// Summarises `data` (any order; it is sorted in place).
    pub fn of(data: &mut [f64]) -> Self {
        sort_total(data);
        let n = data.len();
        Summary {
            mean: if n == 0 {
                f64::NAN
            } else {
                data.iter().sum::<f64>() / n as f64
            },
            p50: percentile(data, 50.0),
            p75: percentile(data, 75.0),
            p95: percentile(data, 95.0),
            max: data.last().copied().unwrap_or(f64::NAN),
            count: n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summarises_one_to_hundred() {
        let mut d: Vec<f64> = (1..=100).map(f64::from).collect();
        d.reverse();
        let s = Summary::of(&mut d);
        assert_eq!(s.mean, 50.5);
        assert_eq!(s.p50, 50.5);
        assert!((s.p75 - 75.25).abs() < 1e-12);
        assert_eq!(s.max, 100.0);
        assert_eq!(s.count, 100);
    }

    #[test]
    fn empty_data_has_count_zero_and_nan_statistics() {
        let s = Summary::of(&mut []);
        assert_eq!(s.count, 0);
        assert!(s.mean.is_nan() && s.p75.is_nan());
    }
}
