/// The `p`-th percentile (0–100) of ascending `sorted` data by linear interpolation between
/// closest ranks (the definition of numpy's default and Excel's PERCENTILE.INC). NaN for no data.
///
/// ```
/// use loratrack::percentile;
/// assert_eq!(percentile(&[1.0, 2.0, 3.0, 4.0], 50.0), 2.5);
/// assert_eq!(percentile(&[1.0, 2.0, 3.0, 4.0], 75.0), 3.25);
/// ```
pub fn percentile(sorted: &[f64], p: f64) -> f64 {
    match sorted.len() {
        0 => f64::NAN,
        1 => sorted[0],
        n => {
            let rank = (p / 100.0).clamp(0.0, 1.0) * (n - 1) as f64;
            let lo = rank.floor() as usize;
            let hi = (lo + 1).min(n - 1);
            sorted[lo] + (rank - lo as f64) * (sorted[hi] - sorted[lo])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_and_empty() {
        let d = [1.0, 5.0, 9.0];
        assert_eq!(percentile(&d, 0.0), 1.0);
        assert_eq!(percentile(&d, 100.0), 9.0);
        assert_eq!(percentile(&d, 50.0), 5.0);
        assert!(percentile(&[], 50.0).is_nan());
    }
}
